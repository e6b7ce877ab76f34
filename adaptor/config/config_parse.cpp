#include "adaptor/config/config_parse.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "adaptor/config/config_output.hpp"

#include "adaptor/config/camera_path.hpp"
#include "adaptor/config/config_annotations.hpp"
#include "adaptor/config/config_colormap_parse.hpp"
#include "adaptor/config/config_lod.hpp"
#include "adaptor/config/config_probes.hpp"
#include "adaptor/config/config_shading_parse.hpp"
#include "adaptor/config/config_views.hpp"
#include "adaptor/config/config_volume.hpp"
#include "adaptor/config/yaml_reader.hpp"
#include "render/scene/iso_palette.hpp"

namespace tetray::config {
namespace {

render::Vec3d vec3(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  const auto v = r.numbers(node, key, 3, 3);
  return {v[0], v[1], v[2]};
}

// A point of the scene (camera eye, look_at): within the renderer's coordinate range.
render::Vec3d position(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  const auto v = r.numbers_in(node, key, 3, 3, -render::kMaxCoordinate, render::kMaxCoordinate);
  return {v[0], v[1], v[2]};
}

// A direction (up, view_direction) as a unit vector, whatever its scale.
render::Vec3d direction(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  const render::Vec3d v = render::unit_direction(vec3(r, node, key));
  if (dot(v, v) == 0) r.fail(node, key, "must not be the zero vector");
  return v;
}

Trigger parse_trigger(const YamlReader& r, const YAML::Node& node, std::string_view key) {
  r.allow_keys(node, key, {"every", "every_time"});
  const bool steps = static_cast<bool>(node["every"]);
  const bool time = static_cast<bool>(node["every_time"]);
  if (steps == time) r.fail(node, key, "give exactly one of every (steps) or every_time");
  Trigger t;
  if (steps) t.every_steps = r.integer_in(node["every"], child_key(key, "every"), 1, 1'000'000'000);
  if (time) {
    t.every_time = r.number(node["every_time"], child_key(key, "every_time"));
    if (t.every_time <= 0) r.fail(node["every_time"], child_key(key, "every_time"), "must be > 0");
  }
  return t;
}

int parse_writer_rank(const YamlReader& r, const YAML::Node& node, int rank_count) {
  const auto rank = r.integer_in(node, "output.writer_rank", 0, 1'000'000'000);
  if (rank >= rank_count) {
    r.fail(node, "output.writer_rank",
           "rank " + std::to_string(rank) + " does not exist: the communicator has " +
               std::to_string(rank_count) + " rank(s)");
  }
  return static_cast<int>(rank);
}

Output parse_output(const YamlReader& r, const YAML::Node& node, int rank_count) {
  const std::string key = "output";
  r.allow_keys(node, key,
               {"directory", "formats", "cinema", "png_compression", "writer_queue_depth", "quiet",
                "writer_rank", "per_rank_images", "exr_compression", "writer_threads", "movie"});
  Output out;
  if (node["directory"]) out.directory = r.string(node["directory"], "output.directory");
  if (const YAML::Node formats = node["formats"]) {
    r.expect_list(formats, "output.formats");
    if (formats.size() == 0) r.fail(formats, "output.formats", "name at least one of exr, png");
    out.exr = out.png = false;
    for (std::size_t i = 0; i < formats.size(); ++i) {
      const std::string f =
          r.choice(formats[i], item_key("output.formats", i), {"exr", "png", "mp4"});
      (f == "exr" ? out.exr : f == "png" ? out.png : out.mp4) = true;
    }
  }
  if (node["cinema"]) out.cinema = r.boolean(node["cinema"], "output.cinema");
  parse_encoding(r, node, out);
  if (node["writer_queue_depth"]) {
    out.queue_depth = static_cast<int>(
        r.integer_in(node["writer_queue_depth"], "output.writer_queue_depth", 0, 64));
  }
  if (node["quiet"]) out.quiet = r.boolean(node["quiet"], "output.quiet");
  if (node["writer_rank"]) out.writer_rank = parse_writer_rank(r, node["writer_rank"], rank_count);
  if (node["per_rank_images"]) {
    out.per_rank_images = r.boolean(node["per_rank_images"], "output.per_rank_images");
  }
  return out;
}

render::UpdatePolicy parse_bvh(const YamlReader& r, const YAML::Node& node) {
  r.allow_keys(node, "bvh", {"builder", "leaf_size", "rebuild_ratio"});
  render::UpdatePolicy policy;
  if (node["builder"]) {
    policy.build.builder = r.choice(node["builder"], "bvh.builder", {"bih", "sah"}) == "sah"
                               ? render::BvhBuilder::sah
                               : render::BvhBuilder::bih;
  }
  if (node["leaf_size"]) {
    policy.build.leaf_size =
        static_cast<int>(r.integer_in(node["leaf_size"], "bvh.leaf_size", 1, render::kMaxLeafSize));
  }
  if (node["rebuild_ratio"]) {
    policy.rebuild_ratio = r.number_in(node["rebuild_ratio"], "bvh.rebuild_ratio", 1.0, 1e6);
  }
  return policy;
}

}  // namespace

CameraSpec parse_camera(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  r.allow_keys(node, key, {"eye", "look_at", "up", "fov_deg", "auto_fit", "view_direction"});
  CameraSpec cam;
  cam.auto_fit =
      node["auto_fit"] ? r.boolean(node["auto_fit"], child_key(key, "auto_fit")) : !node["eye"];
  if (node["fov_deg"])
    cam.fov_deg = r.number_in(node["fov_deg"], child_key(key, "fov_deg"), render::kMinFovDeg,
                              render::kMaxFovDeg);
  if (node["up"]) cam.up = direction(r, node["up"], child_key(key, "up"));
  if (cam.auto_fit) {
    for (const char* k : {"eye", "look_at"}) {
      if (node[k])
        r.fail(node[k], child_key(key, k), "not allowed with auto_fit (give view_direction)");
    }
    if (node["view_direction"]) {
      cam.view_direction = direction(r, node["view_direction"], child_key(key, "view_direction"));
    }
    // The fitted camera looks along view_direction: checked as a camera at that side.
    const render::Camera fitted{cam.view_direction, {0, 0, 0}, cam.up, cam.fov_deg};
    if (std::string problem = render::camera_problem(fitted); !problem.empty()) {
      r.fail(node, key, problem);
    }
    return cam;
  }
  if (node["view_direction"]) {
    r.fail(node["view_direction"], child_key(key, "view_direction"), "needs auto_fit: true");
  }
  if (!node["eye"] || !node["look_at"])
    r.fail(node, key, "an explicit camera needs eye and look_at");
  cam.fixed.eye = position(r, node["eye"], child_key(key, "eye"));
  cam.fixed.look_at = position(r, node["look_at"], child_key(key, "look_at"));
  cam.fixed.up = cam.up;
  cam.fixed.fov_deg = cam.fov_deg;
  if (std::string problem = render::camera_problem(cam.fixed); !problem.empty()) {
    r.fail(node, key, problem);
  }
  return cam;
}

namespace {

// The memory a scene's image costs, per pixel: the framebuffer (RGBA and depth floats and a hit
// key: 24 B), the composited copy waiting for the writer (24 B) and its encoded file (at most
// 12 B for EXR half RGBA and float Z).
constexpr double kBytesPerPixel = 60;

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

std::string image_memory(double pixels) {
  return "about " + gigabytes(pixels * kBytesPerPixel) + " at " +
         std::to_string(static_cast<int>(kBytesPerPixel)) + " bytes per pixel";
}

// A side outside [1, kMaxImageSide]; a too large one names the memory of the whole image.
void check_image_side(const YamlReader& r, const YAML::Node& node, const std::string& key,
                      std::int64_t side, std::int64_t width, std::int64_t height) {
  if (side >= 1 && side <= kMaxImageSide) return;
  std::string what =
      "value " + std::to_string(side) + " is outside [1, " + std::to_string(kMaxImageSide) + "]";
  if (side > kMaxImageSide) {
    what += "; a " + std::to_string(width) + " x " + std::to_string(height) + " image would need " +
            image_memory(static_cast<double>(width) * static_cast<double>(height));
  }
  r.fail(node, key, what);
}

void parse_image(const YamlReader& r, const YAML::Node& node, const std::string& key, Scene& s) {
  r.allow_keys(node, key, {"width", "height"});
  const std::string width_key = child_key(key, "width"), height_key = child_key(key, "height");
  const std::int64_t width = node["width"] ? r.integer(node["width"], width_key) : s.width;
  const std::int64_t height = node["height"] ? r.integer(node["height"], height_key) : s.height;
  if (node["width"]) check_image_side(r, node["width"], width_key, width, width, height);
  if (node["height"]) check_image_side(r, node["height"], height_key, height, width, height);
  s.width = static_cast<int>(width);
  s.height = static_cast<int>(height);
}

void parse_surfaces(const YamlReader& r, const YAML::Node& node, const std::string& key, Scene& s) {
  const auto values = r.numbers_in(node["isovalues"], child_key(key, "isovalues"), 1,
                                   static_cast<std::size_t>(render::kMaxIsovalues),
                                   -render::kMaxFieldValue, render::kMaxFieldValue);
  const YAML::Node colors = node["colors"];
  if (colors) {
    r.expect_list(colors, child_key(key, "colors"));
    if (colors.size() != values.size()) {
      r.fail(colors, child_key(key, "colors"), "give one color per isovalue");
    }
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    render::IsoSurface surface;
    surface.value = static_cast<float>(values[i]);
    surface.color = render::default_iso_color(i);
    if (colors) {
      const auto c = r.numbers(colors[i], item_key(child_key(key, "colors"), i), 3, 3);
      for (std::size_t a = 0; a < 3; ++a) {
        if (c[a] < 0 || c[a] > 1)
          r.fail(colors[i], item_key(child_key(key, "colors"), i), "components must lie in [0, 1]");
      }
      surface.color = {static_cast<float>(c[0]), static_cast<float>(c[1]),
                       static_cast<float>(c[2])};
    }
    s.surfaces.push_back(surface);
  }
}

// A volume scene's isosurfaces, layers along the walk (render/walk/surface_crossing.hpp): the
// keys of an isosurface scene (isovalues, colors, opacity) and the field they are of.
void parse_volume_surfaces(const YamlReader& r, const YAML::Node& node, const std::string& key,
                           Scene& s) {
  r.expect_map(node, key);
  r.allow_keys(node, key, {"field", "isovalues", "colors", "opacity"});
  if (!node["isovalues"]) r.fail(node, child_key(key, "isovalues"), "missing (required)");
  if (node["field"]) {
    const std::string field = r.string(node["field"], child_key(key, "field"));
    if (field != s.field) s.volume->surface_field = field;
  }
  parse_surfaces(r, node, key, s);
  parse_layers(r, node, key, s.surfaces, s.shading);
}

void parse_coloring(const YamlReader& r, const YAML::Node& node, const std::string& key, Scene& s) {
  if (!node["color_by"]) {
    for (const char* k : {"colormap", "color_range"}) {
      if (node[k]) r.fail(node[k], child_key(key, k), "needs color_by");
    }
    return;
  }
  if (node["colors"]) r.fail(node["colors"], child_key(key, "colors"), "not allowed with color_by");
  s.color_by = r.string(node["color_by"], child_key(key, "color_by"));
  if (node["colormap"])
    s.colormap_name = parse_colormap_name(r, node["colormap"], child_key(key, "colormap"));
  if (node["color_range"])
    s.color_range = parse_color_range(r, node["color_range"], child_key(key, "color_range"));
}

void parse_background(const YamlReader& r, const YAML::Node& node, const std::string& key,
                      Scene& s) {
  const auto c = r.numbers(node, key, 3, 4);
  for (std::size_t a = 0; a < c.size(); ++a) {
    if (c[a] < 0 || c[a] > 1) r.fail(node, key, "components must lie in [0, 1]");
    s.background[a] = static_cast<float>(c[a]);
  }
  if (c.size() == 3) s.background[3] = 1;
}

bool valid_scene_name(const std::string& name) {
  for (char ch : name) {
    const bool ok =
        std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.';
    if (!ok) return false;
  }
  return name.front() != '.';
}

Scene parse_scene(const YamlReader& r, const YAML::Node& node, const std::string& key,
                  const Trigger& default_trigger) {
  r.allow_keys(node, key,
               {"name",        "field",   "isovalues",  "colors",     "color_by", "colormap",
                "color_range", "camera",  "image",      "background", "lights",   "trigger",
                "annotations", "orbit",   "volume",     "shading",    "clip",     "lod",
                "camera_path", "opacity", "max_layers", "surfaces"});
  Scene s;
  for (const char* k : {"name", "field"}) {
    if (!node[k]) r.fail(node, child_key(key, k), "missing (required)");
  }
  s.name = r.string(node["name"], child_key(key, "name"));
  if (!valid_scene_name(s.name)) {
    r.fail(node["name"], child_key(key, "name"),
           "use only letters, digits, '_', '-' and '.' (it names files)");
  }
  s.field = r.string(node["field"], child_key(key, "field"));
  if (node["volume"]) {
    parse_volume_scene(r, node, key, s);
    if (node["surfaces"]) parse_volume_surfaces(r, node["surfaces"], child_key(key, "surfaces"), s);
  } else {
    if (node["surfaces"]) {
      r.fail(node["surfaces"], child_key(key, "surfaces"),
             "needs volume (an isosurface scene lists its isovalues itself)");
    }
    if (!node["isovalues"]) r.fail(node, child_key(key, "isovalues"), "missing (required)");
    parse_surfaces(r, node, key, s);
    parse_coloring(r, node, key, s);
  }
  if (node["image"]) parse_image(r, node["image"], child_key(key, "image"), s);
  if (node["camera"]) s.camera = parse_camera(r, node["camera"], child_key(key, "camera"));
  s.camera.auto_fit = s.camera.auto_fit || !node["camera"];
  if (node["background"]) parse_background(r, node["background"], child_key(key, "background"), s);
  if (node["lights"])
    parse_lights(r, node["lights"], child_key(key, "lights"), s.ambient, s.shading);
  parse_shading(r, node, key, s.shading);
  parse_layers(r, node, key, s.surfaces, s.shading);
  if (node["annotations"]) {
    s.annotations = parse_annotations(r, node["annotations"], child_key(key, "annotations"), s);
  }
  if (node["orbit"]) s.orbit = parse_orbit(r, node["orbit"], child_key(key, "orbit"), s);
  if (node["lod"]) {
    if (node["volume"])
      r.fail(node["lod"], child_key(key, "lod"), "applies to isosurfaces, not to volume scenes");
    s.lod_node_pixels = parse_lod(r, node["lod"], child_key(key, "lod"));
  }
  if (node["camera_path"]) s.keyframes = parse_camera_path(r, node, key);
  s.trigger = node["trigger"] ? parse_trigger(r, node["trigger"], child_key(key, "trigger"))
                              : default_trigger;
  return s;
}

// Every scene keeps its own image per view: together they must stay within kMaxTotalPixels.
void check_total_pixels(const YamlReader& r, const YAML::Node& node,
                        const std::vector<Scene>& scenes) {
  double pixels = 0;
  for (const Scene& s : scenes) {
    pixels +=
        static_cast<double>(s.width) * s.height * static_cast<double>(orbit_views(s.orbit).size());
  }
  if (pixels <= static_cast<double>(kMaxTotalPixels)) return;
  r.fail(node, "scenes",
         "the scenes' images hold " + std::to_string(static_cast<std::int64_t>(pixels)) +
             " pixels together, more than the limit of " + std::to_string(kMaxTotalPixels) + " (" +
             std::to_string(kMaxImageSide) + " x " + std::to_string(kMaxImageSide) +
             "); they would need " + image_memory(pixels));
}

Config parse_root(const YamlReader& r, const YAML::Node& root, const std::string& source,
                  int rank_count) {
  r.allow_keys(root, "", {"output", "trigger", "scenes", "bvh", "nonfinite", "threads", "probes"});
  Config config;
  config.source = source;
  if (root["output"]) config.output = parse_output(r, root["output"], rank_count);
  const Trigger default_trigger =
      root["trigger"] ? parse_trigger(r, root["trigger"], "trigger") : Trigger{};
  if (root["bvh"]) {
    config.bvh = parse_bvh(r, root["bvh"]);
    config.bvh_leaf_size_given = static_cast<bool>(root["bvh"]["leaf_size"]);
  }
  if (root["threads"]) {
    config.threads = static_cast<int>(r.integer_in(root["threads"], "threads", 1, kMaxThreads));
  }
  if (root["nonfinite"]) {
    config.nonfinite =
        r.choice(root["nonfinite"], "nonfinite", {"error", "skip_tets"}) == "skip_tets"
            ? render::NonFinitePolicy::skip_tets
            : render::NonFinitePolicy::error;
  }
  const YAML::Node scenes = root["scenes"];
  if (!scenes) r.fail(root, "scenes", "missing (required): list at least one scene");
  r.expect_list(scenes, "scenes");
  if (scenes.size() == 0) r.fail(scenes, "scenes", "list at least one scene");
  if (scenes.size() > kMaxScenes) {
    r.fail(scenes, "scenes",
           std::to_string(scenes.size()) + " scenes exceed the limit of " +
               std::to_string(kMaxScenes) + "; their default 1024 x 1024 images alone would need " +
               image_memory(static_cast<double>(scenes.size()) * 1024 * 1024));
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string key = item_key("scenes", i);
    config.scenes.push_back(parse_scene(r, scenes[i], key, default_trigger));
    if (!names.insert(config.scenes.back().name).second) {
      r.fail(scenes[i]["name"], child_key(key, "name"), "duplicate scene name");
    }
  }
  check_total_pixels(r, scenes, config.scenes);
  if (root["probes"]) config.probes = parse_probes(r, root["probes"]);
  return config;
}

}  // namespace

ParseResult parse_config(std::string_view yaml, const std::string& source, int rank_count) {
  ParseResult result;
  if (yaml.size() > kMaxConfigBytes) {
    result.error = source + ": the config is " + std::to_string(yaml.size()) +
                   " bytes, more than the limit of " + std::to_string(kMaxConfigBytes) + " bytes";
    return result;
  }
  try {
    const YAML::Node root = YAML::Load(std::string(yaml));
    YamlReader reader(source);
    if (!root.IsMap())
      reader.fail(root, "(document)", "expected a map with output, trigger, scenes, bvh");
    result.config = parse_root(reader, root, source, rank_count);
  } catch (const LocatedError& e) {
    result.error = e.what();
  } catch (const YAML::Exception& e) {
    result.error = source + ":" + std::to_string(e.mark.line + 1) + ":" +
                   std::to_string(e.mark.column + 1) + ": YAML syntax: " + e.msg;
  } catch (const std::exception& e) {
    result.error = source + ": " + e.what();
  }
  return result;
}

ParseResult load_config_file(const std::string& path, int rank_count) {
  std::ifstream in(path);
  if (!in) return {std::nullopt, path + ": cannot open the config file"};
  std::ostringstream text;
  text << in.rdbuf();
  return parse_config(text.str(), path, rank_count);
}

}  // namespace tetray::config
