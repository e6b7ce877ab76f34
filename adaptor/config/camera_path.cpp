#include "adaptor/config/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tetray {
namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

}  // namespace

std::vector<View> orbit_views(const config::Orbit& orbit) {
  std::vector<View> views;
  for (double theta : orbit.elevation_deg) {
    for (double phi : orbit.azimuth_deg) views.push_back({phi, theta});
  }
  return views;
}

double camera_elevation_deg(render::Vec3d towards_eye, render::Vec3d up) {
  const render::Vec3d u = normalize(up);
  const double height = dot(towards_eye, u);
  const render::Vec3d across = towards_eye - height * u;
  return std::atan2(height, std::sqrt(dot(across, across))) / kRadiansPerDegree;
}

render::Camera orbit_camera(const render::Camera& base, const View& view) {
  const render::Vec3d offset = base.eye - base.look_at;
  const render::Vec3d u = normalize(base.up);
  const double distance = std::sqrt(dot(offset, offset));
  // The offset's direction in the plane normal to up, turned by phi (Rodrigues about u).
  const render::Vec3d level = normalize(offset - dot(offset, u) * u);
  const double phi = view.phi_deg * kRadiansPerDegree;
  const render::Vec3d turned = std::cos(phi) * level + std::sin(phi) * cross(u, level);
  const double elevation = (camera_elevation_deg(offset, u) + view.theta_deg) * kRadiansPerDegree;
  render::Camera camera = base;
  camera.eye = base.look_at + distance * (std::cos(elevation) * turned + std::sin(elevation) * u);
  return camera;
}

render::Camera keyframe_camera(const std::vector<config::Keyframe>& keyframes, double time) {
  const auto later = std::upper_bound(
      keyframes.begin(), keyframes.end(), time,
      [](double t, const config::Keyframe& keyframe) { return t < keyframe.time; });
  if (later == keyframes.begin()) return keyframes.front().camera;
  const config::Keyframe& a = *(later - 1);
  // At a keyframe's time the keyframe itself, bit for bit (renormalizing its unit up vector
  // could move the last bit); after the last keyframe, the last.
  if (later == keyframes.end() || a.time == time) return a.camera;
  const config::Keyframe& b = *later;
  const double s = (time - a.time) / (b.time - a.time);
  const auto lerp = [s](auto x, auto y) { return x + s * (y - x); };
  render::Camera camera = a.camera;
  camera.eye = lerp(a.camera.eye, b.camera.eye);
  camera.look_at = lerp(a.camera.look_at, b.camera.look_at);
  camera.up = normalize(lerp(a.camera.up, b.camera.up));
  camera.fov_deg = lerp(a.camera.fov_deg, b.camera.fov_deg);
  return camera;
}

bool degenerate_camera(const render::Camera& camera) {
  return !render::camera_problem(camera).empty();
}

}  // namespace tetray
