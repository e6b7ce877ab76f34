#include "adaptor/config/config_views.hpp"

#include <cmath>
#include <cstdio>

#include "adaptor/config/camera_path.hpp"

namespace tetray::config {
namespace {

// Within this of a pole the view is too close to parallel to up (the camera check of
// config_parse.cpp allows 1e-6 rad; an orbit keeps a clear margin).
constexpr double kPoleMarginDeg = 1;

// The time between two keyframes is cut into this many equal parts and the interpolated camera
// checked at each inner cut: a frame that degenerates between the cuts is still finite when
// drawn, as render::make_frame falls back to the default camera's, but not the image meant.
constexpr int kSegmentChecks = 256;

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// A keyframe: the keys of an explicit camera (parse_camera reads and checks them) and its time.
Keyframe parse_keyframe(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  r.expect_map(node, key);
  r.allow_keys(node, key, {"time", "eye", "look_at", "up", "fov_deg"});
  for (const char* k : {"time", "eye", "look_at"}) {
    if (!node[k]) r.fail(node, child_key(key, k), "missing (required)");
  }
  Keyframe keyframe;
  keyframe.time = r.number(node["time"], child_key(key, "time"));
  YAML::Node camera = YAML::Clone(node);  // keeps the marks: messages name the lines
  camera.remove("time");
  keyframe.camera = parse_camera(r, camera, key).fixed;
  return keyframe;
}

// Every keyframe after the first is later than the one before it.
void check_increasing(const YamlReader& r, const YAML::Node& list, const std::string& key,
                      const std::vector<Keyframe>& keyframes) {
  for (std::size_t i = 1; i < keyframes.size(); ++i) {
    if (keyframes[i].time > keyframes[i - 1].time) continue;
    r.fail(list[i]["time"], child_key(item_key(key, i), "time"),
           number_text(keyframes[i].time) + " is not later than " +
               child_key(item_key(key, i - 1), "time") + " = " +
               number_text(keyframes[i - 1].time) + " (keyframes go in strictly increasing time)");
  }
}

// No interpolated camera between two keyframes looks along its up vector.
void check_segments(const YamlReader& r, const YAML::Node& list, const std::string& key,
                    const std::vector<Keyframe>& keyframes) {
  for (std::size_t i = 1; i < keyframes.size(); ++i) {
    const double t0 = keyframes[i - 1].time, t1 = keyframes[i].time;
    for (int j = 1; j < kSegmentChecks; ++j) {
      const double t = t0 + (t1 - t0) * j / kSegmentChecks;
      if (!degenerate_camera(keyframe_camera(keyframes, t))) continue;
      r.fail(list[i], item_key(key, i),
             "at time " + number_text(t) + ", between this keyframe and the one before, the " +
                 "interpolated view direction is parallel to the interpolated up (or one of "
                 "them vanishes): add a keyframe between them or change up");
    }
  }
}

}  // namespace

std::vector<Keyframe> parse_camera_path(const YamlReader& r, const YAML::Node& scene,
                                        const std::string& key) {
  const std::string path_key = child_key(key, "camera_path");
  for (const char* other : {"orbit", "camera"}) {
    if (scene[other]) {
      r.fail(scene[other], child_key(key, other),
             "not allowed with camera_path (its keyframes give the camera)");
    }
  }
  const YAML::Node node = scene["camera_path"];
  r.expect_map(node, path_key);
  r.allow_keys(node, path_key, {"keyframes"});
  const std::string list_key = child_key(path_key, "keyframes");
  const YAML::Node list = node["keyframes"];
  if (!list) r.fail(node, list_key, "missing (required)");
  r.expect_list(list, list_key);
  if (list.size() < 2 || list.size() > kMaxKeyframes) {
    r.fail(list, list_key,
           "give 2 to " + std::to_string(kMaxKeyframes) + " keyframes, not " +
               std::to_string(list.size()));
  }
  std::vector<Keyframe> keyframes;
  for (std::size_t i = 0; i < list.size(); ++i) {
    keyframes.push_back(parse_keyframe(r, list[i], item_key(list_key, i)));
  }
  check_increasing(r, list, list_key, keyframes);
  check_segments(r, list, list_key, keyframes);
  return keyframes;
}

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
             "with the camera's own elevation of " + number_text(own) + " degrees the view is at " +
                 number_text(total) + " degrees, within " + number_text(kPoleMarginDeg) +
                 " degree of the pole of up (keep the total within +-" +
                 number_text(90 - kPoleMarginDeg) + ")");
    }
  }
  return orbit;
}

}  // namespace tetray::config
