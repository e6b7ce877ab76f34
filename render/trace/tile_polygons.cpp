#include "render/trace/tile_polygons.hpp"

#include <bit>
#include <cmath>
#include <stdexcept>

namespace tetray::render {
namespace {

using simd::Floats;
using simd::Ints;
using simd::Mask;
constexpr int W = simd::kWidth;

// IsoCase::ends by case, for a lookup per lane: end[e][k][case].
struct EdgeEnds {
  alignas(64) std::int32_t end[2][4][16];
};

constexpr EdgeEnds make_edge_ends() {
  EdgeEnds table{};
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 16; ++c) table.end[e][k][c] = kIsoCases[c].ends[e][k];
  return table;
}

constexpr EdgeEnds kEdgeEnds = make_edge_ends();

// One of a tet's four corners per lane (which: 0 to 3), as the masks that select it.
struct CornerChoice {
  Mask is1, is2, is3;

  explicit CornerChoice(Ints which)
      : is1(xsimd::bool_cast(which == Ints(1))),
        is2(xsimd::bool_cast(which == Ints(2))),
        is3(xsimd::bool_cast(which == Ints(3))) {}

  Floats of(const Floats (&corner)[4]) const {
    return xsimd::select(is3, corner[3],
                         xsimd::select(is2, corner[2], xsimd::select(is1, corner[1], corner[0])));
  }
};

Mask as_mask(xsimd::batch_bool<std::int32_t> m) { return xsimd::bool_cast(m); }

// The case of each lane's tet for the isovalue (isopolygon.hpp's iso_case, lanewise).
Ints iso_cases(const TetBatch& batch, float iso) {
  Ints cases(0);
  for (int k = 0; k < 4; ++k)
    cases = cases | xsimd::select(xsimd::bool_cast(batch.corner[3][k] >= Floats(iso)), Ints(1 << k),
                                  Ints(0));
  return cases;
}

// Corner k of each lane's polygon: where the isosurface crosses edge k of the case's table
// (extract_isopolygon, lanewise). xyz[c][k].
void polygon_corners(const TetBatch& batch, Ints cases, float iso, Floats (&xyz)[3][4]) {
  for (int k = 0; k < 4; ++k) {
    const CornerChoice from(simd::lookup16(kEdgeEnds.end[0][k], cases));
    const CornerChoice to(simd::lookup16(kEdgeEnds.end[1][k], cases));
    Floats a[4], b[4], crossing[3];
    for (int c = 0; c < 4; ++c) {
      a[c] = from.of(batch.corner[c]);
      b[c] = to.of(batch.corner[c]);
    }
    edge_crossings(a, b, iso, crossing);
    for (int c = 0; c < 3; ++c) xyz[c][k] = crossing[c];
  }
}

// The pixels whose centers the positions of the four corners cover (covered_range, lanewise).
void covered_lanes(const Floats (&position)[4], int limit, Ints& first, Ints& last) {
  Floats lo = position[0], hi = position[0];
  for (int k = 1; k < 4; ++k) {
    lo = xsimd::select(position[k] < lo, position[k], lo);
    hi = xsimd::select(position[k] > hi, position[k], hi);
  }
  Floats first_center, last_center;
  covered_pixels(lo, hi, limit, first_center, last_center);
  first = simd::to_int(first_center);
  last = simd::to_int(last_center);
}

// The lanes whose four points (relative to the eye, q[c][k]) all lie outside one plane of the
// frustum (PacketFrustum::misses_hull, lanewise).
Mask outside_frustum(const Floats (&q)[3][4], const PacketFrustum& frustum) {
  Mask outside(false);
  for (int p = 0; p < 4; ++p) {
    Mask all(true);
    for (int k = 0; k < 4; ++k) {
      const Floats d = q[0][k] * frustum.nx[p] + q[1][k] * frustum.ny[p] + q[2][k] * frustum.nz[p];
      all = all & (d < Floats(-frustum.slack[p]));
    }
    outside = outside | all;
  }
  return outside;
}

using V = Vec3<Floats>;

V lane_corner(const Floats (&xyz)[3][4], int k) { return {xyz[0][k], xyz[1][k], xyz[2][k]}; }

V relative_corner(const Floats (&f)[TilePolygons::kFloats], int k) {
  return {f[TilePolygons::kRel + k], f[TilePolygons::kRel + 4 + k], f[TilePolygons::kRel + 8 + k]};
}

// The polygon's normal, plane and edge planes (polygon_planes, lanewise) into its fields; the
// lanes whose polygon has an area.
Mask lanewise_planes(const Floats (&xyz)[3][4], Vec3f eye, Floats (&f)[TilePolygons::kFloats]) {
  const V normal =
      cross(lane_corner(xyz, 2) - lane_corner(xyz, 0), lane_corner(xyz, 3) - lane_corner(xyz, 1));
  f[TilePolygons::kNormal] = normal.x;
  f[TilePolygons::kNormal + 1] = normal.y;
  f[TilePolygons::kNormal + 2] = normal.z;
  f[TilePolygons::kPlane] = dot(normal, relative_corner(f, 0));
  for (int k = 0; k < 4; ++k) {
    const int next = (k + 1) % 4;
    const Floats p[3] = {xyz[0][k], xyz[1][k], xyz[2][k]};
    const Floats q[3] = {xyz[0][next], xyz[1][next], xyz[2][next]};
    Floats e[3];
    edge_plane_normals(p, q, eye, e);
    for (int c = 0; c < 3; ++c) f[TilePolygons::kEdge + 4 * c + k] = e[c];
  }
  return (normal.x != Floats(0.0f)) | (normal.y != Floats(0.0f)) | (normal.z != Floats(0.0f));
}

// The bounds of an ill-conditioned distance (distance_bounds, lanewise) into the polygons'
// fields.
void lanewise_distance_bounds(float depth_slack, Floats (&f)[TilePolygons::kFloats]) {
  Floats squared[4], diameter_squared(0.0f);
  for (int k = 0; k < 4; ++k) {
    const V r = relative_corner(f, k);
    squared[k] = dot(r, r);
  }
  // The pairs in distance_bounds' order: k to k + 1, then k to k + 2.
  for (int step = 1; step <= 2; ++step)
    for (int k = 0; k < 4; ++k) {
      const V d = relative_corner(f, (k + step) % 4) - relative_corner(f, k);
      diameter_squared = simd::vmax(dot(d, d), diameter_squared);
    }
  Floats nearest = squared[0], farthest_squared = squared[0];
  for (int k = 1; k < 4; ++k) {
    nearest = simd::vmin(squared[k], nearest);
    farthest_squared = simd::vmax(squared[k], farthest_squared);
  }
  const Floats farthest = simd::sqrt(farthest_squared);
  f[TilePolygons::kClosest] =
      closest_floor(nearest, diameter_squared, farthest, f[TilePolygons::kNearFloor], depth_slack);
  f[TilePolygons::kFarCeiling] = far_ceiling(farthest, depth_slack);
}

// The tile pixels the polygon's projection covers (project_rows, lanewise) and its distance
// floor into its fields; the lanes whose polygon covers a pixel center of the tile.
Mask covered_tile_pixels(const Tile& tile, Floats (&f)[TilePolygons::kFloats],
                         Ints (&n)[TilePolygons::kInts]) {
  const RowProjection& pr = tile.projection;
  Floats row[4], column[4], nearest(0.0f);
  Mask in_front(true);
  for (int k = 0; k < 4; ++k) {
    const V r = relative_corner(f, k);
    const Floats depth = r.x * pr.forward.x + r.y * pr.forward.y + r.z * pr.forward.z;
    const Floats height = r.x * pr.up.x + r.y * pr.up.y + r.z * pr.up.z;
    const Floats across = r.x * pr.right.x + r.y * pr.right.y + r.z * pr.right.z;
    row[k] = Floats(pr.row_center) - Floats(pr.row_scale) * height / depth;
    column[k] = Floats(pr.column_center) + Floats(pr.column_scale) * across / depth;
    nearest = k == 0 ? depth : xsimd::select(depth < nearest, depth, nearest);
    in_front = in_front & (depth > Floats(0.0f));
  }
  f[TilePolygons::kNearFloor] = near_floor(nearest, pr.depth_slack);
  Ints rows[2], columns[2];
  covered_lanes(row, tile.last_row, rows[0], rows[1]);
  covered_lanes(column, tile.last_column, columns[0], columns[1]);
  const auto front = xsimd::bool_cast(in_front);
  n[TilePolygons::kFirstRow] = xsimd::select(front, rows[0], Ints(0));
  n[TilePolygons::kLastRow] = xsimd::select(front, rows[1], Ints(tile.last_row));
  n[TilePolygons::kFirstColumn] = xsimd::select(front, columns[0], Ints(0));
  n[TilePolygons::kLastColumn] = xsimd::select(front, columns[1], Ints(tile.last_column));
  return as_mask(n[TilePolygons::kFirstRow] <= n[TilePolygons::kLastRow]) &
         as_mask(n[TilePolygons::kFirstColumn] <= n[TilePolygons::kLastColumn]);
}

}  // namespace

