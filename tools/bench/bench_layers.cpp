#include "bench_layers.hpp"

#include <array>
#include <cstdio>
#include <functional>
#include <vector>

#include "bench_timing.hpp"
#include "render/trace/layer_shading.hpp"
#include "render/trace/shadow_rays.hpp"
#include "tools/bench_common/bench_scene.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::bench {
namespace {

// The bench surface and a second one beside it, both half transparent.
std::array<render::IsoSurface, 2> transparent_surfaces() {
  render::IsoSurface near = bench_surface(), far = bench_surface();
  far.value = near.value + 0.5f;
  far.color = {0.35f, 0.55f, 0.9f};
  near.opacity = far.opacity = 0.5f;
  return {near, far};
}

render::TraceOptions all_modalities() {
  render::TraceOptions options;
  options.lights.count = 2;
  options.lights.light[0] = {render::LightKind::headlight, {}, false};
  options.lights.light[1] = {render::LightKind::point, {3.0, 4.0, 2.0}, true};
  options.clip.has_box = true;
  options.clip.box_lo = {-2, -2, -2};
  options.clip.box_hi = {0, 2, 2};
  return options;
}

// One rank's frame of a transparent scene: the layers, each layer's shadows, the blend.
void layered_frame(const render::TetVolume& volume, const render::Bvh& bvh,
                   const render::Camera& camera, std::span<const render::IsoSurface> surfaces,
                   const render::TraceOptions& options, render::LayerImage& layers,
                   render::Framebuffer& image) {
  render::trace_layers(layers, volume, bvh, camera, surfaces, options);
  // As the adaptor does (render/parallel/scene_layers.cpp): the depths only for shadow rays.
  std::vector<float> depth(layers.shadow_terms.empty() ? 0 : layers.color.pixel_count());
  for (int layer = 0; !layers.shadow_terms.empty() && layer < options.max_layers; ++layer) {
    render::layer_view_depths(layers.color, camera, layer, depth);
    render::keep_lit_layer_points(layers.shadow_terms, layer, depth);
    const std::vector<std::uint8_t> occluded =
        render::trace_shadow_rays(volume, bvh, camera, surfaces, options, depth);
    render::apply_layer_shadows(layers.color, layers.shadow_terms, layer, occluded);
  }
  render::flatten_layers(layers.color, camera, image);
}

double per_ray(const render::LayerImage& layers) {
  return static_cast<double>(layers.color.fragments.size()) /
         static_cast<double>(layers.color.pixel_count());
}

}  // namespace

LayerFigures measure_layers(const GyroidTwist& scene, const render::Camera& camera) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  const render::IsoSurface surface = bench_surface();
  const std::array<render::IsoSurface, 2> transparent = transparent_surfaces();
  std::array<render::IsoSurface, 2> opaque_pair = transparent;
  for (render::IsoSurface& s : opaque_pair) s.opacity = 1;
  render::Framebuffer image;
  // One layer image per configuration, kept from frame to frame as a scene's is in situ: shared,
  // each frame would first regrow or shrink what the other configuration left.
  render::LayerImage plain_layers, all_layers;
  const render::TraceOptions plain{}, all = all_modalities();
  const auto plain_frame = [&] {
    return time_ms([&] { render::trace_into(image, volume, bvh, camera, {&surface, 1}, plain); });
  };
  const auto layered = [&](const render::TraceOptions& options, render::LayerImage& layers) {
    // The layer image by address: the frame outlives this call's reference parameter.
    return [&, options, target = &layers] {
      return time_ms(
          [&] { layered_frame(volume, bvh, camera, transparent, options, *target, image); });
    };
  };
  const auto opaque_pair_frame = [&] {
    return time_ms([&] { render::trace_into(image, volume, bvh, camera, opaque_pair, plain); });
  };
  // Warm-ups: the image and each layer image grown to their frames' sizes.
  plain_frame();
  layered(plain, plain_layers)();
  layered(all, all_layers)();
  const std::array<double, 4> best =
      best_in_turn_ms<4>(kRepetitions, {std::function<double()>(plain_frame),
                                        std::function<double()>(opaque_pair_frame),
                                        layered(plain, plain_layers), layered(all, all_layers)});
  LayerFigures figures{best[0], best[1], best[2], best[3], 0, 0};
  figures.layers_per_ray = per_ray(plain_layers);
  figures.all_layers_per_ray = per_ray(all_layers);
  return figures;
}

void print_layers(const LayerFigures& f) {
  std::printf(
      "  transparency   two surfaces at 4 layers %.1f ms (%.2fx, %.2f layers per ray; the same "
      "two opaque %.1f ms, %.2fx); with a shadowing point light and the half clip box %.1f ms "
      "(%.2fx, %.2f layers per ray)\n",
      f.transparent_ms, f.transparent_ms / f.plain_ms, f.layers_per_ray, f.opaque_pair_ms,
      f.opaque_pair_ms / f.plain_ms, f.all_ms, f.all_ms / f.plain_ms, f.all_layers_per_ray);
}

Json::Value layers_json(const LayerFigures& f) {
  Json::Value json;
  json["plain_ms"] = number(f.plain_ms);
  json["opaque_pair_ms"] = number(f.opaque_pair_ms);
  json["opaque_pair_ratio"] = number(f.opaque_pair_ms / f.plain_ms);
  json["transparent_ms"] = number(f.transparent_ms);
  json["transparent_ratio"] = number(f.transparent_ms / f.plain_ms);
  json["transparent_layers_per_ray"] = number(f.layers_per_ray);
  json["all_modalities_ms"] = number(f.all_ms);
  json["all_modalities_ratio"] = number(f.all_ms / f.plain_ms);
  json["all_modalities_layers_per_ray"] = number(f.all_layers_per_ray);
  return json;
}

}  // namespace tetray::bench
