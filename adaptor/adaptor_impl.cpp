#include "adaptor_impl.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "annotations.hpp"
#include "color_field.hpp"
#include "input_views.hpp"
#include "output_files.hpp"
#include "render/composite/composite.hpp"
#include "render/composite/fragment_composite.hpp"
#include "render/core/stopwatch.hpp"
#include "render/isa/isa.hpp"
#include "render/parallel/scene_layers.hpp"
#include "render/parallel/scene_shadows.hpp"
#include "render/parallel/step_reductions.hpp"
#include "render/trace/layer_shading.hpp"
#include "render/trace/trace.hpp"
#include "render/volume/mesh_check.hpp"
#include "render/walk/clip_cap.hpp"
#include "thread_budget.hpp"
#include "tie_keys.hpp"

namespace tetray {
namespace {

Status invalid(std::string message) { return {StatusCode::invalid_argument, std::move(message)}; }

// Whether a scene of volume v has the property `of` (of its config::Scene).
template <typename Scenes, typename Property>
bool any_scene_of(const Scenes& scenes, std::size_t v, Property of) {
  return std::any_of(scenes.begin(), scenes.end(),
                     [&](const auto& s) { return s.volume == v && of(s.config); });
}

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

constexpr std::uint8_t kGradientsUpdated = 1;
constexpr std::uint8_t kGradientsLoaded = 2;

// The field of a volume scene's surfaces when it is not the scene's own; else empty.
const std::string& surface_field(const config::Scene& s) {
  static const std::string none;
  return s.volume ? s.volume->surface_field : none;
}

std::uint64_t count_zeros(const std::vector<std::uint8_t>& keep) {
  return static_cast<std::uint64_t>(std::count(keep.begin(), keep.end(), std::uint8_t{0}));
}

}  // namespace

Adaptor::Impl::Impl(Communicator comm, config::Config config)
    : comm_(comm),
      config_(std::move(config)),
      threads_(config_.threads > 0 ? config_.threads : default_thread_count()),
      arena_(threads_),
      probes_(config_.probes) {
  for (const config::Scene& s : config_.scenes) {
    SceneState state(s);
    const auto same_field = [&](const FieldVolume& v) { return v.field() == s.field; };
    const auto found = std::find_if(volumes_.begin(), volumes_.end(), same_field);
    state.volume = static_cast<std::size_t>(found - volumes_.begin());
    if (found == volumes_.end()) volumes_.emplace_back(s.field);
    if (!s.color_by.empty()) state.colormap = render::find_colormap(s.colormap_name);
    if (!s.shading.cap.field.empty())
      state.cap_colormap = render::find_colormap(s.shading.cap.colormap_name);
    scenes_.push_back(std::move(state));
  }
  skipped_.assign(volumes_.size(), 0);
  walks_.resize(volumes_.size());
  shared_gradients_.resize(volumes_.size());
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
  if (started_ && is_writer() && !config_.output.quiet) {
    std::printf("tetray: kernels %s\n", render::isa::choice_note().c_str());
    std::fflush(stdout);
  }
  return status;
}

Status Adaptor::Impl::prepare_outputs_on_this_rank() {
  const config::Output& output = config_.output;
  std::string error;
  if (is_writer()) error = prepare_outputs(output, config_.scenes);
  if (error.empty() && is_writer()) error = probes_.prepare(output.directory);
  if (error.empty() && output.per_rank_images) {
    error = prepare_rank_image_directories(output, config_.scenes, comm_.rank);
  }
  if (!error.empty()) return {StatusCode::io_error, error};
  if (is_writer()) writer_ = std::make_unique<ImageWriter>(output, threads_);
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
  // A mesh of cells is read as their tets from here on.
  MeshView tet_mesh;
  Status status = guarded("validation", [&] {
    begin_step(step, time);
    if (Status pending = take_pending_error(); !pending.ok()) return pending;
    const render::Stopwatch split;
    if (std::string e = cell_tets_.resolve(mesh, epochs_.topology, tet_mesh); !e.empty()) {
      return invalid(e);
    }
    if (SceneState* first = first_due_scene()) first->record.ingest_ms += split.ms();
    local_tets_ = tet_mesh.tets.count;
    return validate(tet_mesh, fields);
  });
  status = agree(comm_, status, &ranges_, &skips_);
  if (!status.ok()) return status;
  drop_skipped_scenes();
  if (!ranges_.points.empty()) origin_ = 0.5 * (ranges_.points.lo() + ranges_.points.hi());
  ranges_.clear();
  status = guarded("BVH update", [&] { return update_volumes(tet_mesh, fields); });
  status = share_gradients(tet_mesh, status);
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
  if (!probes_.empty()) {
    // Located in the first due scene's volume, which this step brought up to date.
    const SceneState* first = first_due_scene();
    std::string error = probes_.sample(comm_, config_.output.writer_rank,
                                       first ? &volumes_[first->volume] : nullptr, fields, step,
                                       time, config_.output.directory);
    if (pending_.ok() && !error.empty()) pending_ = {StatusCode::io_error, std::move(error)};
  }
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
    for (const std::string* name : {&s.config.field, &s.config.color_by,
                                    &s.config.shading.cap.field, &surface_field(s.config)}) {
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
    for (const std::string* colored :
         {&s.config.color_by, &s.config.shading.cap.field, &surface_field(s.config)}) {
      if (colored->empty() || *colored == volume.field()) continue;
      const Status color_check = check(*colored, color_keep_);
      if (color_check.failed()) return color_check;
      if (!color_check.ok()) {
        skip(k, color_check.message);
        break;
      }
      for (std::size_t t = 0; t < color_keep_.size(); ++t) volume.keep()[t] &= color_keep_[t];
    }
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
  gradient_changes_.assign(volumes_.size(), 0);
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
    // On several ranks the gradients wait for the other ranks' sums (share_gradients).
    const bool smooth = smooth_volume(v);
    policy.vertex_gradients = smooth && comm_.size == 1;
    if (smooth)
      gradient_changes_[v] = volume.needs_load(epochs_) ? kGradientsLoaded : kGradientsUpdated;
    policy.node_planes =
        any_scene_of(scenes_, v, [](const config::Scene& c) { return c.lod_node_pixels > 0; });
    // A cap locates a point per pixel in the leaves: smaller ones, unless the config says.
    const bool caps = any_scene_of(
        scenes_, v, [](const config::Scene& c) { return !c.shading.cap.field.empty(); });
    if (caps && !config_.bvh_leaf_size_given)
      policy.build.leaf_size = render::kPointLocationLeafSize;
    const render::UpdateResult result = volume.update(inputs, epochs_, policy, origin_);
    walks_[v].after_update(volume.volume(), result.kind);
    first->record.bvh_ms = watch.ms();
    first->record.bvh_update = render::to_string(result.kind);
    strongest = std::max(strongest, result.kind);
  }
  bvh_decision_ = render::to_string(strongest);
  return Status::success();
}

bool Adaptor::Impl::smooth_volume(std::size_t v) const {
  return any_scene_of(scenes_, v, [](const config::Scene& c) { return c.shading.smooth; });
}

// A rank whose tets share a vertex with another rank's sees only its own tets there, so the
// exact partial sums are combined over the ranks (render/parallel/shared_gradients.hpp). Every rank
// takes part when any rank's volume changed, and none when any rank's update failed (the agreement
// that follows reports it).
Status Adaptor::Impl::share_gradients(const MeshView& mesh, Status updated) {
  if (comm_.size == 1) return updated;
  std::vector<std::size_t> smooth;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    if (smooth_volume(v) && first_due_scene(v) != nullptr) smooth.push_back(v);
  }
  if (smooth.empty()) return updated;
  std::vector<std::uint8_t> changes = gradient_changes_;
  changes.push_back(updated.ok() ? 0 : 1);
  if (const int rc = render::or_over_ranks(changes, comm_.comm); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "smooth shading: agreeing on changes: " + mpi_error_text(rc)};
  }
  if (changes.back() != 0) return updated;
  return guarded("smooth shading", [&]() -> Status {
    for (std::size_t v : smooth) {
      if (changes[v] == 0) continue;
      const render::Stopwatch watch;
      render::TetVolume& volume = volumes_[v].volume();
      render::ProtocolStatus shared = render::ProtocolStatus::success();
      if (changes[v] & kGradientsLoaded) {
        shared = shared_gradients_[v].match(volume, point_source(mesh.points), comm_.comm);
      }
      if (shared.ok()) shared = shared_gradients_[v].compute(volume);
      if (!shared.ok()) return to_status(std::move(shared));
      first_due_scene(v)->record.bvh_ms += watch.ms();
    }
    return Status::success();
  });
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
    const bool volume_range = s.config.volume && s.config.volume->range.automatic;
    if ((s.colormap != nullptr && s.config.color_range.automatic) || volume_range) {
      const render::Stopwatch watch;
      const std::string& colored = volume_range ? s.config.field : s.config.color_by;
      ranges.color = local_field_range(field_or_empty(fields, colored));
      s.record.color_ms += watch.ms();
    }
    if (s.cap_colormap != nullptr && s.config.shading.cap.range.automatic)
      ranges.cap = local_field_range(field_or_empty(fields, s.config.shading.cap.field));
  }
  return Status::success();
}

