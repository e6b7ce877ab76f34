#include "minisolver/tet_geometry.hpp"

#include <Eigen/Dense>

namespace minisolver {
namespace {

Eigen::Matrix3d edge_matrix(const std::array<Vec3, 4>& x) {
  Eigen::Matrix3d edges;
  for (int e = 0; e < 3; ++e)
    for (int a = 0; a < 3; ++a) edges(a, e) = x[e + 1][a] - x[0][a];
  return edges;
}

}  // namespace

double signed_volume(const std::array<Vec3, 4>& x) { return edge_matrix(x).determinant() / 6; }

TetGeometry tet_geometry(const std::array<Vec3, 4>& x) {
  const Eigen::Matrix3d edges = edge_matrix(x);
  const Eigen::Matrix3d inverse = edges.inverse();
  TetGeometry g;
  g.volume = edges.determinant() / 6;
  // Row e of the inverse edge matrix is the gradient of barycentric coordinate e+1; the four
  // coordinates sum to one, so the first gradient is minus the sum of the others.
  for (int e = 0; e < 3; ++e)
    for (int a = 0; a < 3; ++a) {
      g.gradient[e + 1][a] = inverse(e, a);
      g.gradient[0][a] -= inverse(e, a);
    }
  return g;
}

}  // namespace minisolver
