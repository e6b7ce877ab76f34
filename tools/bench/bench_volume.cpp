#include "bench_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "bench_timing.hpp"
#include "bench_walk.hpp"
#include "render/core/fragments.hpp"
#include "tools/bench_common/bench_scene.hpp"
#include "tools/bench_common/image_error.hpp"

namespace tetray::bench {
namespace {

constexpr std::array<float, 3> kShellValues = {-0.6f, 0.0f, 0.6f};
constexpr double kShellHalfWidth = 0.15;  // 5% of the field's range [-1.5, 1.5], as the demo's

struct Frame {
  double ms = 0;
  render::VolumeRenderStats stats;
  render::Framebuffer image;
};

Frame volume_frame(const render::TetVolume& volume, const render::WalkStructure& walk,
                   const render::Camera& camera, const render::VolumeRenderOptions& options) {
  Frame frame;
  render::VolumeFragmentImage fragments;  // the last timed frame's, resolved once
  frame.ms = best_of_ms(kRepetitions, [&] {
    return time_ms(
        [&] { fragments = render::render_volume(volume, walk, camera, options, &frame.stats); });
  });
  frame.image = render::resolve(fragments);
  return frame;
}

VolumeCase measure_case(const render::TetVolume& volume, const render::Bvh& bvh,
                        const render::WalkStructure& walk, const render::Camera& camera,
                        render::VolumeRenderOptions options, int threads) {
  options.bvh = &bvh;
  const Frame skipping = volume_frame(volume, walk, camera, options);
  options.bvh = nullptr;
  const Frame all = volume_frame(volume, walk, camera, options);
  VolumeCase c;
  c.ms = skipping.ms;
  c.walk_all_ms = all.ms;
  c.mtet_steps_per_core =
      static_cast<double>(skipping.stats.tets_visited) / (skipping.ms * 1e3 * threads);
  c.busy_fraction = static_cast<double>(skipping.stats.busy_tets) /
                    static_cast<double>(std::max<std::size_t>(1, volume.tets.size()));
  c.jumps_per_ray = static_cast<double>(skipping.stats.jumps) /
                    static_cast<double>(std::max<std::uint64_t>(1, skipping.stats.rays));
  c.max_difference = image_error(all.image, skipping.image, camera).color_max;
  const auto per_ray = [](const render::VolumeRenderStats& stats) {
    return static_cast<double>(stats.tets_visited) /
           static_cast<double>(std::max<std::uint64_t>(1, stats.rays));
  };
  c.tets_per_ray = per_ray(skipping.stats);
  c.walk_all_tets_per_ray = per_ray(all.stats);
  return c;
}

void print_case(const char* name, const VolumeCase& c) {
  std::printf("  %-8s %10.1f %12.1f %12.1f %8.1f%% %10.2f %9.1f %9.1f %12.1e\n", name, c.ms,
              c.walk_all_ms, c.mtet_steps_per_core, 100 * c.busy_fraction, c.jumps_per_ray,
              c.tets_per_ray, c.walk_all_tets_per_ray, c.max_difference);
}

Json::Value case_json(const VolumeCase& c) {
  Json::Value v;
  v["ms"] = c.ms;
  v["walk_all_ms"] = c.walk_all_ms;
  v["mtet_steps_per_s_per_core"] = c.mtet_steps_per_core;
  v["busy_fraction"] = c.busy_fraction;
  v["jumps_per_ray"] = c.jumps_per_ray;
  v["tets_per_ray"] = c.tets_per_ray;
  v["walk_all_tets_per_ray"] = c.walk_all_tets_per_ray;
  v["max_difference_to_walk_all"] = c.max_difference;
  return v;
}

}  // namespace

render::VolumeRenderOptions shell_options() {
  render::VolumeRenderOptions options;
  options.transfer = {render::find_colormap("viridis"), -1.5, 1.5, {}, 0.5};
  for (const float v : kShellValues) {
    options.transfer.opacity.push_back({v - kShellHalfWidth, 0});
    options.transfer.opacity.push_back({v, 3});
    options.transfer.opacity.push_back({v + kShellHalfWidth, 0});
  }
  options.termination = 1;
  return options;
}

render::VolumeRenderOptions sparse_options() {
  render::VolumeRenderOptions options = shell_options();
  options.transfer.opacity = {{1.2, 0}, {1.35, 3}, {1.5, 0}};
  return options;
}

render::VolumeRenderOptions dense_options() { return dvr_options(1.0); }

VolumeFigures measure_volume(const GyroidTwist& scene, const render::Camera& camera, int threads) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  const render::WalkStructure walk = render::build_walk_structure(volume);
  VolumeFigures figures;
  figures.threads = threads;
  std::vector<render::IsoSurface> surfaces;
  for (const float v : kShellValues) surfaces.push_back({v, {0.9f, 0.75f, 0.45f}});
  render::Framebuffer image;
  figures.iso_ms = best_of_ms(kRepetitions, [&] {
    return time_ms([&] { render::trace_into(image, volume, bvh, camera, surfaces, {}); });
  });
  figures.shells = measure_case(volume, bvh, walk, camera, shell_options(), threads);
  figures.dense = measure_case(volume, bvh, walk, camera, dense_options(), threads);
  figures.sparse = measure_case(volume, bvh, walk, camera, sparse_options(), threads);
  return figures;
}

void print_volume(const VolumeFigures& f) {
  std::printf(
      "volume rendering (exact integral, no early termination; isosurfaces at the shells' "
      "values %.1f ms):\n",
      f.iso_ms);
  std::printf("  %-8s %10s %12s %12s %9s %10s %9s %9s %12s\n", "transfer", "ms", "walk-all ms",
              "Mtets/s/core", "busy", "jumps/ray", "tets/ray", "(all)", "max diff");
  print_case("shells", f.shells);
  print_case("dense", f.dense);
  print_case("sparse", f.sparse);
}

Json::Value volume_json(const VolumeFigures& f) {
  Json::Value json;
  json["iso_ms"] = f.iso_ms;
  json["shells"] = case_json(f.shells);
  json["dense"] = case_json(f.dense);
  json["sparse"] = case_json(f.sparse);
  return json;
}

}  // namespace tetray::bench
