// One execute call: the triggers say whether this step renders, and render_step runs its data
// flow (docs/architecture.md §2): validate the solver's arrays -> update the volumes and BVHs ->
// render the scenes on each rank -> composite onto the writer rank -> hand the images to the
// writer thread, and their log rows once the call's clock has stopped. Every rank agrees on the
// outcome before each collective stage. One clock (clock_) times the whole call: each stage
// charges its phase to its log column, and what falls between the stages to other_ms.
#include "adaptor/step/step_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace tetray {

bool Adaptor::Impl::will_render(std::int64_t step, double time) const {
  return std::any_of(scenes_.begin(), scenes_.end(),
                     [&](const SceneState& s) { return s.clock.due(step, time); });
}

Status Adaptor::Impl::execute(std::int64_t step, double time, const MeshView& mesh,
                              std::span<const FieldView> fields, const Changes& changes,
                              ExecuteReport* report) {
  if (finalized_) return {StatusCode::not_initialized, "execute called after finalize"};
  clock_.start(&step_costs_.other_ms);
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
  // Nothing is logged, so the clock is read again only for a report (the next call's start()
  // resets it): the most frequent call costs one clock read, as before the log's phases.
  if (!any_due) {
    if (report != nullptr) fill_report(Status::success(), clock_.stop(), *report);
    return Status::success();
  }
  // Charged from here on; the time since start() goes to the fresh other_ms at the first phase.
  step_costs_ = StepRecord{};
  handed_over_.clear();
  const Status status = arena_.execute([&] { return render_step(step, time, mesh, fields); });
  const double blocked_ms = clock_.stop();
  const Status logged = guarded("timing log", [&] {
    log_step(blocked_ms);
    return Status::success();
  });
  if (pending_.ok() && !logged.ok()) pending_ = logged;  // reported at the next agreement
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
  status = agree_on(status, &ranges_, &skips_);
  if (!status.ok()) return status;
  drop_skipped_scenes();
  if (!ranges_.points.empty()) origin_ = 0.5 * (ranges_.points.lo() + ranges_.points.hi());
  ranges_.clear();
  status = update_step(tet_mesh, fields);
  status = agree_on(status, &ranges_);
  if (!status.ok()) return status;
  status = render_scenes(fields);
  status = agree_on(status);
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
      s.view_times.assign(s.views.size(), ViewTimes{});
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
  const PhaseClock::Phase phase(clock_, step_costs_.probes_ms);
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

Status Adaptor::Impl::agree_on(const Status& local, StepRanges* ranges, SceneSkips* skips) {
  const PhaseClock::Phase phase(clock_, step_costs_.agree_ms);
  return agree(comm_, local, ranges, skips);
}

// Each row gets its view's hand-off (which ended after its row was made) and the call's blocked
// time; the first row also the step's costs that belong to no scene. Summed over the rows, the
// stage columns are then the whole call (docs/outputs.md, "The timing log").
void Adaptor::Impl::log_step(double blocked_ms) {
  if (handed_over_.empty()) return;
  std::vector<StepRecord> rows;
  rows.reserve(handed_over_.size());
  for (HandedOver& h : handed_over_) {
    const ViewTimes& times = scenes_[h.scene].view_times[h.view];
    h.row.hand_off_ms = times.hand_off_ms;
    h.row.queue_wait_ms = times.queue_wait_ms;
    h.row.blocked_ms = blocked_ms;
    rows.push_back(std::move(h.row));
  }
  handed_over_.clear();
  StepRecord& first = rows.front();
  first.check_ms += step_costs_.check_ms;
  first.ingest_ms += step_costs_.ingest_ms;
  first.agree_ms += step_costs_.agree_ms;
  first.probes_ms += step_costs_.probes_ms;
  first.other_ms += step_costs_.other_ms;
  writer_->log_rows(std::move(rows));
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
    for (const ViewTimes& view : s.view_times) trace_ms += view.trace_ms;
    ++rendered;
  }
  std::printf("tetray: step %lld t=%s: %d scene(s), bvh %s, trace %.1f ms, blocked %.1f ms\n",
              static_cast<long long>(step), time_text(time).c_str(), rendered,
              bvh_decision_.c_str(), trace_ms, blocked_ms);
  std::fflush(stdout);
}

}  // namespace tetray
