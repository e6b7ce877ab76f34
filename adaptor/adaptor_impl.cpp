#include "adaptor_impl.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "color_field.hpp"
#include "input_views.hpp"
#include "output_files.hpp"
#include "render/composite/composite.hpp"
#include "render/core/stopwatch.hpp"
#include "render/trace/trace.hpp"
#include "render/volume/mesh_check.hpp"
#include "scene_shadows.hpp"
#include "thread_budget.hpp"
#include "tie_keys.hpp"

namespace tetray {
namespace {

Status invalid(std::string message) { return {StatusCode::invalid_argument, std::move(message)}; }

// A check that failed only for non-finite field values: the field is unusable, the mesh is not,
// so only the scenes reading that field are skipped.
bool field_fault(const render::MeshCheck& found) {
  return !found.error.empty() && found.nonfinite_values > 0 && found.tets_out_of_range == 0 &&
         found.nonfinite_points == 0;
}

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

std::uint64_t count_zeros(const std::vector<std::uint8_t>& keep) {
  return static_cast<std::uint64_t>(std::count(keep.begin(), keep.end(), std::uint8_t{0}));
}

}  // namespace

Adaptor::Impl::Impl(Communicator comm, config::Config config)
    : comm_(comm),
      config_(std::move(config)),
      threads_(config_.threads > 0 ? config_.threads : default_thread_count()),
      arena_(threads_) {
  for (const config::Scene& s : config_.scenes) {
    SceneState state(s);
    const auto same_field = [&](const FieldVolume& v) { return v.field() == s.field; };
    const auto found = std::find_if(volumes_.begin(), volumes_.end(), same_field);
    state.volume = static_cast<std::size_t>(found - volumes_.begin());
    if (found == volumes_.end()) volumes_.emplace_back(s.field);
    if (!s.color_by.empty()) state.colormap = render::find_colormap(s.colormap_name);
    scenes_.push_back(std::move(state));
  }
  skipped_.assign(volumes_.size(), 0);
  skips_.resize(scenes_.size());
  ranges_.scenes.resize(scenes_.size());
}

Adaptor::Impl::~Impl() {
  finalize();
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_.comm != MPI_COMM_NULL) MPI_Comm_free(&comm_.comm);
}

Status Adaptor::Impl::start() {
  const Status status =
      agree(comm_, guarded("create", [&] { return prepare_outputs_on_this_rank(); }));
  started_ = status.ok();
  return status;
}

Status Adaptor::Impl::prepare_outputs_on_this_rank() {
  const config::Output& output = config_.output;
  std::string error;
  if (is_writer()) error = prepare_outputs(output, config_.scenes);
  if (error.empty() && output.per_rank_images) {
    error = prepare_rank_image_directories(output, config_.scenes, comm_.rank);
  }
  if (!error.empty()) return {StatusCode::io_error, error};
  if (is_writer()) writer_ = std::make_unique<ImageWriter>(output);
  return Status::success();
}

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

Status Adaptor::Impl::render_step(std::int64_t step, double time, const MeshView& mesh,
                                  std::span<const FieldView> fields) {
  // A failure this rank met since the last agreement is this step's outcome, on every rank.
  Status status = guarded("validation", [&] {
    begin_step(step, time, mesh);
    Status pending = take_pending_error();
    return pending.ok() ? validate(mesh, fields) : pending;
  });
  status = agree(comm_, status, &ranges_, &skips_);
  if (!status.ok()) return status;
  drop_skipped_scenes();
  if (!ranges_.points.empty()) origin_ = 0.5 * (ranges_.points.lo() + ranges_.points.hi());
  ranges_.clear();
  status = guarded("BVH update", [&] { return update_volumes(mesh, fields); });
  if (status.ok())
    status = guarded("bounds and color ranges", [&] { return global_inputs(fields); });
  status = agree(comm_, status, &ranges_);
  if (!status.ok()) return status;
  status = guarded("trace", [&] { return trace_scenes(fields); });
  if (status.ok() && config_.output.per_rank_images) {
    status = guarded("per-rank images", [&] { return write_rank_images(); });
  }
  status = agree(comm_, status);
  if (!status.ok()) return status;
  // Every rank agreed that the step renders: the triggers advance alike on every rank, whatever
  // the rank-local compositing stage below meets (it is reported at the next agreement).
  for (SceneState& s : scenes_) {
    if (s.due) s.clock.mark_rendered(time);
  }
  pending_ = guarded("composite", [&] { return composite_and_submit(); });
  return skipped_status();
}

void Adaptor::Impl::begin_step(std::int64_t step, double time, const MeshView& mesh) {
  for (SceneState& s : scenes_) {
    if (s.due) {
      s.record =
          StepRecord{.step = step, .time = time, .scene = s.config.name, .threads = threads_};
    }
  }
  bvh_decision_ = "none";
  tets_skipped_ = 0;
  local_tets_ = mesh.tets.count;
  ranges_.clear();
  std::fill(skips_.begin(), skips_.end(), std::string());
}

