#include "support/mesh_slabs.hpp"

#include <algorithm>

namespace tetray::testing {

Slab x_slab(const BoxMesh& mesh, int rank, int ranks) {
  Slab s;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    double x = 0;
    for (int k = 0; k < 4; ++k) x += mesh.points[3 * mesh.tets[4 * t + k]] / 4;
    const int owner = std::clamp(static_cast<int>((x + 1) / 2 * ranks), 0, ranks - 1);
    if (owner != rank) continue;
    s.tets.insert(s.tets.end(), &mesh.tets[4 * t], &mesh.tets[4 * t + 4]);
    s.ids.push_back(static_cast<std::int64_t>(t));
  }
  return s;
}

}  // namespace tetray::testing
