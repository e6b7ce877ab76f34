#include "adaptor/config/config_annotations.hpp"

namespace tetray::config {

Annotations parse_annotations(const YamlReader& r, const YAML::Node& node, const std::string& key,
                              const Scene& scene) {
  r.allow_keys(node, key, {"colorbar", "time", "title", "font"});
  Annotations a;
  if (node["colorbar"]) a.colorbar = r.boolean(node["colorbar"], child_key(key, "colorbar"));
  if (node["time"]) a.time = r.boolean(node["time"], child_key(key, "time"));
  if (node["title"]) a.title = r.string(node["title"], child_key(key, "title"));
  const bool colormapped =
      !scene.color_by.empty() || !scene.shading.cap.field.empty() || scene.volume.has_value();
  if (a.colorbar && !colormapped) {
    r.fail(node["colorbar"], child_key(key, "colorbar"),
           "needs color_by, a clip cap or a volume scene (a scene with one color per isovalue "
           "has no colormap to show)");
  }
  const std::string font_key = child_key(key, "font");
  const std::string path =
      node["font"] ? r.string(node["font"], font_key) : render::kDefaultFontPath;
  if (!a.colorbar && !a.time && a.title.empty()) return a;
  render::FontResult opened = render::Font::open(path);
  if (!opened.font) {
    r.fail(node["font"] ? node["font"] : node, node["font"] ? font_key : key,
           opened.error + (node["font"] ? "" : " (install fonts-dejavu-core or give font: PATH)"));
  }
  a.font = std::move(opened.font);
  return a;
}

}  // namespace tetray::config
