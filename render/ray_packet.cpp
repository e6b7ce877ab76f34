#include "render/ray_packet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetray::render {
namespace {

// 1/d with zero components replaced by a huge value of the same sign, so that slab tests never
// compute 0 * inf.
float safe_inverse(float d) {
  constexpr float kHuge = 1e30f;
  if (std::abs(d) < 1.0f / kHuge) return std::copysign(kHuge, d);
  return 1.0f / d;
}

}  // namespace

template <int S>
void setup_packet(RayPacket<S>& packet, const Camera& camera, const CameraFrame& frame,
                  const PixelDirections& directions, Vec3d origin, int x0, int y0) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  packet.eye = static_cast<Vec3f>(frame.eye - origin);
  packet.x0 = x0;
  packet.y0 = y0;
  const int x1 = std::min(x0 + S, camera.width) - 1, y1 = std::min(y0 + S, camera.height) - 1;
  float* inv[3] = {packet.ix, packet.iy, packet.iz};
  for (int r = 0; r < RayPacket<S>::kRays; ++r) {
    const int i = x0 + r % S, j = y0 + r / S;
    const Vec3f d = static_cast<Vec3f>(directions.direction(std::min(i, x1), std::min(j, y1)));
    packet.dx[r] = d.x;
    packet.dy[r] = d.y;
    packet.dz[r] = d.z;
    packet.ix[r] = safe_inverse(d.x);
    packet.iy[r] = safe_inverse(d.y);
    packet.iz[r] = safe_inverse(d.z);
    packet.tmax[r] = (i <= x1 && j <= y1) ? kInf : -kInf;
    packet.key[r] = kNoHit;
    packet.tet[r] = -1;
    packet.iso[r] = -1;
  }
  for (int a = 0; a < 3; ++a) {
    const auto [lo, hi] = std::minmax_element(inv[a], inv[a] + RayPacket<S>::kRays);
    packet.inv_lo[a] = *lo;
    packet.inv_hi[a] = *hi;
    packet.inv_straddles[a] = *lo < 0 && *hi > 0;
  }
  const double px[2] = {x0 + 0.5, x1 + 0.5}, py[2] = {y0 + 0.5, y1 + 0.5};
  packet.corner_length_sq_max = 0;
  for (int c = 0; c < 4; ++c) {
    packet.corner[c] =
        static_cast<Vec3f>(frame.direction_at(px[c & 1], py[c >> 1], camera.width, camera.height));
    packet.corner_length_sq_max =
        std::max(packet.corner_length_sq_max, dot(packet.corner[c], packet.corner[c]));
  }
  packet.tmax_bound = kInf;
  packet.forward = static_cast<Vec3f>(frame.forward);
  packet.up = static_cast<Vec3f>(frame.up);
  // Row j's center has ndc_y = (1 - 2 (j + 0.5) / H) scale_y.
  packet.row_scale = static_cast<float>(camera.height / (2.0 * frame.scale_y));
  packet.row_center = static_cast<float>(camera.height / 2.0 - 0.5 - y0);
}

template <int S>
void update_tmax_bound(RayPacket<S>& packet) {
  packet.tmax_bound = *std::max_element(packet.tmax, packet.tmax + RayPacket<S>::kRays);
}

template void setup_packet<1>(RayPacket<1>&, const Camera&, const CameraFrame&,
                              const PixelDirections&, Vec3d, int, int);
template void setup_packet<8>(RayPacket<8>&, const Camera&, const CameraFrame&,
                              const PixelDirections&, Vec3d, int, int);
template void setup_packet<16>(RayPacket<16>&, const Camera&, const CameraFrame&,
                               const PixelDirections&, Vec3d, int, int);
template void update_tmax_bound<1>(RayPacket<1>&);
template void update_tmax_bound<8>(RayPacket<8>&);
template void update_tmax_bound<16>(RayPacket<16>&);

}  // namespace tetray::render
