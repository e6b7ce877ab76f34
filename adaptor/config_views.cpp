#include "config_views.hpp"

#include <cmath>
#include <cstdio>

#include "camera_path.hpp"

namespace tetray::config {
namespace {

// Within this of a pole the view is too close to parallel to up (the camera check of
// config_parse.cpp allows 1e-6 rad; an orbit keeps a clear margin).
constexpr double kPoleMarginDeg = 1;

std::string degrees(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

Orbit parse_orbit(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  const Scene& scene) {
  r.allow_keys(node, key, {"azimuth", "elevation"});
  Orbit orbit;
  orbit.enabled = true;
  const std::string azimuth_key = child_key(key, "azimuth");
  const std::string elevation_key = child_key(key, "elevation");
  if (node["azimuth"]) {
    orbit.azimuth_deg = r.numbers_in(node["azimuth"], azimuth_key, 1, kMaxViews, -360, 360);
  }
  if (node["elevation"]) {
    orbit.elevation_deg = r.numbers_in(node["elevation"], elevation_key, 1, kMaxViews, -180, 180);
  }
  if (orbit.azimuth_deg.size() * orbit.elevation_deg.size() > kMaxViews) {
    r.fail(node, key,
           std::to_string(orbit.azimuth_deg.size() * orbit.elevation_deg.size()) +
               " views (azimuths x elevations) exceed the limit of " + std::to_string(kMaxViews));
  }
  const CameraSpec& camera = scene.camera;
  const render::Vec3d towards_eye =
      camera.auto_fit ? camera.view_direction : camera.fixed.eye - camera.fixed.look_at;
  const double own = camera_elevation_deg(towards_eye, camera.up);
  for (std::size_t i = 0; i < orbit.elevation_deg.size(); ++i) {
    const double total = own + orbit.elevation_deg[i];
    if (std::abs(total) > 90 - kPoleMarginDeg) {
      r.fail(node["elevation"], item_key(elevation_key, i),
             "with the camera's own elevation of " + degrees(own) + " degrees the view is at " +
                 degrees(total) + " degrees, within " + degrees(kPoleMarginDeg) +
                 " degree of the pole of up (keep the total within +-" +
                 degrees(90 - kPoleMarginDeg) + ")");
    }
  }
  return orbit;
}

}  // namespace tetray::config
