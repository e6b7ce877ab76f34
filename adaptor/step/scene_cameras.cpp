// Each view's camera: keyframes at the step's time, the camera as given, or one fitted to the
// volume's box agreed over the ranks; an orbit's view turns it about its look_at.
#include "adaptor/config/camera_path.hpp"
#include "adaptor/step/step_runner.hpp"

namespace tetray {

render::Camera Adaptor::Impl::view_camera(const SceneState& s, std::size_t k, std::size_t v) const {
  const render::Camera camera = camera_for(s, ranges_.scenes[k]);
  return s.config.orbit.enabled ? orbit_camera(camera, s.views[v]) : camera;
}

render::Camera Adaptor::Impl::camera_for(const SceneState& s, const SceneRanges& ranges) const {
  const config::CameraSpec& spec = s.config.camera;
  const std::vector<config::Keyframe>& keyframes = s.config.keyframes;
  if (!keyframes.empty() || !spec.auto_fit) {
    render::Camera camera =
        keyframes.empty() ? spec.fixed : keyframe_camera(keyframes, s.record.time);
    camera.width = s.config.width;
    camera.height = s.config.height;
    return camera;
  }
  render::Vec3d lo{-1, -1, -1}, hi{1, 1, 1};  // nothing to fit on any rank
  if (!ranges.box.empty()) {
    lo = ranges.box.lo();
    hi = ranges.box.hi();
  }
  return render::fit_camera(lo, hi, spec.view_direction, spec.up, spec.fov_deg, s.config.width,
                            s.config.height);
}

}  // namespace tetray
