#include "tools/render/render_camera.hpp"

namespace tetray::tools {
namespace {

// Looking at the mesh from the +x, +y, +z octant, slightly above, like a default 3D view.
constexpr render::Vec3d kFitViewDirection{1.0, 0.7, 1.3};

void point_bounds(const std::vector<double>& xyz, render::Vec3d& lo, render::Vec3d& hi) {
  lo = {xyz[0], xyz[1], xyz[2]};
  hi = lo;
  for (std::size_t p = 0; p < xyz.size(); p += 3) {
    const render::Vec3d v{xyz[p], xyz[p + 1], xyz[p + 2]};
    lo = render::min(lo, v);
    hi = render::max(hi, v);
  }
}

}  // namespace

render::Camera make_camera(const RenderOptions& options, const std::vector<double>& points,
                           std::string& error) {
  const render::Vec3d up = options.up.value_or(render::Vec3d{0, 1, 0});
  if (!options.eye) {
    // The view the fit looks along, checked before fitting: a degenerate up makes a NaN frame.
    error = render::camera_problem({kFitViewDirection, {0, 0, 0}, up, options.fov_deg});
    if (!error.empty()) return {};
  }
  render::Vec3d lo, hi;
  point_bounds(points, lo, hi);
  const render::Camera camera =
      options.eye ? render::Camera{*options.eye,
                                   options.look_at.value_or(0.5 * (lo + hi)),
                                   up,
                                   options.fov_deg,
                                   options.width,
                                   options.height}
                  : render::fit_camera(lo, hi, kFitViewDirection, up, options.fov_deg,
                                       options.width, options.height);
  error = render::camera_problem(camera);
  return camera;
}

}  // namespace tetray::tools
