// The adaptor behind the public API: per-scene triggers, one FieldVolume per isosurface field,
// the render step of docs/architecture.md §2 as a sequence of stages, and the writer thread on the
// writer rank (output.writer_rank).
#pragma once

#include <tbb/task_arena.h>

#include <memory>
#include <span>
#include <vector>

#include "cell_tets.hpp"

#include "annotations.hpp"
#include "camera_path.hpp"
#include "collective.hpp"
#include "config.hpp"
#include "field_volume.hpp"
#include "image_writer.hpp"
#include "probes.hpp"
#include "render/core/framebuffer.hpp"
#include "render/parallel/global_reduce.hpp"
#include "render/parallel/shared_gradients.hpp"
#include "render/parallel/step_reductions.hpp"
#include "render/scene/colormap.hpp"
#include "render/trace/trace.hpp"
#include "step_record.hpp"
#include "tetray/adaptor.hpp"
#include "trigger.hpp"
#include "volume_scene.hpp"

namespace tetray {

class Adaptor::Impl {
 public:
  Impl(Communicator comm, config::Config config);
  ~Impl();

  // Collective: the writer rank creates the output directories and logs (every rank its own
  // per-rank image directories); every rank gets the outcome. Only a started adaptor's finalize
  // is collective.
  Status start();

  bool will_render(std::int64_t step, double time) const;
  Status execute(std::int64_t step, double time, const MeshView& mesh,
                 std::span<const FieldView> fields, const Changes& changes, ExecuteReport* report);
  Status execute_failed(std::int64_t step, double time, Status error, const Changes& changes,
                        ExecuteReport* report);
  Status finalize();

 private:
  struct SceneState {
    SceneState(const config::Scene& scene)
        : config(scene), clock(scene.trigger), views(orbit_views(scene.orbit)) {}

    config::Scene config;
    TriggerClock clock;
    std::size_t volume = 0;                      // index into volumes_
    const render::Colormap* colormap = nullptr;  // null without color_by
    bool due = false;                            // this step; cleared when the scene is skipped
    bool skipped_last = false;                // at its last due step: its inputs are checked again
    render::ValueRange color_range;           // of the colormap (a volume scene: its transfer
                                              // function's), this step
    std::vector<View> views;                  // one without an orbit
    std::vector<render::Framebuffer> images;  // per view
    std::vector<double> trace_ms;             // per view
    std::vector<render::VolumeFragmentImage> fragments;  // a volume scene's per view, before
                                                         // compositing
    // Per view, one term per shadowing light (render/parallel/scene_shadows.hpp).
    std::vector<std::vector<render::Framebuffer>> shadow_terms;
    // Per view, a transparent scene's layers (render/parallel/scene_layers.hpp).
    std::vector<render::LayerImage> layers;
    StepRecord record;
    // A clip cap (render/walk/clip_cap.hpp); the colormap is null without one.
    const render::Colormap* cap_colormap = nullptr;
    render::ValueRange cap_range;  // of the cap's colormap, this step
    std::vector<float> cap_field;  // per vertex of the scene's volume
    // A volume scene's surfaces of another field than its own: that field per vertex.
    std::vector<float> surface_field;
  };

  static constexpr std::size_t kAnyVolume = ~std::size_t{0};

