// Isopolygons (seed 000 §4.1): the plane of a linear tet's isosurface bounded by its edges,
// found by the 16-case marching-tetrahedra table. A vertex with f >= iso counts as above
// (DESIGN §3), which makes every case well defined, values equal to the isovalue included.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "render/tet_volume.hpp"
#include "render/vec.hpp"

namespace tetray::render {

struct IsoCase {
  std::uint8_t vertex_count;  // 0, 3 or 4
  std::uint8_t edges[4][2];   // tet vertex pairs, in order around the polygon
};

// The table for case = sum of (f_i >= iso) << i.
const std::array<IsoCase, 16>& iso_cases();

// The case of a tet for an isovalue.
inline int iso_case(const Vertex* v[4], float iso) {
  return (v[0]->f >= iso ? 1 : 0) | (v[1]->f >= iso ? 2 : 0) | (v[2]->f >= iso ? 4 : 0) |
         (v[3]->f >= iso ? 8 : 0);
}

// A tet holds a piece of the isosurface iff some vertex is below and some at or above.
inline bool range_straddles(float fmin, float fmax, float iso) { return fmin < iso && iso <= fmax; }

struct Isopolygon {
  int vertex_count = 0;
  Vec3f p[4];  // relative to the volume's local origin
};

inline bool comes_first(const Vertex& a, const Vertex& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.f < b.f;
}

// The point where the isosurface crosses the edge (a, b). The two ends are ordered by position
// (not by index), so every tet sharing the edge, on any rank, computes bitwise the same point:
// neighbouring isopolygons meet exactly and the surface has no cracks. An end whose value
// equals the isovalue is returned exactly, so polygons meeting at a mesh vertex through
// different edges meet there too; and the point is clamped to the edge's bounding box, which
// rounding could otherwise leave by an ulp (the BVH bounds the vertices, not the polygons).
inline Vec3f edge_crossing(const Vertex& a, const Vertex& b, float iso) {
  const bool a_first = comes_first(a, b);
  const Vertex& p = a_first ? a : b;
  const Vertex& q = a_first ? b : a;
  if (p.f == iso) return {p.x, p.y, p.z};
  if (q.f == iso) return {q.x, q.y, q.z};
  // p.f != q.f: one end is at or above the isovalue and the other below.
  const float s = (iso - p.f) / (q.f - p.f);
  auto along = [s](float from, float to) {
    return std::clamp(from + s * (to - from), std::min(from, to), std::max(from, to));
  };
  return {along(p.x, q.x), along(p.y, q.y), along(p.z, q.z)};
}

// The isopolygon of a tet for an isovalue; vertex_count 0 when the tet holds none.
inline Isopolygon extract_isopolygon(const Vertex* v[4], float iso) {
  const IsoCase& entry = iso_cases()[iso_case(v, iso)];
  Isopolygon poly;
  poly.vertex_count = entry.vertex_count;
  for (int k = 0; k < entry.vertex_count; ++k)
    poly.p[k] = edge_crossing(*v[entry.edges[k][0]], *v[entry.edges[k][1]], iso);
  return poly;
}

}  // namespace tetray::render
