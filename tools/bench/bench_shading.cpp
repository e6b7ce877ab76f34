#include "bench_shading.hpp"

#include <array>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

#include "bench_timing.hpp"
#include "render/trace/shadow_rays.hpp"
#include "render/update/vertex_gradients.hpp"
#include "tools/bench_common/bench_scene.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::bench {
namespace {

render::TraceOptions with_point_light() {
  render::TraceOptions options;
  options.lights.count = 2;
  options.lights.light[0] = {render::LightKind::headlight, {}, false};
  options.lights.light[1] = {render::LightKind::point, {3.0, 4.0, 2.0}, true};
  return options;
}

render::TraceOptions with_half_clipped() {
  render::TraceOptions options;
  options.clip.has_box = true;
  options.clip.box_lo = {-2, -2, -2};
  options.clip.box_hi = {0, 2, 2};
  return options;
}

}  // namespace

ShadingFigures measure_shading(const GyroidTwist& scene, const render::Camera& camera) {
  render::TetVolume volume;
  render::Bvh bvh;
  render::UpdatePolicy policy;
  policy.vertex_gradients = true;  // for the smooth frame; the others do not read them
  load_scene(scene, volume, bvh, policy);
  const render::IsoSurface surface = bench_surface();
  const std::span<const render::IsoSurface> surfaces{&surface, 1};
  render::Framebuffer image;
  std::vector<render::Framebuffer> terms;
  std::vector<std::uint8_t> occluded;
  const render::TraceOptions plain{}, lit = with_point_light(), clipped = with_half_clipped();
  render::TraceOptions smooth;
  smooth.smooth = true;
  const auto frame = [&](const render::TraceOptions& options) {
    return [&, options] {
      return time_ms([&] { render::trace_into(image, volume, bvh, camera, surfaces, options); });
    };
  };
  const auto shadowed_frame = [&] {
    return time_ms([&] {
      render::trace_into(image, volume, bvh, camera, surfaces, lit, nullptr, &terms);
      occluded = render::trace_shadow_rays(volume, bvh, camera, surfaces, lit,
                                           render::shadow_ray_depths(image, terms));
      render::apply_shadows(image, terms, occluded);
    });
  };
  // As the adaptor computes them for this scene: at the corners of the tets its surface crosses.
  const float isovalue = surface.value;
  const auto gradients = [&] {
    return time_ms([&] { render::compute_vertex_gradients(volume, {&isovalue, 1}); });
  };
  std::vector<double> points, field;
  deform_gyroid_twist(scene.mesh, kTimeStep, points, field);
  const auto step_update = [&] {
    return time_ms([&] {
      render::update_volume(volume, bvh, point_source(points), field_source(field), {true, true},
                            {});
    });
  };
  step_update();  // every figure on the new step, its gradients current
  gradients();
  frame(plain)();  // warm-up
  const std::array<double, 6> best = best_in_turn_ms<6>(
      kRepetitions,
      {frame(plain), std::function<double()>(shadowed_frame), frame(clipped), frame(smooth),
       std::function<double()>(gradients), std::function<double()>(step_update)});
  ShadingFigures figures{best[0], best[1], best[2], best[3], best[4], best[5], 0, 0};
  std::size_t hits = 0, reached = 0, shadowed = 0;
  shadowed_frame();
  const std::vector<float> traced = render::shadow_ray_depths(image, terms);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    if (image.hit[p] == render::kNoHit) continue;
    ++hits;
    reached += traced[p] < std::numeric_limits<float>::infinity();
    shadowed += occluded[p] != 0;
  }
  const auto share = [](std::size_t part, std::size_t whole) {
    return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
  };
  figures.reached_fraction = share(reached, hits);
  figures.shadowed_fraction = share(shadowed, reached);
  return figures;
}

void print_shading(const ShadingFigures& f) {
  std::printf(
      "  shading        plain %.1f ms; shadowing point light %.1f ms (%.2fx; it reaches %.0f%% of "
      "the hits, %.0f%% of those in shadow); clip box keeping half %.1f ms (%.2fx); smooth normals "
      "%.1f ms (%.2fx), their "
      "vertex gradients %.1f ms per update (%.2fx); the step's update %.1f ms, the smooth step "
      "%.2fx the flat one\n",
      f.plain_ms, f.shadow_ms, f.shadow_ms / f.plain_ms, 100 * f.reached_fraction,
      100 * f.shadowed_fraction, f.clip_ms, f.clip_ms / f.plain_ms, f.smooth_ms,
      f.smooth_ms / f.plain_ms, f.gradients_ms, f.gradients_ms / f.plain_ms, f.update_ms,
      smooth_step_ratio(f));
}

double smooth_step_ratio(const ShadingFigures& f) {
  return (f.update_ms + f.gradients_ms + f.smooth_ms) / (f.update_ms + f.plain_ms);
}

Json::Value shading_json(const ShadingFigures& f) {
  Json::Value json;
  json["plain_ms"] = number(f.plain_ms);
  json["shadow_point_light_ms"] = number(f.shadow_ms);
  json["shadow_point_light_ratio"] = number(f.shadow_ms / f.plain_ms);
  json["reached_fraction"] = number(f.reached_fraction);
  json["shadowed_fraction"] = number(f.shadowed_fraction);
  json["clip_half_box_ms"] = number(f.clip_ms);
  json["clip_half_box_ratio"] = number(f.clip_ms / f.plain_ms);
  json["smooth_ms"] = number(f.smooth_ms);
  json["smooth_ratio"] = number(f.smooth_ms / f.plain_ms);
  json["vertex_gradients_ms"] = number(f.gradients_ms);
  json["vertex_gradients_ratio"] = number(f.gradients_ms / f.plain_ms);
  json["update_ms"] = number(f.update_ms);
  json["smooth_step_ratio"] = number(smooth_step_ratio(f));
  return json;
}

}  // namespace tetray::bench