Tile make_tile(const Camera& camera, const CameraFrame& frame, Vec3d origin, float magnitude,
               int x0, int y0, int size) {
  Tile tile;
  tile.eye = static_cast<Vec3f>(frame.eye - origin);
  tile.x0 = x0;
  tile.y0 = y0;
  tile.last_row = std::min(size, camera.height - y0) - 1;
  tile.last_column = std::min(size, camera.width - x0) - 1;
  tile.frustum = make_packet_frustum(camera, frame, x0, y0, x0 + tile.last_column,
                                     y0 + tile.last_row, magnitude);
  tile.projection = row_projection(camera, frame, x0, y0, magnitude);
  tile.center_direction = static_cast<Vec3f>(
      frame.direction_at(x0 + 0.5 * size, y0 + 0.5 * size, camera.width, camera.height));
  return tile;
}

void TilePolygons::reset(int packets_across, int packets_down, int packet_size) {
  if (!std::has_single_bit(static_cast<unsigned>(packet_size)))
    throw std::invalid_argument("TilePolygons: the packet size must be a power of two");
  across_ = packets_across;
  packet_shift_ = std::countr_zero(static_cast<unsigned>(packet_size));
  bins_.resize(std::max(bins_.size(), static_cast<std::size_t>(packets_across * packets_down)));
  empty_bins();
  added_ = 0;
}

