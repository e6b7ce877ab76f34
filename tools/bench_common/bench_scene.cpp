#include "tools/bench_common/bench_scene.hpp"

#include <cmath>
#include <numbers>

namespace tetray::bench {

render::Camera bench_camera(int size_px) {
  render::Camera camera;
  camera.eye = {2.5, 1.8, 3.2};
  camera.look_at = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.fov_deg = 40.0;
  camera.width = size_px;
  camera.height = size_px;
  return camera;
}

render::IsoSurface bench_surface() { return {kIsovalue, {0.9f, 0.75f, 0.45f}}; }

render::PointSource point_source(const std::vector<double>& points) {
  render::PointSource source;
  source.xyz = points.data();
  source.xyz_kind = render::ScalarKind::f64;
  source.count = points.size() / 3;
  return source;
}

render::FieldSource field_source(const std::vector<double>& field) {
  return {field.data(), render::ScalarKind::f64, field.size()};
}

render::UpdateResult load_scene(const GyroidTwist& scene, render::TetVolume& volume,
                                render::Bvh& bvh, const render::UpdatePolicy& policy) {
  return render::load_volume(volume, bvh, scene.mesh.tets, {}, {}, point_source(scene.mesh.points),
                             field_source(scene.field), policy);
}

void trace_scene(const render::TetVolume& volume, const render::Bvh& bvh,
                 const render::Camera& camera, render::PacketSize packet,
                 render::Framebuffer& image, render::TraceStats* stats) {
  const render::IsoSurface surface = bench_surface();
  render::TraceOptions options;
  options.packet = packet;
  options.collect_stats = stats != nullptr;
  render::trace_into(image, volume, bvh, camera, {&surface, 1}, options, stats);
}

std::vector<double> strong_twist(const BoxMesh& reference) {
  std::vector<double> points = reference.points;
  for (std::size_t p = 0; p < points.size(); p += 3) {
    const double theta = std::numbers::pi * (points[p + 2] + 1.0);
    const double x = points[p], y = points[p + 1];
    points[p] = std::cos(theta) * x - std::sin(theta) * y;
    points[p + 1] = std::sin(theta) * x + std::cos(theta) * y;
  }
  return points;
}

std::size_t estimated_bytes(int n) {
  // Measured peak RSS of the n = 56 run (220 MB for 1.05 M tets), with some margin: generated
  // connectivity, two renderer copies with BVHs, VTK's cell types, contour and Embree's BVH.
  constexpr std::size_t kBytesPerTet = 250;
  const auto cells = static_cast<std::size_t>(n) * n * n;
  return 6 * cells * kBytesPerTet;
}

}  // namespace tetray::bench
