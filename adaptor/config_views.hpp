// The `orbit` key of a scene (docs/architecture.md §4): azimuth and elevation lists.
#pragma once

#include <string>

#include "config.hpp"
#include "yaml_reader.hpp"

namespace tetray::config {

// At most this many views per scene and step.
inline constexpr std::size_t kMaxViews = 256;

// Reads the map at `node` for `scene`, whose camera is already parsed: every view's total
// elevation must stay off the poles of its up vector, where the view would be parallel to up.
Orbit parse_orbit(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  const Scene& scene);

}  // namespace tetray::config