void TilePolygons::empty_bins() {
  for (std::vector<TilePolygon>& bin : bins_) bin.clear();
}

void TilePolygons::add(const Floats (&floats)[kFloats], const Ints (&ints)[kInts], Mask valid) {
  alignas(64) float f[kFloats][W];
  alignas(64) std::int32_t n[kInts][W];
  for (int k = 0; k < kFloats; ++k) floats[k].store_aligned(f[k]);
  for (int k = 0; k < kInts; ++k) ints[k].store_aligned(n[k]);
  for (std::uint64_t lanes = simd::bits(valid); lanes; lanes &= lanes - 1) {
    const int l = std::countr_zero(lanes);
    const int first_row = n[kFirstRow][l], last_row = n[kLastRow][l];
    const int first_column = n[kFirstColumn][l], last_column = n[kLastColumn][l];
    // Written in place in its first bin, and copied from there to any other it covers.
    TilePolygon& p = bins_[bin_of(first_row, first_column)].emplace_back();
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 4; ++k) p.setup.edge[c][k] = f[kEdge + 4 * c + k][l];
    p.setup.normal = {f[kNormal][l], f[kNormal + 1][l], f[kNormal + 2][l]};
    p.setup.plane = f[kPlane][l];
    p.setup.near_floor = f[kNearFloor][l];
    p.setup.closest = f[kClosest][l];
    p.setup.far_ceiling = f[kFarCeiling][l];
    p.id = {static_cast<std::uint32_t>(n[kKey][l]), n[kTet][l], n[kIso][l]};
    p.first_row = static_cast<std::int16_t>(first_row);
    p.last_row = static_cast<std::int16_t>(last_row);
    p.first_column = static_cast<std::int16_t>(first_column);
    p.last_column = static_cast<std::int16_t>(last_column);
    // Most polygons cover a few pixels of one bin: asked of the lane's values, not of p's just
    // written fields, and without a call.
    if (spans_bins(first_row, last_row, first_column, last_column)) copy_to_other_bins(p);
    ++added_;
  }
}

