// The few collective operations of the adaptor besides render/composite/global_reduce and
// render/composite. Each is a no-op on one rank.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <new>
#include <span>
#include <string>

#include "adaptor/step_reductions.hpp"
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

// Agrees on a stage's outcome and, in the same allreduce, on the global unions of `ranges` and
// on which scenes `skips` names, when given. Every rank gets the status of the lowest failing
// rank, prefixed with that rank, or success; and for each scene skipped on some rank, the reason
// of the lowest such rank, prefixed with it (one broadcast per skipped scene, none otherwise).
Status agree(const Communicator& c, const Status& local, StepRanges* ranges = nullptr,
             SceneSkips* skips = nullptr);

std::string mpi_error_text(int code);

// Runs a stage; whatever it throws (std::bad_alloc, a library's exception) becomes a status, so
// the rank still reaches the agreement that follows: an exception on one rank must not leave the
// others waiting there.
template <typename Stage>
Status guarded(const char* name, Stage&& stage) {
  try {
    return stage();
  } catch (const std::bad_alloc&) {
    return {StatusCode::internal_error, std::string(name) + ": out of memory"};
  } catch (const std::exception& e) {
    return {StatusCode::internal_error, std::string(name) + ": " + e.what()};
  } catch (...) {
    return {StatusCode::internal_error, std::string(name) + ": unknown exception"};
  }
}

}  // namespace tetray
