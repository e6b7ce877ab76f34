// The few collective operations of the adaptor besides render/composite/global_reduce and
// render/composite. Each is a no-op on one rank.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>

#include "step_reductions.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

struct Communicator {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  int size = 1;
};

// Element-wise sums of the scenes' counters and the maximum of `value` onto `root`, in place.
int reduce_sum_to_root(const Communicator& c, int root, std::span<SceneCounters> counters);
int reduce_max_to_root(const Communicator& c, int root, std::uint64_t& value);

// Copies `root`'s status to every rank.
int broadcast_status(const Communicator& c, int root, Status& status);

// Agrees on a stage's outcome and, in the same allreduce, on the global unions of `ranges` when
// given. Every rank gets the status of the lowest failing rank, prefixed with that rank, or
// success.
Status agree(const Communicator& c, const Status& local, StepRanges* ranges = nullptr);

std::string mpi_error_text(int code);

}  // namespace tetray
