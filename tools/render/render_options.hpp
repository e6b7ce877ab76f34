// The command line of tetray-render.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/core/vec.hpp"
#include "render/trace/trace.hpp"

namespace tetray::tools {

struct RenderOptions {
  std::string input;   // .vtu or .pvtu
  std::string field;   // point field whose isosurfaces are drawn
  std::string output;  // .exr or .png
  std::vector<double> isovalues;
  std::optional<render::Vec3d> eye, look_at, up;  // eye set: explicit camera; else fit the mesh
  double fov_deg = 40.0;
  int width = 1024;
  int height = 1024;
  int threads = 0;  // 0: every core
};

// Parses the command line into `options`. Returns the process exit code when the program should
// stop here (--help: 0; a bad option: nonzero, with CLI11's message on stderr), else nullopt.
std::optional<int> parse_render_options(int argc, char** argv, RenderOptions& options);

}  // namespace tetray::tools
