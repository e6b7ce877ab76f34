#include "render/trace/ray_packet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetray::render {
namespace {

// A direction component of exactly zero becomes a tiny one of the same sign. Every test then
// sees the same, slightly tilted ray: a ray in the plane of a box face (the eye on a grid
// plane) is inside or outside the box on the same side where the isopolygon tests put it, so
// exact ties on shared faces resolve the same way in every packet layout; and the slab test
// never computes 0 * inf.
float tilt_zero(float d) { return d == 0 ? std::copysign(1e-20f, d) : d; }

}  // namespace

// Directions of one packet row: pixel (x0 + col, y) for col in [0, S), normalize(column + row)
// in float (PixelDirections), written so the compiler vectorizes them, then moved to the row's
// places in the packet's blocks.
template <int S>
void setup_row(RayPacket<S>& packet, const PixelDirections& directions, int x0, int pixel_row,
               int row, bool row_valid, int valid_columns) {
  static_assert(S <= PixelDirections::kPastEdge, "a packet row may reach past the last column");
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const Vec3f r = directions.row[pixel_row];
  const float* cx = directions.column_x.data() + x0;
  const float* cy = directions.column_y.data() + x0;
  const float* cz = directions.column_z.data() + x0;
  alignas(64) float dx[S], dy[S], dz[S], tmax[S];
  for (int col = 0; col < S; ++col) {
    const float x = cx[col] + r.x, y = cy[col] + r.y, z = cz[col] + r.z;
    const float inverse_length = 1.0f / std::sqrt(x * x + y * y + z * z);
    dx[col] = tilt_zero(inverse_length * x);
    dy[col] = tilt_zero(inverse_length * y);
    dz[col] = tilt_zero(inverse_length * z);
    tmax[col] = row_valid && col < valid_columns ? kInf : -kInf;
  }
  constexpr int block = RayPacket<S>::kBlockColumns;
  for (int col = 0; col < S; col += block) {
    const int ray = RayPacket<S>::index(row, col);
    std::copy_n(dx + col, block, packet.dx + ray);
    std::copy_n(dy + col, block, packet.dy + ray);
    std::copy_n(dz + col, block, packet.dz + ray);
    std::copy_n(tmax + col, block, packet.tmax + ray);
  }
}

namespace {

// No hits yet, and the batches' bounds.
template <int S>
void clear_hits(RayPacket<S>& packet) {
  constexpr int n = RayPacket<S>::kRays;
  std::fill_n(packet.key, n, kNoHit);
  std::fill_n(packet.tet, n, -1);
  std::fill_n(packet.iso, n, -1);
  // Shading reads every ray's normal at once, a ray without a hit included.
  for (float* normal : {packet.nx, packet.ny, packet.nz}) std::fill_n(normal, n, 0.0f);
  reset_batch_bounds(packet);
}

}  // namespace

template <int S>
void prepare_rays(RayPacket<S>& packet) {
  constexpr int n = RayPacket<S>::kRays;
  for (int r = 0; r < n; ++r) {
    packet.ix[r] = 1.0f / packet.dx[r];
    packet.iy[r] = 1.0f / packet.dy[r];
    packet.iz[r] = 1.0f / packet.dz[r];
  }
  const float* inv[3] = {packet.ix, packet.iy, packet.iz};
  for (int a = 0; a < 3; ++a) {
    simd::min_max(inv[a], n, packet.inv_lo[a], packet.inv_hi[a]);
    packet.inv_straddles[a] = packet.inv_lo[a] < 0 && packet.inv_hi[a] > 0;
  }
  clear_hits(packet);
}

template <int S>
void reset_batch_bounds(RayPacket<S>& packet) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr int w = RayPacket<S>::kLaneWidth;
  for (int b = 0; b < RayPacket<S>::kBatches; ++b) {
    const float* tmax = packet.tmax + b * w;
    packet.batch_missing[b] = static_cast<std::int32_t>(std::count(tmax, tmax + w, kInf));
    packet.batch_far[b] = packet.batch_missing[b] > 0 ? kInf : *std::max_element(tmax, tmax + w);
  }
}

