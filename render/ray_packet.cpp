#include "render/ray_packet.hpp"

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

template <int S>
void setup_packet(RayPacket<S>& packet, const Camera& camera, const CameraFrame& frame,
                  const PixelDirections& directions, Vec3d origin, int x0, int y0) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  packet.eye = static_cast<Vec3f>(frame.eye - origin);
  const int x1 = std::min(x0 + S, camera.width) - 1, y1 = std::min(y0 + S, camera.height) - 1;
  for (int row = 0; row < S; ++row) {
    const bool row_valid = y0 + row <= y1;
    for (int col = 0; col < S; ++col) {
      const int r = row * S + col;
      const Vec3f d =
          static_cast<Vec3f>(directions.direction(std::min(x0 + col, x1), std::min(y0 + row, y1)));
      packet.dx[r] = tilt_zero(d.x);
      packet.dy[r] = tilt_zero(d.y);
      packet.dz[r] = tilt_zero(d.z);
      packet.tmax[r] = row_valid && x0 + col <= x1 ? kInf : -kInf;
    }
  }
  constexpr int n = RayPacket<S>::kRays;
  for (int r = 0; r < n; ++r) {
    packet.ix[r] = 1.0f / packet.dx[r];
    packet.iy[r] = 1.0f / packet.dy[r];
    packet.iz[r] = 1.0f / packet.dz[r];
  }
  std::fill_n(packet.key, n, kNoHit);
  std::fill_n(packet.tet, n, -1);
  std::fill_n(packet.iso, n, -1);
  const float* inv[3] = {packet.ix, packet.iy, packet.iz};
  for (int a = 0; a < 3; ++a) {
    float lo = inv[a][0], hi = inv[a][0];
    for (int r = 1; r < n; ++r) {
      lo = std::min(lo, inv[a][r]);
      hi = std::max(hi, inv[a][r]);
    }
    packet.inv_lo[a] = lo;
    packet.inv_hi[a] = hi;
    packet.inv_straddles[a] = lo < 0 && hi > 0;
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
