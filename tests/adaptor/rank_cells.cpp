#include "rank_cells.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <span>

namespace tetray::testing {

MeshView RankCells::view() const {
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(xyz));
  mesh.cells = {types.data(),     offsets.data(), connectivity.data(),
                IndexType::int64, types.size(),   ghost.empty() ? nullptr : ghost.data()};
  return mesh;
}

std::vector<FieldView> RankCells::fields() const {
  return {FieldView::of("distance", std::span<const double>(distance))};
}

namespace {

// The cells `cells` of `mesh` over the points they use, in `seed`'s shuffled order, with
// value(point of mesh, position) as the field.
template <typename Value>
RankCells gather(const CellMesh& mesh, const std::vector<std::size_t>& cells, unsigned seed,
                 Value value) {
  std::vector<std::int64_t> used;
  for (const std::size_t c : cells) {
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
    out.distance.push_back(value(used[k], p));
  }
  for (const std::size_t c : cells) {
    out.types.push_back(mesh.types[c]);
    for (auto v = mesh.offsets[c]; v < mesh.offsets[c + 1]; ++v) {
      out.connectivity.push_back(local[mesh.connectivity[v]]);
    }
    out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
  }
  return out;
}

}  // namespace

RankCells share(const CellMesh& mesh, std::size_t first, std::size_t last, unsigned seed) {
  std::vector<std::size_t> cells;
  for (auto c = first; c < last; ++c) cells.push_back(c);
  return gather(mesh, cells, seed, [](std::int64_t, const double* p) {
    return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  });
}

RankCells share_with_ghosts(const CellMesh& mesh, std::size_t first, std::size_t last,
                            unsigned seed, const std::vector<double>& values) {
  std::vector<std::uint8_t> touched(mesh.points.size(), 0);
  for (auto v = mesh.offsets[first]; v < mesh.offsets[last]; ++v) touched[mesh.connectivity[v]] = 1;
  std::vector<std::size_t> cells;
  std::vector<std::uint8_t> ghost;
  for (std::size_t c = 0; c < mesh.types.size(); ++c) {
    const bool own = c >= first && c < last;
    bool near = own;
    for (auto v = mesh.offsets[c]; v < mesh.offsets[c + 1] && !near; ++v) {
      near = touched[mesh.connectivity[v]] != 0;
    }
    if (!near) continue;
    cells.push_back(c);
    ghost.push_back(own ? 0 : 1);
  }
  RankCells out = gather(mesh, cells, seed, [&](std::int64_t p, const double*) {
    return values[static_cast<std::size_t>(p)];
  });
  out.ghost = std::move(ghost);
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