Status Adaptor::Impl::trace_scenes(std::span<const FieldView> fields) {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    FieldVolume& volume = volumes_[s.volume];
    if (s.config.volume) {
      const render::Stopwatch watch;
      render::VolumeRenderOptions options =
          volume_options(*s.config.volume, ranges_.scenes[k].color);
      s.color_range = {options.transfer.range_lo, options.transfer.range_hi};
      options.surfaces = s.config.surfaces;
      options.ambient = s.config.ambient;
      if (!surface_field(s.config).empty()) {
        render::load_vertex_field(volume.volume(),
                                  field_source(field_or_empty(fields, surface_field(s.config))),
                                  s.surface_field);
        options.surface_field = s.surface_field;
      }
      s.fragments.resize(s.views.size());
      s.images.resize(s.views.size());
      s.trace_ms.assign(s.views.size(), 0);
      s.trace_ms[0] = watch.ms();  // the transfer function and the surfaces' field, once
      for (std::size_t v = 0; v < s.views.size(); ++v) {
        const render::Stopwatch view_watch;
        const render::Camera camera = view_camera(s, k, v);
        // A camera inside this rank's tets starts every ray's walk in the eye's tet.
        options.eye_tet = render::locate_eye(volume.volume(), volume.bvh(), camera);
        s.fragments[v] = render::render_volume(
            volume.volume(), walks_[s.volume].get(volume.volume()), camera, options);
        s.images[v] = render::resolve(s.fragments[v]);
        s.trace_ms[v] += view_watch.ms();
      }
      continue;
    }
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
      s.color_range = range;
      options.color_by = {s.colormap, static_cast<float>(range.lo), static_cast<float>(range.hi)};
      s.record.color_ms += watch.ms();
    }
    if (s.cap_colormap != nullptr) load_cap(s, ranges_.scenes[k].cap, fields);
    // Every view from the one BVH of the step: only the camera changes.
    const bool shadows = options.lights.shadow_count() > 0;
    s.images.resize(s.views.size());
    s.trace_ms.resize(s.views.size());
    s.shadow_terms.resize(s.views.size());
    const bool transparent = render::has_transparency(s.config.surfaces);
    s.layers.resize(transparent ? s.views.size() : 0);
    for (std::size_t v = 0; v < s.views.size(); ++v) {
      const render::Stopwatch watch;
      const render::Camera camera = view_camera(s, k, v);
      if (transparent) {
        render::trace_layers(s.layers[v], volume.volume(), volume.bvh(), camera, s.config.surfaces,
                             options);
        if (config_.output.per_rank_images && v == 0) {
          render::FragmentImage mine = s.layers[0].color;
          render::flatten_layers(mine, camera, s.images[0]);
        }
      } else {
        std::vector<render::Framebuffer>* terms = shadows ? &s.shadow_terms[v] : nullptr;
        render::trace_into(s.images[v], volume.volume(), volume.bvh(), camera, s.config.surfaces,
                           options, nullptr, terms);
        if (s.cap_colormap != nullptr) {
          const render::ClipCap cap{s.cap_colormap, static_cast<float>(s.cap_range.lo),
                                    static_cast<float>(s.cap_range.hi), s.cap_field};
          render::draw_clip_cap(s.images[v], volume.volume(), volume.bvh(), camera, options, cap,
                                terms);
        }
      }
      s.trace_ms[v] = watch.ms();
    }
  }
  return Status::success();
}

