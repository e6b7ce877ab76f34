#include "adaptor/config/config_colormap_parse.hpp"

#include "render/core/value_bounds.hpp"
#include "render/scene/colormap.hpp"

namespace tetray::config {

std::string parse_colormap_name(const YamlReader& r, const YAML::Node& node,
                                const std::string& key) {
  std::string name = r.string(node, key);
  if (!render::find_colormap(name)) {
    r.fail(node, key, "unknown colormap '" + name + "' (known: viridis, coolwarm, grayscale)");
  }
  return name;
}

ColorRange parse_color_range(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  if (node.IsScalar()) {
    r.choice(node, key, {"auto"});
    return {};
  }
  const auto lo_hi = r.numbers_in(node, key, 2, 2, -render::kMaxFieldValue, render::kMaxFieldValue);
  if (!(lo_hi[0] < lo_hi[1])) r.fail(node, key, "needs low < high");
  return {false, static_cast<float>(lo_hi[0]), static_cast<float>(lo_hi[1])};
}

}  // namespace tetray::config
