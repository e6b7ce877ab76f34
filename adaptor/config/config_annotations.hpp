// The `annotations` key of a scene (docs/config.md): colorbar, caption, title, font.
#pragma once

#include <string>

#include "adaptor/config/config.hpp"
#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// Reads the map at `node`; opens the font when anything is to be drawn, so that a missing or
// unreadable font fails creation, naming the file. `scene` is the scene parsed so far: a
// colorbar needs its color_by.
Annotations parse_annotations(const YamlReader& r, const YAML::Node& node, const std::string& key,
                              const Scene& scene);

}  // namespace tetray::config
