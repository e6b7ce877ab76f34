// Where a ray crosses a face it passes through: the barycentric weights of the ray in the
// projected triangle (each the edge determinant opposite a corner), so the crossing point and
// the linearly interpolated field are the same whichever of the face's two tets asks, and the
// field along a walk is continuous from tet to tet. A second point field (the isosurfaces of a
// volume scene, surface_crossing.hpp) is interpolated with the same weights.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>

#include "render/volume/tet_volume.hpp"
#include "render/walk/ray_frame.hpp"

namespace tetray::render {

inline Vec3d vertex_position(const TetVolume& volume, std::uint32_t v) {
  const Vertex& p = volume.vertices[v];
  return {p.x, p.y, p.z};
}

// A face as the walk holds it: three vertex indices and their projections, counter-clockwise
// around the ray (ray_side is +1 for each edge 0->1, 1->2, 2->0).
struct ProjectedFace {
  std::uint32_t vertex[3];
  Point2 point[3];
};

struct FaceCrossing {
  double t = 0;  // ray parameter
  double f = 0;  // field value
  double g = 0;  // the second field's value, or f without one
};

// `second`: a second field per vertex of the vertex store, or empty. The weights are each
// corner's own edge determinant, the same from both tets of the face. The crossing interpolates
// from the corner first in order of position (the same on every rank, unlike the vertex indices,
// which each rank's store numbers its own way; by index only where two corners coincide), and
// the other two enter only through sums whose two terms swap without changing a bit, so the
// crossing is the same to the last bit whichever tet, walk or rank asks, and a field that is
// constant over the face crosses it at exactly that value (an isosurface lying in a face is met
// the same way on every rank count).
inline FaceCrossing cross_face(const TetVolume& volume, const RayFrame& frame,
                               const ProjectedFace& face, std::span<const float> second = {}) {
  const Point2* p = face.point;
  double w[3] = {std::max(0.0, edge_determinant(p[1], p[2])),
                 std::max(0.0, edge_determinant(p[2], p[0])),
                 std::max(0.0, edge_determinant(p[0], p[1]))};
  const auto before = [&](int i, int j) {
    const Vertex& vi = volume.vertices[face.vertex[i]];
    const Vertex& vj = volume.vertices[face.vertex[j]];
    if (vi.x != vj.x) return vi.x < vj.x;
    if (vi.y != vj.y) return vi.y < vj.y;
    if (vi.z != vj.z) return vi.z < vj.z;
    return face.vertex[i] < face.vertex[j];
  };
  int a = before(1, 0) ? 1 : 0;
  if (before(2, a)) a = 2;
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  double sum = w[a] + (w[b] + w[c]);
  if (!(sum > 0)) {  // the face seen edge-on: any point of it is as good
    w[0] = w[1] = w[2] = 1;
    sum = 3;
  }
  const double wb = w[b] / sum, wc = w[c] / sum;
  const auto mix = [&](double va, double vb, double vc) {
    return va + (wb * (vb - va) + wc * (vc - va));
  };
  const Vec3d xa = vertex_position(volume, face.vertex[a]);
  const Vec3d xb = vertex_position(volume, face.vertex[b]);
  const Vec3d xc = vertex_position(volume, face.vertex[c]);
  const Vec3d point{mix(xa.x, xb.x, xc.x), mix(xa.y, xb.y, xc.y), mix(xa.z, xb.z, xc.z)};
  const auto value = [&](auto of) {
    return mix(of(face.vertex[a]), of(face.vertex[b]), of(face.vertex[c]));
  };
  const double f = value([&](std::uint32_t v) { return double{volume.vertices[v].f}; });
  const double g = second.empty() ? f : value([&](std::uint32_t v) { return double{second[v]}; });
  return {frame.parameter(point), f, g};
}

}  // namespace tetray::render
