// Parsing of the keys every colormapped thing of a scene shares: a colormap name and a value
// range, `auto` or [low, high].
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "adaptor/config/config_colormap.hpp"
#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// A known colormap's name (render::find_colormap), else a config error at `key`.
std::string parse_colormap_name(const YamlReader& r, const YAML::Node& node,
                                const std::string& key);

// `auto`, or [low, high] with low < high within the field values tetray accepts.
ColorRange parse_color_range(const YamlReader& r, const YAML::Node& node, const std::string& key);

}  // namespace tetray::config
