// The adaptor's configuration after validation (docs/config.md): everything the YAML can
// say, with defaults filled in. Parsing and validation live in config_parse.cpp; nothing here
// touches YAML, so the rest of the adaptor never sees a parse error.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/image/image_write.hpp"
#include "render/image/movie_writer.hpp"

#include "adaptor/config/config_shading.hpp"
#include "render/annotate/font.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "render/volume/mesh_check.hpp"
#include "render/walk/transfer_function.hpp"

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

// Drawn on the written image (render/annotate); the font is opened when the config is read and
// null when nothing is to be drawn.
struct Annotations {
  bool colorbar = false;  // the colormap with the color_by field's name and ticks
  bool time = false;      // a caption: scene name, step, simulated time
  std::string title;      // empty: none
  std::shared_ptr<const render::Font> font;
};

// The views of a scene at each rendered step: its camera orbited about look_at by every azimuth
// (Cinema's phi: about the camera's up vector) and elevation (theta: towards up), in degrees.
// Without an `orbit` key, the one view is the camera as given.
struct Orbit {
  bool enabled = false;
  std::vector<double> azimuth_deg{0};
  std::vector<double> elevation_deg{0};
};

// An explicit camera at a simulated time: one point of a scene's `camera_path` (config_views.cpp).
struct Keyframe {
  double time = 0;
  render::Camera camera{};
};

// Direct volume rendering of the scene's field (adaptor/config/config_volume.cpp,
// docs/architecture.md §8): a colormap over a value range and opacity points, per unit distance.
struct VolumeSpec {
  std::string colormap_name = "viridis";
  ColorRange range{};                         // automatic: the field's global range each step
  std::vector<render::OpacityPoint> opacity;  // ascending values
  double unit_distance = 1;
  double termination = 1;  // opacity that ends a ray; 1: no early termination (exact across ranks)
  // The field of the scene's isosurfaces met along the walk (Scene::surfaces, the `surfaces`
  // key); empty: the scene's field.
  std::string surface_field;
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
  Annotations annotations{};
  Orbit orbit{};
  std::vector<Keyframe> keyframes;   // strictly increasing times; empty: the camera as given
  std::optional<VolumeSpec> volume;  // a volume scene: its surfaces are layers along the walk
  ShadingSpec shading{};
  float lod_node_pixels = 0;  // level of detail (config_lod.hpp); 0: exact images
};

struct Output {
  std::string directory = "tetray_out";
  bool exr = true;
  bool png = true;
  bool cinema = true;
  int png_compression = 1;  // deflate level 0..12, fast by default (config_output.cpp)
  render::ExrCompression exr_compression = render::EncodeOptions{}.exr_compression;
  int writer_threads = 0;  // encoding threads on the writer rank; 0: writer_thread_share
  bool mp4 = false;        // a movie per scene, its frames the images written
  render::MovieOptions movie{};
  int queue_depth = 2;  // images waiting for the writer thread; 0 writes in execute
  bool quiet = false;
  int writer_rank = 0;  // receives the composited image; writes images, Cinema rows, the log
  bool per_rank_images = false;  // each rank also writes its own layer (debugging)
};

// Points where fields are sampled at every rendered step, independent of the scenes: the
// points given and the lines' samples, in the order of the config (adaptor/step/probes.hpp).
struct ProbeSet {
  std::string name;                 // names the CSV file
  std::vector<std::string> fields;  // sampled at each point
  std::vector<render::Vec3d> points;
};

struct Config {
  std::string source;  // file name, or "<yaml string>", for messages
  Output output{};
  std::vector<Scene> scenes;
  render::UpdatePolicy bvh{};
  bool bvh_leaf_size_given =
      false;  // else each volume's leaves follow its scenes (step/update.cpp)
  render::NonFinitePolicy nonfinite = render::NonFinitePolicy::error;
  int threads = 0;  // the renderer's threads on each rank; 0: default_thread_count()
  std::vector<ProbeSet> probes;
};

}  // namespace tetray::config
