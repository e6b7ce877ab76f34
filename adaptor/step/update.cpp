// The second stage of a render step: each due volume brought to this step (a refit of what
// changed, or a rebuild), smooth shading's gradients summed over the ranks that share a vertex,
// and this rank's bounds and color ranges for the agreement that unites them.
#include <algorithm>

#include "adaptor/input/input_views.hpp"
#include "adaptor/step/color_field.hpp"
#include "adaptor/step/step_runner.hpp"
#include "render/parallel/step_reductions.hpp"

namespace tetray {
namespace {

// Whether a scene of volume v has the property `of` (of its config::Scene).
template <typename Scenes, typename Property>
bool any_scene_of(const Scenes& scenes, std::size_t v, Property of) {
  return std::any_of(scenes.begin(), scenes.end(),
                     [&](const auto& s) { return s.volume == v && of(s.config); });
}

constexpr std::uint8_t kGradientsUpdated = 1;
constexpr std::uint8_t kGradientsLoaded = 2;

}  // namespace

Status Adaptor::Impl::update_volumes(const MeshView& mesh, std::span<const FieldView> fields) {
  render::BvhUpdateKind strongest = render::BvhUpdateKind::none;
  gradient_changes_.assign(volumes_.size(), 0);
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    SceneState* first = first_due_scene(v);
    if (first == nullptr) continue;
    FieldVolume& volume = volumes_[v];
    tets_skipped_ += skipped_[v];
    if (!volume.stale(epochs_)) continue;  // nothing it reads changed: no refit
    const PhaseClock::Phase phase(clock_, first->record.bvh_ms);
    const VolumeInputs inputs{tets_, tie_keys_, point_source(mesh.points),
                              field_source(field_or_empty(fields, volume.field()))};
    const render::UpdatePolicy policy = update_policy(v);
    if (smooth_volume(v))
      gradient_changes_[v] = volume.needs_load(epochs_) ? kGradientsLoaded : kGradientsUpdated;
    const render::UpdateResult result = volume.update(inputs, epochs_, policy, origin_);
    walks_[v].after_update(volume.volume(), result.kind);
    first->record.bvh_update = render::to_string(result.kind);
    strongest = std::max(strongest, result.kind);
  }
  bvh_decision_ = render::to_string(strongest);
  return Status::success();
}

// The config's BVH policy with what volume v's scenes need of it.
render::UpdatePolicy Adaptor::Impl::update_policy(std::size_t v) const {
  render::UpdatePolicy policy = config_.bvh;
  // On several ranks the gradients wait for the other ranks' sums (share_gradients).
  policy.vertex_gradients = smooth_volume(v) && comm_.size == 1;
  policy.gradient_isovalues = gradient_isovalues(v);
  policy.node_planes =
      any_scene_of(scenes_, v, [](const config::Scene& c) { return c.lod_node_pixels > 0; });
  // A cap locates a point per pixel in the leaves: smaller ones, unless the config says.
  const bool caps =
      any_scene_of(scenes_, v, [](const config::Scene& c) { return !c.shading.cap.field.empty(); });
  if (caps && !config_.bvh_leaf_size_given) policy.build.leaf_size = render::kPointLocationLeafSize;
  return policy;
}

bool Adaptor::Impl::smooth_volume(std::size_t v) const {
  return any_scene_of(scenes_, v, [](const config::Scene& c) { return c.shading.smooth; });
}

// The isovalues whose tets' corners need gradients: the surfaces of volume v's smooth scenes,
// ascending. Empty (every vertex) when one of them draws level-of-detail proxies, whose hits
// name a tet of the node that need not straddle a surface.
std::vector<float> Adaptor::Impl::gradient_isovalues(std::size_t v) const {
  std::vector<float> values;
  for (const SceneState& s : scenes_) {
    if (s.volume != v || !s.config.shading.smooth) continue;
    if (s.config.lod_node_pixels > 0) return {};
    for (const render::IsoSurface& surface : s.config.surfaces) values.push_back(surface.value);
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

// A rank whose tets share a vertex with another rank's sees only its own tets there, so the
// exact partial sums are combined over the ranks (render/parallel/shared_gradients.hpp). Every
// rank takes part when any rank's volume changed, and none when any rank's update failed (the
// agreement that follows reports it).
Status Adaptor::Impl::share_gradients(const MeshView& mesh, Status updated) {
  if (comm_.size == 1) return updated;
  std::vector<std::size_t> smooth;
  for (std::size_t v = 0; v < volumes_.size(); ++v) {
    if (smooth_volume(v) && first_due_scene(v) != nullptr) smooth.push_back(v);
  }
  if (smooth.empty()) return updated;
  std::vector<std::uint8_t> changes = gradient_changes_;
  changes.push_back(updated.ok() ? 0 : 1);
  {
    const PhaseClock::Phase phase(clock_, step_costs_.agree_ms);
    if (const int rc = render::or_over_ranks(changes, comm_.comm); rc != MPI_SUCCESS) {
      return {StatusCode::mpi_error, "smooth shading: agreeing on changes: " + mpi_error_text(rc)};
    }
  }
  if (changes.back() != 0) return updated;
  return guarded("smooth shading", [&]() -> Status {
    for (std::size_t v : smooth) {
      if (changes[v] == 0) continue;
      // The exchange with the other ranks is part of the gradients, so of the volume's update.
      const PhaseClock::Phase phase(clock_, first_due_scene(v)->record.bvh_ms);
      render::TetVolume& volume = volumes_[v].volume();
      render::ProtocolStatus shared = render::ProtocolStatus::success();
      if (changes[v] & kGradientsLoaded) {
        shared = shared_gradients_[v].match(volume, point_source(mesh.points), comm_.comm);
      }
      if (shared.ok()) shared = shared_gradients_[v].compute(volume, gradient_isovalues(v));
      if (!shared.ok()) return to_status(std::move(shared));
    }
    return Status::success();
  });
}

// This rank's part of what every rank needs: the box of each auto-fit camera's volume and the
// ranges of the automatic colormaps (surfaces' color_by, a volume's transfer function, a cap).
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
      const PhaseClock::Phase phase(clock_, s.record.color_ms);
      const std::string& colored = volume_range ? s.config.field : s.config.color_by;
      ranges.color = local_field_range(field_or_empty(fields, colored));
    }
    if (s.cap_colormap != nullptr && s.config.shading.cap.range.automatic) {
      const PhaseClock::Phase phase(clock_, s.record.color_ms);
      ranges.cap = local_field_range(field_or_empty(fields, s.config.shading.cap.field));
    }
  }
  return Status::success();
}

}  // namespace tetray
