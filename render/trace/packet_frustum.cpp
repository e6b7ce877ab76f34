#include "render/trace/packet_frustum.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::render {
namespace {

// Bound of the rounding of one coordinate relative to `magnitude`: a few ulps of it.
constexpr double kCoordinateError = 0x1p-19;

// The image-plane slope (ndc) of a pixel center along one axis, widened by `outward` pixels
// and 1e-5 of itself in the direction `sign`.
double widened_slope(double pixel_center, int pixels, double scale, double outward, double sign) {
  const double slope = (2.0 * pixel_center / pixels - 1.0) * scale;
  const double pixel = 2.0 * scale / pixels;
  return slope + sign * (outward * pixel + 1e-5 * (1.0 + std::abs(slope)));
}

double l1_norm(Vec3d v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }

// The frustum of the rays from the eye whose slopes along r and u, relative to the axis f
// (orthonormal), lie in [left, right] and [bottom, top].
PacketFrustum frustum_from_slopes(Vec3d f, Vec3d r, Vec3d u, double left, double right,
                                  double bottom, double top, float magnitude) {
  // Inside each: slope along right (up) of p - eye at least `left` (`bottom`) times its depth,
  // at most `right` (`top`) times it.
  const Vec3d normals[4] = {r - left * f, right * f - r, u - bottom * f, top * f - u};
  const double error = kCoordinateError * magnitude;
  PacketFrustum frustum;
  for (int k = 0; k < 4; ++k) {
    frustum.nx[k] = static_cast<float>(normals[k].x);
    frustum.ny[k] = static_cast<float>(normals[k].y);
    frustum.nz[k] = static_cast<float>(normals[k].z);
    frustum.slack[k] = static_cast<float>(error * l1_norm(normals[k]));
  }
  frustum.forward = static_cast<Vec3f>(f);
  frustum.forward_slack = depth_rounding(f, magnitude);
  return frustum;
}

}  // namespace

float depth_rounding(Vec3d forward, float magnitude) {
  return static_cast<float>(kCoordinateError * magnitude * l1_norm(forward));
}

PacketFrustum make_packet_frustum(const Camera& camera, const CameraFrame& frame, int x0, int y0,
                                  int x1, int y1, float magnitude) {
  constexpr double kOutward = 1.0 / 16;  // pixels
  const double left = widened_slope(x0 + 0.5, camera.width, frame.scale_x, kOutward, -1);
  const double right = widened_slope(x1 + 0.5, camera.width, frame.scale_x, kOutward, 1);
  // Rows count downwards: the bottom row y1 has the lowest slope.
  const double bottom = -widened_slope(y1 + 0.5, camera.height, frame.scale_y, kOutward, 1);
  const double top = -widened_slope(y0 + 0.5, camera.height, frame.scale_y, kOutward, -1);
  return frustum_from_slopes(frame.forward, frame.right, frame.up, left, right, bottom, top,
                             magnitude);
}

std::optional<PacketFrustum> make_direction_frustum(const float* dx, const float* dy,
                                                    const float* dz, int count, float magnitude) {
  Vec3d mean{};
  for (int k = 0; k < count; ++k) mean = mean + Vec3d{dx[k], dy[k], dz[k]};
  if (!(length(mean) > 0)) return std::nullopt;
  const Vec3d f = normalize(mean);
  const Vec3d other = std::abs(f.x) < 0.5 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  const Vec3d r = normalize(cross(f, other)), u = cross(r, f);
  double left = 1e300, right = -1e300, bottom = 1e300, top = -1e300;
  for (int k = 0; k < count; ++k) {
    const Vec3d d{dx[k], dy[k], dz[k]};
    const double depth = dot(d, f);
    // Beyond 60 degrees from the axis the slopes grow without bound; such a packet is too wide
    // for a frustum to cull much.
    if (!(depth > 0.5)) return std::nullopt;
    const double x = dot(d, r) / depth, y = dot(d, u) / depth;
    left = std::min(left, x);
    right = std::max(right, x);
    bottom = std::min(bottom, y);
    top = std::max(top, y);
  }
  // Against the rounding of the directions and of the slopes above.
  const auto widen = [](double& lo, double& hi) {
    lo -= 1e-5 * (1.0 + std::abs(lo));
    hi += 1e-5 * (1.0 + std::abs(hi));
  };
  widen(left, right);
  widen(bottom, top);
  return frustum_from_slopes(f, r, u, left, right, bottom, top, magnitude);
}

}  // namespace tetray::render
