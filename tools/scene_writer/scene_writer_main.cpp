// tetray-scene: writes the gyroid-twist benchmark scene (docs/architecture.md §6) as a .vtu with
// its point field `f`, so that tetray-render and tetray-replay can draw the benchmark's mesh with
// any config (the README's gyroid images of each shading modality come from it).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "scenes/box_mesh.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::tools {
namespace {

struct SceneOptions {
  int size = 32;  // cells per side: 6 n^3 tets
  double time = 0;
  std::string output;
};

vtkio::TetGrid gyroid_grid(const SceneOptions& options) {
  GyroidTwist scene = make_gyroid_twist(options.size, options.time);
  vtkio::TetGrid grid;
  grid.points = std::move(scene.mesh.points);
  grid.tets = std::move(scene.mesh.tets);
  grid.point_fields["f"] = std::move(scene.field);
  return grid;
}

}  // namespace
}  // namespace tetray::tools

int main(int argc, char** argv) {
  tetray::tools::SceneOptions options;
  CLI::App app{"Write the gyroid-twist benchmark scene as a .vtu with its point field 'f'."};
  app.add_option("--size", options.size, "cells per side of the box mesh (6 n^3 tets)")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  app.add_option("--time", options.time, "time of the twist")
      ->check(CLI::Range(-1e6, 1e6))
      ->capture_default_str();
  app.add_option("-o,--output", options.output, "output grid (.vtu)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  std::string error;
  try {
    const tetray::vtkio::TetGrid grid = tetray::tools::gyroid_grid(options);
    if (tetray::vtkio::write_vtu(options.output, grid, error)) {
      std::printf("tetray-scene: %zu tets, %zu points, wrote %s\n", grid.tets.size() / 4,
                  grid.points.size() / 3, options.output.c_str());
      return 0;
    }
  } catch (const std::exception& e) {
    error = std::string("unexpected failure: ") + e.what();
  }
  std::fprintf(stderr, "tetray-scene: error: %s\n", error.c_str());
  return 1;
}
