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

#include "render/scene/clip_region.hpp"
#include "render/trace/isopolygon.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

struct PolygonHit {
  std::uint32_t key;  // tie key: the tet's id
  std::int32_t tet;   // index into volume.tets
  std::int32_t iso;   // isovalue index
};

// What a polygon's ray tests need that depends only on the polygon and the eye, so a polygon
// seen by several packets is set up once; its corners are not among it (the tiles copy each
// polygon into the bins of the packets it covers, and the corners were a third of the copy).
// Per edge k (from corner k to corner k + 1), component c at [c][k].
struct PolygonSetup {
  alignas(16) float edge[3][4];  // edge plane normals (zero for a triangle's repeated corner)
  Vec3f normal;                  // polygon plane normal
  float plane = 0;               // dot(normal, corner 0 relative to the eye)
  float near_floor = 0;          // no distance to the polygon is computed below it (near_floor)
  // An ill-conditioned distance is clamped between these: bounds of the distances from the eye
  // of the polygon's points (closest_floor, far_ceiling).
  float closest = 0, far_ceiling = 0;

  Vec3f edge_normal(int k) const { return {edge[0][k], edge[1][k], edge[2][k]}; }
};

// The corners relative to the eye (the first part of a set-up).
inline void relative_corners(const Isopolygon& poly, Vec3f eye, simd::Float4 (&rel)[3]) {
  const float e[3] = {eye.x, eye.y, eye.z};
  for (int c = 0; c < 3; ++c) rel[c] = poly.xyz[c] - simd::Float4(e[c]);
}

// The view depths of four points relative to the eye (zero with the projection of shadow rays,
// which have no view axis).
inline simd::Float4 view_depths(const simd::Float4 (&rel)[3], const RowProjection& p) {
  return rel[0] * p.forward.x + rel[1] * p.forward.y + rel[2] * p.forward.z;
}

// The floor under every distance computed to a polygon (distance()) from the smallest view depth
// of its corners: a ray's distance to a point is at least the point's depth, and depth is linear
// over the polygon, so a well-conditioned distance never lies below it; the floor sits below it
// by far more than the rounding of either (2^-16 of it plus the frame's depth_slack). Where a ray
// grazes the polygon's plane, the division behind the distance is ill-conditioned; the floor then
// keeps the result at the polygon's depth, as it keeps every result, which is what lets a
// polygon be culled by its depth alone (intersect_rays). For one polygon (float) or lanewise.
template <typename F>
inline F near_floor(F nearest_depth, float depth_slack) {
  return nearest_depth - (xsimd::abs(nearest_depth) * 0x1p-16f + F(depth_slack));
}

// The ceiling over every distance computed to a polygon (distance()) from the largest distance
// of its corners to the eye: the hit of a ray through the polygon is a convex combination of its
// corners, so its distance along a unit direction is at most the corners' largest; the ceiling
// lies above it by far more than the rounding of either (2^-16 of it plus the frame's
// depth_slack). For one polygon (float) or lanewise.
template <typename F>
inline F far_ceiling(F farthest, float depth_slack) {
  return farthest + (farthest * 0x1p-16f + F(depth_slack));
}

// The floor under an ill-conditioned distance to the polygon (distance()). For a point h of a
// polygon, a convex combination of corners c_k with weights w_k, |h|^2 = sum w_k |c_k|^2 -
// 1/2 sum_jk w_j w_k |c_j - c_k|^2 >= m^2 - 3/8 D^2, with m the nearest corner's distance and D
// the diameter (the farthest two corners apart; sum_{j != k} w_j w_k <= 3/4 for four weights).
// For a polygon wholly in front of the eye (its distance floor, near_floor, positive) the floor
// is the root of that, less 2^-18 of the farthest corner's squared distance inside the root and
// 2^-16 of its distance and the frame's depth_slack outside (far above the rounding of the
// terms): a few ulps below the polygon's true nearest distance for a polygon small beside its
// distance (second order in D / m), which keeps the tiles' box culling exact
// (tile_occlusion.hpp), and never above it. A polygon reaching behind the eye, whose rays'
// distances may be negative, or one for rays without a view axis (shadow rays: the floor is
// negative), keeps the distance floor. From squared distances; for one polygon (float) or
// lanewise.
template <typename F>
inline F closest_floor(F nearest_squared, F diameter_squared, F farthest, F near_floor,
                       float depth_slack) {
  const F squared = nearest_squared - F(0.375f) * diameter_squared - farthest * farthest * 0x1p-18f;
  const F closest =
      simd::sqrt(simd::vmax(squared, F(0.0f))) - (farthest * 0x1p-16f + F(depth_slack));
  return simd::select(near_floor > F(0.0f), simd::vmax(closest, near_floor), near_floor);
}

