// The adaptor's configuration after validation (docs/architecture.md §4): everything the YAML can
// say, with defaults filled in. Parsing and validation live in config_parse.cpp; nothing here
// touches YAML, so the rest of the adaptor never sees a parse error.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config_shading.hpp"
#include "render/trace/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "render/volume/mesh_check.hpp"

namespace tetray::config {

// Limits of what a config may ask for, so that a mistake is a config error naming the limit and
// the memory it would need, not an allocation failure in the solver's process. A scene keeps
// its own image, about 60 bytes per pixel (config_parse.cpp): one image of the largest size
// needs about 16 GB, and all images together at most that much again.
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::size_t kMaxScenes = 256;
inline constexpr int kMaxThreads = 1024;  // the renderer's threads per rank
inline constexpr std::int64_t kMaxTotalPixels = std::int64_t{kMaxImageSide} * kMaxImageSide;
// A config is a few kB; a much larger text is a mistake (and its YAML tree alone costs memory).
inline constexpr std::size_t kMaxConfigBytes = 1 << 22;

// Render every `every_steps` steps, or each time the simulated time reaches the next multiple
// of `every_time` (exactly one of the two is set).
struct Trigger {
  std::int64_t every_steps = 1;
  double every_time = 0;  // > 0: time trigger
};

struct CameraSpec {
  bool auto_fit = false;
  render::Camera fixed{};                 // used when !auto_fit (width/height from the image)
  render::Vec3d view_direction{1, 1, 1};  // auto-fit: from the target towards the eye
  render::Vec3d up{0, 1, 0};              // auto-fit
  double fov_deg = 40;                    // auto-fit
};

struct ColorRange {
  bool automatic = true;  // global min/max of the color field at each rendered step
  float lo = 0, hi = 1;
};

struct Scene {
  std::string name;
  std::string field;
  std::vector<render::IsoSurface> surfaces;  // isovalues with their colors
  std::string color_by;                      // empty: per-isovalue colors
  std::string colormap_name = "viridis";
  ColorRange color_range{};
  CameraSpec camera{};
  int width = 1024, height = 1024;
  float background[4] = {0, 0, 0, 0};  // RGBA, put under the image (alpha 0: transparent)
  float ambient = 0.15f;               // of the headlight (the only light type)
  Trigger trigger{};
  ShadingSpec shading{};
};

struct Output {
  std::string directory = "tetray_out";
  bool exr = true;
  bool png = true;
  bool cinema = true;
  int png_compression = 1;  // zlib level 0..9, fast by default
  int queue_depth = 2;      // images waiting for the writer thread; 0 writes in execute
  bool quiet = false;
  int writer_rank = 0;  // receives the composited image; writes images, Cinema rows, the log
  bool per_rank_images = false;  // each rank also writes its own layer (debugging)
};

struct Config {
  std::string source;  // file name, or "<yaml string>", for messages
  Output output{};
  std::vector<Scene> scenes;
  render::UpdatePolicy bvh{};
  render::NonFinitePolicy nonfinite = render::NonFinitePolicy::error;
  int threads = 0;  // the renderer's threads on each rank; 0: default_thread_count()
};

}  // namespace tetray::config