// The cap's field in the vertex store's order and its colormap range for this step.
void Adaptor::Impl::load_cap(SceneState& s, const render::ValueRange& global,
                             std::span<const FieldView> fields) const {
  const render::Stopwatch watch;
  const config::CapSpec& spec = s.config.shading.cap;
  render::load_vertex_field(volumes_[s.volume].volume(),
                            field_source(field_or_empty(fields, spec.field)), s.cap_field);
  s.cap_range = spec.range.automatic ? global : render::ValueRange{spec.range.lo, spec.range.hi};
  usable_color_range(s.cap_range);
  s.record.color_ms += watch.ms();
}

render::TraceOptions Adaptor::Impl::trace_options(const SceneState& s) const {
  render::TraceOptions options;
  options.ambient = s.config.ambient;
  options.smooth = s.config.shading.smooth;
  options.clip = s.config.shading.clip;
  options.lights = s.config.shading.lights;
  if (s.config.lod_node_pixels > 0)
    options.lod = {s.config.lod_node_pixels, volumes_[s.volume].bvh().lod_planes};
  options.max_layers = s.config.shading.max_layers;
  return options;
}

render::Camera Adaptor::Impl::view_camera(const SceneState& s, std::size_t k, std::size_t v) const {
  const render::Camera camera = camera_for(s, ranges_.scenes[k]);
  return s.config.orbit.enabled ? orbit_camera(camera, s.views[v]) : camera;
}

