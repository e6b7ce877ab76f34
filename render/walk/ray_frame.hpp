// A ray seen along itself (Aman et al. 2022, §4): a 2D basis (u, v) orthogonal to the direction
// d, with (u, v, d) right-handed, and the ray's origin at the 2D origin. A vertex is projected
// once per tet it enters; which face a ray leaves through is then decided by the side of the
// ray relative to projected edges. That side is a function of the directed edge alone, exactly
// antisymmetric (swapping the ends negates it bit for bit) and never zero: where the ray meets
// the edge's line exactly, it is decided as if the ray were moved by (e, e^2) for an
// infinitesimal e (simulation of simplicity, Edelsbrunner and Mücke 1990), and by the vertex
// indices where both ends project to the same point. Every tet sharing the edge therefore sees
// the same side, so a ray through a vertex or along an edge still crosses one face at a time,
// never two or none.
#pragma once

#include <cmath>
#include <cstdint>

#include "render/core/vec.hpp"

namespace tetray::render {

struct Point2 {
  double x = 0, y = 0;
};

struct RayFrame {
  Vec3d origin;
  Vec3d direction;  // unit length
  Vec3d u, v;

  // A frame for a ray in the volume's local coordinates; `direction` need not be unit length.
  // The basis is Duff et al. 2017's branchless orthonormal basis.
  RayFrame(Vec3d ray_origin, Vec3d ray_direction) : origin(ray_origin) {
    direction = normalize(ray_direction);
    const Vec3d n = direction;
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    u = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    v = {b, sign + n.y * n.y * a, -n.y};
    if (dot(cross(u, v), direction) < 0) std::swap(u, v);
  }

  Point2 project(Vec3d p) const {
    const Vec3d q = p - origin;
    return {dot(u, q), dot(v, q)};
  }

  // Ray parameter of a point, measured along the unit direction.
  double parameter(Vec3d p) const { return dot(p - origin, direction); }
};

// Twice the signed area of (a, b, ray): positive when the ray passes left of a -> b.
inline double edge_determinant(Point2 a, Point2 b) { return a.x * b.y - a.y * b.x; }

// +1 when the ray passes left of the directed edge a -> b (vertex indices ia, ib), else -1.
inline int ray_side(Point2 a, std::uint32_t ia, Point2 b, std::uint32_t ib) {
  const double det = edge_determinant(a, b);
  if (det != 0) return det > 0 ? 1 : -1;
  if (a.y != b.y) return a.y > b.y ? 1 : -1;
  if (a.x != b.x) return b.x > a.x ? 1 : -1;
  return ia < ib ? 1 : -1;
}

}  // namespace tetray::render
