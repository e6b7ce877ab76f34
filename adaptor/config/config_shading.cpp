#include <algorithm>
#include <cmath>

#include "adaptor/config/config_colormap_parse.hpp"
#include "adaptor/config/config_shading_parse.hpp"
#include "render/core/value_bounds.hpp"
#include "render/scene/camera.hpp"

namespace tetray::config {
namespace {

render::Vec3d point_in_range(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  const auto v = r.numbers_in(node, key, 3, 3, -render::kMaxCoordinate, render::kMaxCoordinate);
  return {v[0], v[1], v[2]};
}

// A plane normal or light direction as a unit vector, whatever its scale.
render::Vec3d plane_normal(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  const auto v = r.numbers(node, key, 3, 3);
  const render::Vec3d unit = render::unit_direction({v[0], v[1], v[2]});
  if (dot(unit, unit) == 0) r.fail(node, key, "must not be the zero vector");
  return unit;
}

void parse_clip_box(const YamlReader& r, const YAML::Node& node, const std::string& key,
                    render::ClipRegion& clip) {
  r.allow_keys(node, key, {"min", "max"});
  for (const char* k : {"min", "max"}) {
    if (!node[k]) r.fail(node, child_key(key, k), "missing (required)");
  }
  clip.has_box = true;
  clip.box_lo = point_in_range(r, node["min"], child_key(key, "min"));
  clip.box_hi = point_in_range(r, node["max"], child_key(key, "max"));
  for (int a = 0; a < 3; ++a) {
    if (!(clip.box_lo[a] < clip.box_hi[a])) r.fail(node, key, "needs min < max on every axis");
  }
}

void parse_clip_planes(const YamlReader& r, const YAML::Node& node, const std::string& key,
                       render::ClipRegion& clip) {
  r.expect_list(node, key);
  if (node.size() > static_cast<std::size_t>(render::kMaxClipPlanes)) {
    r.fail(node, key, "give at most " + std::to_string(render::kMaxClipPlanes) + " planes");
  }
  for (std::size_t k = 0; k < node.size(); ++k) {
    const std::string plane_key = item_key(key, k);
    r.allow_keys(node[k], plane_key, {"point", "normal"});
    for (const char* field : {"point", "normal"}) {
      if (!node[k][field]) r.fail(node[k], child_key(plane_key, field), "missing (required)");
    }
    clip.planes[k] = {point_in_range(r, node[k]["point"], child_key(plane_key, "point")),
                      plane_normal(r, node[k]["normal"], child_key(plane_key, "normal"))};
  }
  clip.plane_count = static_cast<int>(node.size());
}

void parse_cap(const YamlReader& r, const YAML::Node& node, const std::string& key, CapSpec& cap) {
  r.expect_map(node, key);
  r.allow_keys(node, key, {"field", "colormap", "range"});
  if (!node["field"]) r.fail(node, child_key(key, "field"), "missing (required)");
  cap.field = r.string(node["field"], child_key(key, "field"));
  if (cap.field.empty()) r.fail(node["field"], child_key(key, "field"), "must name a field");
  if (node["colormap"])
    cap.colormap_name = parse_colormap_name(r, node["colormap"], child_key(key, "colormap"));
  if (node["range"]) cap.range = parse_color_range(r, node["range"], child_key(key, "range"));
}

void parse_clip(const YamlReader& r, const YAML::Node& node, const std::string& key,
                ShadingSpec& spec) {
  r.allow_keys(node, key, {"box", "planes", "cap"});
  if (!node["box"] && !node["planes"]) {
    r.fail(node, key,
           node["cap"] ? "cap needs a box or planes to cut the mesh along"
                       : "give a box, planes or both");
  }
  if (node["box"]) parse_clip_box(r, node["box"], child_key(key, "box"), spec.clip);
  if (node["planes"]) parse_clip_planes(r, node["planes"], child_key(key, "planes"), spec.clip);
  if (node["cap"]) parse_cap(r, node["cap"], child_key(key, "cap"), spec.cap);
}

void parse_light(const YamlReader& r, const YAML::Node& node, const std::string& key,
                 render::Light& light) {
  const std::string type = node["type"] ? r.choice(node["type"], child_key(key, "type"),
                                                   {"headlight", "point", "directional"})
                                        : "headlight";
  if (type == "headlight") {
    r.allow_keys(node, key, {"type", "ambient"});
    light.kind = render::LightKind::headlight;
    return;
  }
  const char* where = type == "point" ? "position" : "direction";
  r.allow_keys(node, key, {"type", "ambient", where, "shadows"});
  if (!node[where]) r.fail(node, child_key(key, where), "missing (required)");
  if (type == "point") {
    light.kind = render::LightKind::point;
    light.vector = point_in_range(r, node[where], child_key(key, where));
  } else {
    light.kind = render::LightKind::directional;
    light.vector = plane_normal(r, node[where], child_key(key, where));
  }
  if (node["shadows"]) light.shadows = r.boolean(node["shadows"], child_key(key, "shadows"));
}

}  // namespace

void parse_lights(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  float& ambient, ShadingSpec& spec) {
  r.expect_list(node, key);
  if (node.size() == 0 || node.size() > static_cast<std::size_t>(render::kMaxLights)) {
    r.fail(node, key, "give 1 to " + std::to_string(render::kMaxLights) + " lights");
  }
  bool headlight = false, ambient_given = false;
  for (std::size_t k = 0; k < node.size(); ++k) {
    const std::string light_key = item_key(key, k);
    render::Light& light = spec.lights.light[k];
    parse_light(r, node[k], light_key, light);
    if (light.kind == render::LightKind::headlight) {
      if (headlight) r.fail(node[k], light_key, "give at most one headlight");
      headlight = true;
    }
    if (const YAML::Node a = node[k]["ambient"]) {
      if (ambient_given)
        r.fail(a, child_key(light_key, "ambient"), "give ambient on one light only");
      ambient_given = true;
      ambient = static_cast<float>(r.number_in(a, child_key(light_key, "ambient"), 0, 1));
    }
  }
  spec.lights.count = static_cast<int>(node.size());
}

void parse_layers(const YamlReader& r, const YAML::Node& scene, const std::string& key,
                  std::vector<render::IsoSurface>& surfaces, ShadingSpec& spec) {
  const std::string opacity_key = child_key(key, "opacity");
  if (const YAML::Node opacity = scene["opacity"]) {
    if (surfaces.empty()) r.fail(opacity, opacity_key, "needs isovalues (not a volume scene's)");
    const auto values = r.numbers_in(opacity, opacity_key, 0, render::kMaxIsovalues, 0, 1);
    if (values.size() != surfaces.size()) r.fail(opacity, opacity_key, "give one per isovalue");
    for (std::size_t k = 0; k < values.size(); ++k)
      surfaces[k].opacity = static_cast<float>(values[k]);
    // The cap pass fills the opaque image's pixels; layered scenes composite fragments instead.
    if (!spec.cap.field.empty() && render::has_transparency(surfaces))
      r.fail(opacity, opacity_key, "a transparent surface cannot be combined with clip.cap");
  }
  if (const YAML::Node layers = scene["max_layers"]) {
    spec.max_layers =
        static_cast<int>(r.integer_in(layers, child_key(key, "max_layers"), 1, render::kMaxLayers));
  }
}

void parse_shading(const YamlReader& r, const YAML::Node& scene, const std::string& key,
                   ShadingSpec& spec) {
  if (const YAML::Node shading = scene["shading"]) {
    spec.smooth = r.choice(shading, child_key(key, "shading"), {"smooth", "flat"}) == "smooth";
  }
  if (const YAML::Node clip = scene["clip"]) {
    if (clip["cap"] && scene["volume"]) {
      r.fail(clip["cap"], child_key(child_key(key, "clip"), "cap"),
             "not allowed in a volume scene (a cap cuts isosurface scenes)");
    }
    parse_clip(r, clip, child_key(key, "clip"), spec);
  }
}

}  // namespace tetray::config
