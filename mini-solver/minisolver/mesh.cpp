#include "minisolver/mesh.hpp"

#include <cmath>
#include <utility>

#include "minisolver/tet_geometry.hpp"

namespace minisolver {
namespace {

std::int64_t grid_index(std::array<int, 3> ijk, std::array<int, 3> cells) {
  return (static_cast<std::int64_t>(ijk[2]) * (std::int64_t{cells[1]} + 1) + ijk[1]) *
             (std::int64_t{cells[0]} + 1) +
         ijk[0];
}

void add_grid_points(std::array<int, 3> cells, const ParameterMap& map, Mesh& mesh) {
  const std::size_t count = grid_counts(cells).points;
  mesh.points.reserve(3 * count);
  mesh.faces.reserve(count);
  for (int k = 0; k <= cells[2]; ++k)
    for (int j = 0; j <= cells[1]; ++j)
      for (int i = 0; i <= cells[0]; ++i) {
        const Vec3 unit{static_cast<double>(i) / cells[0], static_cast<double>(j) / cells[1],
                        static_cast<double>(k) / cells[2]};
        const Vec3 x = map(unit);
        mesh.points.insert(mesh.points.end(), x.begin(), x.end());
        mesh.faces.push_back(grid_point_faces({i, j, k}, cells));
      }
}

// The six Kuhn tets of hex (i, j, k): one per axis order, walking (0,0,0) -> e_a -> e_a+e_b ->
// (1,1,1). A mapped grid may flip orientation, so each tet is checked and fixed by volume.
void add_hex_tets(std::array<int, 3> ijk, std::array<int, 3> cells, Mesh& mesh) {
  static constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                        {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (const auto& order : kOrders) {
    std::array<int, 3> corner = ijk;
    std::array<std::int64_t, 4> v{};
    v[0] = grid_index(corner, cells);
    for (int s = 0; s < 3; ++s) {
      ++corner[order[s]];
      v[s + 1] = grid_index(corner, cells);
    }
    const std::array<Vec3, 4> x{mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]),
                                mesh.point(v[3])};
    if (signed_volume(x) < 0) std::swap(v[2], v[3]);
    mesh.tets.insert(mesh.tets.end(), v.begin(), v.end());
  }
}

}  // namespace

GridCounts grid_counts(std::array<int, 3> cells) {
  GridCounts counts{1, 6};
  for (const int n : cells) {
    counts.points *= static_cast<std::uint64_t>(n) + 1;
    counts.tets *= static_cast<std::uint64_t>(n);
  }
  return counts;
}

std::uint8_t grid_point_faces(std::array<int, 3> ijk, std::array<int, 3> cells) {
  std::uint8_t bits = 0;
  for (int a = 0; a < 3; ++a) {
    if (ijk[a] == 0) bits |= static_cast<std::uint8_t>(1 << (2 * a));
    if (ijk[a] == cells[a]) bits |= static_cast<std::uint8_t>(1 << (2 * a + 1));
  }
  return bits;
}

Mesh make_mapped_grid(std::array<int, 3> cells, const ParameterMap& map) {
  Mesh mesh;
  add_grid_points(cells, map, mesh);
  mesh.tets.reserve(4 * grid_counts(cells).tets);
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) add_hex_tets({i, j, k}, cells, mesh);
  mesh.material.assign(mesh.tet_count(), 0);
  return mesh;
}

Mesh make_beam(std::array<int, 3> cells, const Vec3& lo, const Vec3& hi) {
  return make_mapped_grid(cells, [&](const Vec3& u) {
    return Vec3{lo[0] + u[0] * (hi[0] - lo[0]), lo[1] + u[1] * (hi[1] - lo[1]),
                lo[2] + u[2] * (hi[2] - lo[2])};
  });
}

Mesh make_shell_sector(std::array<int, 3> cells, const ShellSpec& spec) {
  return make_mapped_grid(cells, [&](const Vec3& u) {
    const double azimuth = u[0] * spec.azimuth_span;
    const double polar = spec.polar_min + u[1] * (spec.polar_max - spec.polar_min);
    const double radius = spec.inner_radius + u[2] * (spec.outer_radius - spec.inner_radius);
    return Vec3{radius * std::sin(polar) * std::cos(azimuth), radius * std::cos(polar),
                radius * std::sin(polar) * std::sin(azimuth)};
  });
}

void split_materials(Mesh& mesh, int axis, double at) {
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    double centroid = 0;
    for (int c = 0; c < 4; ++c) centroid += 0.25 * mesh.points[3 * mesh.tets[4 * t + c] + axis];
    mesh.material[t] = centroid > at ? 1 : 0;
  }
}

}  // namespace minisolver