Status Adaptor::Impl::validate(const MeshView& mesh, std::span<const FieldView> fields) {
  if (std::string e = check_mesh_shape(mesh); !e.empty()) return invalid(e);
  if (Status st = check_scene_fields(mesh, fields); !st.ok()) return st;
  const render::Stopwatch ingest;
  if (std::string e = convert_topology(mesh); !e.empty()) return invalid(e);
  if (SceneState* first = first_due_scene()) first->record.ingest_ms += ingest.ms();
  bool loading = false;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    if (!needs_check(v)) continue;
    if (Status st = check_volume(v, mesh, fields); !st.ok()) return st;
    loading = loading || (first_due_scene(v) != nullptr && volumes_[v].needs_load(epochs_));
  }
  if (loading) add_point_bounds(mesh.points, ranges_.points);
  return Status::success();
}

// A field a due scene needs but that was not passed skips the scene (a rank without tets need
// not pass any); a passed field of the wrong shape is the caller's error.
Status Adaptor::Impl::check_scene_fields(const MeshView& mesh, std::span<const FieldView> fields) {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    const SceneState& s = scenes_[k];
    for (const std::string* name : {&s.config.field, &s.config.color_by}) {
      if (!s.due || name->empty()) continue;
      std::string e = missing_field(fields, *name, s.config.name, mesh.tets.count);
      if (!e.empty()) {
        skip(k, std::move(e));
        continue;
      }
      e = check_field_shape(fields, *name, mesh.points.count);
      if (!e.empty()) return invalid(e);
    }
  }
  return Status::success();
}

// A stale volume, or one of a scene skipped last time (its fields may still be bad although
// nothing the volume reads changed since it was last updated for the other scenes).
bool Adaptor::Impl::needs_check(std::size_t v) {
  if (first_due_scene(v) == nullptr) return false;
  if (volumes_[v].stale(epochs_)) return true;
  return std::any_of(scenes_.begin(), scenes_.end(),
                     [&](const SceneState& s) { return s.due && s.volume == v && s.skipped_last; });
}

void Adaptor::Impl::skip(std::size_t scene, std::string reason) {
  skips_[scene] = std::move(reason);
  scenes_[scene].due = false;
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

std::string Adaptor::Impl::convert_topology(const MeshView& mesh) {
  const TetsView& tets = mesh.tets;
  const bool fresh = converted_topology_ == epochs_.topology;
  if (tets.type == IndexType::int64 || !fresh) {
    tets_ = connectivity_int64(tets, tets_converted_);
  } else {
    tets_ = tets_converted_;
  }
  if (fresh) return {};
  std::string error = tie_keys(tets, tets_, mesh.points, tie_keys_);
  if (error.empty()) converted_topology_ = epochs_.topology;
  return error;
}

Status Adaptor::Impl::check_volume(std::size_t v, const MeshView& mesh,
                                   std::span<const FieldView> fields) {
  const render::Stopwatch watch;
  FieldVolume& volume = volumes_[v];
  const render::PointSource points = point_source(mesh.points);
  const CheckedIndices now{epochs_.topology, mesh.points.count};
  // Empty when usable; else the finding, with code partial when only the field is at fault.
  const auto check = [&](const std::string& name, std::vector<std::uint8_t>& keep) {
    const bool indices_known =
        checked_indices_.topology == now.topology && checked_indices_.points == now.points;
    const render::MeshCheck found =
        render::check_mesh(tets_, points, field_source(field_or_empty(fields, name)),
                           config_.nonfinite, keep, !indices_known);
    if (found.error.empty()) {
      checked_indices_ = now;
      return Status::success();
    }
    return Status{field_fault(found) ? StatusCode::partial : StatusCode::invalid_argument,
                  "mesh with field '" + name + "': " + found.error};
  };
  // Partial: only the field is at fault. A faulty isosurface field skips every scene of the
  // volume, a faulty color field only its scene.
  const Status volume_check = check(volume.field(), volume.keep());
  if (volume_check.failed()) return volume_check;
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    const SceneState& s = scenes_[k];
    if (!s.due || s.volume != v) continue;
    if (!volume_check.ok()) {
      skip(k, volume_check.message);
      continue;
    }
    if (s.config.color_by.empty() || s.config.color_by == volume.field()) continue;
    const Status color_check = check(s.config.color_by, color_keep_);
    if (color_check.failed()) return color_check;
    if (!color_check.ok()) {
      skip(k, color_check.message);
      continue;
    }
    for (std::size_t t = 0; t < color_keep_.size(); ++t) volume.keep()[t] &= color_keep_[t];
  }
  if (first_due_scene(v) == nullptr) return Status::success();
  const bool skipping = config_.nonfinite == render::NonFinitePolicy::skip_tets;
  skipped_[v] = skipping ? count_zeros(volume.keep()) : 0;
  drop_ghost_tets(mesh.tets.ghost, volume.keep());
  first_due_scene(v)->record.check_ms += watch.ms();
  return Status::success();
}

