// What the adaptor keeps per scene of the config: its trigger, its volume, and what one render
// step makes of it (images, layers, shadow terms, colormap ranges, its log row) until the writer
// rank takes them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "adaptor/config/camera_path.hpp"
#include "adaptor/config/config.hpp"
#include "adaptor/output/step_record.hpp"
#include "adaptor/step/trigger.hpp"
#include "render/composite/fragment_composite.hpp"
#include "render/core/fragments.hpp"
#include "render/core/framebuffer.hpp"
#include "render/parallel/global_reduce.hpp"
#include "render/parallel/scene_layers.hpp"
#include "render/scene/colormap.hpp"
#include "render/trace/trace.hpp"

namespace tetray {

// One view's own columns of its log row, this step; the columns the views share are the scene's
// `record`.
struct ViewTimes {
  double trace_ms = 0, composite_ms = 0, hand_off_ms = 0, queue_wait_ms = 0;
};

struct SceneState {
  SceneState(const config::Scene& scene)
      : config(scene), clock(scene.trigger), views(orbit_views(scene.orbit)) {}

  config::Scene config;
  TriggerClock clock;
  std::size_t volume = 0;                      // index into the adaptor's volumes
  const render::Colormap* colormap = nullptr;  // null without color_by
  bool due = false;                            // this step; cleared when the scene is skipped
  bool skipped_last = false;                   // at its last due step: its inputs are checked again
  render::ValueRange color_range;              // of the colormap (a volume scene: its transfer
                                               // function's), this step
  std::vector<View> views;                     // one without an orbit
  std::vector<render::Framebuffer> images;     // per view
  std::vector<ViewTimes> view_times;           // per view, zeroed at each due step
  std::vector<render::VolumeFragmentImage> fragments;  // a volume scene's per view, before
                                                       // compositing
  // Per view, a volume scene's fragment compositing buffers, kept from frame to frame so that
  // their storage is reused.
  std::vector<render::FragmentWorkspace<render::VolumeFragment>> fragment_workspaces;
  // Per view, one term per shadowing light (render/parallel/scene_shadows.hpp).
  std::vector<std::vector<render::Framebuffer>> shadow_terms;
  // Per view, a transparent scene's (render/parallel/scene_layers.hpp).
  std::vector<render::LayerImage> layers;
  std::vector<render::MergedLayers> merged_layers;
  StepRecord record;
  // A clip cap (render/walk/clip_cap.hpp); the colormap is null without one.
  const render::Colormap* cap_colormap = nullptr;
  render::ValueRange cap_range;  // of the cap's colormap, this step
  std::vector<float> cap_field;  // per vertex of the scene's volume
  // A volume scene's surfaces of another field than its own: that field per vertex.
  std::vector<float> surface_field;
};

// The field of a volume scene's surfaces when it is not the scene's own; else empty.
inline const std::string& surface_field(const config::Scene& s) {
  static const std::string none;
  return s.volume ? s.volume->surface_field : none;
}

}  // namespace tetray
