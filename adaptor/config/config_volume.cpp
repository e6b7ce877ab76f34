#include "adaptor/config/config_volume.hpp"

#include "adaptor/config/config_colormap_parse.hpp"

#include "render/core/value_bounds.hpp"

namespace tetray::config {
namespace {

std::vector<render::OpacityPoint> parse_opacity(const YamlReader& r, const YAML::Node& node,
                                                const std::string& key) {
  r.expect_list(node, key);
  if (node.size() == 0 || node.size() > kMaxOpacityPoints) {
    r.fail(node, key,
           "give 1 to " + std::to_string(kMaxOpacityPoints) + " [value, opacity] points");
  }
  std::vector<render::OpacityPoint> points;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string point_key = item_key(key, i);
    const auto v = r.numbers(node[i], point_key, 2, 2);
    if (std::abs(v[0]) > render::kMaxFieldValue) {
      r.fail(node[i], point_key, "the value lies beyond the field range tetray accepts");
    }
    if (v[1] < 0 || v[1] > 1e6) r.fail(node[i], point_key, "the opacity must lie in [0, 1e6]");
    if (!points.empty() && !(v[0] > points.back().value)) {
      r.fail(node[i], point_key, "values must increase from point to point");
    }
    points.push_back({v[0], v[1]});
  }
  return points;
}

}  // namespace

void parse_volume_scene(const YamlReader& r, const YAML::Node& node, const std::string& key,
                        Scene& s) {
  for (const char* k : {"isovalues", "colors", "opacity", "max_layers"}) {
    if (node[k]) {
      r.fail(node[k], child_key(key, k),
             "not allowed in a volume scene (its isosurfaces go under surfaces)");
    }
  }
  for (const char* k : {"color_by", "colormap", "color_range"}) {
    if (node[k]) r.fail(node[k], child_key(key, k), "not allowed in a volume scene");
  }
  const std::string vkey = child_key(key, "volume");
  const YAML::Node v = node["volume"];
  r.expect_map(v, vkey);
  r.allow_keys(v, vkey, {"colormap", "range", "opacity", "unit_distance", "termination"});
  if (!v["opacity"]) r.fail(v, child_key(vkey, "opacity"), "missing (required)");
  VolumeSpec spec;
  if (v["colormap"])
    spec.colormap_name = parse_colormap_name(r, v["colormap"], child_key(vkey, "colormap"));
  if (v["range"]) spec.range = parse_color_range(r, v["range"], child_key(vkey, "range"));
  spec.opacity = parse_opacity(r, v["opacity"], child_key(vkey, "opacity"));
  if (v["unit_distance"]) {
    spec.unit_distance =
        r.number_in(v["unit_distance"], child_key(vkey, "unit_distance"), 1e-12, 1e12);
  }
  if (v["termination"]) {
    spec.termination = r.number_in(v["termination"], child_key(vkey, "termination"), 0.5, 1.0);
  }
  s.volume = spec;
}

}  // namespace tetray::config
