// The adaptor behind the public API (class Adaptor::Impl): per-scene triggers, one FieldVolume
// per isosurface field, the render step of docs/architecture.md §2 as a sequence of stages, and
// the writer thread on the writer rank (output.writer_rank). The stages are defined one file per
// phase of the step, in the order an execute call runs them:
//   step.cpp              execute: the triggers, then render_step, the data flow of one step
//   validate.cpp          the solver's arrays checked and converted (connectivity, tie keys)
//   update.cpp            the volumes and BVHs brought to the step, shared gradients, ranges
//   trace_scenes.cpp      the surfaces of each view traced on this rank
//   render_volume_scenes.cpp  the volume scenes rendered on this rank
//   scene_cameras.cpp     each view's camera
//   composite.cpp         each view composited onto the writer rank, with its shadows
//   output_hand_off.cpp   the writer rank's images and log rows to the writer thread
//   step_runner.cpp       creation, start and finalize
#pragma once

#include <tbb/task_arena.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "adaptor/config/camera_path.hpp"
#include "adaptor/config/config.hpp"
#include "adaptor/input/cell_tets.hpp"
#include "adaptor/output/annotations.hpp"
#include "adaptor/output/image_writer.hpp"
#include "adaptor/output/step_record.hpp"
#include "adaptor/step/collective.hpp"
#include "adaptor/step/field_volume.hpp"
#include "adaptor/step/phase_clock.hpp"
#include "adaptor/step/probes.hpp"
#include "adaptor/step/scene_state.hpp"
#include "adaptor/step/volume_scene.hpp"
#include "render/composite/composite.hpp"
#include "render/composite/composite_region.hpp"
#include "render/core/framebuffer.hpp"
#include "render/parallel/global_reduce.hpp"
#include "render/parallel/shared_gradients.hpp"
#include "render/parallel/step_reductions.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/colormap.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "tetray/adaptor.hpp"

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
  static constexpr std::size_t kAnyVolume = ~std::size_t{0};

  // step.cpp. The stages of a render step (docs/architecture.md §2); each returns what went wrong
  // on this rank, and render_step agrees on the outcome across ranks before every collective
  // stage. A fault of one scene's field skips that scene (on every rank) and the step goes on.
  Status render_step(std::int64_t step, double time, const MeshView& mesh,
                     std::span<const FieldView> fields);
  void begin_step(std::int64_t step, double time);
  void drop_skipped_scenes();
  Status update_step(const MeshView& mesh, std::span<const FieldView> fields);
  Status render_scenes(std::span<const FieldView> fields);
  void sample_probes(std::int64_t step, double time, std::span<const FieldView> fields);
  Status skipped_status() const;
  // The first due scene (of volume v); null when none is due.
  SceneState* first_due_scene(std::size_t v = kAnyVolume);
  void print_progress(std::int64_t step, double time, double blocked_ms) const;
  void fill_report(const Status& status, double blocked_ms, ExecuteReport& report) const;
  // agree() on comm_, its time (waiting for the slowest rank included) charged to agree_ms.
  Status agree_on(const Status& local, StepRanges* ranges = nullptr, SceneSkips* skips = nullptr);
  // On the writer rank, after the call's clock stopped: the log rows of the views it handed over.
  void log_step(double blocked_ms);

  // validate.cpp. A mesh of cells comes back in `tet_mesh` as its tets.
  Status validate_step(std::int64_t step, double time, const MeshView& mesh,
                       std::span<const FieldView> fields, MeshView& tet_mesh);
  Status split_and_validate(const MeshView& mesh, std::span<const FieldView> fields,
                            MeshView& tet_mesh);
  void forget_topology();  // the split and tie keys are made again at the next step
  Status validate(const MeshView& mesh, std::span<const FieldView> fields);
  Status check_scene_fields(const MeshView& mesh, std::span<const FieldView> fields);
  std::string convert_topology(const MeshView& mesh);
  bool needs_check(std::size_t v);
  Status check_volume(std::size_t v, const MeshView& mesh, std::span<const FieldView> fields);
  Status check_field(const std::string& name, std::vector<std::uint8_t>& keep, const MeshView& mesh,
                     std::span<const FieldView> fields);
  void skip(std::size_t scene, std::string reason);

  // update.cpp
  Status update_volumes(const MeshView& mesh, std::span<const FieldView> fields);
  render::UpdatePolicy update_policy(std::size_t v) const;
  // Smooth shading's gradients of the volumes split over ranks, after `updated` (the update's
  // outcome on this rank). Collective when some due scene is smooth and there are several ranks.
  Status share_gradients(const MeshView& mesh, Status updated);
  bool smooth_volume(std::size_t v) const;
  std::vector<float> gradient_isovalues(std::size_t v) const;
  Status global_inputs(std::span<const FieldView> fields);

  // trace_scenes.cpp and render_volume_scenes.cpp
  Status trace_scenes(std::span<const FieldView> fields);
  void trace_surface_scene(SceneState& s, std::size_t k, std::span<const FieldView> fields);
  void trace_surface_view(SceneState& s, std::size_t k, std::size_t v,
                          const render::TraceOptions& options);
  void render_volume_scene(SceneState& s, std::size_t k, std::span<const FieldView> fields);
  render::TraceOptions trace_options(const SceneState& s) const;
  void load_color(SceneState& s, std::size_t k, std::span<const FieldView> fields,
                  render::TraceOptions& options);
  void load_cap(SceneState& s, const render::ValueRange& global, std::span<const FieldView> fields);

  // scene_cameras.cpp. Scene k's camera for view v (its orbit's, or the camera as given).
  render::Camera view_camera(const SceneState& s, std::size_t k, std::size_t v) const;
  render::Camera camera_for(const SceneState& s, const SceneRanges& ranges) const;

  // composite.cpp
  Status composite_and_submit();
  // Per view of a scene: compositing (and shadows), then the writer's job.
  Status composite_and_submit_view(SceneState& s, std::size_t k, std::size_t v,
                                   const SceneCounters& sums, std::uint64_t rss,
                                   Status& local_failure);
  Status composite_view(SceneState& s, std::size_t k, std::size_t v, Status& local_failure);
  std::optional<render::PixelRect> active_hint(const SceneState& s, std::size_t k,
                                               std::size_t v) const;
  Status composite_layered_view(SceneState& s, std::size_t k, std::size_t v, Status& local_failure);

  // output_hand_off.cpp
  Status write_rank_images();
  void submit_view(SceneState& s, std::size_t k, std::size_t v, StepRecord r,
                   const SceneCounters& sums, std::uint64_t rss);
  std::vector<ColorScale> color_scales(const SceneState& s) const;

  // step_runner.cpp
  Status prepare_outputs_on_this_rank();
  bool is_writer() const { return comm_.rank == config_.output.writer_rank; }
  Status take_pending_error();

  Communicator comm_;
  config::Config config_;
  // The clock of the execute call in progress (phase_clock.hpp); the step's costs that belong to
  // no scene (check, ingest, agree, probes, other), which go to its first log row; and on the
  // writer rank the rows of the views handed to the writer, completed when the call returns.
  PhaseClock clock_;
  StepRecord step_costs_;
  struct HandedOver {
    std::size_t scene = 0, view = 0;
    StepRecord row;
  };
  std::vector<HandedOver> handed_over_;
  std::vector<SceneState> scenes_;
  std::vector<FieldVolume> volumes_;
  std::vector<WalkCache> walks_;  // per volume, built for volume scenes and clip caps only
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
  // The compositor's receive buffers, kept between steps (render/composite/composite.hpp).
  render::CompositeWorkspace composite_workspace_;
  std::string bvh_decision_;
  std::uint64_t tets_skipped_ = 0;

  // The renderer's threads: every parallel loop of a render step runs in this arena, so a rank
  // uses config.threads or what its affinity mask and CPU quota allow
  // (adaptor/step/thread_budget.hpp).
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
