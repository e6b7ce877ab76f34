#include "adaptor/config/config_lod.hpp"

namespace tetray::config {

float parse_lod(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  r.expect_map(node, key);
  r.allow_keys(node, key, {"node_pixels"});
  const std::string pixels_key = child_key(key, "node_pixels");
  if (!node["node_pixels"]) r.fail(node, pixels_key, "missing (required)");
  const double pixels = r.number_in(node["node_pixels"], pixels_key, 0, kMaxLodNodePixels);
  if (pixels <= 0) {
    r.fail(node["node_pixels"], pixels_key, "must be above 0 (leave out `lod` for exact images)");
  }
  return static_cast<float>(pixels);
}

}  // namespace tetray::config
