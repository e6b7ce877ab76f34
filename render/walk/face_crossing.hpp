// Where a ray crosses a face it passes through: the barycentric weights of the ray in the
// projected triangle (each the edge determinant opposite a corner), so the crossing point and
// the linearly interpolated field are the same whichever of the face's two tets asks, and the
// field along a walk is continuous from tet to tet. A second point field (the isosurfaces of a
// volume scene, surface_crossing.hpp) is interpolated with the same weights.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>

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

// `second`: a second field per vertex of the vertex store, or empty.
inline FaceCrossing cross_face(const TetVolume& volume, const RayFrame& frame,
                               const ProjectedFace& face, std::span<const float> second = {}) {
  const Point2* p = face.point;
  double w[3] = {std::max(0.0, edge_determinant(p[1], p[2])),
                 std::max(0.0, edge_determinant(p[2], p[0])),
                 std::max(0.0, edge_determinant(p[0], p[1]))};
  double sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) {  // the face seen edge-on: any point of it is as good
    w[0] = w[1] = w[2] = 1;
    sum = 3;
  }
  Vec3d point{};
  double f = 0, g = 0;
  for (int c = 0; c < 3; ++c) {
    point = point + (w[c] / sum) * vertex_position(volume, face.vertex[c]);
    f += (w[c] / sum) * volume.vertices[face.vertex[c]].f;
    if (!second.empty()) g += (w[c] / sum) * second[face.vertex[c]];
  }
  return {frame.parameter(point), f, second.empty() ? f : g};
}

}  // namespace tetray::render
