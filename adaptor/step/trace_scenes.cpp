// The third stage of a render step, on each rank alone: every view of every due scene traced
// against this rank's tets, each from the step's one BVH (only the camera changes). A surface
// scene is traced here, a volume scene rendered in render_volume_scenes.cpp.
#include "adaptor/input/input_views.hpp"
#include "adaptor/step/color_field.hpp"
#include "adaptor/step/step_runner.hpp"
#include "render/trace/layer_shading.hpp"
#include "render/walk/clip_cap.hpp"
#include "render/walk/volume_render.hpp"

namespace tetray {

Status Adaptor::Impl::trace_scenes(std::span<const FieldView> fields) {
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    SceneState& s = scenes_[k];
    if (!s.due) continue;
    if (s.config.volume) {
      render_volume_scene(s, k, fields);
    } else {
      trace_surface_scene(s, k, fields);
    }
  }
  return Status::success();
}

void Adaptor::Impl::trace_surface_scene(SceneState& s, std::size_t k,
                                        std::span<const FieldView> fields) {
  render::TraceOptions options = trace_options(s);
  if (s.colormap != nullptr) load_color(s, k, fields, options);
  if (s.cap_colormap != nullptr) load_cap(s, ranges_.scenes[k].cap, fields);
  // Every view from the one BVH of the step: only the camera changes.
  s.images.resize(s.views.size());
  s.shadow_terms.resize(s.views.size());
  const bool transparent = render::has_transparency(s.config.surfaces);
  s.layers.resize(transparent ? s.views.size() : 0);
  s.merged_layers.resize(s.layers.size());
  for (std::size_t v = 0; v < s.views.size(); ++v) trace_surface_view(s, k, v, options);
}

// A transparent scene's view as its layers (the first view also flattened, for a per-rank
// image); else its image, with one shadow term per shadowing light and the clip cap drawn in.
void Adaptor::Impl::trace_surface_view(SceneState& s, std::size_t k, std::size_t v,
                                       const render::TraceOptions& options) {
  const FieldVolume& volume = volumes_[s.volume];
  const bool shadows = options.lights.shadow_count() > 0;
  const PhaseClock::Phase phase(clock_, s.view_times[v].trace_ms);
  const render::Camera camera = view_camera(s, k, v);
  if (!s.layers.empty()) {
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
      // The walk structure's adjacency lets a cap point be found from the previous pixel's tet.
      const render::WalkStructure& walk = walks_[s.volume].get(volume.volume());
      render::draw_clip_cap(s.images[v], volume.volume(), volume.bvh(), camera, options, cap, terms,
                            &walk.adjacency);
    }
  }
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

// The color_by field in the vertex store's order, and its colormap range for this step (the
// agreed global range when automatic).
void Adaptor::Impl::load_color(SceneState& s, std::size_t k, std::span<const FieldView> fields,
                               render::TraceOptions& options) {
  const PhaseClock::Phase phase(clock_, s.record.color_ms);
  render::load_color_field(volumes_[s.volume].volume(),
                           field_source(field_or_empty(fields, s.config.color_by)));
  render::ValueRange range =
      s.config.color_range.automatic
          ? ranges_.scenes[k].color
          : render::ValueRange{s.config.color_range.lo, s.config.color_range.hi};
  usable_color_range(range);
  s.color_range = range;
  options.color_by = {s.colormap, static_cast<float>(range.lo), static_cast<float>(range.hi)};
}

// The cap's field in the vertex store's order and its colormap range for this step.
void Adaptor::Impl::load_cap(SceneState& s, const render::ValueRange& global,
                             std::span<const FieldView> fields) {
  const PhaseClock::Phase phase(clock_, s.record.color_ms);
  const config::CapSpec& spec = s.config.shading.cap;
  render::load_vertex_field(volumes_[s.volume].volume(),
                            field_source(field_or_empty(fields, spec.field)), s.cap_field);
  s.cap_range = spec.range.automatic ? global : render::ValueRange{spec.range.lo, spec.range.hi};
  usable_color_range(s.cap_range);
}

}  // namespace tetray
