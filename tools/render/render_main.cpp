// tetray-render: ray-traces isosurfaces of one VTK grid of tets into an EXR or PNG. The grid goes
// through the adaptor like one step of a solver's run (tetray-replay's pipeline, on one rank): the
// adaptor checks the mesh, leaves out the ghost cells that are not drawn, builds the BVH, traces
// and writes. The tool only reads the file, chooses the camera and names the image.
#include <mpi.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <numeric>
#include <span>
#include <vector>

#include "render/scene/camera.hpp"
#include "render/trace/trace.hpp"
#include "tetray/adaptor.hpp"
#include "tools/render/render_camera.hpp"
#include "tools/render/render_config.hpp"
#include "tools/render/render_options.hpp"
#include "tools/render/scratch_output.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::tools {
namespace {

bool has_field(const vtkio::TetGrid& grid, const RenderOptions& options, std::string& error) {
  if (grid.point_fields.count(options.field) != 0) return true;
  error = "'" + options.input + "' has no scalar point field '" + options.field + "'; it has: ";
  if (grid.point_fields.empty()) error += "none";
  for (auto it = grid.point_fields.begin(); it != grid.point_fields.end(); ++it) {
    error += (it == grid.point_fields.begin() ? "'" : ", '") + it->first + "'";
  }
  return false;
}

// The grid, with the field to draw and at least one tet, and the camera that looks at it.
bool read_scene(const RenderOptions& options, vtkio::TetGrid& grid, render::Camera& camera,
                std::string& error) {
  if (!vtkio::read_grid(options.input, grid, error)) return false;
  if (!has_field(grid, options, error)) return false;
  if (grid.tets.empty()) {
    error = "'" + options.input + "' has no tets";
    return false;
  }
  camera = make_camera(options, grid.points, error);
  return error.empty();
}

// The grid's views, as the VTK bridge makes them (tetray/vtk_bridge.hpp), with the one thing the
// bridge has no room for: the tets' positions in the file as their global ids, so that an exact
// depth tie goes to the tet that comes first in the file, as it always did in tetray-render. The
// keys the bridge leaves to the adaptor (from the corners' coordinates) pick the other tet at
// some ties (an axis-aligned view of a structured mesh meets many) and change those pixels.
Status execute_grid(Adaptor& adaptor, const vtkio::TetGrid& grid) {
  std::vector<std::int64_t> ids(grid.tets.size() / 4);
  std::iota(ids.begin(), ids.end(), std::int64_t{0});
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(grid.points));
  mesh.tets = TetsView::of(std::span<const std::int64_t>(grid.tets));
  mesh.tets.global_ids = ids.data();
  if (!grid.ghost.empty()) mesh.tets.ghost = grid.ghost.data();
  std::vector<FieldView> fields;
  for (const auto& [name, values] : grid.point_fields) {
    fields.push_back(FieldView::of(name, std::span<const double>(values)));
  }
  return adaptor.execute(0, 0.0, mesh, fields);
}

// One step of an adaptor on this process alone (each process of an MPI launch renders the whole
// file, as the tool always did), finalized so that the image is on disk.
bool render_step(const std::string& config, const vtkio::TetGrid& grid, std::string& error) {
  Status status;
  const std::unique_ptr<Adaptor> adaptor = Adaptor::create_from_yaml(MPI_COMM_SELF, config, status);
  if (adaptor) status = execute_grid(*adaptor, grid);
  // Partial: the one scene was skipped (its field unusable), so there is no image.
  if (adaptor && status.ok()) status = adaptor->finalize();
  if (status.ok()) return true;
  error = status.message;
  return false;
}

bool render_file(const RenderOptions& options, std::string& error) {
  vtkio::TetGrid grid;
  render::Camera camera;
  if (!read_scene(options, grid, camera, error)) return false;
  ScratchOutput scratch;
  if (!scratch.create(options.output, error)) return false;
  if (!render_step(render_config(options, camera, scratch.directory()), grid, error)) {
    error = "'" + options.input + "': " + error;
    return false;
  }
  StepFigures figures;
  if (!scratch.read_figures(figures, error)) return false;
  if (!scratch.move_image(kRenderScene, options.output, error)) return false;
  std::printf(
      "tetray-render: %dx%d, %zu tets, trace %.1f ms, %llu hit pixels, wrote %s (%.1f ms)\n",
      options.width, options.height, grid.tets.size() / 4, figures.trace_ms,
      static_cast<unsigned long long>(figures.hits), options.output.c_str(), figures.write_ms);
  return true;
}

int render_and_report(const RenderOptions& options) {
  std::string error;
  try {
    if (render_file(options, error)) return 0;
  } catch (const std::exception& e) {
    error = std::string("unexpected failure: ") + e.what();
  }
  std::fprintf(stderr, "tetray-render: error: %s\n", error.c_str());
  return 1;
}

}  // namespace
}  // namespace tetray::tools

int main(int argc, char** argv) {
  tetray::tools::RenderOptions options;
  if (const auto exit_code = tetray::tools::parse_render_options(argc, argv, options)) {
    return *exit_code;
  }
  // After the command line: --help and usage errors need no MPI.
  MPI_Init(&argc, &argv);
  const int code = tetray::tools::render_and_report(options);
  MPI_Finalize();
  return code;
}
