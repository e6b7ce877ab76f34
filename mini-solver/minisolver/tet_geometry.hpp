// Geometry of one linear (P1) tet: signed volume and the gradients of its barycentric
// coordinates, which are constant over the tet and carry every P1 element matrix.
#pragma once

#include <array>

#include "minisolver/mesh.hpp"

namespace minisolver {

double signed_volume(const std::array<Vec3, 4>& x);

struct TetGeometry {
  double volume = 0;
  std::array<Vec3, 4> gradient{};  // of barycentric coordinate a
};

TetGeometry tet_geometry(const std::array<Vec3, 4>& x);

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace minisolver
