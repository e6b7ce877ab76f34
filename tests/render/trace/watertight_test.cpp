// Watertightness (docs/architecture.md §5): a closed level set seen from many random cameras. Every
// ray whose exact path passes through the enclosed region {f_PL < iso} (decided in double by
// the reference, with a small margin) must hit the surface: zero misses, with every packet size.
#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>

#include "support/reference_comparison.hpp"
#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

// The ray must dip this far below the isovalue (f has unit gradient here, so it is also a
// length): far above float rounding, far below a tet.
constexpr double kRegionMargin = 1e-5;

constexpr auto kPackets = render::kPacketSizes;

struct MissCounts {
  std::size_t rays = 0;                               // rays through the enclosed region
  std::size_t crossing_from_inside = 0;               // of those, from an eye inside it
  std::array<std::size_t, kPackets.size()> misses{};  // per packet size
};

std::vector<std::uint8_t> rays_through_region(const BelowLevelProbe& probe,
                                              const render::Camera& camera) {
  const ReferenceCamera rays(camera);
  std::vector<std::uint8_t> through(static_cast<std::size_t>(camera.width) * camera.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height), [&](const auto& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < camera.width; ++i) {
        through[static_cast<std::size_t>(j) * camera.width + i] =
            probe.passes_below(camera.eye, rays.pixel_direction(i, j));
      }
    }
  });
  return through;
}

// Counts the misses among the rays through the region, and reports the first few with the
// reference's view of the ray (how close it passes to an isopolygon edge).
void count_misses(const RenderScene& scene, const BelowLevelProbe& probe,
                  const render::Camera& camera, std::span<const render::IsoSurface> surfaces,
                  bool eye_inside, const std::string& label, MissCounts& counts) {
  const std::vector<std::uint8_t> through = rays_through_region(probe, camera);
  const std::size_t rays = static_cast<std::size_t>(std::count(through.begin(), through.end(), 1));
  counts.rays += rays;
  if (eye_inside) counts.crossing_from_inside += rays;
  for (std::size_t k = 0; k < std::size(kPackets); ++k) {
    const render::Framebuffer image = trace_image(scene, camera, surfaces, kPackets[k]);
    EXPECT_EQ(malformed_pixels(image), 0u) << label;
    int reported = 0;
    for (std::size_t p = 0; p < through.size(); ++p) {
      if (!through[p] || image.hit[p] != render::kNoHit) continue;
      ++counts.misses[k];
      if (reported++ >= 3) continue;
      const ReferenceIntersector reference(scene.volume, isovalues_of(surfaces));
      const int i = static_cast<int>(p) % camera.width, j = static_cast<int>(p) / camera.width;
      const ReferenceCamera reference_camera(camera);
      const ReferenceHit ref =
          reference.trace_ray(reference_camera, reference_camera.pixel_direction(i, j));
      ADD_FAILURE() << label << " packet " << render::to_string(kPackets[k])
                    << ": pinhole at pixel (" << i << ", " << j << "); reference depth "
                    << ref.depth << " tet " << ref.tet_id << ", isopolygon edge distance "
                    << ref.isopolygon_edge_distance << ", tet edge distance "
                    << ref.tet_edge_distance;
    }
  }
}

void print_counts(const std::string& label, const MissCounts& counts) {
  std::cout << "[ watertight ] " << label << ": rays through the enclosed region " << counts.rays
            << " (" << counts.crossing_from_inside << " from eyes inside it); misses per packet";
  for (std::size_t k = 0; k < std::size(kPackets); ++k) {
    std::cout << (k ? ", " : " ") << render::to_string(kPackets[k]) << ": " << counts.misses[k];
  }
  std::cout << "\n";
}

Vec3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return normalize(Vec3d{normal(rng), normal(rng), normal(rng)});
}

enum class EyePlace { outside_mesh, inside_mesh, inside_region };

// A camera whose view the region of radius `radius` around `center` (roughly) fills: from
// outside the region it aims near the center with the region's angular size; from inside it
// looks anywhere.
render::Camera random_camera(std::mt19937& rng, EyePlace place, Vec3d center, double radius,
                             int width, int height) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double distance = place == EyePlace::outside_mesh  ? 2.0 + 3.0 * unit(rng)
                          : place == EyePlace::inside_mesh ? radius * (1.1 + 0.3 * unit(rng))
                                                           : radius * 0.8 * unit(rng);
  const Vec3d eye = center + distance * random_unit(rng);
  const Vec3d up = random_unit(rng);
  if (place == EyePlace::inside_region) {
    return look_at(eye, eye + random_unit(rng), 60 + 40 * unit(rng), width, height, up);
  }
  const double half_angle = std::asin(radius / distance);
  const double fov =
      std::min(120.0, 2 * std::atan(0.9 * std::tan(half_angle)) * 180 / std::numbers::pi);
  const Vec3d target = center + 0.1 * radius * unit(rng) * random_unit(rng);
  return look_at(eye, target, fov, width, height, up);
}

TEST(Watertight, SphereLevelSetFromRandomCameras) {
  const BoxMesh mesh = jittered_box(8);
  const Vec3d center{0.06, -0.04, 0.09};
  const double iso = 0.62;
  const std::vector<double> field =
      sample_field(mesh.points, [&](Vec3d x) { return length(x - center); });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {iso};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const BelowLevelProbe probe(scene.volume, iso - kRegionMargin);

  const int width = scaled_side(176), height = scaled_side(144);
  std::mt19937 rng(2024);
  MissCounts counts;
  constexpr int kCameras = 60;
  for (int c = 0; c < kCameras; ++c) {
    // Half the eyes outside the mesh bounds, a quarter inside them but outside the sphere,
    // a quarter inside the sphere.
    const EyePlace place = c % 2 == 0   ? EyePlace::outside_mesh
                           : c % 4 == 1 ? EyePlace::inside_mesh
                                        : EyePlace::inside_region;
    const render::Camera camera = random_camera(rng, place, center, iso, width, height);
    count_misses(scene, probe, camera, surfaces, place == EyePlace::inside_region,
                 "sphere camera " + std::to_string(c), counts);
  }
  print_counts("sphere, " + std::to_string(kCameras) + " cameras", counts);
  EXPECT_GT(counts.rays, 1'000'000u / kSanitizerSlowdown);
  for (const std::size_t misses : counts.misses) EXPECT_EQ(misses, 0u);
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
