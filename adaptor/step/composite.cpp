// The fourth stage of a render step, collective: the log counters summed onto the writer rank,
// then every view of every due scene composited onto it (depth, fragments or transparent
// layers), with its shadows across ranks, and handed to the writer (output_hand_off.cpp).
#include <sys/resource.h>

#include "adaptor/step/step_runner.hpp"
#include "render/composite/composite.hpp"
#include "render/composite/fragment_composite.hpp"
#include "render/parallel/scene_layers.hpp"
#include "render/parallel/scene_shadows.hpp"
#include "render/parallel/step_reductions.hpp"
#include "render/scene/screen_bound.hpp"

namespace tetray {
namespace {

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

}  // namespace

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
  {
    const PhaseClock::Phase phase(clock_, step_costs_.agree_ms);
    const int reduced = render::sum_counters_to_root(sums, writer, comm_.comm);
    if (reduced != MPI_SUCCESS || render::max_to_root(rss, writer, comm_.comm) != MPI_SUCCESS) {
      return {StatusCode::mpi_error, "reducing the log counters: " + mpi_error_text(reduced)};
    }
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
  if (Status st = composite_view(s, k, v, local_failure); !st.ok()) return st;
  if (!is_writer()) return Status::success();
  StepRecord r = s.record;
  r.trace_ms = s.view_times[v].trace_ms;
  r.composite_ms = s.view_times[v].composite_ms;
  if (v > 0) {
    r.check_ms = r.ingest_ms = r.bvh_ms = r.color_ms = 0;
    r.bvh_update = "none";
  }
  submit_view(s, k, v, std::move(r), sums, rss);
  return Status::success();
}

// Where this rank's hits of a view can be: the screen bound of its volume's box (nothing when
// the box reaches behind the eye, then the compositor scans the whole image); an empty rectangle
// for a rank without tets. The image holds only this rank's trace of its tets and their cap.
std::optional<render::PixelRect> Adaptor::Impl::active_hint(const SceneState& s, std::size_t k,
                                                            std::size_t v) const {
  const FieldVolume& volume = volumes_[s.volume];
  if (volume.bvh().empty()) return render::PixelRect{};
  const render::Bounds4& b = volume.bvh().nodes[0].bounds;
  const render::Vec3d origin = volume.volume().origin;
  const render::Vec3d lo{origin.x + b.lo[0], origin.y + b.lo[1], origin.z + b.lo[2]};
  const render::Vec3d hi{origin.x + b.hi[0], origin.y + b.hi[1], origin.z + b.hi[2]};
  const std::optional<render::ScreenRect> rect = render::screen_bound(view_camera(s, k, v), lo, hi);
  if (!rect) return std::nullopt;
  return render::PixelRect{rect->x0, rect->y0, rect->x1, rect->y1};
}

// Collective. An MPI error is returned; a failure of this rank alone in the shadows goes to
// `local_failure`, since the other scenes' collectives still need this rank.
Status Adaptor::Impl::composite_view(SceneState& s, std::size_t k, std::size_t v,
                                     Status& local_failure) {
  render::Framebuffer& image = s.images[v];
  const int writer = config_.output.writer_rank;
  if (!s.layers.empty()) return composite_layered_view(s, k, v, local_failure);
  if (comm_.size > 1) {
    const PhaseClock::Phase phase(clock_, s.view_times[v].composite_ms);
    const int rc = s.config.volume
                       ? render::composite_fragments(s.fragments[v], comm_.comm, writer, image, {},
                                                     nullptr, &s.fragment_workspaces[v])
                       : render::composite(image, comm_.comm,
                                           {.root = writer, .active_hint = active_hint(s, k, v)},
                                           nullptr, &composite_workspace_);
    if (rc != MPI_SUCCESS) {
      return {StatusCode::mpi_error,
              "compositing scene '" + s.config.name + "': " + mpi_error_text(rc)};
    }
  }
  if (s.config.volume || s.config.shading.lights.shadow_count() == 0) return Status::success();
  const PhaseClock::Phase phase(clock_, s.view_times[v].composite_ms);
  const FieldVolume& volume = volumes_[s.volume];
  const render::Camera camera = view_camera(s, k, v);
  const render::TraceOptions options = trace_options(s);
  const render::ShadowScene scene{volume.volume(), volume.bvh(), camera, s.config.surfaces,
                                  options};
  Status st =
      to_status(render::shadow_across_ranks(image, s.shadow_terms[v], scene, writer, comm_.comm));
  if (st.code == StatusCode::mpi_error) return st;
  if (!st.ok() && local_failure.ok()) local_failure = std::move(st);
  return Status::success();
}

// A transparent scene's view: its layers composited onto the writer rank, with their shadows.
Status Adaptor::Impl::composite_layered_view(SceneState& s, std::size_t k, std::size_t v,
                                             Status& local_failure) {
  const PhaseClock::Phase phase(clock_, s.view_times[v].composite_ms);
  const FieldVolume& volume = volumes_[s.volume];
  const render::Camera camera = view_camera(s, k, v);
  const render::TraceOptions options = trace_options(s);
  const render::ShadowScene scene{volume.volume(), volume.bvh(), camera, s.config.surfaces,
                                  options};
  Status st = to_status(render::composite_layers(s.layers[v], scene, config_.output.writer_rank,
                                                 comm_.comm, s.images[v], s.merged_layers[v]));
  if (st.code == StatusCode::mpi_error) {
    return {StatusCode::mpi_error, "compositing scene '" + s.config.name + "': " + st.message};
  }
  if (!st.ok() && local_failure.ok()) local_failure = std::move(st);
  return Status::success();
}

}  // namespace tetray
