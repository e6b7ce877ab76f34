// Packet-isopolygon intersection (seed 000 §4.2-4.3). Each isopolygon edge, seen from the
// eye, spans a plane through the eye; a ray is inside the polygon's projection when it lies on
// the inner side of every such plane, a 2D half-space test per edge in the image plane.
//
// Watertightness: the edge plane's normal is computed from the edge's two points in a fixed
// order (by position) as (A - e) x (B - A), then negated if the polygon walks the edge from B to
// A. A neighbouring tet computes the same two points bitwise (edge_crossing orders them by
// position too), hence the same canonical normal, and negation is exact; so is the sign of its
// dot with the ray (no fused multiply-add: render/ is built with -ffp-contract=off). A ray
// therefore falls on one side of a shared edge or exactly on it, never into a gap. The test
// accepts a ray when all its edge values have one sign, which needs no knowledge of the
// polygon's orientation; zero counts for both sides.
//
// Precision: (A - e) x (B - A) equals (A - e) x (B - e) but never subtracts two long, nearly
// parallel vectors, so tiny polygons far from the eye keep a relative accuracy of a few ulps
// (the eye-relative form lost all of it and reported hits pixels away).
//
// Packets: only the packet rows the polygon's projection covers are tested (restrict_to_rows),
// usually one to three rows of a 16x16 packet. (A test of the packet's corner rays against the
// edge planes, to skip the rows too, cost more than the rows it saved once the rows were cut
// this tight.)
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "render/isopolygon.hpp"
#include "render/ray_packet.hpp"
#include "render/trace.hpp"

namespace tetray::render {

struct PolygonHit {
  std::uint32_t key;  // tie key: the tet's id
  std::int32_t tet;   // index into volume.tets
  std::int32_t iso;   // isovalue index
};

template <int S, bool kStats>
class IsopolygonIntersector {
 public:
  using Packet = RayPacket<S>;
  using F = typename Packet::Lanes::F;
  static constexpr int W = Packet::kLaneWidth;

  IsopolygonIntersector(Packet& packet, TraceStats& stats) : packet_(packet), stats_(stats) {}

  // Intersects rays [first_active, kRays) with the polygon; returns whether any ray got a new
  // nearest hit.
  bool intersect(const Isopolygon& poly, const PolygonHit& id, int first_active) {
    if (poly.vertex_count < 3) return false;
    Setup s;
    s.n = poly.vertex_count;
    for (int k = 0; k < s.n; ++k) s.rel[k] = poly.p[k] - packet_.eye;
    int begin = first_active, end = Packet::kRays;
    if constexpr (S > 1) restrict_to_rows(s, begin, end);
    const Vec3f* p = poly.p;
    s.normal = s.n == 3 ? cross(p[1] - p[0], p[2] - p[0]) : cross(p[2] - p[0], p[3] - p[1]);
    // A polygon of zero area (all its vertices on one tet vertex or edge, where the isovalue
    // equals vertex values) holds no surface; its neighbours hold it. Its edge values would all
    // be zero, and "inside" for every ray.
    if (s.normal.x == 0 && s.normal.y == 0 && s.normal.z == 0) begin = end;
    if (begin < end) {
      for (int k = 0; k < s.n; ++k)
        s.edge[k] = edge_normal(poly.p[k], poly.p[k + 1 < s.n ? k + 1 : 0]);
      return intersect_rays(s, id, begin, end);
    }
    if constexpr (kStats) ++stats_.frustum_culled_isopolygons;
    return false;
  }

 private:
  struct Setup {
    int n = 0;
    Vec3f rel[4];     // vertices relative to the eye
    Vec3f edge[4];    // edge plane normals
    Vec3f normal;     // polygon plane normal
    float plane = 0;  // dot(normal, rel[0])
  };

  bool intersect_rays(Setup& s, const PolygonHit& id, int begin, int end) {
    s.plane = dot(s.normal, s.rel[0]);
    bool any_hit = false;
    for (int base = begin / W * W; base < end; base += W) any_hit |= intersect_lanes(s, id, base);
    return any_hit;
  }

  static bool position_first(Vec3f a, Vec3f b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
  }

  // Normal of the plane through the eye and the edge p -> q (see the file comment).
  Vec3f edge_normal(Vec3f p, Vec3f q) const {
    const bool forward = position_first(p, q);
    const Vec3f a = forward ? p : q, b = forward ? q : p;
    const Vec3f n = cross(a - packet_.eye, b - a);
    return forward ? n : -n;
  }

