#include "minisolver/error_norms.hpp"

#include <algorithm>
#include <cmath>

#include "minisolver/tet_geometry.hpp"

namespace minisolver {
namespace {

// Four-point rule, exact for quadratics: barycentric (a, b, b, b) and permutations.
constexpr double kA = 0.5854101966249685, kB = 0.1381966011250105;

}  // namespace

ErrorNorms error_norms(const DofSpace& space, std::span<const double> uh,
                       const std::function<void(const Vec3&, double*)>& exact) {
  const LocalMesh& mesh = space.mesh();
  const auto c = static_cast<std::size_t>(space.components());
  double squared = 0, largest = 0;
  double at[3];
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const auto x = mesh.tet_points(t);
    const double volume = signed_volume(x);
    for (int q = 0; q < 4; ++q) {
      Vec3 point{};
      double weights[4];
      for (int a = 0; a < 4; ++a) {
        weights[a] = a == q ? kA : kB;
        for (int k = 0; k < 3; ++k) point[k] += weights[a] * x[a][k];
      }
      exact(point, at);
      for (std::size_t i = 0; i < c; ++i) {
        double approx = 0;
        for (int a = 0; a < 4; ++a) approx += weights[a] * uh[c * mesh.tets[4 * t + a] + i];
        squared += 0.25 * volume * (approx - at[i]) * (approx - at[i]);
      }
    }
  }
  for (std::size_t p = 0; p < mesh.point_count(); ++p) {
    if (!mesh.owned[p]) continue;
    exact(mesh.point(p), at);
    for (std::size_t i = 0; i < c; ++i)
      largest = std::max(largest, std::abs(uh[c * p + i] - at[i]));
  }
  return {std::sqrt(space.comm().sum(squared)), space.comm().max(largest)};
}

}  // namespace minisolver
