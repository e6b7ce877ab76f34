// Hilbert order of the tets (Aman et al. 2022, §5): tets sorted along a 3D Hilbert curve through
// their centroids, vertices renumbered in the order the sorted tets first use them. The walk
// steps from a tet to a face neighbour, so the order in which tets lie in memory decides how
// often a step misses the cache; the renderer keeps the BVH's leaf order (which the traversal
// needs), and the benchmark measures the walk in both orders (docs/architecture.md §8).
#pragma once

#include <cstdint>

#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// The index along the Hilbert curve of order `bits` (1..21) of the grid point (x, y, z), each
// below 2^bits (Skilling 2004, "Programming the Hilbert curve": axes to transpose, then the
// transposed bits interleaved).
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

// A copy of `volume` (tets, tet ids, vertices and, where present, the per-vertex arrays) in
// Hilbert order of the tets' centroids on a 2^21 grid over the vertices' bounding box; the
// geometry and field are unchanged, point_vertex follows the renumbering.
TetVolume hilbert_ordered(const TetVolume& volume);

}  // namespace tetray::render
