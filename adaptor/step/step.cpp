// One execute call: the triggers say whether this step renders, and render_step runs its data
// flow (docs/architecture.md §2): validate the solver's arrays -> update the volumes and BVHs ->
// render the scenes on each rank -> composite onto the writer rank -> hand the images and log
// rows to the writer thread. Every rank agrees on the outcome before each collective stage.
#include "adaptor/step/step_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "render/core/stopwatch.hpp"

namespace tetray {

bool Adaptor::Impl::will_render(std::int64_t step, double time) const {
  return std::any_of(scenes_.begin(), scenes_.end(),
                     [&](const SceneState& s) { return s.clock.due(step, time); });
}

Status Adaptor::Impl::execute(std::int64_t step, double time, const MeshView& mesh,
                              std::span<const FieldView> fields, const Changes& changes,
                              ExecuteReport* report) {
  if (finalized_) return {StatusCode::not_initialized, "execute called after finalize"};
  const render::Stopwatch blocked;
  // Changes accumulate over off-trigger calls: a volume sees everything since its last update.
  epochs_.geometry += changes.geometry;
  epochs_.topology += changes.topology;
  epochs_.fields += changes.fields;
  bool any_due = false;
  for (SceneState& s : scenes_) {
    s.due = s.clock.due(step, time);
    any_due = any_due || s.due;
  }
  // Off-trigger: no MPI, and ok on every rank (a writer error waits for the next agreement).
  if (!any_due) {
    if (report != nullptr) fill_report(Status::success(), blocked.ms(), *report);
    return Status::success();
  }
  const Status status = arena_.execute([&] { return render_step(step, time, mesh, fields); });
  const double blocked_ms = blocked.ms();
  if (report != nullptr) fill_report(status, blocked_ms, *report);
  if (!status.failed() && is_writer() && !config_.output.quiet) {
    print_progress(step, time, blocked_ms);
  }
  return status;
}

// The error becomes this rank's pending one (unless an older one waits): the render step's first
// agreement reports it, and no view is read.
Status Adaptor::Impl::execute_failed(std::int64_t step, double time, Status error,
                                     const Changes& changes, ExecuteReport* report) {
  if (pending_.ok()) pending_ = std::move(error);
  return execute(step, time, MeshView{}, {}, changes, report);
}

Status Adaptor::Impl::render_step(std::int64_t step, double time, const MeshView& mesh,
                                  std::span<const FieldView> fields) {
  // A failure this rank met since the last agreement is this step's outcome, on every rank.
  // A mesh of cells is read as their tets from here on.
  MeshView tet_mesh;
  Status status =
      guarded("validation", [&] { return validate_step(step, time, mesh, fields, tet_mesh); });
  status = agree(comm_, status, &ranges_, &skips_);
  if (!status.ok()) return status;
  drop_skipped_scenes();
  if (!ranges_.points.empty()) origin_ = 0.5 * (ranges_.points.lo() + ranges_.points.hi());
  ranges_.clear();
  status = update_step(tet_mesh, fields);
  status = agree(comm_, status, &ranges_);
  if (!status.ok()) return status;
  status = render_scenes(fields);
  status = agree(comm_, status);
  if (!status.ok()) return status;
  // Every rank agreed that the step renders: the triggers advance alike on every rank, whatever
  // the rank-local compositing stage below meets (it is reported at the next agreement).
  for (SceneState& s : scenes_) {
    if (s.due) s.clock.mark_rendered(time);
  }
  pending_ = guarded("composite", [&] { return composite_and_submit(); });
  sample_probes(step, time, fields);
  return skipped_status();
}

void Adaptor::Impl::begin_step(std::int64_t step, double time) {
  for (SceneState& s : scenes_) {
    if (s.due) {
      s.record =
          StepRecord{.step = step, .time = time, .scene = s.config.name, .threads = threads_};
    }
  }
  bvh_decision_ = "none";
  tets_skipped_ = 0;
  local_tets_ = 0;
  ranges_.clear();
  std::fill(skips_.begin(), skips_.end(), std::string());
}

// After the agreement: a scene some rank skipped is skipped on every rank.
void Adaptor::Impl::drop_skipped_scenes() {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    const bool skipped = !skips_[k].empty();
    if (skipped || s.due) s.skipped_last = skipped;
    if (skipped) s.due = false;
  }
}

