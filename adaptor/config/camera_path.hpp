// The camera paths of a scene: the views of its orbit (config::Orbit), the scene's camera moved
// on the sphere about its look_at, keeping its distance, up vector and field of view; or its
// keyframes (config::Keyframe), one camera per step interpolated at the step's simulated time.
// Every view of a step is traced from the step's one BVH; only the rays change.
#pragma once

#include <vector>

#include "adaptor/config/config.hpp"
#include "render/scene/camera.hpp"

namespace tetray {

struct View {
  double phi_deg = 0;    // azimuth about the camera's up vector (right-handed)
  double theta_deg = 0;  // elevation towards up, added to the camera's own
};

// Every elevation with every azimuth, elevation-major: (theta_0, phi_0), (theta_0, phi_1), ...
std::vector<View> orbit_views(const config::Orbit& orbit);

// The camera's own elevation above the plane normal to `up`, in degrees: the angle of
// eye - look_at (or an auto-fit camera's view_direction) with that plane.
double camera_elevation_deg(render::Vec3d towards_eye, render::Vec3d up);

// `base` seen from `view`: its offset from look_at turned by phi about up, then raised by theta.
// The caller keeps the total elevation inside (-90, 90) degrees (config_views.cpp checks it).
render::Camera orbit_camera(const render::Camera& base, const View& view);

// The camera of `keyframes` (at least one, strictly increasing times) at simulated time `time`:
// eye, look_at and fov_deg linear in time between the two keyframes around it, up linear and
// renormalized; before the first keyframe the first holds, after the last the last. At a
// keyframe's time, exactly that keyframe's camera.
render::Camera keyframe_camera(const std::vector<config::Keyframe>& keyframes, double time);

// Whether the camera's frame is undefined or dominated by rounding (render::camera_problem, the
// check config_parse.cpp puts on every camera).
bool degenerate_camera(const render::Camera& camera);

}  // namespace tetray
