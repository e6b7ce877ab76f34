// A volume scene's views on this rank (docs/architecture.md §8): the transfer function of the
// step, the surfaces' own field when it is not the scene's, then per view a walk through this
// rank's tets, kept as fragments for the compositor and resolved for a per-rank image where one
// is used.
#include "adaptor/input/input_views.hpp"
#include "adaptor/step/step_runner.hpp"
#include "render/walk/volume_render.hpp"

namespace tetray {

void Adaptor::Impl::render_volume_scene(SceneState& s, std::size_t k,
                                        std::span<const FieldView> fields) {
  FieldVolume& volume = volumes_[s.volume];
  render::VolumeRenderOptions options;
  {
    // The transfer function and the surfaces' field, once for all views: the first view's trace.
    const PhaseClock::Phase setup(clock_, s.view_times[0].trace_ms);
    options = volume_options(*s.config.volume, ranges_.scenes[k].color);
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
    s.fragment_workspaces.resize(s.views.size());
    s.images.resize(s.views.size());
  }
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    const PhaseClock::Phase phase(clock_, s.view_times[v].trace_ms);
    const render::Camera camera = view_camera(s, k, v);
    // A camera inside this rank's tets starts every ray's walk in the eye's tet.
    options.eye_tet = render::locate_eye(volume.volume(), volume.bvh(), camera);
    options.bvh = &volume.bvh();
    s.fragments[v] = render::render_volume(volume.volume(), walks_[s.volume].get(volume.volume()),
                                           camera, options);
    // One rank's image is the output. On several, the writer's comes from compositing the
    // fragments, and the others' images are only written when asked for (of the first view).
    if (comm_.size == 1 || (config_.output.per_rank_images && v == 0))
      s.images[v] = render::resolve(s.fragments[v]);
  }
}

}  // namespace tetray
