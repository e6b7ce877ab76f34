#include "adaptor/step/volume_scene.hpp"

#include "adaptor/step/color_field.hpp"
#include "render/scene/colormap.hpp"

namespace tetray {

void WalkCache::after_update(const render::TetVolume& volume, render::BvhUpdateKind kind) {
  if (kind == render::BvhUpdateKind::rebuild) walk_.reset();
  if (kind == render::BvhUpdateKind::refit && walk_) {
    render::refit_boundary_faces(volume, walk_->boundary);
  }
}

const render::WalkStructure& WalkCache::get(const render::TetVolume& volume) {
  if (!walk_) walk_ = render::build_walk_structure(volume);
  return *walk_;
}

render::VolumeRenderOptions volume_options(const config::VolumeSpec& spec,
                                           render::ValueRange global_range) {
  render::ValueRange range =
      spec.range.automatic ? global_range : render::ValueRange{spec.range.lo, spec.range.hi};
  usable_color_range(range);
  render::VolumeRenderOptions options;
  options.transfer.colormap = render::find_colormap(spec.colormap_name);
  options.transfer.range_lo = range.lo;
  options.transfer.range_hi = range.hi;
  options.transfer.opacity = spec.opacity;
  options.transfer.unit_distance = spec.unit_distance;
  options.termination = spec.termination;
  return options;
}

}  // namespace tetray
