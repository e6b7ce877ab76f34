#include "render/scene/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace tetray::render {

namespace {

bool finite(Vec3d v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const CameraFrame& f) {
  return finite(f.eye) && finite(f.forward) && finite(f.right) && finite(f.up) &&
         std::isfinite(f.scale_x) && std::isfinite(f.scale_y);
}

CameraFrame frame_of(const Camera& camera) {
  CameraFrame frame;
  frame.eye = camera.eye;
  frame.forward = normalize(camera.look_at - camera.eye);
  frame.right = normalize(cross(frame.forward, camera.up));
  frame.up = cross(frame.right, frame.forward);
  const double tan_half = std::tan(camera.fov_deg * std::numbers::pi / 360.0);
  frame.scale_y = tan_half;
  frame.scale_x = tan_half * static_cast<double>(camera.width) / camera.height;
  return frame;
}

}  // namespace

Vec3d unit_direction(Vec3d v) {
  // Divided by its largest component first, so that neither [1e-300, 0, 0] underflows nor
  // [1e300, 0, 0] overflows in the length.
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest > 0 ? normalize((1 / largest) * v) : v;
}

std::string camera_problem(const Camera& camera) {
  if (!finite(camera.eye)) return "the eye is not a finite point";
  if (!finite(camera.look_at)) return "look_at is not a finite point";
  if (!finite(camera.up)) return "up is not a finite direction";
  if (!(camera.fov_deg >= kMinFovDeg && camera.fov_deg <= kMaxFovDeg)) {
    std::ostringstream text;
    text << "the field of view is " << camera.fov_deg << " degrees, outside [" << kMinFovDeg << ", "
         << kMaxFovDeg << "]";
    return text.str();
  }
  const Vec3d forward = unit_direction(camera.look_at - camera.eye);
  const Vec3d up = unit_direction(camera.up);
  if (dot(forward, forward) == 0) return "eye and look_at are the same point";
  if (dot(up, up) == 0) return "up must not be the zero vector";
  const Vec3d c = cross(forward, up);
  if (!(dot(c, c) > 1e-12)) return "the view direction is parallel to up";
  return {};
}

CameraFrame make_frame(const Camera& camera) {
  const CameraFrame frame = frame_of(camera);
  if (finite(frame)) return frame;
  // A degenerate camera (NaN, eye on look_at, up zero or along the view) would send NaN rays
  // into the traversal; it draws the default view of its image size instead. The config and
  // tetray-render refuse such cameras first.
  Camera fallback;
  fallback.width = camera.width;
  fallback.height = camera.height;
  return frame_of(fallback);
}

double column_slope(const CameraFrame& frame, double px, int width) {
  return (2.0 * px / width - 1.0) * frame.scale_x;
}

double row_slope(const CameraFrame& frame, double py, int height) {
  return (1.0 - 2.0 * py / height) * frame.scale_y;
}

namespace {

Vec3d column_term(const CameraFrame& frame, double px, int width) {
  return frame.forward + column_slope(frame, px, width) * frame.right;
}

Vec3d row_term(const CameraFrame& frame, double py, int height) {
  return row_slope(frame, py, height) * frame.up;
}

}  // namespace

Vec3d CameraFrame::direction_at(double px, double py, int width, int height) const {
  return column_term(*this, px, width) + row_term(*this, py, height);
}

Vec3d pixel_direction(const CameraFrame& frame, const Camera& camera, int i, int j) {
  return normalize(frame.direction_at(i + 0.5, j + 0.5, camera.width, camera.height));
}

PixelDirections::PixelDirections(const CameraFrame& frame, const Camera& camera)
    : row(camera.height) {
  const int columns = camera.width + kPastEdge;
  column_x.resize(columns);
  column_y.resize(columns);
  column_z.resize(columns);
  for (int i = 0; i < columns; ++i) {
    const Vec3d c = column_term(frame, std::min(i, camera.width - 1) + 0.5, camera.width);
    column_x[i] = static_cast<float>(c.x);
    column_y[i] = static_cast<float>(c.y);
    column_z[i] = static_cast<float>(c.z);
  }
  for (int j = 0; j < camera.height; ++j)
    row[j] = static_cast<Vec3f>(row_term(frame, j + 0.5, camera.height));
}

Camera fit_camera(Vec3d lo, Vec3d hi, Vec3d from_direction, Vec3d up, double fov_deg, int width,
                  int height) {
  // A box that is empty or not finite (no points, or points the mesh check did not bound) is
  // fitted as the unit box, never as a NaN or infinite eye.
  if (!finite(lo) || !finite(hi) || !finite(hi - lo) ||
      !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) {
    lo = {-1, -1, -1};
    hi = {1, 1, 1};
  }
  const Vec3d center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), 1e-12);
  const double tan_half = std::tan(fov_deg * std::numbers::pi / 360.0);
  const double tan_half_min = tan_half * std::min(1.0, static_cast<double>(width) / height);
  // Distance at which a sphere of that radius fits the narrower half-angle.
  const double distance = radius / std::sin(std::atan(tan_half_min));
  Camera camera;
  camera.look_at = center;
  camera.eye = center + distance * normalize(from_direction);
  camera.up = up;
  camera.fov_deg = fov_deg;
  camera.width = width;
  camera.height = height;
  return camera;
}

}  // namespace tetray::render