// Before compositing, which leaves only the writer rank's image defined. Of an orbit, the first
// view.
Status Adaptor::Impl::write_rank_images() {
  for (const SceneState& s : scenes_) {
    if (!s.due) continue;
    std::string error =
        write_rank_image(config_.output, s.config.name, s.record.step, comm_.rank, s.images[0]);
    if (!error.empty()) return {StatusCode::io_error, std::move(error)};
  }
  return Status::success();
}

render::Camera Adaptor::Impl::camera_for(const SceneState& s, const SceneRanges& ranges) const {
  const config::CameraSpec& spec = s.config.camera;
  const std::vector<config::Keyframe>& keyframes = s.config.keyframes;
  if (!keyframes.empty() || !spec.auto_fit) {
    render::Camera camera =
        keyframes.empty() ? spec.fixed : keyframe_camera(keyframes, s.record.time);
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
  const int reduced = render::sum_counters_to_root(sums, writer, comm_.comm);
  if (reduced != MPI_SUCCESS || render::max_to_root(rss, writer, comm_.comm) != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "reducing the log counters: " + mpi_error_text(reduced)};
  }
  Status local_failure = Status::success();
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    for (std::size_t v = 0; v < s.views.size(); ++v) {
      Status st = composite_and_submit_view(s, k, v, sums[k], rss, local_failure);
      if (!st.ok()) return st;
    }
  }
  return local_failure;
}

// One view of a scene: composited onto the writer rank (with its shadows), which queues it with
// its own log row: this view's trace and composite times, and (first view only, as shared work
// goes to the first due scene) the stages the views share, run once for all of them.
Status Adaptor::Impl::composite_and_submit_view(SceneState& s, std::size_t k, std::size_t v,
                                                const SceneCounters& sums, std::uint64_t rss,
                                                Status& local_failure) {
  StepRecord r = s.record;
  r.trace_ms = s.trace_ms[v];
  if (v > 0) {
    r.check_ms = r.ingest_ms = r.bvh_ms = r.color_ms = 0;
    r.bvh_update = "none";
  }
  if (Status st = composite_view(s, k, v, r, local_failure); !st.ok()) return st;
  if (is_writer()) submit_view(s, v, std::move(r), sums, rss);
  return Status::success();
}

