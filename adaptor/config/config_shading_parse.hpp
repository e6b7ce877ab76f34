// Parsing of the shading keys of a scene (config_shading.hpp) for config_parse.cpp.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "adaptor/config/config_shading.hpp"
#include "adaptor/config/yaml_reader.hpp"
#include "render/trace/trace.hpp"

namespace tetray::config {

// Reads the shading keys of the scene map `scene` (key path `key`) that are present.
void parse_shading(const YamlReader& r, const YAML::Node& scene, const std::string& key,
                   ShadingSpec& spec);

// Reads the scene's transparency keys: `opacity` (one per isovalue, in [0, 1], into `surfaces`)
// and `max_layers` (1..render::kMaxLayers).
void parse_layers(const YamlReader& r, const YAML::Node& scene, const std::string& key,
                  std::vector<render::IsoSurface>& surfaces, ShadingSpec& spec);

// Reads the scene's `lights` list (key path `key`) into spec.lights and the ambient term.
void parse_lights(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  float& ambient, ShadingSpec& spec);

}  // namespace tetray::config
