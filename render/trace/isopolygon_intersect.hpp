// Packet-isopolygon intersection (Wald et al. 2007, §4.2-4.3). Each isopolygon edge, seen from the
// eye, spans a plane through the eye; a ray is inside the polygon's projection when it lies on
// the inner side of every such plane, a 2D half-space test per edge in the image plane.
//
// Watertightness: the edge plane's normal is computed from the edge's two points in a fixed
// order (by position) as (A - e) x (B - A), then negated if the polygon walks the edge from B to
// A. A neighbouring tet computes the same two points bitwise (edge_crossings orders them by
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
// Packets: a polygon whose corners all lie outside one plane of the packet's frustum is skipped
// (four plane tests, no division: a third of the polygons of tets that meet the frustum lie
// beside it), and of the others only the packet rows the polygon's projection covers are tested
// (restrict_to_projection), usually one to three rows of a 16x16 packet, and in packets wider
// than a lane batch only the batches of each row its columns reach. (A test of the packet's corner
// rays against the edge planes, to skip the rows too, cost more than the rows it saved once the
// rows were cut this tight.)
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "render/trace/clip_region.hpp"
#include "render/trace/isopolygon.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

struct PolygonHit {
  std::uint32_t key;  // tie key: the tet's id
  std::int32_t tet;   // index into volume.tets
  std::int32_t iso;   // isovalue index
};

// A hit filter (clip_region.hpp) may discard hits by their point; the default keeps all and
// compiles to nothing.
template <int S, bool kStats, typename HitFilter = NoHitFilter>
class IsopolygonIntersector {
 public:
  using Packet = RayPacket<S>;
  using F = typename Packet::Lanes::F;
  static constexpr int W = Packet::kLaneWidth;

  IsopolygonIntersector(Packet& packet, TraceStats& stats, HitFilter filter = {})
      : packet_(packet), stats_(stats), filter_(filter) {}

  // Intersects rays [first_active, kRays) with the polygon; returns whether any ray got a new
  // nearest hit.
  bool intersect(const Isopolygon& poly, const PolygonHit& id, int first_active) {
    if (poly.vertex_count < 3) return false;
    Setup s;
    const float eye[3] = {packet_.eye.x, packet_.eye.y, packet_.eye.z};
    simd::Float4 rel[3];
    for (int c = 0; c < 3; ++c) {
      rel[c] = poly.xyz[c] - simd::Float4(eye[c]);
      rel[c].store_aligned(s.rel[c]);
    }
    int begin = first_active, end = Packet::kRays, first_column = 0, last_column = S - 1;
    if constexpr (S > 1) {
      if (packet_.frustum.misses_hull(rel)) return culled();
      restrict_to_projection(rel, begin, end, first_column, last_column);
    }
    alignas(16) float corner[3][4];
    for (int c = 0; c < 3; ++c) poly.xyz[c].store_aligned(corner[c]);
    auto p = [&](int k) { return Vec3f{corner[0][k], corner[1][k], corner[2][k]}; };
    // For a triangle (p[3] == p[0]) this is bitwise cross(p[1] - p[0], p[2] - p[0]).
    s.normal = cross(p(2) - p(0), p(3) - p(1));
    // A polygon of zero area (all its vertices on one tet vertex or edge, where the isovalue
    // equals vertex values) holds no surface; its neighbours hold it. Its edge values would all
    // be zero, and "inside" for every ray.
    if (s.normal.x == 0 && s.normal.y == 0 && s.normal.z == 0) begin = end;
    if (begin >= end || first_column > last_column) return culled();
    edge_normals(poly, s);
    return intersect_rays(s, id, begin, end, first_column, last_column);
  }

 private:
  bool culled() {
    if constexpr (kStats) ++stats_.frustum_culled_isopolygons;
    return false;
  }

  // Per corner k (and the edge from it to corner k + 1), component c at [c][k].
  struct Setup {
    alignas(16) float rel[3][4];   // corners relative to the eye
    alignas(16) float edge[3][4];  // edge plane normals (zero for a triangle's repeated corner)
    Vec3f normal;                  // polygon plane normal
    float plane = 0;               // dot(normal, rel[.][0])

    Vec3f corner(int k) const { return {rel[0][k], rel[1][k], rel[2][k]}; }
    Vec3f edge_normal(int k) const { return {edge[0][k], edge[1][k], edge[2][k]}; }
  };

  // Tests the lane batches of rays [begin, end) that hold a column of [first_column,
  // last_column] (every batch where a batch spans whole rows).
  bool intersect_rays(Setup& s, const PolygonHit& id, int begin, int end, int first_column,
                      int last_column) {
    s.plane = dot(s.normal, s.corner(0));
    bool any_hit = false;
    if constexpr (S > W) {
      const int first_batch = first_column / W * W;
      for (int row = begin / S * S; row < end; row += S)
        for (int base = std::max(row + first_batch, begin / W * W); base <= row + last_column;
             base += W)
          any_hit |= intersect_lanes(s, id, base);
    } else {
      for (int base = begin / W * W; base < end; base += W) any_hit |= intersect_lanes(s, id, base);
    }
    return any_hit;
  }