// Normals of the planes through the eye and the edges p -> q, lanewise (see the file comment):
// the ends ordered by position, n = (a - e) x (b - a), negated where the edge runs from b to a.
template <typename Batch>
inline void edge_plane_normals(const Batch (&p)[3], const Batch (&q)[3], Vec3f eye, Batch (&n)[3]) {
  const auto forward = simd::lexicographic_less<3>(p, q);
  const float e[3] = {eye.x, eye.y, eye.z};
  Batch u[3], v[3];
  for (int c = 0; c < 3; ++c) {
    const Batch a = xsimd::select(forward, p[c], q[c]), b = xsimd::select(forward, q[c], p[c]);
    u[c] = a - Batch(e[c]);
    v[c] = b - a;
  }
  const Batch m[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                      u[0] * v[1] - u[1] * v[0]};
  for (int c = 0; c < 3; ++c) n[c] = xsimd::select(forward, m[c], -m[c]);
}

// The four edges k -> k + 1 of a polygon in the lanes of one register.
inline void edge_normals(const Isopolygon& poly, Vec3f eye, PolygonSetup& s) {
  using simd::Float4;
  const Float4(&p)[3] = poly.xyz;
  const Float4 q[3] = {simd::next_lane(p[0]), simd::next_lane(p[1]), simd::next_lane(p[2])};
  Float4 n[3];
  edge_plane_normals(p, q, eye, n);
  for (int c = 0; c < 3; ++c) n[c].store_aligned(s.edge[c]);
}

// The plane of the polygon and its edges' planes; false for a polygon of zero area (all its
// vertices on one tet vertex or edge, where the isovalue equals vertex values): it holds no
// surface, its neighbours hold it, and its edge values would all be zero, "inside" for every ray.
inline bool polygon_planes(const Isopolygon& poly, Vec3f eye, PolygonSetup& s) {
  alignas(16) float corner[3][4];
  for (int c = 0; c < 3; ++c) poly.xyz[c].store_aligned(corner[c]);
  auto p = [&](int k) { return Vec3f{corner[0][k], corner[1][k], corner[2][k]}; };
  // For a triangle (p[3] == p[0]) this is bitwise cross(p[1] - p[0], p[2] - p[0]).
  s.normal = cross(p(2) - p(0), p(3) - p(1));
  if (s.normal.x == 0 && s.normal.y == 0 && s.normal.z == 0) return false;
  edge_normals(poly, eye, s);
  s.plane = dot(s.normal, p(0) - eye);  // bitwise the lanes' corner 0 less the eye
  return true;
}

// The pixel rows (or columns) [first, last], clamped to [0, limit] (first limit + 1 or last -1
// where none), whose centers lie in [lo, hi] widened by a margin: 1/16 pixel plus 1e-5 of the
// position, far above the rounding of the projection (about 1e-3 row at 1024 rows) and of the
// rays' own directions, so a ray through the polygon's extreme vertex is never cut off. For one
// range (float) or lanewise (simd::Floats, tile_polygons.cpp).
template <typename F>
inline void covered_pixels(F lo, F hi, int limit, F& first, F& last) {
  const F margin(1.0f / 16), relative(1e-5f), none_before(-1.0f), end(float(limit + 1));
  const F ceiling = simd::ceil(lo - (margin + relative * xsimd::abs(lo)));
  const F floor = simd::floor(hi + (margin + relative * xsimd::abs(hi)));
  // Clamped before any conversion: a polygon far off the packet projects to huge positions.
  first = simd::select(ceiling < F(0.0f), F(0.0f), simd::select(ceiling > end, end, ceiling));
  last = simd::select(floor < none_before, none_before,
                      simd::select(floor > end - 1.0f, end - 1.0f, floor));
}

// The rows (or columns) within [0, limit] whose centers lie within the range of four projected
// positions.
inline void covered_range(simd::Float4 positions, int limit, int& first, int& last) {
  alignas(16) float p[4];
  positions.store_aligned(p);
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (float v : p) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  float first_center = 0, last_center = 0;
  covered_pixels(lo, hi, limit, first_center, last_center);
  first = static_cast<int>(first_center);
  last = static_cast<int>(last_center);
}

// The rows and columns, within [0, last_row] and [0, last_column], that the polygon's projection
// covers (a convex polygon in front of the eye projects inside its vertices' ranges), given its
// corners relative to the eye and their view depths; a polygon reaching behind the eye covers
// them all. Columns are left whole unless `columns`.
struct CoveredPixels {
  int first_row, last_row, first_column, last_column;
};

