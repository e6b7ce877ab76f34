#include "scenes/box_mesh.hpp"

#include <cmath>

#include "render/core/hash.hpp"

namespace tetray {
namespace {

// Uniform in [-1, 1] from the point index and the axis.
double unit_jitter(std::uint64_t point, int axis) {
  const std::uint64_t h = render::mix64(point * 3 + static_cast<std::uint64_t>(axis));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

void add_points(const BoxMeshSpec& spec, BoxMesh& mesh) {
  const auto& c = spec.cells;
  mesh.points.resize(3 * (static_cast<std::size_t>(c[0]) + 1) *
                     (static_cast<std::size_t>(c[1]) + 1) * (static_cast<std::size_t>(c[2]) + 1));
  for (int k = 0; k <= c[2]; ++k)
    for (int j = 0; j <= c[1]; ++j)
      for (int i = 0; i <= c[0]; ++i) {
        const std::int64_t p = mesh.point_index(i, j, k);
        const int ijk[3] = {i, j, k};
        const bool interior = i > 0 && j > 0 && k > 0 && i < c[0] && j < c[1] && k < c[2];
        for (int a = 0; a < 3; ++a) {
          const double h = (spec.hi[a] - spec.lo[a]) / c[a];
          double x = spec.lo[a] + h * ijk[a];
          if (interior) x += spec.jitter * h * unit_jitter(static_cast<std::uint64_t>(p), a);
          mesh.points[3 * static_cast<std::size_t>(p) + a] = x;
        }
      }
}

// The six Kuhn tets of a hex: one per axis order (a, b, c), walking 0 -> e_a -> e_a+e_b ->
// (1,1,1). Odd permutations swap two vertices to keep the orientation positive.
void add_tets(BoxMesh& mesh) {
  static constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                        {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  const auto& c = mesh.cells;
  mesh.tets.reserve(24 * static_cast<std::size_t>(c[0]) * c[1] * c[2]);
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i)
        for (int t = 0; t < 6; ++t) {
          int corner[3] = {i, j, k};
          std::int64_t v[4];
          v[0] = mesh.point_index(i, j, k);
          for (int s = 0; s < 3; ++s) {
            ++corner[kOrders[t][s]];
            v[s + 1] = mesh.point_index(corner[0], corner[1], corner[2]);
          }
          if (t >= 3) std::swap(v[2], v[3]);
          mesh.tets.insert(mesh.tets.end(), v, v + 4);
        }
}

double gyroid_value(double x, double y, double z, double t) {
  return std::sin(4 * x + t) * std::cos(4 * y) + std::sin(4 * y) * std::cos(4 * z + 0.5 * t) +
         std::sin(4 * z) * std::cos(4 * x);
}

}  // namespace

BoxMesh make_box_mesh(const BoxMeshSpec& spec) {
  BoxMesh mesh;
  mesh.cells = spec.cells;
  add_points(spec, mesh);
  add_tets(mesh);
  return mesh;
}

void deform_gyroid_twist(const BoxMesh& reference, double t, std::vector<double>& points,
                         std::vector<double>& field) {
  const std::size_t n = reference.point_count();
  points.resize(3 * n);
  field.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const double x = reference.points[3 * p], y = reference.points[3 * p + 1],
                 z = reference.points[3 * p + 2];
    const double theta = 0.3 * z * std::sin(t);
    const double c = std::cos(theta), s = std::sin(theta);
    const double xr = c * x - s * y, yr = s * x + c * y;
    points[3 * p] = xr;
    points[3 * p + 1] = yr;
    points[3 * p + 2] = z;
    field[p] = gyroid_value(xr, yr, z, t);
  }
}

GyroidTwist make_gyroid_twist(int n, double t) {
  BoxMeshSpec spec;
  spec.cells = {n, n, n};
  spec.jitter = 0.15;
  GyroidTwist scene;
  scene.mesh = make_box_mesh(spec);
  std::vector<double> deformed;
  deform_gyroid_twist(scene.mesh, t, deformed, scene.field);
  scene.mesh.points = std::move(deformed);
  return scene;
}

}  // namespace tetray