  // Normals of the planes through the eye and each edge k -> k + 1 (see the file comment), the
  // four edges in the lanes of one register: the ends ordered by position, n = (a - e) x (b - a),
  // negated where the polygon walks the edge from b to a.
  void edge_normals(const Isopolygon& poly, Setup& s) const {
    using simd::Float4;
    const Float4* p = poly.xyz;
    const Float4 q[3] = {simd::next_lane(p[0]), simd::next_lane(p[1]), simd::next_lane(p[2])};
    const simd::Mask4 forward = simd::lexicographic_less<3>(p, q);
    const float eye[3] = {packet_.eye.x, packet_.eye.y, packet_.eye.z};
    Float4 u[3], v[3];
    for (int c = 0; c < 3; ++c) {
      const Float4 a = xsimd::select(forward, p[c], q[c]), b = xsimd::select(forward, q[c], p[c]);
      u[c] = a - Float4(eye[c]);
      v[c] = b - a;
    }
    const Float4 n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                         u[0] * v[1] - u[1] * v[0]};
    for (int c = 0; c < 3; ++c) xsimd::select(forward, n[c], -n[c]).store_aligned(s.edge[c]);
  }

  // Narrows [begin, end) to the packet rows the polygon's projection covers, and for packets
  // wider than a lane batch [first_column, last_column] to its columns (a convex polygon in
  // front of the eye projects inside its vertices' ranges); polygons reaching behind the eye
  // keep every row and column.
  void restrict_to_projection(const simd::Float4 (&rel)[3], int& begin, int& end, int& first_column,
                              int& last_column) const {
    using simd::Float4;
    const Vec3f f = packet_.forward, u = packet_.up, r = packet_.right;
    const Float4 depth = rel[0] * f.x + rel[1] * f.y + rel[2] * f.z;
    if (!xsimd::all(depth > Float4(0.0f))) return;
    const Float4 height = rel[0] * u.x + rel[1] * u.y + rel[2] * u.z;
    int first_row = 0, last_row = S - 1;
    covered_range(Float4(packet_.row_center) - Float4(packet_.row_scale) * height / depth,
                  first_row, last_row);
    begin = std::max(begin, first_row * S);
    end = std::min(end, (last_row + 1) * S);
    if constexpr (S > W) {
      const Float4 across = rel[0] * r.x + rel[1] * r.y + rel[2] * r.z;
      covered_range(Float4(packet_.column_center) + Float4(packet_.column_scale) * across / depth,
                    first_column, last_column);
    }
  }

  // The packet rows (or columns) [first, last] whose centers lie within the range of four
  // projected positions. The margin, 1/16 row plus 1e-5 of the position, is far above the
  // rounding of the projection (about 1e-3 row at 1024 rows) and of the rays' own directions,
  // so a ray through the polygon's extreme vertex is never cut off.
  static void covered_range(simd::Float4 positions, int& first, int& last) {
    alignas(16) float p[4];
    positions.store_aligned(p);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float v : p) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    constexpr float kMargin = 1.0f / 16, kRelativeMargin = 1e-5f;
    lo -= kMargin + kRelativeMargin * std::abs(lo);
    hi += kMargin + kRelativeMargin * std::abs(hi);
    // Clamped before the conversion: a polygon far off the packet projects to huge positions.
    first = static_cast<int>(std::clamp(std::ceil(lo), 0.0f, float(S)));
    last = static_cast<int>(std::clamp(std::floor(hi), -1.0f, float(S - 1)));
  }

  bool intersect_lanes(const Setup& s, const PolygonHit& id, int base) {
    if constexpr (kStats) stats_.ray_isopolygon_tests += W;
    const F dx = simd::load(packet_.dx + base, F{}), dy = simd::load(packet_.dy + base, F{}),
            dz = simd::load(packet_.dz + base, F{});
    F lo = edge_value(s.edge_normal(0), dx, dy, dz), hi = lo;
    for (int k = 1; k < 4; ++k) {
      const F v = edge_value(s.edge_normal(k), dx, dy, dz);
      lo = simd::vmin(lo, v);
      hi = simd::vmax(hi, v);
    }
    const auto inside = simd::either(lo >= F(0.0f), hi <= F(0.0f));
    if (!simd::any(inside)) return false;
    const F t = distance(s, dx, dy, dz);
    const F tmax = simd::load(packet_.tmax + base, F{});
    auto ahead = simd::both(inside, t > F(0.0f));
    if constexpr (!HitFilter::kKeepsAll)
      ahead = simd::both(ahead, filter_.keeps(packet_.eye, t, dx, dy, dz, base, id.key));
    // Nearer than the hit so far, or exactly as near (a shared edge or vertex, or a surface seen
    // twice) with a smaller tie key.
    const auto tie_won =
        simd::both(simd::both(ahead, t == tmax), simd::greater(packet_.key + base, id.key, F{}));
    const auto wins = simd::either(simd::both(ahead, t < tmax), tie_won);
    if (!simd::any(wins)) return false;
    const auto first_hit = simd::both(wins, tmax == F(std::numeric_limits<float>::infinity()));
    packet_.rays_without_hit -= std::popcount(simd::bits(first_hit));
    simd::store_where(wins, t, packet_.tmax + base);
    simd::store_where(wins, id.key, packet_.key + base);
    simd::store_where(wins, id.tet, packet_.tet + base);
    simd::store_where(wins, id.iso, packet_.iso + base);
    simd::store_where(wins, F(s.normal.x), packet_.nx + base);
    simd::store_where(wins, F(s.normal.y), packet_.ny + base);
    simd::store_where(wins, F(s.normal.z), packet_.nz + base);
    return true;
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
    F near = edge_value(s.corner(0), dx, dy, dz), far = near;
    for (int k = 1; k < 4; ++k) {
      const F v = edge_value(s.corner(k), dx, dy, dz);
      near = simd::vmin(near, v);
      far = simd::vmax(far, v);
    }
    const F clamped = simd::select(t >= near, simd::select(t <= far, t, far), near);
    return simd::select(den != F(0.0f), clamped, F(-1.0f));
  }

  Packet& packet_;
  TraceStats& stats_;
  [[no_unique_address]] HitFilter filter_;
};

}  // namespace tetray::render
