// The adaptor's agreement of statuses across ranks: a stage's outcome, the skipped scenes and
// the step's ranges agreed on every rank (the protocols themselves are render/parallel's). Each
// is a no-op on one rank.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "render/parallel/protocol_status.hpp"
#include "render/parallel/step_reductions.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

// The step's reductions and MPI's error text, render/parallel's, by their names in the adaptor.
using render::mpi_error_text;
using render::SceneCounters;
using render::SceneRanges;
using render::StepRanges;

// Per scene, why this rank cannot render it this step (empty: it can). Agreed with a stage's
// outcome: a scene skipped on one rank is skipped on all, since its image would be incomplete.
using SceneSkips = std::vector<std::string>;

struct Communicator {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  int size = 1;
};

// Copies `root`'s status to every rank.
int broadcast_status(const Communicator& c, int root, Status& status);

// Agrees on a stage's outcome and, in the same allreduce, on the global unions of `ranges` and
// on which scenes `skips` names, when given. Every rank gets the status of the lowest failing
// rank, prefixed with that rank, or success; and for each scene skipped on some rank, the reason
// of the lowest such rank, prefixed with it (one broadcast per skipped scene, none otherwise).
Status agree(const Communicator& c, const Status& local, StepRanges* ranges = nullptr,
             SceneSkips* skips = nullptr);

// A render/parallel protocol's outcome as the adaptor's: an MPI failure stays one, a failure of
// this rank's own work is an internal error.
Status to_status(render::ProtocolStatus status);

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
