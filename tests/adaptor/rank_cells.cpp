#include "rank_cells.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <span>

namespace tetray::testing {

MeshView RankCells::view() const {
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(xyz));
  mesh.cells = {types.data(), offsets.data(), connectivity.data(), IndexType::int64, types.size()};
  return mesh;
}

std::vector<FieldView> RankCells::fields() const {
  return {FieldView::of("distance", std::span<const double>(distance))};
}

RankCells share(const CellMesh& mesh, std::size_t first, std::size_t last, unsigned seed) {
  std::vector<std::int64_t> used;
  for (auto c = first; c < last; ++c) {
    used.insert(used.end(), mesh.connectivity.begin() + mesh.offsets[c],
                mesh.connectivity.begin() + mesh.offsets[c + 1]);
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  if (seed != 0) std::shuffle(used.begin(), used.end(), std::mt19937(seed));
  std::vector<std::int64_t> local(mesh.points.size(), -1);
  RankCells out;
  const std::vector<double> xyz = mesh.xyz(-1, 1);
  for (std::size_t k = 0; k < used.size(); ++k) {
    local[used[k]] = static_cast<std::int64_t>(k);
    const double* p = &xyz[3 * used[k]];
    out.xyz.insert(out.xyz.end(), p, p + 3);
    out.distance.push_back(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
  }
  for (auto c = first; c < last; ++c) {
    out.types.push_back(mesh.types[c]);
    for (auto v = mesh.offsets[c]; v < mesh.offsets[c + 1]; ++v) {
      out.connectivity.push_back(local[mesh.connectivity[v]]);
    }
    out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
  }
  return out;
}

std::string ball_config(const std::string& directory, double radius, const std::string& eye,
                        double fov_deg, int side) {
  return "output: {directory: " + directory + ", formats: [png], quiet: true}\n" +
         "scenes:\n"
         "  - name: ball\n"
         "    field: distance\n"
         "    isovalues: [" +
         std::to_string(radius) + "]\n    camera: {eye: " + eye +
         ", look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: " + std::to_string(fov_deg) +
         "}\n    image: {width: " + std::to_string(side) + ", height: " + std::to_string(side) +
         "}\n";
}

}  // namespace tetray::testing
