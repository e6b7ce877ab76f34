// The `lod:` key of a scene (docs/config.md, docs/architecture.md §9): level of detail for its
// isosurfaces, off (exact images) without it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// Widest node_pixels accepted: a node wider than the image is never a detail.
inline constexpr double kMaxLodNodePixels = 4096;

// Reads `lod: {node_pixels: N}` (key path `key`): the traversal stops at BVH nodes narrower
// than N pixels at their distance and draws their fitted surface instead of their tets.
float parse_lod(const YamlReader& r, const YAML::Node& node, const std::string& key);

}  // namespace tetray::config
