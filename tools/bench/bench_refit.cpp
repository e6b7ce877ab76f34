#include "bench_refit.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "bench_bandwidth.hpp"
#include "bench_reference_step.hpp"
#include "bench_timing.hpp"
#include "tools/bench_common/bench_scene.hpp"

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
  if (values.empty()) return 0.0;
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
// refit and rebuild) and traced into the image kept from the step before, in 16x16 packets and
// in the default ones; the reference contours, builds and traces the same step. The three are
// timed in turn, a few times each (best_in_turn_ms): each figure of a step is its best run (a
// run again refits to the same positions: the same work), and each total the median over the
// steps.
void measure_steps(const GyroidTwist& start, const render::Camera& camera, const StepOptions& o,
                   RefitFigures& figures) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(start, volume, bvh);
  ReferenceStep reference(start.mesh.tets, camera, o.threads, o.reference_packets);
  render::Framebuffer image_16x16, image_default;
  render::UpdateResult last;
  auto tetray_step_ms = [&](const StepArrays& arrays, render::PacketSize packet,
                            render::Framebuffer& image) {
    return time_ms([&] {
      last = update(volume, bvh, arrays.points, arrays.field, kGeometryAndField);
      trace_scene(volume, bvh, camera, packet, image);
    });
  };
  enum Figure { kStep16x16, kStepDefault, kReference, kFigures };
  std::array<std::vector<double>, kFigures> times;
  for (int s = 1; s < o.steps; ++s) {
    const StepArrays arrays = step_arrays(start.mesh, s * kTimeStep);
    const auto best = best_in_turn_ms<kFigures>(
        kRepetitions,
        {[&] { return tetray_step_ms(arrays, render::PacketSize::p16x16, image_16x16); },
         [&] { return tetray_step_ms(arrays, render::TraceOptions{}.packet, image_default); },
         [&] { return reference.run_ms(arrays.points, arrays.field); }});
    for (int k = 0; k < kFigures; ++k) times[k].push_back(best[k]);
  }
  figures.step_total_ms = median(times[kStep16x16]);
  figures.step_total_default_ms = median(times[kStepDefault]);
  figures.ref_step_total_ms = median(times[kReference]);
  figures.quality_ratio_after_steps = last.quality_ratio;
}

// A deformation far beyond the benchmark's steps: the policy's decision.
void measure_strong_deformation(const GyroidTwist& start, RefitFigures& figures) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(start, volume, bvh);
  const render::UpdateResult strong =
      update(volume, bvh, strong_twist(start.mesh), start.field, kGeometryAndField);
  figures.strong_deformation_kind = render::to_string(strong.kind);
  figures.strong_deformation_ratio = strong.quality_ratio;
}

}  // namespace

RefitFigures measure_refit(const GyroidTwist& start, const render::Camera& camera,
                           const StepOptions& options) {
  RefitFigures figures;
  measure_updates(start, figures);
  measure_steps(start, camera, options, figures);
  measure_strong_deformation(start, figures);
  return figures;
}

}  // namespace tetray::bench