template <int S, bool kTraverses>
void setup_packet(RayPacket<S>& packet, const Camera& camera, const CameraFrame& frame,
                  const PixelDirections& directions, Vec3d origin, const PacketFrustum& frustum,
                  float magnitude, int x0, int y0) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  packet.eye = static_cast<Vec3f>(frame.eye - origin);
  const int x1 = std::min(x0 + S, camera.width) - 1, y1 = std::min(y0 + S, camera.height) - 1;
  packet.frustum = frustum;
  for (int row = 0; row < S; ++row)
    setup_row(packet, directions, x0, std::min(y0 + row, y1), row, y0 + row <= y1, x1 - x0 + 1);
  if constexpr (kTraverses) {
    prepare_rays(packet);
  } else {
    clear_hits(packet);
  }
  packet.tmax_bound = kInf;
  packet.rays_without_hit = (x1 - x0 + 1) * (y1 - y0 + 1);
  packet.projection = row_projection(camera, frame, x0, y0, magnitude);
}

RowProjection row_projection(const Camera& camera, const CameraFrame& frame, int x0, int y0,
                             float magnitude) {
  RowProjection p;
  p.depth_slack = depth_rounding(frame.forward, magnitude);
  p.forward = static_cast<Vec3f>(frame.forward);
  p.up = static_cast<Vec3f>(frame.up);
  // Row j's center has ndc_y = (1 - 2 (j + 0.5) / H) scale_y.
  p.row_scale = static_cast<float>(camera.height / (2.0 * frame.scale_y));
  p.row_center = static_cast<float>(camera.height / 2.0 - 0.5 - y0);
  // Column i's center has ndc_x = (2 (i + 0.5) / W - 1) scale_x.
  p.right = static_cast<Vec3f>(frame.right);
  p.column_scale = static_cast<float>(camera.width / (2.0 * frame.scale_x));
  p.column_center = static_cast<float>(camera.width / 2.0 - 0.5 - x0);
  return p;
}

template <int S>
void update_tmax_bound(RayPacket<S>& packet) {
  if (packet.rays_without_hit > 0) return;
  float lowest;
  simd::min_max(packet.tmax, RayPacket<S>::kRays, lowest, packet.tmax_bound);
}

template void setup_packet<1, true>(RayPacket<1>&, const Camera&, const CameraFrame&,
                                    const PixelDirections&, Vec3d, const PacketFrustum&, float, int,
                                    int);
template void setup_packet<8, true>(RayPacket<8>&, const Camera&, const CameraFrame&,
                                    const PixelDirections&, Vec3d, const PacketFrustum&, float, int,
                                    int);
template void setup_packet<16, true>(RayPacket<16>&, const Camera&, const CameraFrame&,
                                     const PixelDirections&, Vec3d, const PacketFrustum&, float,
                                     int, int);
template void setup_packet<32, true>(RayPacket<32>&, const Camera&, const CameraFrame&,
                                     const PixelDirections&, Vec3d, const PacketFrustum&, float,
                                     int, int);
template void setup_packet<32, false>(RayPacket<32>&, const Camera&, const CameraFrame&,
                                      const PixelDirections&, Vec3d, const PacketFrustum&, float,
                                      int, int);
template void prepare_rays<1>(RayPacket<1>&);
template void prepare_rays<16>(RayPacket<16>&);
template void reset_batch_bounds<1>(RayPacket<1>&);
template void reset_batch_bounds<8>(RayPacket<8>&);
template void reset_batch_bounds<16>(RayPacket<16>&);
template void reset_batch_bounds<32>(RayPacket<32>&);
template void update_tmax_bound<1>(RayPacket<1>&);
template void update_tmax_bound<8>(RayPacket<8>&);
template void update_tmax_bound<16>(RayPacket<16>&);
template void update_tmax_bound<32>(RayPacket<32>&);

}  // namespace tetray::render