// Collective. An MPI error is returned; a failure of this rank alone in the shadows goes to
// `local_failure`, since the other scenes' collectives still need this rank.
Status Adaptor::Impl::composite_view(SceneState& s, std::size_t k, std::size_t v, StepRecord& r,
                                     Status& local_failure) {
  render::Framebuffer& image = s.images[v];
  const int writer = config_.output.writer_rank;
  if (!s.layers.empty()) return composite_layered_view(s, k, v, r, local_failure);
  if (comm_.size > 1) {
    const render::Stopwatch watch;
    const int rc = s.config.volume
                       ? render::composite_fragments(s.fragments[v], comm_.comm, writer, image)
                       : render::composite(image, comm_.comm, {.root = writer});
    if (rc != MPI_SUCCESS) {
      return {StatusCode::mpi_error,
              "compositing scene '" + s.config.name + "': " + mpi_error_text(rc)};
    }
    r.composite_ms = watch.ms();
  }
  if (s.config.volume || s.config.shading.lights.shadow_count() == 0) return Status::success();
  const render::Stopwatch watch;
  const FieldVolume& volume = volumes_[s.volume];
  const render::Camera camera = view_camera(s, k, v);
  const render::TraceOptions options = trace_options(s);
  const render::ShadowScene scene{volume.volume(), volume.bvh(), camera, s.config.surfaces,
                                  options};
  Status st =
      to_status(render::shadow_across_ranks(image, s.shadow_terms[v], scene, writer, comm_.comm));
  if (st.code == StatusCode::mpi_error) return st;
  if (!st.ok() && local_failure.ok()) local_failure = std::move(st);
  r.composite_ms += watch.ms();
  return Status::success();
}

// A transparent scene's view: its layers composited onto the writer rank, with their shadows.
Status Adaptor::Impl::composite_layered_view(SceneState& s, std::size_t k, std::size_t v,
                                             StepRecord& r, Status& local_failure) {
  const render::Stopwatch watch;
  const FieldVolume& volume = volumes_[s.volume];
  const render::Camera camera = view_camera(s, k, v);
  const render::TraceOptions options = trace_options(s);
  const render::ShadowScene scene{volume.volume(), volume.bvh(), camera, s.config.surfaces,
                                  options};
  Status st = to_status(render::composite_layers(s.layers[v], scene, config_.output.writer_rank,
                                                 comm_.comm, s.images[v]));
  if (st.code == StatusCode::mpi_error) {
    return {StatusCode::mpi_error, "compositing scene '" + s.config.name + "': " + st.message};
  }
  if (!st.ok() && local_failure.ok()) local_failure = std::move(st);
  r.composite_ms = watch.ms();
  return Status::success();
}

// What the scene colored through a colormap this step, for its colorbars: the surfaces' color
// field or the volume's transfer function, then the cap.
std::vector<ColorScale> Adaptor::Impl::color_scales(const SceneState& s) const {
  std::vector<ColorScale> scales;
  if (s.colormap != nullptr)
    scales.push_back({s.config.color_by, s.colormap, s.color_range.lo, s.color_range.hi});
  if (s.config.volume) {
    scales.push_back({s.config.field, render::find_colormap(s.config.volume->colormap_name),
                      s.color_range.lo, s.color_range.hi});
  }
  if (s.cap_colormap != nullptr)
    scales.push_back({s.config.shading.cap.field, s.cap_colormap, s.cap_range.lo, s.cap_range.hi});
  return scales;
}

// On the writer rank: the view's image and log row to the writer thread.
void Adaptor::Impl::submit_view(SceneState& s, std::size_t v, StepRecord r,
                                const SceneCounters& sums, std::uint64_t rss) {
  render::Framebuffer& image = s.images[v];
  r.tets = sums.tets;
  r.kept_tets = sums.kept_tets;
  r.skipped_tets = sums.skipped_tets;
  r.bvh_bytes = sums.bytes;
  r.peak_rss_bytes = rss;
  r.rays = static_cast<std::uint64_t>(image.pixel_count()) * static_cast<std::uint64_t>(comm_.size);
  ImageJob job;
  job.image = std::move(image);
  std::copy(std::begin(s.config.background), std::end(s.config.background), job.background);
  job.record = r;
  job.annotations = annotations_for(s.config, r, color_scales(s));
  // The viewer page goes with the run's first image, not at create: creating writes only what
  // must exist before any step (folders, table headers), so a nearly full disk fails at an image.
  if (!viewer_page_sent_ && config_.output.cinema) {
    for (const config::Scene& scene : config_.scenes) job.viewer_page_scenes.push_back(scene.name);
    viewer_page_sent_ = true;
  }
  if (s.config.orbit.enabled) {
    job.view = static_cast<int>(v);
    job.phi = s.views[v].phi_deg;
    job.theta = s.views[v].theta_deg;
  }
  writer_->submit(std::move(job));
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
    for (double ms : s.trace_ms) trace_ms += ms;
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
    if (writer_) writer_->finish();
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
