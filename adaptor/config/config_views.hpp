// The `orbit` and `camera_path` keys of a scene (docs/config.md): azimuth and
// elevation lists, or keyframed cameras over simulated time.
#pragma once

#include <string>
#include <vector>

#include "adaptor/config/config.hpp"
#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// At most this many views per scene and step, and keyframes per camera path.
inline constexpr std::size_t kMaxViews = 256;
inline constexpr std::size_t kMaxKeyframes = 4096;

// Reads the map at `node` for `scene`, whose camera is already parsed: every view's total
// elevation must stay off the poles of its up vector, where the view would be parallel to up.
Orbit parse_orbit(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  const Scene& scene);

// Reads `camera_path` of the scene map `scene` (key path `key`): at least two keyframes, each an
// explicit camera with a time, in strictly increasing time, and no `orbit` or `camera` beside it.
std::vector<Keyframe> parse_camera_path(const YamlReader& r, const YAML::Node& scene,
                                        const std::string& key);

// A scene's `camera` map at key path `key` (config_parse.cpp); also reads each keyframe.
CameraSpec parse_camera(const YamlReader& r, const YAML::Node& node, const std::string& key);

}  // namespace tetray::config
