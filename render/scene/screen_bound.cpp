#include "render/scene/screen_bound.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::render {

std::optional<PixelPoint> pixel_position(const CameraFrame& frame, const Camera& camera,
                                         const Vec3d& point) {
  const Vec3d d = point - frame.eye;
  const double depth = dot(d, frame.forward);
  if (!(depth > 1e-9 * std::max(1.0, length(d)))) return std::nullopt;
  return PixelPoint{0.5 * camera.width * (dot(d, frame.right) / (depth * frame.scale_x) + 1.0),
                    0.5 * camera.height * (1.0 - dot(d, frame.up) / (depth * frame.scale_y))};
}

std::optional<ScreenRect> screen_bound(const Camera& camera, const Vec3d& lo, const Vec3d& hi) {
  const CameraFrame frame = make_frame(camera);
  double px_min = INFINITY, px_max = -INFINITY, py_min = INFINITY, py_max = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3d point{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    const std::optional<PixelPoint> at = pixel_position(frame, camera, point);
    if (!at) return std::nullopt;
    px_min = std::min(px_min, at->x);
    px_max = std::max(px_max, at->x);
    py_min = std::min(py_min, at->y);
    py_max = std::max(py_max, at->y);
  }
  // A box in front of the eye projects inside the convex hull of its corners' projections.
  const auto clip = [](double value, int size) {
    return static_cast<int>(std::clamp(value, 0.0, static_cast<double>(size)));
  };
  constexpr double kMargin = 2.0;
  return ScreenRect{clip(std::floor(px_min - kMargin), camera.width),
                    clip(std::floor(py_min - kMargin), camera.height),
                    clip(std::ceil(px_max + kMargin), camera.width),
                    clip(std::ceil(py_max + kMargin), camera.height)};
}

}  // namespace tetray::render