  // Narrows [begin, end) to the packet rows the polygon's projection covers (a convex
  // polygon in front of the eye projects inside its vertices' row range); polygons reaching
  // behind the eye keep every row. The margin, 1/16 row plus 1e-5 of the row value, is far
  // above the rounding of the projection (about 1e-3 row at 1024 rows) and of the rays' own
  // directions, so a ray on the polygon's top or bottom vertex is never cut off.
  void restrict_to_rows(const Setup& s, int& begin, int& end) const {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int k = 0; k < s.n; ++k) {
      const float depth = dot(s.rel[k], packet_.forward);
      if (!(depth > 0)) return;
      const float row = packet_.row_center - packet_.row_scale * dot(s.rel[k], packet_.up) / depth;
      lo = std::min(lo, row);
      hi = std::max(hi, row);
    }
    constexpr float kRowMargin = 1.0f / 16, kRelativeMargin = 1e-5f;
    lo -= kRowMargin + kRelativeMargin * std::abs(lo);
    hi += kRowMargin + kRelativeMargin * std::abs(hi);
    // Clamped before the conversion: a polygon far off the packet projects to huge rows.
    const int first_row = static_cast<int>(std::clamp(std::ceil(lo), 0.0f, float(S)));
    const int last_row = static_cast<int>(std::clamp(std::floor(hi), -1.0f, float(S - 1)));
    begin = std::max(begin, first_row * S);
    end = std::min(end, (last_row + 1) * S);
  }

  bool intersect_lanes(const Setup& s, const PolygonHit& id, int base) {
    if constexpr (kStats) stats_.ray_isopolygon_tests += W;
    const F dx = simd::load(packet_.dx + base, F{}), dy = simd::load(packet_.dy + base, F{}),
            dz = simd::load(packet_.dz + base, F{});
    F lo = edge_value(s.edge[0], dx, dy, dz), hi = lo;
    for (int k = 1; k < s.n; ++k) {
      const F v = edge_value(s.edge[k], dx, dy, dz);
      lo = simd::vmin(lo, v);
      hi = simd::vmax(hi, v);
    }
    const auto inside = simd::either(lo >= F(0.0f), hi <= F(0.0f));
    if (!simd::any(inside)) return false;
    const F t = distance(s, dx, dy, dz);
    const F tmax = simd::load(packet_.tmax + base, F{});
    const auto closer = simd::both(inside, simd::both(t > F(0.0f), t <= tmax));
    std::uint64_t lanes = simd::bits(closer);
    if (!lanes) return false;
    alignas(64) float ts[W];
    simd::store(ts, t);
    bool updated = false;
    for (; lanes; lanes &= lanes - 1) {
      const int r = base + std::countr_zero(lanes);
      const float tr = ts[r - base];
      if (tr == packet_.tmax[r] && packet_.key[r] <= id.key) continue;  // tie rule
      packet_.tmax[r] = tr;
      packet_.key[r] = id.key;
      packet_.tet[r] = id.tet;
      packet_.iso[r] = id.iso;
      packet_.nx[r] = s.normal.x;
      packet_.ny[r] = s.normal.y;
      packet_.nz[r] = s.normal.z;
      updated = true;
    }
    return updated;
  }

  static F edge_value(Vec3f n, F dx, F dy, F dz) { return n.x * dx + n.y * dy + n.z * dz; }

  // Distance to the polygon's plane. When the ray runs almost inside the plane, the division is
  // ill-conditioned; the hit then lies between the polygon's nearest and farthest vertex along
  // the ray, and is clamped there (an exact bound for a ray through the polygon). A ray exactly
  // parallel to the plane (the eye in it) sees the polygon edge-on, with no area: every edge
  // value is zero there, so it is rejected here with a negative distance.
  F distance(const Setup& s, F dx, F dy, F dz) const {
    const F den = edge_value(s.normal, dx, dy, dz);
    const F t = F(s.plane) / den;
    F near = edge_value(s.rel[0], dx, dy, dz), far = near;
    for (int k = 1; k < s.n; ++k) {
      const F v = edge_value(s.rel[k], dx, dy, dz);
      near = simd::vmin(near, v);
      far = simd::vmax(far, v);
    }
    const F clamped = simd::select(t >= near, simd::select(t <= far, t, far), near);
    return simd::select(den != F(0.0f), clamped, F(-1.0f));
  }

  Packet& packet_;
  TraceStats& stats_;
};

}  // namespace tetray::render