Status Adaptor::Impl::update_volumes(const MeshView& mesh, std::span<const FieldView> fields) {
  render::BvhUpdateKind strongest = render::BvhUpdateKind::none;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    SceneState* first = first_due_scene(v);
    if (first == nullptr) continue;
    FieldVolume& volume = volumes_[v];
    tets_skipped_ += skipped_[v];
    if (!volume.stale(epochs_)) continue;  // nothing it reads changed: no refit
    const render::Stopwatch watch;
    const VolumeInputs inputs{tets_, tie_keys_, point_source(mesh.points),
                              field_source(field_or_empty(fields, volume.field()))};
    render::UpdatePolicy policy = config_.bvh;
    policy.vertex_gradients = std::any_of(scenes_.begin(), scenes_.end(), [&](const auto& s) {
      return s.volume == v && s.config.shading.smooth;
    });
    const render::UpdateResult result = volume.update(inputs, epochs_, policy, origin_);
    first->record.bvh_ms = watch.ms();
    first->record.bvh_update = render::to_string(result.kind);
    strongest = std::max(strongest, result.kind);
  }
  bvh_decision_ = render::to_string(strongest);
  return Status::success();
}

Status Adaptor::Impl::global_inputs(std::span<const FieldView> fields) {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    SceneRanges& ranges = ranges_.scenes[k];
    const FieldVolume& volume = volumes_[s.volume];
    if (s.config.camera.auto_fit && !volume.bvh().empty()) {
      const render::Bounds4& b = volume.bvh().nodes[0].bounds;
      for (int a = 0; a < 3; ++a) {
        ranges.box.axis[a].include(volume.volume().origin[a] + b.lo[a]);
        ranges.box.axis[a].include(volume.volume().origin[a] + b.hi[a]);
      }
    }
    if (s.colormap != nullptr && s.config.color_range.automatic) {
      const render::Stopwatch watch;
      ranges.color = local_field_range(field_or_empty(fields, s.config.color_by));
      s.record.color_ms += watch.ms();
    }
  }
  return Status::success();
}

Status Adaptor::Impl::trace_scenes(std::span<const FieldView> fields) {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    FieldVolume& volume = volumes_[s.volume];
    render::TraceOptions options = trace_options(s);
    if (s.colormap != nullptr) {
      const render::Stopwatch watch;
      render::load_color_field(volume.volume(),
                               field_source(field_or_empty(fields, s.config.color_by)));
      render::ValueRange range =
          s.config.color_range.automatic
              ? ranges_.scenes[k].color
              : render::ValueRange{s.config.color_range.lo, s.config.color_range.hi};
      usable_color_range(range);
      options.color_by = {s.colormap, static_cast<float>(range.lo), static_cast<float>(range.hi)};
      s.record.color_ms += watch.ms();
    }
    const render::Stopwatch watch;
    const bool shadows = options.lights.shadow_count() > 0;
    render::trace_into(s.image, volume.volume(), volume.bvh(), camera_for(s, ranges_.scenes[k]),
                       s.config.surfaces, options, nullptr, shadows ? &s.shadow_terms : nullptr);
    s.record.trace_ms = watch.ms();
  }
  return Status::success();
}

render::TraceOptions Adaptor::Impl::trace_options(const SceneState& s) const {
  render::TraceOptions options;
  options.ambient = s.config.ambient;
  options.smooth = s.config.shading.smooth;
  options.clip = s.config.shading.clip;
  options.lights = s.config.shading.lights;
  return options;
}

// Before compositing, which leaves only the writer rank's image defined.
Status Adaptor::Impl::write_rank_images() {
  for (const SceneState& s : scenes_) {
    if (!s.due) continue;
    std::string error =
        write_rank_image(config_.output, s.config.name, s.record.step, comm_.rank, s.image);
    if (!error.empty()) return {StatusCode::io_error, std::move(error)};
  }
  return Status::success();
}

render::Camera Adaptor::Impl::camera_for(const SceneState& s, const SceneRanges& ranges) const {
  const config::CameraSpec& spec = s.config.camera;
  if (!spec.auto_fit) {
    render::Camera camera = spec.fixed;
    camera.width = s.config.width;
    camera.height = s.config.height;
    return camera;
  }
  render::Vec3d lo{-1, -1, -1}, hi{1, 1, 1};  // nothing to fit on any rank
  if (!ranges.box.empty()) {
    lo = ranges.box.lo();
    hi = ranges.box.hi();
  }
  return render::fit_camera(lo, hi, spec.view_direction, spec.up, spec.fov_deg, s.config.width,
                            s.config.height);
}

