// Shadows across ranks (Wald et al. 2007, §7, made exact for a split mesh): an occluder of a hit
// point may live on any rank. After depth compositing the root shares the composited depth, every
// rank traces the shadow rays of every hit point against its own tets
// (render/trace/shadow_rays.hpp), and the "occluded" bits are combined by a logical OR onto the
// root, which then shades. The bits are the same for any split of the mesh, so is the image.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>

namespace tetray::render {

// Collective: `depth` (the same size on every rank) becomes the root's on every rank. Returns
// MPI_SUCCESS or the MPI error code.
int share_composited_depth(std::span<float> depth, int root, MPI_Comm comm);

// Collective: the root's `occluded` becomes the bitwise OR of every rank's (the same size on
// every rank); the others' are left as they were. Returns MPI_SUCCESS or the MPI error code.
int combine_occlusion(std::span<std::uint8_t> occluded, int root, MPI_Comm comm);

}  // namespace tetray::render
