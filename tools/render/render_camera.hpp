// The camera of tetray-render: --eye (looking at --look-at or the mesh center), else one that fits
// the bounds of every point of the grid. The tool chooses it and hands it to the adaptor as an
// explicit camera: the adaptor's own auto_fit fits the bounds of the tets it keeps, in the vertex
// store's single precision, which would move the camera (and every pixel) by a rounding.
#pragma once

#include <string>
#include <vector>

#include "render/scene/camera.hpp"
#include "tools/render/render_options.hpp"

namespace tetray::tools {

// `points` xyz interleaved, at least one point. Empty `error` unless the camera is unusable
// (render::camera_problem, the same check the config puts on a camera).
render::Camera make_camera(const RenderOptions& options, const std::vector<double>& points,
                           std::string& error);

}  // namespace tetray::tools
