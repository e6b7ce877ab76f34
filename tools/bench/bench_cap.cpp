#include "bench_cap.hpp"

#include <array>
#include <cstdio>
#include <functional>
#include <vector>

#include "bench_timing.hpp"
#include "render/scene/colormap.hpp"
#include "render/walk/clip_cap.hpp"
#include "tools/bench_common/bench_scene.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::bench {
namespace {

// Cuts away the half of the volume towards the eye, so that the cap covers much of the image.
render::TraceOptions with_plane_facing(const render::Camera& camera) {
  render::TraceOptions options;
  options.clip.plane_count = 1;
  options.clip.planes[0] = {camera.look_at, camera.eye - camera.look_at};
  return options;
}

}  // namespace

CapFigures measure_cap(const GyroidTwist& scene, const render::Camera& camera) {
  render::TetVolume volume;
  render::Bvh bvh;
  render::UpdatePolicy policy;  // the adaptor's leaves for a volume with a cap
  policy.build.leaf_size = render::kPointLocationLeafSize;
  load_scene(scene, volume, bvh, policy);
  std::vector<float> field;
  render::load_vertex_field(
      volume, {scene.field.data(), render::ScalarKind::f64, scene.field.size()}, field);
  const render::ClipCap cap{render::find_colormap("viridis"), -2, 2, field};
  // As the adaptor: the face adjacency of the volume, built once per topology.
  const render::FaceAdjacency<render::Tet20> adjacency =
      render::build_face_adjacency<render::Tet20>(volume);
  const render::IsoSurface surface = bench_surface();
  const std::span<const render::IsoSurface> surfaces{&surface, 1};
  const render::TraceOptions plain{}, clipped = with_plane_facing(camera);
  render::Framebuffer image, uncapped;
  const auto frame = [&](const render::TraceOptions& options, bool capped) {
    return std::function<double()>([&, options, capped] {
      return time_ms([&] {
        render::trace_into(image, volume, bvh, camera, surfaces, options);
        if (capped)
          render::draw_clip_cap(image, volume, bvh, camera, options, cap, nullptr, &adjacency);
      });
    });
  };
  frame(plain, false)();  // warm-up
  const std::array<double, 3> best = best_in_turn_ms<3>(
      kRepetitions, {frame(plain, false), frame(clipped, false), frame(clipped, true)});
  CapFigures figures{best[0], best[1], best[2], 0};
  render::trace_into(uncapped, volume, bvh, camera, surfaces, clipped);
  frame(clipped, true)();
  std::size_t capped = 0;
  for (std::size_t p = 0; p < image.pixel_count(); ++p)
    capped += image.depth[p] != uncapped.depth[p] || image.hit[p] != uncapped.hit[p];
  figures.cap_fraction = static_cast<double>(capped) / static_cast<double>(image.pixel_count());
  return figures;
}

void print_cap(const CapFigures& f) {
  std::printf(
      "  clip cap       plain %.1f ms; a plane cutting half %.1f ms (%.2fx); with its cap %.1f ms "
      "(%.2fx, %.0f%% of the pixels on the cap)\n",
      f.plain_ms, f.clip_ms, f.clip_ms / f.plain_ms, f.cap_ms, f.cap_ms / f.plain_ms,
      100 * f.cap_fraction);
}

Json::Value cap_json(const CapFigures& f) {
  Json::Value json;
  json["plain_ms"] = number(f.plain_ms);
  json["clip_plane_ms"] = number(f.clip_ms);
  json["clip_plane_ratio"] = number(f.clip_ms / f.plain_ms);
  json["cap_ms"] = number(f.cap_ms);
  json["cap_ratio"] = number(f.cap_ms / f.plain_ms);
  json["cap_fraction"] = number(f.cap_fraction);
  return json;
}

}  // namespace tetray::bench
