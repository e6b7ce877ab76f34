// Quantities every rank needs in their global form: the bounds of the whole mesh (camera
// auto-fit) and the value ranges of fields (colormap ranges). Each rank states its own part;
// one allreduce makes the union, so an empty rank (nothing included) is harmless.
#pragma once

#include <mpi.h>

#include <span>

#include "render/core/value_bounds.hpp"

namespace tetray::render {

// Replaces every range by its union over the ranks of `comm`, all in one MPI_Allreduce.
// Collective; returns MPI_SUCCESS or the MPI error code.
int global_ranges(std::span<ValueRange> ranges, MPI_Comm comm);

// Replaces `box` and `ranges` by their unions over the ranks of `comm`, in one MPI_Allreduce:
// the usual need of a render step (camera fit and colormap ranges together).
int global_bounds_and_ranges(BoundingBox& box, std::span<ValueRange> ranges, MPI_Comm comm);

}  // namespace tetray::render