  // The stages of a render step (docs/architecture.md §2); each returns what went wrong on this
  // rank, and render_step agrees on the outcome across ranks before every collective stage.
  // A fault of one scene's field skips that scene (on every rank) and the step goes on.
  Status render_step(std::int64_t step, double time, const MeshView& mesh,
                     std::span<const FieldView> fields);
  void begin_step(std::int64_t step, double time);
  Status validate(const MeshView& mesh, std::span<const FieldView> fields);
  Status check_scene_fields(const MeshView& mesh, std::span<const FieldView> fields);
  std::string convert_topology(const MeshView& mesh);
  bool needs_check(std::size_t v);
  Status check_volume(std::size_t v, const MeshView& mesh, std::span<const FieldView> fields);
  void skip(std::size_t scene, std::string reason);
  void drop_skipped_scenes();
  Status skipped_status() const;
  Status update_volumes(const MeshView& mesh, std::span<const FieldView> fields);
  // Smooth shading's gradients of the volumes split over ranks, after `updated` (the update's
  // outcome on this rank). Collective when some due scene is smooth and there are several ranks.
  Status share_gradients(const MeshView& mesh, Status updated);
  bool smooth_volume(std::size_t v) const;
  Status global_inputs(std::span<const FieldView> fields);
  Status trace_scenes(std::span<const FieldView> fields);
  Status write_rank_images();
  Status composite_and_submit();
  // Per view of a scene: compositing (and shadows), then the writer's job.
  Status composite_and_submit_view(SceneState& s, std::size_t k, std::size_t v,
                                   const SceneCounters& sums, std::uint64_t rss,
                                   Status& local_failure);
  Status composite_view(SceneState& s, std::size_t k, std::size_t v, StepRecord& r,
                        Status& local_failure);
  void submit_view(SceneState& s, std::size_t v, StepRecord r, const SceneCounters& sums,
                   std::uint64_t rss);
  Status composite_layered_view(SceneState& s, std::size_t k, std::size_t v, StepRecord& r,
                                Status& local_failure);
  render::TraceOptions trace_options(const SceneState& s) const;
  std::vector<ColorScale> color_scales(const SceneState& s) const;
  void load_cap(SceneState& s, const render::ValueRange& global,
                std::span<const FieldView> fields) const;
  // Scene k's camera for view v (its orbit's, or the camera as given).
  render::Camera view_camera(const SceneState& s, std::size_t k, std::size_t v) const;

  Status prepare_outputs_on_this_rank();
  bool is_writer() const { return comm_.rank == config_.output.writer_rank; }
  // The first due scene (of volume v); null when none is due.
  SceneState* first_due_scene(std::size_t v = kAnyVolume);
  render::Camera camera_for(const SceneState& s, const SceneRanges& ranges) const;
  void print_progress(std::int64_t step, double time, double blocked_ms) const;
  void fill_report(const Status& status, double blocked_ms, ExecuteReport& report) const;
  Status take_pending_error();

  Communicator comm_;
  config::Config config_;
  std::vector<SceneState> scenes_;
  std::vector<FieldVolume> volumes_;
  std::vector<WalkCache> walks_;  // per volume, built for volume scenes only
  std::vector<render::SharedGradients> shared_gradients_;  // per volume, smooth on several ranks
  // Per volume, this step's update on this rank: kGradientsUpdated or kGradientsLoaded (a new
  // topology or set of rendered tets, so new shared vertices), for smooth volumes only.
  std::vector<std::uint8_t> gradient_changes_;
  std::vector<std::uint64_t> skipped_;  // per volume, at its last check
  SceneSkips skips_;                    // per scene, this step
  ChangeEpochs epochs_{};
  StepRanges ranges_;

  CellTets cell_tets_;  // the split of a mesh given as cells, kept until the topology changes
  // This step's connectivity as int64, and the int32 conversion and tie keys kept across steps
  // until the topology changes.
  std::span<const std::int64_t> tets_;
  std::vector<std::int64_t> tets_converted_;
  std::vector<std::uint32_t> tie_keys_;
  std::uint64_t converted_topology_ = ~std::uint64_t{0};
  // The topology epoch and point count whose indices were last checked: until either changes,
  // the index check (most of a check's cost) is not repeated.
  struct CheckedIndices {
    std::uint64_t topology = ~std::uint64_t{0};
    std::size_t points = 0;
  } checked_indices_;
  std::size_t local_tets_ = 0;
  std::vector<std::uint8_t> color_keep_;
  render::Vec3d origin_{};
  std::string bvh_decision_;
  std::uint64_t tets_skipped_ = 0;

  // The renderer's threads: every parallel loop of a render step runs in this arena, so a rank
  // uses config.threads or what its affinity mask and CPU quota allow (thread_budget.hpp).
  int threads_ = 1;
  tbb::task_arena arena_;
  std::unique_ptr<ImageWriter> writer_;  // on the writer rank only
  ProbeSampler probes_;
  // A failure of this rank after the step's last agreement (compositing, handing the image to
  // the writer): reported at the next agreement, with the writer's errors, so that every rank
  // returns the same status from each call.
  Status pending_;
  bool viewer_page_sent_ = false;  // index.html, with the writer rank's first image
  bool started_ = false;
  bool finalized_ = false;
};

}  // namespace tetray
