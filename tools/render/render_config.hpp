// The adaptor config of one tetray-render run: a single scene drawing the options' isosurfaces
// from the tool's camera, written as one image file into a scratch folder, the log beside it.
// Everything else (the mesh check, the ghost cells not drawn, the BVH, the trace, the encoding)
// is the adaptor's, as in a solver's run or tetray-replay's.
#pragma once

#include <string>

#include "render/scene/camera.hpp"
#include "tools/render/render_options.hpp"

namespace tetray::tools {

// The one scene's name: its image is `<directory>/<name>/<name>_<step>.<format>`.
inline constexpr const char* kRenderScene = "render";

// The YAML the adaptor reads (Adaptor::create_from_yaml), writing into `directory`.
std::string render_config(const RenderOptions& options, const render::Camera& camera,
                          const std::string& directory);

}  // namespace tetray::tools
