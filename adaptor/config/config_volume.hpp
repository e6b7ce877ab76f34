// The `volume:` key of a scene (docs/config.md): direct volume rendering of the
// scene's field instead of isosurfaces.
#pragma once

#include <string>

#include "adaptor/config/config.hpp"
#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// Most opacity points of one transfer function.
inline constexpr std::size_t kMaxOpacityPoints = 256;

// Fills s.volume from node["volume"]; isovalues, colors, opacity and color_by are not allowed
// beside it (a volume scene's isosurfaces are its `surfaces`, config_parse.cpp).
void parse_volume_scene(const YamlReader& r, const YAML::Node& node, const std::string& key,
                        Scene& s);

}  // namespace tetray::config