void TilePolygons::add(const TilePolygon& p) {
  bins_[bin_of(p.first_row, p.first_column)].push_back(p);
  copy_to_other_bins(p);
  ++added_;
}

void TilePolygons::copy_to_other_bins(const TilePolygon& p) {
  const int first_y = p.first_row >> packet_shift_, last_y = p.last_row >> packet_shift_;
  const int first_x = p.first_column >> packet_shift_, last_x = p.last_column >> packet_shift_;
  for (int y = first_y; y <= last_y; ++y)
    for (int x = first_x; x <= last_x; ++x)
      if (y != first_y || x != first_x)
        bins_[static_cast<std::size_t>(y * across_ + x)].push_back(p);
}

TetBatch gather_tets(const TetVolume& volume, const std::uint32_t* tets, int count) {
  alignas(64) std::int32_t index[W];
  for (int k = 0; k < W; ++k) index[k] = static_cast<std::int32_t>(tets[k < count ? k : 0]);
  TetBatch batch;
  batch.index = Ints::load_aligned(index);
  batch.valid = as_mask(simd::lane_indices() < Ints(count));
  const float* vertex = &volume.vertices.data()->x;
  for (int k = 0; k < 4; ++k) {
    alignas(64) std::int32_t corner[W];
    for (int j = 0; j < W; ++j) corner[j] = volume.tets[static_cast<std::size_t>(index[j])].v[k];
    Floats column[4];
    simd::gather_rows(vertex, corner, column);
    for (int c = 0; c < 4; ++c) batch.corner[c][k] = column[c];
  }
  return batch;
}

Mask outside_tile(const TetBatch& batch, const Tile& tile) {
  const float eye[3] = {tile.eye.x, tile.eye.y, tile.eye.z};
  Floats q[3][4];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 4; ++k) q[c][k] = batch.corner[c][k] - Floats(eye[c]);
  return outside_frustum(q, tile.frustum);
}

int set_up_polygons(const TetVolume& volume, const TetBatch& batch, Mask live, float iso,
                    int iso_index, const Tile& tile, TilePolygons& out) {
  const Ints cases = iso_cases(batch, iso);
  live = live & as_mask(cases != Ints(0)) & as_mask(cases != Ints(15));
  const int extracted = std::popcount(simd::bits(live));
  if (extracted == 0) return 0;
  Floats xyz[3][4];
  polygon_corners(batch, cases, iso, xyz);
  Floats f[TilePolygons::kFloats];
  Ints n[TilePolygons::kInts];
  const float eye[3] = {tile.eye.x, tile.eye.y, tile.eye.z};
  Floats rel[3][4];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 4; ++k)
      f[TilePolygons::kRel + 4 * c + k] = rel[c][k] = xyz[c][k] - Floats(eye[c]);
  live = live & !outside_frustum(rel, tile.frustum) & lanewise_planes(xyz, tile.eye, f) &
         covered_tile_pixels(tile, f, n);
  if (!xsimd::any(live)) return extracted;
  lanewise_distance_bounds(tile.projection.depth_slack, f);
  n[TilePolygons::kKey] =
      simd::gather(reinterpret_cast<const std::int32_t*>(volume.tet_ids.data()), batch.index);
  n[TilePolygons::kTet] = batch.index;
  n[TilePolygons::kIso] = Ints(iso_index);
  out.add(f, n, live);
  return extracted;
}

}  // namespace tetray::render
