// The first stage of a render step: the solver's mesh and fields checked (shape, indices,
// non-finite values) and converted once per topology (cells to tets, int64 connectivity, tie
// keys). A field at fault skips the scenes that read it; a mesh at fault fails the step.
#include <algorithm>
#include <utility>

#include "adaptor/input/input_views.hpp"
#include "adaptor/input/tie_keys.hpp"
#include "adaptor/step/step_runner.hpp"
#include "render/volume/mesh_check.hpp"

namespace tetray {
namespace {

Status invalid(std::string message) { return {StatusCode::invalid_argument, std::move(message)}; }

// A check that failed only for non-finite field values: the field is unusable, the mesh is not,
// so only the scenes reading that field are skipped.
bool field_fault(const render::MeshCheck& found) {
  return !found.error.empty() && found.nonfinite_values > 0 && found.tets_out_of_range == 0 &&
         found.nonfinite_points == 0;
}

std::uint64_t count_zeros(const std::vector<std::uint8_t>& keep) {
  return static_cast<std::uint64_t>(std::count(keep.begin(), keep.end(), std::uint8_t{0}));
}

}  // namespace

Status Adaptor::Impl::validate_step(std::int64_t step, double time, const MeshView& mesh,
                                    std::span<const FieldView> fields, MeshView& tet_mesh) {
  begin_step(step, time);
  if (Status pending = take_pending_error(); !pending.ok()) return pending;
  Status status = split_and_validate(mesh, fields, tet_mesh);
  // The cells' split and the tie keys follow the points' positions at a new topology and are
  // kept while the solver says the topology holds: a step whose arrays failed their checks (a
  // NaN coordinate) leaves none behind, or its repair, passed as new geometry only, would still
  // be cut and tied by the bad positions.
  if (status.failed()) forget_topology();
  return status;
}

Status Adaptor::Impl::split_and_validate(const MeshView& mesh, std::span<const FieldView> fields,
                                         MeshView& tet_mesh) {
  {
    const PhaseClock::Phase split(clock_, step_costs_.ingest_ms);
    if (std::string e = cell_tets_.resolve(mesh, epochs_.topology, tet_mesh); !e.empty()) {
      return invalid(e);
    }
  }
  local_tets_ = tet_mesh.tets.count;
  return validate(tet_mesh, fields);
}

void Adaptor::Impl::forget_topology() {
  cell_tets_.forget();
  converted_topology_ = ~std::uint64_t{0};
}

Status Adaptor::Impl::validate(const MeshView& mesh, std::span<const FieldView> fields) {
  if (std::string e = check_mesh_shape(mesh); !e.empty()) return invalid(e);
  if (Status st = check_scene_fields(mesh, fields); !st.ok()) return st;
  {
    const PhaseClock::Phase ingest(clock_, step_costs_.ingest_ms);
    if (std::string e = convert_topology(mesh); !e.empty()) return invalid(e);
  }
  bool loading = false;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    if (!needs_check(v)) continue;
    if (Status st = check_volume(v, mesh, fields); !st.ok()) return st;
    loading = loading || (first_due_scene(v) != nullptr && volumes_[v].needs_load(epochs_));
  }
  if (loading) {
    // The bounds of a load's points, for the local origin every rank shares: part of loading.
    const PhaseClock::Phase ingest(clock_, step_costs_.ingest_ms);
    add_point_bounds(mesh.points, ranges_.points);
  }
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

// Partial: only the field is at fault. A faulty isosurface field skips every scene of the
// volume, a faulty color field only its scene.
Status Adaptor::Impl::check_volume(std::size_t v, const MeshView& mesh,
                                   std::span<const FieldView> fields) {
  const PhaseClock::Phase phase(clock_, step_costs_.check_ms);
  FieldVolume& volume = volumes_[v];
  const Status volume_check = check_field(volume.field(), volume.keep(), mesh, fields);
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
      const Status color_check = check_field(*colored, color_keep_, mesh, fields);
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
  return Status::success();
}

// The mesh with the field `name`: its keep mask in `keep`; success when usable, else the finding,
// with code partial when only the field is at fault. The indices are checked again only when the
// topology or the point count changed since they last passed.
Status Adaptor::Impl::check_field(const std::string& name, std::vector<std::uint8_t>& keep,
                                  const MeshView& mesh, std::span<const FieldView> fields) {
  const CheckedIndices now{epochs_.topology, mesh.points.count};
  const bool indices_known =
      checked_indices_.topology == now.topology && checked_indices_.points == now.points;
  const render::MeshCheck found = render::check_mesh(tets_, point_source(mesh.points),
                                                     field_source(field_or_empty(fields, name)),
                                                     config_.nonfinite, keep, !indices_known);
  if (found.error.empty()) {
    checked_indices_ = now;
    return Status::success();
  }
  return Status{field_fault(found) ? StatusCode::partial : StatusCode::invalid_argument,
                "mesh with field '" + name + "': " + found.error};
}

}  // namespace tetray
