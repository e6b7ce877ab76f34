// The check before compositing: every rank must pass a well-formed image of the same size and
// the same options. One small allreduce, so that a mismatch returns an error on every rank
// instead of hanging the schedule.
#pragma once

#include <mpi.h>

#include "render/composite/composite.hpp"

namespace tetray::render {

// MPI_SUCCESS when every rank agrees; MPI_ERR_ROOT for a root out of range, MPI_ERR_ARG for a
// malformed image or differing sizes or algorithms; or the allreduce's error. Collective.
int agree_on_inputs(int image_width, int image_height, bool image_ok, MPI_Comm comm,
                    const CompositeOptions& options, int rank_count);

}  // namespace tetray::render
