#include "support/render_fixtures.hpp"

#include <cmath>
#include <random>

#include "render/update/volume_update.hpp"

namespace tetray::test {

int scaled_side(int full) {
  const double side = full / std::sqrt(static_cast<double>(kSanitizerSlowdown));
  return std::max(8, static_cast<int>(side));
}

RenderScene load_scene(std::span<const double> points, std::span<const std::int64_t> tets,
                       std::span<const double> field, const render::UpdatePolicy& policy) {
  render::PointSource point_source;
  point_source.xyz = points.data();
  point_source.count = points.size() / 3;
  render::FieldSource field_source;
  field_source.values = field.data();
  field_source.count = field.size();
  RenderScene scene;
  render::load_volume(scene.volume, scene.bvh, tets, {}, {}, point_source, field_source, policy);
  return scene;
}

render::TetVolume volume_by_hand(std::span<const double> points, std::span<const std::int64_t> tets,
                                 std::span<const double> field) {
  render::TetVolume volume;
  Vec3d lo{points[0], points[1], points[2]}, hi = lo;
  for (std::size_t p = 0; p < field.size(); ++p) {
    const Vec3d x{points[3 * p], points[3 * p + 1], points[3 * p + 2]};
    lo = min(lo, x);
    hi = max(hi, x);
  }
  volume.origin = 0.5 * (lo + hi);
  for (std::size_t p = 0; p < field.size(); ++p) {
    const auto local = [&](int axis) {
      return static_cast<float>(points[3 * p + axis] - volume.origin[axis]);
    };
    volume.vertices.push_back({local(0), local(1), local(2), static_cast<float>(field[p])});
  }
  for (std::size_t t = 0; t < tets.size() / 4; ++t) {
    render::Tet tet{};
    for (int c = 0; c < 4; ++c) tet.v[c] = static_cast<std::int32_t>(tets[4 * t + c]);
    volume.tets.push_back(tet);
    volume.tet_ids.push_back(static_cast<std::uint32_t>(t));
  }
  return volume;
}

std::vector<double> sample_field(std::span<const double> points, const ScalarFunction& f) {
  std::vector<double> values(points.size() / 3);
  for (std::size_t p = 0; p < values.size(); ++p) {
    values[p] = f({points[3 * p], points[3 * p + 1], points[3 * p + 2]});
  }
  return values;
}

std::vector<double> random_field(std::size_t point_count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> values(point_count);
  for (double& v : values) v = value(rng);
  return values;
}

BoxMesh jittered_box(int cells, double jitter) {
  BoxMeshSpec spec;
  spec.cells = {cells, cells, cells};
  spec.jitter = jitter;
  return make_box_mesh(spec);
}

GyroidTwist gyroid(int n) { return make_gyroid_twist(n, 0.2); }

std::vector<render::IsoSurface> make_surfaces(std::span<const double> isovalues) {
  std::vector<render::IsoSurface> surfaces;
  for (std::size_t k = 0; k < isovalues.size(); ++k) {
    // Golden-ratio steps through the channels give distinct colors for any count.
    const auto channel = [&](double phase) {
      return static_cast<float>(0.25 +
                                0.75 * std::fmod(0.618034 * static_cast<double>(k) + phase, 1.0));
    };
    surfaces.push_back(
        {static_cast<float>(isovalues[k]), {channel(0.1), channel(0.45), channel(0.8)}});
  }
  return surfaces;
}

std::vector<double> isovalues_of(std::span<const render::IsoSurface> surfaces) {
  std::vector<double> values;
  for (const render::IsoSurface& s : surfaces) values.push_back(s.value);
  return values;
}

render::Camera look_at(Vec3d eye, Vec3d target, double fov_deg, int width, int height, Vec3d up) {
  render::Camera camera;
  camera.eye = eye;
  camera.look_at = target;
  camera.up = up;
  camera.fov_deg = fov_deg;
  camera.width = width;
  camera.height = height;
  return camera;
}

render::Camera benchmark_camera(int side) {
  return look_at({2.5, 1.8, 3.2}, {0, 0, 0}, 40, side, side);
}

std::vector<render::Camera> standard_cameras(int width, int height, Vec3d center) {
  return {
      look_at(center + Vec3d{2.5, 1.8, 3.2}, center, 40, width, height),
      look_at(center + Vec3d{0, 0, 4}, center, 35, width, height),
      look_at(center + Vec3d{-3.1, 0.4, -1.3}, center + Vec3d{0.1, -0.2, 0}, 45, width, height,
              {0.2, 1, 0.1}),
      look_at(center + Vec3d{0.15, 0.2, -0.3}, center + Vec3d{0.9, -0.5, 0.4}, 75, width, height),
      look_at(center + Vec3d{-0.7, 0.6, 0.55}, center + Vec3d{0.2, -0.1, -0.6}, 60, width, height),
      look_at(center + Vec3d{210, -140, 260}, center, 0.6, width, height),
  };
}

render::Framebuffer trace_image(const RenderScene& scene, const render::Camera& camera,
                                std::span<const render::IsoSurface> surfaces,
                                render::PacketSize packet) {
  render::TraceOptions options;
  options.packet = packet;
  return render::trace(scene.volume, scene.bvh, camera, surfaces, options);
}

}  // namespace tetray::test