inline CoveredPixels project_rows(const simd::Float4 (&rel)[3], simd::Float4 depth,
                                  const RowProjection& p, int last_row, int last_column,
                                  bool columns) {
  using simd::Float4;
  CoveredPixels covered{0, last_row, 0, last_column};
  if (!xsimd::all(depth > Float4(0.0f))) return covered;
  const Vec3f u = p.up, r = p.right;
  const Float4 height = rel[0] * u.x + rel[1] * u.y + rel[2] * u.z;
  covered_range(Float4(p.row_center) - Float4(p.row_scale) * height / depth, last_row,
                covered.first_row, covered.last_row);
  if (columns) {
    const Float4 across = rel[0] * r.x + rel[1] * r.y + rel[2] * r.z;
    covered_range(Float4(p.column_center) + Float4(p.column_scale) * across / depth, last_column,
                  covered.first_column, covered.last_column);
  }
  return covered;
}

// The bounds of an ill-conditioned distance (closest_floor, far_ceiling) of a polygon from its
// corners relative to the eye (lane k: corner k).
inline void distance_bounds(const simd::Float4 (&rel)[3], float depth_slack, PolygonSetup& s) {
  using V = Vec3<simd::Float4>;
  const V corner{rel[0], rel[1], rel[2]};
  const V next{simd::next_lane(rel[0]), simd::next_lane(rel[1]), simd::next_lane(rel[2])};
  const V after_next{simd::next_lane(next.x), simd::next_lane(next.y), simd::next_lane(next.z)};
  // Corner k to k + 1, then k to k + 2 (its lanes 2 and 3 repeat 0 and 1).
  const V to_next = next - corner, across = after_next - corner;
  const float diameter_squared =
      std::max(simd::max_of(dot(to_next, to_next)), simd::max_of(dot(across, across)));
  const simd::Float4 squared = dot(corner, corner);
  const float farthest = simd::sqrt(simd::max_of(squared));
  s.closest =
      closest_floor(simd::min_of(squared), diameter_squared, farthest, s.near_floor, depth_slack);
  s.far_ceiling = far_ceiling(farthest, depth_slack);
}

// Sets up one polygon for rays from `eye`: its corners relative to the eye, distance floor,
// planes, and the pixels within [0, last_row] x [0, last_column] of `projection` its projection
// covers (columns left whole unless `columns`). False when none of those rays can hit it: its
// hull lies outside `frustum` (none: single rays), it covers no pixel center, or it has no area.
inline bool set_up_polygon(const Isopolygon& poly, Vec3f eye, const PacketFrustum* frustum,
                           const RowProjection& projection, int last_row, int last_column,
                           bool columns, PolygonSetup& s, CoveredPixels& covered) {
  simd::Float4 rel[3];
  relative_corners(poly, eye, rel);
  const simd::Float4 depth = view_depths(rel, projection);
  s.near_floor = near_floor(simd::min_of(depth), projection.depth_slack);
  covered = {0, last_row, 0, last_column};
  if (frustum) {
    if (frustum->misses_hull(rel)) return false;
    covered = project_rows(rel, depth, projection, last_row, last_column, columns);
  }
  if (covered.first_row > covered.last_row || covered.first_column > covered.last_column ||
      !polygon_planes(poly, eye, s))
    return false;
  distance_bounds(rel, projection.depth_slack, s);
  return true;
}

