#include "adaptor_impl.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <new>

#include "color_field.hpp"
#include "input_views.hpp"
#include "output_files.hpp"
#include "render/composite/composite.hpp"
#include "render/core/stopwatch.hpp"
#include "render/trace/trace.hpp"
#include "render/volume/mesh_check.hpp"

namespace tetray {
namespace {

Status invalid(std::string message) { return {StatusCode::invalid_argument, std::move(message)}; }

// Runs a stage; whatever it throws (std::bad_alloc, a library's exception) becomes a status, so
// the rank can still take part in the agreement that follows.
template <typename Stage>
Status guarded(const char* name, Stage&& stage) {
  try {
    return stage();
  } catch (const std::bad_alloc&) {
    return {StatusCode::internal_error, std::string(name) + ": out of memory"};
  } catch (const std::exception& e) {
    return {StatusCode::internal_error, std::string(name) + ": " + e.what()};
  } catch (...) {
    return {StatusCode::internal_error, std::string(name) + ": unknown exception"};
  }
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
    : comm_(comm), config_(std::move(config)) {
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
  ranges_.scenes.resize(scenes_.size());
}

Adaptor::Impl::~Impl() {
  finalize();
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_.comm != MPI_COMM_NULL) MPI_Comm_free(&comm_.comm);
}

Status Adaptor::Impl::start() {
  const Status status = guarded("create", [&] { return prepare_outputs_on_this_rank(); });
  return agree(comm_, status);
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
  if (!any_due) {
    if (report != nullptr) {
      report->rendered = false;
      report->scenes_rendered = 0;
      report->bvh_decision = "none";
      report->tets_skipped = 0;
      report->seconds_blocked = blocked.ms() * 1e-3;
    }
    return take_writer_error();
  }
  const Status status = render_step(step, time, mesh, fields);
  const double blocked_ms = blocked.ms();
  if (report != nullptr) {
    report->rendered = status.ok();
    report->scenes_rendered =
        status.ok() ? static_cast<int>(std::count_if(scenes_.begin(), scenes_.end(),
                                                     [](const SceneState& s) { return s.due; }))
                    : 0;
    report->bvh_decision = bvh_decision_;
    report->tets_skipped = tets_skipped_;
    report->seconds_blocked = blocked_ms * 1e-3;
  }
  if (!status.ok()) return status;
  if (is_writer() && !config_.output.quiet) print_progress(step, time, blocked_ms);
  return take_writer_error();
}

Status Adaptor::Impl::render_step(std::int64_t step, double time, const MeshView& mesh,
                                  std::span<const FieldView> fields) {
  for (SceneState& s : scenes_) {
    if (s.due) s.record = StepRecord{.step = step, .time = time, .scene = s.config.name};
  }
  bvh_decision_ = "none";
  tets_skipped_ = 0;
  local_tets_ = mesh.tets.count;
  ranges_.clear();
  Status status = guarded("validation", [&] { return validate(mesh, fields); });
  status = agree(comm_, status, &ranges_);
  if (!status.ok()) return status;
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
  status = guarded("composite", [&] { return composite_and_submit(); });
  if (!status.ok()) return status;
  for (SceneState& s : scenes_) {
    if (s.due) s.clock.mark_rendered(time);
  }
  return status;
}

Status Adaptor::Impl::validate(const MeshView& mesh, std::span<const FieldView> fields) {
  if (std::string e = check_mesh_shape(mesh); !e.empty()) return invalid(e);
  for (const SceneState& s : scenes_) {
    if (!s.due) continue;
    for (const std::string* name : {&s.config.field, &s.config.color_by}) {
      if (name->empty()) continue;
      std::string e = check_field_shape(fields, *name, s.config.name, mesh.points.count);
      if (!e.empty()) return invalid(e);
    }
  }
  const render::Stopwatch ingest;
  if (std::string e = convert_topology(mesh.tets); !e.empty()) return invalid(e);
  first_due_scene()->record.ingest_ms += ingest.ms();
  bool loading = false;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    if (first_due_scene(v) == nullptr || !volumes_[v].stale(epochs_)) continue;
    if (Status st = check_volume(v, mesh, fields); !st.ok()) return st;
    loading = loading || volumes_[v].needs_load(epochs_);
  }
  if (loading) add_point_bounds(mesh.points, ranges_.points);
  return Status::success();
}

std::string Adaptor::Impl::convert_topology(const TetsView& tets) {
  const bool fresh = converted_topology_ == epochs_.topology;
  if (tets.type == IndexType::int64 || !fresh) {
    tets_ = connectivity_int64(tets, tets_converted_);
  } else {
    tets_ = tets_converted_;
  }
  if (fresh) return {};
  std::string error = tie_keys(tets, tie_keys_);
  if (error.empty()) converted_topology_ = epochs_.topology;
  return error;
}

Status Adaptor::Impl::check_volume(std::size_t v, const MeshView& mesh,
                                   std::span<const FieldView> fields) {
  const render::Stopwatch watch;
  FieldVolume& volume = volumes_[v];
  const render::PointSource points = point_source(mesh.points);
  const CheckedIndices now{epochs_.topology, mesh.points.count};
  const auto check = [&](const std::string& name, std::vector<std::uint8_t>& keep) {
    const bool indices_known =
        checked_indices_.topology == now.topology && checked_indices_.points == now.points;
    const render::MeshCheck found =
        render::check_mesh(tets_, points, field_source(field_or_empty(fields, name)),
                           config_.nonfinite, keep, !indices_known);
    if (!found.error.empty()) return invalid("mesh with field '" + name + "': " + found.error);
    checked_indices_ = now;
    return Status::success();
  };
  if (Status st = check(volume.field(), volume.keep()); !st.ok()) return st;
  for (const SceneState& s : scenes_) {
    if (!s.due || s.volume != v || s.config.color_by.empty() ||
        s.config.color_by == volume.field()) {
      continue;
    }
    if (Status st = check(s.config.color_by, color_keep_); !st.ok()) return st;
    for (std::size_t t = 0; t < color_keep_.size(); ++t) volume.keep()[t] &= color_keep_[t];
  }
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
    const render::UpdateResult result = volume.update(inputs, epochs_, config_.bvh, origin_);
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
    render::TraceOptions options;
    options.ambient = s.config.ambient;
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
    s.image = render::trace(volume.volume(), volume.bvh(), camera_for(s, ranges_.scenes[k]),
                            s.config.surfaces, options);
    s.record.trace_ms = watch.ms();
  }
  return Status::success();
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
  return Status::success();
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

Status Adaptor::Impl::take_writer_error() {
  if (!writer_ || !writer_->has_error()) return Status::success();
  return {StatusCode::io_error, writer_->take_error()};
}

Status Adaptor::Impl::finalize() {
  if (finalized_) return Status::success();
  finalized_ = true;
  if (!writer_) return Status::success();
  writer_->drain();
  Status status = take_writer_error();
  writer_.reset();
  return status;
}

}  // namespace tetray
