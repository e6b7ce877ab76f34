#include "bench_refit.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "bench_bandwidth.hpp"
#include "bench_scene.hpp"
#include "bench_timing.hpp"

namespace tetray::bench {
namespace {

constexpr render::StepChanges kFieldOnly{false, true};
constexpr render::StepChanges kGeometryAndField{true, true};

struct StepArrays {
  std::vector<double> points;
  std::vector<double> field;
};

StepArrays step_arrays(const BoxMesh& reference, double t) {
  StepArrays arrays;
  deform_gyroid_twist(reference, t, arrays.points, arrays.field);
  return arrays;
}

render::UpdateResult update(render::TetVolume& volume, render::Bvh& bvh,
                            const std::vector<double>& points, const std::vector<double>& field,
                            render::StepChanges changes, const render::UpdatePolicy& policy = {}) {
  return render::update_volume(volume, bvh, point_source(points), field_source(field), changes,
                               policy);
}

// A policy whose threshold every tree passes: the step takes the rebuild path.
render::UpdatePolicy always_rebuild() {
  render::UpdatePolicy policy;
  policy.rebuild_ratio = 0.0;
  return policy;
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The three update kinds on the step t = 0.1, each the best of a few runs; the refits are timed
// with cold caches in alternation with their bounds (bench_bandwidth.hpp).
// The rebuild figure is a whole step on which the policy rebuilds (ingest, refit, build).
void measure_updates(const GyroidTwist& start, RefitFigures& figures) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(start, volume, bvh);
  const StepArrays next = step_arrays(start.mesh, kTimeStep);

  render::UpdateResult rebuilt;
  figures.rebuild_ms = best_ms(kRepetitions, [&] {
    rebuilt = update(volume, bvh, next.points, next.field, kGeometryAndField, always_rebuild());
  });
  if (rebuilt.kind != render::BvhUpdateKind::rebuild)
    throw std::runtime_error("the policy did not rebuild at threshold 0");

  const UpdateTraffic field_only = field_only_traffic(volume, bvh, field_source(next.field));
  const UpdateTraffic geometry =
      geometry_traffic(volume, bvh, point_source(next.points), field_source(next.field));
  figures.bytes_field_only = field_only.total();
  figures.bytes_geometry = geometry.total();
  const TimeAndBound field_only_time = time_against_bound(
      field_only, [&] { update(volume, bvh, start.mesh.points, next.field, kFieldOnly); });
  const TimeAndBound geometry_time = time_against_bound(
      geometry, [&] { update(volume, bvh, next.points, next.field, kGeometryAndField); });
  figures.field_only_ms = field_only_time.work_ms;
  figures.bound_field_only_ms = field_only_time.bound_ms;
  figures.geometry_ms = geometry_time.work_ms;
  figures.bound_geometry_ms = geometry_time.bound_ms;
}

// The in-situ loop: each new step is ingested (geometry + field, the policy deciding between
// refit and rebuild) and traced in `packet`s into the image kept from the step before. Each
// step is the best of a few runs, as every figure of the bench and of the reference is (a run
// again refits to the same positions: the same work). Returns the median over the steps.
double step_ms(const GyroidTwist& start, const render::Camera& camera, int steps,
               render::PacketSize packet, render::UpdateResult& last) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(start, volume, bvh);
  std::vector<double> times;
  render::Framebuffer image;
  for (int s = 1; s < steps; ++s) {
    const StepArrays arrays = step_arrays(start.mesh, s * kTimeStep);
    times.push_back(best_ms(kRepetitions, [&] {
      last = update(volume, bvh, arrays.points, arrays.field, kGeometryAndField);
      trace_scene(volume, bvh, camera, packet, image);
    }));
  }
  return times.empty() ? 0.0 : median(times);
}

// The steps in 16x16 packets (issue 4's definition) and in the default ones; then the strong
// deformation.
void measure_steps(const GyroidTwist& start, const render::Camera& camera, int steps,
                   RefitFigures& figures) {
  render::UpdateResult last;
  figures.step_total_default_ms =
      step_ms(start, camera, steps, render::TraceOptions{}.packet, last);
  figures.step_total_ms = step_ms(start, camera, steps, render::PacketSize::p16x16, last);
  figures.quality_ratio_after_steps = last.quality_ratio;

  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(start, volume, bvh);
  const render::UpdateResult strong =
      update(volume, bvh, strong_twist(start.mesh), start.field, kGeometryAndField);
  figures.strong_deformation_kind = render::to_string(strong.kind);
  figures.strong_deformation_ratio = strong.quality_ratio;
}

}  // namespace

RefitFigures measure_refit(const GyroidTwist& start, const render::Camera& camera, int steps) {
  RefitFigures figures;
  measure_updates(start, figures);
  measure_steps(start, camera, steps, figures);
  return figures;
}

}  // namespace tetray::bench