Status Adaptor::Impl::composite_and_submit() {
  // Per scene the counters summed over the ranks; the largest peak RSS.
  std::vector<SceneCounters> sums(scenes_.size());
  std::uint64_t rss = peak_rss_bytes();
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    const FieldVolume& volume = volumes_[scenes_[k].volume];
    if (!scenes_[k].due) continue;
    sums[k] = {local_tets_, volume.volume().tets.size(), skipped_[scenes_[k].volume],
               volume.volume().bytes() + volume.bvh().bytes()};
  }
  const int writer = config_.output.writer_rank;
  const int reduced = reduce_sum_to_root(comm_, writer, sums);
  if (reduced != MPI_SUCCESS || reduce_max_to_root(comm_, writer, rss) != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "reducing the log counters: " + mpi_error_text(reduced)};
  }
  Status local_failure = Status::success();
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    if (comm_.size > 1) {
      const render::Stopwatch watch;
      const render::CompositeOptions options{.root = writer};
      if (int rc = render::composite(s.image, comm_.comm, options); rc != MPI_SUCCESS) {
        return {StatusCode::mpi_error,
                "compositing scene '" + s.config.name + "': " + mpi_error_text(rc)};
      }
      s.record.composite_ms = watch.ms();
    }
    if (!s.shadow_terms.empty()) {
      const render::Stopwatch watch;
      const FieldVolume& volume = volumes_[s.volume];
      const render::Camera camera = camera_for(s, ranges_.scenes[k]);
      const render::TraceOptions options = trace_options(s);
      const ShadowScene scene{volume.volume(), volume.bvh(), camera, s.config.surfaces, options};
      Status st = shadow_scene(s.image, s.shadow_terms, scene, comm_, writer);
      if (st.code == StatusCode::mpi_error) return st;
      // A failure of this rank alone: the other scenes' collectives still need it.
      if (!st.ok() && local_failure.ok()) local_failure = std::move(st);
      s.record.composite_ms += watch.ms();
    }
    if (!is_writer()) continue;
    StepRecord& r = s.record;
    r.tets = sums[k].tets;
    r.kept_tets = sums[k].kept_tets;
    r.skipped_tets = sums[k].skipped_tets;
    r.bvh_bytes = sums[k].bytes;
    r.peak_rss_bytes = rss;
    r.rays =
        static_cast<std::uint64_t>(s.image.pixel_count()) * static_cast<std::uint64_t>(comm_.size);
    ImageJob job;
    job.image = std::move(s.image);
    std::copy(std::begin(s.config.background), std::end(s.config.background), job.background);
    job.record = r;
    writer_->submit(std::move(job));
  }
  return local_failure;
}

Adaptor::Impl::SceneState* Adaptor::Impl::first_due_scene(std::size_t v) {
  for (SceneState& s : scenes_) {
    if (s.due && (v == kAnyVolume || s.volume == v)) return &s;
  }
  return nullptr;
}

void Adaptor::Impl::print_progress(std::int64_t step, double time, double blocked_ms) const {
  double trace_ms = 0;
  int rendered = 0;
  for (const SceneState& s : scenes_) {
    if (!s.due) continue;
    trace_ms += s.record.trace_ms;
    ++rendered;
  }
  std::printf("tetray: step %lld t=%s: %d scene(s), bvh %s, trace %.1f ms, blocked %.1f ms\n",
              static_cast<long long>(step), time_text(time).c_str(), rendered,
              bvh_decision_.c_str(), trace_ms, blocked_ms);
  std::fflush(stdout);
}

Status Adaptor::Impl::take_pending_error() {
  Status pending = std::exchange(pending_, Status::success());
  if (pending.ok() && writer_ && writer_->has_error()) {
    pending = {StatusCode::io_error, writer_->take_error()};
  }
  return pending;
}

// Collective (for a started adaptor): the writer rank drains its queue, and every rank gets the
// writer's last errors and its own pending one.
Status Adaptor::Impl::finalize() {
  if (finalized_) return Status::success();
  finalized_ = true;
  if (!started_) return Status::success();
  const Status status = guarded("finalize", [&] {
    if (writer_) writer_->drain();
    Status pending = take_pending_error();
    writer_.reset();
    return pending;
  });
  int mpi_finalized = 0;
  MPI_Finalized(&mpi_finalized);
  // Destroyed after MPI_Finalize without a finalize call: nothing to agree with.
  if (mpi_finalized) return status;
  return agree(comm_, status);
}

}  // namespace tetray
