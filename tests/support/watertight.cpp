#include "support/watertight.hpp"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "support/reference_comparison.hpp"

namespace tetray::test {
namespace {

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

}  // namespace

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

namespace {

Vec3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return normalize(Vec3d{normal(rng), normal(rng), normal(rng)});
}

}  // namespace

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

void expect_sphere_watertight(const RenderScene& scene, Vec3d center, double iso, int cameras,
                              std::size_t min_rays, const std::string& label) {
  const double isovalues[] = {iso};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const BelowLevelProbe probe(scene.volume, iso - kRegionMargin);
  const int width = scaled_side(176), height = scaled_side(144);
  std::mt19937 rng(2024);
  MissCounts counts;
  for (int c = 0; c < cameras; ++c) {
    const EyePlace place = c % 2 == 0   ? EyePlace::outside_mesh
                           : c % 4 == 1 ? EyePlace::inside_mesh
                                        : EyePlace::inside_region;
    const render::Camera camera = random_camera(rng, place, center, iso, width, height);
    count_misses(scene, probe, camera, surfaces, place == EyePlace::inside_region,
                 label + " camera " + std::to_string(c), counts);
  }
  print_counts(label + ", " + std::to_string(cameras) + " cameras", counts);
  EXPECT_GT(counts.rays, min_rays);
  for (const std::size_t misses : counts.misses) EXPECT_EQ(misses, 0u) << label;
}

}  // namespace tetray::test
