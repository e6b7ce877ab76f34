// Watertightness (docs/architecture.md §5): a closed level set seen from many random cameras. Every
// ray whose exact path passes through the enclosed region {f_PL < iso} (decided in double by
// the reference, with a small margin) must hit the surface: zero misses, with every packet size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support/watertight.hpp"

namespace tetray::test {
namespace {

TEST(Watertight, SphereLevelSetFromRandomCameras) {
  const BoxMesh mesh = jittered_box(8);
  const Vec3d center{0.06, -0.04, 0.09};
  const double iso = 0.62;
  const std::vector<double> field =
      sample_field(mesh.points, [&](Vec3d x) { return length(x - center); });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  expect_sphere_watertight(scene, center, iso, 60, 1'000'000u / kSanitizerSlowdown, "sphere");
}

// f = max(|x|, |y|, |z|) on an unjittered grid with the isovalue on a grid plane: the surface
// is made of whole tet faces meeting at grid edges and vertices, and aligned cameras with odd
// image sizes send rays exactly through those edges and vertices.
TEST(Watertight, CubeLevelSetAlongFacesEdgesAndVertices) {
  const BoxMesh mesh = jittered_box(8, 0.0);
  const double iso = 0.5;
  const auto max_norm = [](Vec3d x) {
    return std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  };
  const std::vector<double> field = sample_field(mesh.points, max_norm);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {iso};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const BelowLevelProbe probe(scene.volume, iso - kRegionMargin);

  const int side = scaled_side(121) | 1;
  std::vector<render::Camera> cameras = {
      look_at({0, 0, 3}, {0, 0, 0}, 30, side, side),
      look_at({3, 0, 0}, {0, 0, 0}, 30, side, side, {0, 0, 1}),
      look_at({2, 2, 2}, {0, 0, 0}, 35, side, side, {0, 0, 1}),
      look_at({2, 2, 0}, {0, 0, 0}, 35, side, side, {0, 0, 1}),
      look_at({0, 0, 0.3}, {0, 0, 1}, 90, side, side),
      look_at({0.2, 0.2, 0.2}, {1, 1, 1}, 90, side, side, {0, 0, 1}),
  };
  std::mt19937 rng(77);
  for (int c = 0; c < 12; ++c) {
    const EyePlace place = c % 2 == 0 ? EyePlace::outside_mesh : EyePlace::inside_region;
    cameras.push_back(random_camera(rng, place, {0, 0, 0}, iso, side, side));
  }
  MissCounts counts;
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    const bool eye_inside = max_norm(cameras[c].eye) < iso;
    count_misses(scene, probe, cameras[c], surfaces, eye_inside, "cube camera " + std::to_string(c),
                 counts);
  }
  print_counts("cube faces, " + std::to_string(cameras.size()) + " cameras", counts);
  EXPECT_GT(counts.rays, 100'000u / kSanitizerSlowdown);
  for (const std::size_t misses : counts.misses) EXPECT_EQ(misses, 0u);
}

}  // namespace
}  // namespace tetray::test
