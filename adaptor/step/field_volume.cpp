#include "adaptor/step/field_volume.hpp"

namespace tetray {

bool FieldVolume::stale(const ChangeEpochs& now) const {
  return !loaded_ || now.topology != seen_.topology || now.geometry != seen_.geometry ||
         now.fields != seen_.fields;
}

render::UpdateResult FieldVolume::update(const VolumeInputs& in, const ChangeEpochs& now,
                                         const render::UpdatePolicy& policy,
                                         const render::Vec3d& origin) {
  render::UpdateResult result;
  if (needs_load(now)) {
    result = render::load_volume(volume_, bvh_, in.tets, keep_, in.tie_keys, in.points, in.field,
                                 policy, &origin);
    keep_at_load_ = keep_;
    loaded_ = true;
  } else if (stale(now)) {
    const render::StepChanges changes{now.geometry != seen_.geometry, now.fields != seen_.fields};
    result = render::update_volume(volume_, bvh_, in.points, in.field, changes, policy);
  }
  seen_ = now;
  return result;
}

}  // namespace tetray
