// A rank's share of a mesh in [-1, 1]^3 for the split-mesh tests: the tets whose centroid's x
// falls in its slab, with their indices in the whole mesh as global ids.
#pragma once

#include <cstdint>
#include <vector>

#include "scenes/box_mesh.hpp"

namespace tetray::testing {

struct Slab {
  std::vector<std::int64_t> tets;  // 4 per tet, the whole mesh's point numbers
  std::vector<std::int64_t> ids;   // each tet's index in the whole mesh
};

// Slab `rank` of `ranks` equal slabs of x in [-1, 1] (clamped at the ends).
Slab x_slab(const BoxMesh& mesh, int rank, int ranks);

}  // namespace tetray::testing
