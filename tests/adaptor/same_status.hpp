// For tests run under mpirun: a status every rank must share, checked against rank 0's code and
// whole message (sent by MPI, not through the adaptor whose agreement is under test).
#pragma once

#include <gtest/gtest.h>
#include <mpi.h>

#include <string>

#include "shared_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {

inline void expect_same_on_every_rank(const Status& status) {
  int code = static_cast<int>(status.code);
  int length = static_cast<int>(status.message.size());
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string text = status.message;
  text.resize(static_cast<std::size_t>(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  EXPECT_EQ(static_cast<int>(status.code), code) << "rank " << rank();
  EXPECT_EQ(status.message, text) << "rank " << rank();
}

inline std::string rank_prefix(int r) { return "rank " + std::to_string(r) + ": "; }

}  // namespace tetray::testing