// The volumes brought to this step (update.cpp), then what every rank needs of the others: the
// smooth volumes' shared gradients, and the bounds and color ranges the next agreement unites.
Status Adaptor::Impl::update_step(const MeshView& mesh, std::span<const FieldView> fields) {
  Status status = guarded("BVH update", [&] { return update_volumes(mesh, fields); });
  status = share_gradients(mesh, status);
  if (status.ok())
    status = guarded("bounds and color ranges", [&] { return global_inputs(fields); });
  return status;
}

// Every due scene's views on this rank (trace_scenes.cpp, render_volume_scenes.cpp), and the
// per-rank images before compositing leaves only the writer rank's image defined.
Status Adaptor::Impl::render_scenes(std::span<const FieldView> fields) {
  Status status = guarded("trace", [&] { return trace_scenes(fields); });
  if (status.ok() && config_.output.per_rank_images) {
    status = guarded("per-rank images", [&] { return write_rank_images(); });
  }
  return status;
}

// Located in the first due scene's volume, which this step brought up to date.
void Adaptor::Impl::sample_probes(std::int64_t step, double time,
                                  std::span<const FieldView> fields) {
  if (probes_.empty()) return;
  const SceneState* first = first_due_scene();
  std::string error =
      probes_.sample(comm_, config_.output.writer_rank, first ? &volumes_[first->volume] : nullptr,
                     fields, step, time, config_.output.directory);
  if (pending_.ok() && !error.empty()) pending_ = {StatusCode::io_error, std::move(error)};
}

Status Adaptor::Impl::skipped_status() const {
  std::string message;
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    if (skips_[k].empty()) continue;
    if (!message.empty()) message += "; ";
    message += "scene '" + scenes_[k].config.name + "' skipped: " + skips_[k];
  }
  if (message.empty()) return Status::success();
  return {StatusCode::partial, std::move(message)};
}

SceneState* Adaptor::Impl::first_due_scene(std::size_t v) {
  for (SceneState& s : scenes_) {
    if (s.due && (v == kAnyVolume || s.volume == v)) return &s;
  }
  return nullptr;
}

void Adaptor::Impl::fill_report(const Status& status, double blocked_ms,
                                ExecuteReport& report) const {
  const auto due =
      std::count_if(scenes_.begin(), scenes_.end(), [](const SceneState& s) { return s.due; });
  const bool rendered = !status.failed() && due > 0;
  report.rendered = rendered;
  report.scenes_rendered = rendered ? static_cast<int>(due) : 0;
  report.bvh_decision = rendered ? bvh_decision_ : "none";
  report.tets_skipped = rendered ? tets_skipped_ : 0;
  report.seconds_blocked = blocked_ms * 1e-3;
  report.skipped_scenes.clear();
  if (status.code != StatusCode::partial) return;
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    if (!skips_[k].empty()) report.skipped_scenes.push_back(scenes_[k].config.name);
  }
}

void Adaptor::Impl::print_progress(std::int64_t step, double time, double blocked_ms) const {
  double trace_ms = 0;
  int rendered = 0;
  for (const SceneState& s : scenes_) {
    if (!s.due) continue;
    for (double ms : s.trace_ms) trace_ms += ms;
    ++rendered;
  }
  std::printf("tetray: step %lld t=%s: %d scene(s), bvh %s, trace %.1f ms, blocked %.1f ms\n",
              static_cast<long long>(step), time_text(time).c_str(), rendered,
              bvh_decision_.c_str(), trace_ms, blocked_ms);
  std::fflush(stdout);
}

}  // namespace tetray
