#include "render/trace/packet_frustum.hpp"

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

}  // namespace

PacketFrustum make_packet_frustum(const Camera& camera, const CameraFrame& frame, int x0, int y0,
                                  int x1, int y1, float magnitude) {
  constexpr double kOutward = 1.0 / 16;  // pixels
  const double left = widened_slope(x0 + 0.5, camera.width, frame.scale_x, kOutward, -1);
  const double right = widened_slope(x1 + 0.5, camera.width, frame.scale_x, kOutward, 1);
  // Rows count downwards: the bottom row y1 has the lowest slope.
  const double bottom = -widened_slope(y1 + 0.5, camera.height, frame.scale_y, kOutward, 1);
  const double top = -widened_slope(y0 + 0.5, camera.height, frame.scale_y, kOutward, -1);
  const Vec3d f = frame.forward, r = frame.right, u = frame.up;
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
  frustum.forward_slack = static_cast<float>(error * l1_norm(f));
  return frustum;
}

}  // namespace tetray::render