// A hit filter (render/scene/clip_region.hpp) may discard hits by their point; the default keeps
// all and compiles to nothing.
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
    PolygonSetup s;
    CoveredPixels covered;
    if (!set_up_polygon(poly, packet_.eye, S > 1 ? &packet_.frustum : nullptr, packet_.projection,
                        S - 1, S - 1, S > Packet::kBlockColumns, s, covered))
      return culled();
    if (Packet::index(covered.last_row, covered.last_column) < first_active) return culled();
    return intersect_rays(s, id, first_active, covered);
  }

  // Tests the lane batches (blocks of pixels) that hold a pixel of `covered` and a ray at or after
  // first_active against a polygon set up for the packet's eye. A batch whose every ray has a hit
  // nearer than the polygon's distance floor is skipped (occlusion culling per batch, exact: no
  // distance computed to the polygon can win).
  bool intersect_rays(const PolygonSetup& s, const PolygonHit& id, int first_active,
                      const CoveredPixels& covered) {
    constexpr int rows = Packet::kBlockRows, columns = Packet::kBlockColumns;
    bool any_hit = false;
    for (int row = covered.first_row / rows * rows; row <= covered.last_row; row += rows)
      for (int column = covered.first_column / columns * columns; column <= covered.last_column;
           column += columns) {
        const int base = Packet::index(row, column);
        if (base + W <= first_active || s.near_floor > packet_.batch_far[base / W]) continue;
        any_hit |= intersect_lanes(s, id, base);
      }
    return any_hit;
  }

  // For a caller that keeps more than the nearest hit (nearest_layers.hpp): calls
  // visit(base, ahead, t) for each lane batch that holds a pixel of `covered`, with the lanes
  // whose rays meet the polygon ahead of the eye (and pass the filter) and their distances, by
  // the tests and the distance intersect_rays uses.
  template <typename Visit>
  void for_each_hit_batch(const PolygonSetup& s, const PolygonHit& id, const CoveredPixels& covered,
                          Visit&& visit) {
    constexpr int rows = Packet::kBlockRows, columns = Packet::kBlockColumns;
    for (int row = covered.first_row / rows * rows; row <= covered.last_row; row += rows)
      for (int column = covered.first_column / columns * columns; column <= covered.last_column;
           column += columns) {
        const int base = Packet::index(row, column);
        const auto [ahead, t] = lane_hits(s, id, base);
        if (simd::any(ahead)) visit(base, ahead, t);
      }
  }

 private:
  // The rays of a lane batch that meet a polygon ahead of the eye (and pass the filter), and
  // their distances to it.
  struct LaneHits {
    typename Packet::Lanes::M ahead;
    F t;
  };

  bool culled() {
    if constexpr (kStats) ++stats_.frustum_culled_isopolygons;
    return false;
  }

  LaneHits lane_hits(const PolygonSetup& s, const PolygonHit& id, int base) {
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
    const F t = distance(s, dx, dy, dz);
    auto ahead = simd::both(inside, t > F(0.0f));
    if constexpr (!HitFilter::kKeepsAll)
      ahead = simd::both(ahead, filter_.keeps(packet_.eye, t, dx, dy, dz, base, id.key));
    return {ahead, t};
  }

  // Without a branch on whether any ray is inside the polygon or wins: both are data the branch
  // predictor cannot guess for small polygons, and the masked stores of a lane batch that wins
  // nothing write nothing. The tiled frame without them (AVX-512, alternating runs, best of 5): 1M
  // tets 6.44 -> 5.65 ms, 4M 11.57 -> 10.45 ms, 14M 19.26 -> 17.97 ms, the same images.
  bool intersect_lanes(const PolygonSetup& s, const PolygonHit& id, int base) {
    const auto [ahead, t] = lane_hits(s, id, base);
    const F tmax = simd::load(packet_.tmax + base, F{});
    // Nearer than the hit so far, or exactly as near (a shared edge or vertex, or a surface seen
    // twice) with a smaller tie key.
    const auto tie_won =
        simd::both(simd::both(ahead, t == tmax), simd::greater(packet_.key + base, id.key, F{}));
    const auto wins = simd::either(simd::both(ahead, t < tmax), tie_won);
    const auto first_hit = simd::both(wins, tmax == F(std::numeric_limits<float>::infinity()));
    const int first_hits = std::popcount(simd::bits(first_hit));
    packet_.rays_without_hit -= first_hits;
    simd::store_where(wins, t, packet_.tmax + base);
    simd::store_where(wins, id.key, packet_.key + base);
    simd::store_where(wins, id.tet, packet_.tet + base);
    simd::store_where(wins, id.iso, packet_.iso + base);
    simd::store_where(wins, F(s.normal.x), packet_.nx + base);
    simd::store_where(wins, F(s.normal.y), packet_.ny + base);
    simd::store_where(wins, F(s.normal.z), packet_.nz + base);
    if ((packet_.batch_missing[base / W] -= first_hits) == 0)
      packet_.batch_far[base / W] = simd::max_of(simd::load(packet_.tmax + base, F{}));
    return simd::any(wins);
  }

  static F edge_value(Vec3f n, F dx, F dy, F dz) { return n.x * dx + n.y * dy + n.z * dz; }

  // Distance to the polygon's plane. When the ray runs almost inside the plane, the division is
  // ill-conditioned; the hit then lies between the polygon's bounds of its points' distances
  // (closest_floor, far_ceiling: the floor within a few ulps of its nearest point's distance
  // for a small polygon, the ceiling its farthest corner's), and is clamped there. (The bounds are
  // set up once per polygon: clamping to the corners' distances along each ray took four more dot
  // products per ray tested, and the tiled frame at 4M tets was about 3% slower.) A ray exactly
  // parallel to the plane (the eye in it) sees the polygon edge-on, with no area: every edge value
  // is zero there, so it is rejected here with a negative distance.
  F distance(const PolygonSetup& s, F dx, F dy, F dz) const {
    const F den = edge_value(s.normal, dx, dy, dz);
    const F t = F(s.plane) / den;
    const F near(s.closest), far(s.far_ceiling);
    const F clamped = simd::select(t >= near, simd::select(t <= far, t, far), near);
    return simd::select(den != F(0.0f), clamped, F(-1.0f));
  }

  Packet& packet_;
  TraceStats& stats_;
  [[no_unique_address]] HitFilter filter_;
};

}  // namespace tetray::render
