#include "render/trace/camera.hpp"

#include <algorithm>
#include <numbers>

namespace tetray::render {

CameraFrame make_frame(const Camera& camera) {
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

namespace {

Vec3d column_term(const CameraFrame& frame, double px, int width) {
  return frame.forward + ((2.0 * px / width - 1.0) * frame.scale_x) * frame.right;
}

Vec3d row_term(const CameraFrame& frame, double py, int height) {
  return ((1.0 - 2.0 * py / height) * frame.scale_y) * frame.up;
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
    column_x[i] = c.x;
    column_y[i] = c.y;
    column_z[i] = c.z;
  }
  for (int j = 0; j < camera.height; ++j) row[j] = row_term(frame, j + 0.5, camera.height);
}

Camera fit_camera(Vec3d lo, Vec3d hi, Vec3d from_direction, Vec3d up, double fov_deg, int width,
                  int height) {
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
