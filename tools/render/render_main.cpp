// tetray-render: ray-traces isosurfaces of one VTK grid of tets into an EXR or PNG. The
// same stages as an in-situ step, run once: read -> check -> load (BVH build) ->
// trace -> write.
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <exception>

#include "render/core/stopwatch.hpp"
#include "render/image/image_write.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/iso_palette.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "render/volume/mesh_check.hpp"
#include "tools/render/render_options.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::tools {
namespace {

// vtkGhostType bits of cells that are not drawn: DUPLICATECELL and HIDDENCELL.
constexpr std::uint8_t kHiddenGhostBits = 1 | 32;

// Looking at the mesh from the +x, +y, +z octant, slightly above, like a default 3D view.
constexpr render::Vec3d kFitViewDirection{1.0, 0.7, 1.3};

const std::vector<double>* find_field(const vtkio::TetGrid& grid, const RenderOptions& options,
                                      std::string& error) {
  const auto found = grid.point_fields.find(options.field);
  if (found != grid.point_fields.end()) return &found->second;
  error = "'" + options.input + "' has no scalar point field '" + options.field + "'; it has: ";
  if (grid.point_fields.empty()) error += "none";
  for (auto it = grid.point_fields.begin(); it != grid.point_fields.end(); ++it) {
    error += (it == grid.point_fields.begin() ? "'" : ", '") + it->first + "'";
  }
  return nullptr;
}

void point_bounds(const std::vector<double>& xyz, render::Vec3d& lo, render::Vec3d& hi) {
  lo = {xyz[0], xyz[1], xyz[2]};
  hi = lo;
  for (std::size_t p = 0; p < xyz.size(); p += 3) {
    const render::Vec3d v{xyz[p], xyz[p + 1], xyz[p + 2]};
    lo = render::min(lo, v);
    hi = render::max(hi, v);
  }
}

// The explicit camera of --eye (looking at --look-at or the mesh center), else one that fits
// the mesh bounds. Empty `error` unless the view is degenerate.
render::Camera make_camera(const RenderOptions& options, const vtkio::TetGrid& grid,
                           std::string& error) {
  render::Vec3d lo, hi;
  point_bounds(grid.points, lo, hi);
  const render::Vec3d up = options.up.value_or(render::Vec3d{0, 1, 0});
  render::Camera camera = options.eye
                              ? render::Camera{*options.eye,
                                               options.look_at.value_or(0.5 * (lo + hi)),
                                               up,
                                               options.fov_deg,
                                               options.width,
                                               options.height}
                              : render::fit_camera(lo, hi, kFitViewDirection, up, options.fov_deg,
                                                   options.width, options.height);
  const render::Vec3d forward = camera.look_at - camera.eye;
  if (render::length(forward) == 0) {
    error = "the camera's eye and look-at point coincide";
  } else if (render::length(
                 render::cross(render::normalize(forward), render::normalize(camera.up))) < 1e-6) {
    error = "the camera's up direction is parallel to its view direction (or zero)";
  }
  return camera;
}

std::vector<render::IsoSurface> iso_surfaces(const std::vector<double>& isovalues) {
  std::vector<render::IsoSurface> surfaces;
  for (std::size_t k = 0; k < isovalues.size(); ++k) {
    surfaces.push_back({static_cast<float>(isovalues[k]), render::default_iso_color(k)});
  }
  return surfaces;
}

// Tets to render: all that passed the mesh check, minus hidden and duplicate ghost cells.
std::vector<std::uint8_t> tets_to_keep(const vtkio::TetGrid& grid, std::vector<std::uint8_t> keep) {
  keep.resize(grid.tets.size() / 4, 1);
  for (std::size_t t = 0; t < grid.ghost.size(); ++t) {
    if (grid.ghost[t] & kHiddenGhostBits) keep[t] = 0;
  }
  return keep;
}

// Everything the trace needs, read and checked.
struct Scene {
  vtkio::TetGrid grid;
  const std::vector<double>* field = nullptr;
  render::PointSource points;
  render::FieldSource values;
  std::vector<std::uint8_t> keep;
  render::Camera camera;
};

bool prepare_scene(const RenderOptions& options, Scene& scene, std::string& error) {
  if (!vtkio::read_grid(options.input, scene.grid, error)) return false;
  scene.field = find_field(scene.grid, options, error);
  if (!scene.field) return false;
  if (scene.grid.tets.empty()) {
    error = "'" + options.input + "' has no tets";
    return false;
  }
  scene.camera = make_camera(options, scene.grid, error);
  if (!error.empty()) return false;
  scene.points = {scene.grid.points.data(), render::ScalarKind::f64, nullptr,
                  render::ScalarKind::f64, scene.grid.points.size() / 3};
  scene.values = {scene.field->data(), render::ScalarKind::f64, scene.field->size()};
  const render::MeshCheck check = render::check_mesh(scene.grid.tets, scene.points, scene.values,
                                                     render::NonFinitePolicy::error, scene.keep);
  if (!check.error.empty()) {
    error = "'" + options.input + "': " + check.error;
    return false;
  }
  scene.keep = tets_to_keep(scene.grid, std::move(scene.keep));
  return true;
}

// Builds the BVH and traces in an arena of the requested thread count; returns the trace time.
double trace_scene(const RenderOptions& options, const Scene& scene, render::Framebuffer& image) {
  const std::vector<render::IsoSurface> surfaces = iso_surfaces(options.isovalues);
  render::TraceOptions trace_options;
  trace_options.packet = options.packet;
  double trace_ms = 0;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    render::TetVolume volume;
    render::Bvh bvh;
    render::load_volume(volume, bvh, scene.grid.tets, scene.keep, {}, scene.points, scene.values,
                        render::UpdatePolicy{});
    const render::Stopwatch watch;
    image = render::trace(volume, bvh, scene.camera, surfaces, trace_options);
    trace_ms = watch.ms();
  });
  return trace_ms;
}

bool render_file(const RenderOptions& options, std::string& error) {
  Scene scene;
  if (!prepare_scene(options, scene, error)) return false;
  render::Framebuffer image;
  const double trace_ms = trace_scene(options, scene, image);

  const render::Stopwatch writing;
  const render::WriteResult written = render::write_image(image, options.output);
  if (!written.ok) {
    error = written.message;
    return false;
  }
  const auto hits = std::count_if(image.hit.begin(), image.hit.end(),
                                  [](std::uint32_t h) { return h != render::kNoHit; });
  std::printf("tetray-render: %dx%d, %zu tets, trace %.1f ms, %td hit pixels, wrote %s (%.1f ms)\n",
              image.width, image.height, scene.grid.tets.size() / 4, trace_ms, hits,
              options.output.c_str(), writing.ms());
  return true;
}

}  // namespace
}  // namespace tetray::tools

int main(int argc, char** argv) {
  tetray::tools::RenderOptions options;
  if (const auto exit_code = tetray::tools::parse_render_options(argc, argv, options)) {
    return *exit_code;
  }
  std::string error;
  try {
    if (tetray::tools::render_file(options, error)) return 0;
  } catch (const std::exception& e) {
    error = std::string("unexpected failure: ") + e.what();
  }
  std::fprintf(stderr, "tetray-render: error: %s\n", error.c_str());
  return 1;
}
