// Traversal statistics (Wald et al. 2007, Table 4): with collect_stats the counters agree with
// the image they describe, and collecting them does not change the image.
#include <gtest/gtest.h>

#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr auto kPackets = render::kPacketSizes;

struct TracedWithStats {
  render::Framebuffer image;
  render::TraceStats stats;
};

TracedWithStats trace_with_stats(const RenderScene& scene, const render::Camera& camera,
                                 std::span<const render::IsoSurface> surfaces,
                                 render::PacketSize packet) {
  render::TraceOptions options;
  options.packet = packet;
  options.collect_stats = true;
  TracedWithStats traced;
  traced.image = render::trace(scene.volume, scene.bvh, camera, surfaces, options, &traced.stats);
  return traced;
}

std::uint64_t hit_pixels(const render::Framebuffer& image) {
  return static_cast<std::uint64_t>(image.pixel_count()) -
         static_cast<std::uint64_t>(std::count(image.hit.begin(), image.hit.end(), render::kNoHit));
}

RenderScene gyroid_scene() {
  const GyroidTwist data = gyroid(6);
  return load_scene(data.mesh.points, data.mesh.tets, data.field);
}

TEST(TraceStats, CountersDescribeTheImage) {
  const RenderScene scene = gyroid_scene();
  const double isovalues[] = {0.0, 0.5};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  for (const render::Camera& camera : standard_cameras(100, 37)) {
    for (const render::PacketSize packet : kPackets) {
      const TracedWithStats traced = trace_with_stats(scene, camera, surfaces, packet);
      const render::TraceStats& stats = traced.stats;
      EXPECT_EQ(stats.rays, 100u * 37u);
      EXPECT_EQ(stats.hits, hit_pixels(traced.image));
      ASSERT_GT(stats.hits, 0u);
      EXPECT_GT(stats.packet_box_tests, 0u);
      EXPECT_GT(stats.isorange_tests, 0u);
      EXPECT_GT(stats.isopolygon_extractions, 0u);
      EXPECT_GT(stats.ray_isopolygon_tests + stats.frustum_culled_isopolygons, 0u);
    }
  }
}

// Iso-range culling removes every node when no isovalue is in the field's range: nothing is
// extracted or intersected, yet every ray is counted.
TEST(TraceStats, OutOfRangeIsovalueExtractsNothing) {
  const RenderScene scene = gyroid_scene();
  const double isovalues[] = {7.0};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const render::Camera camera = standard_cameras(64, 48)[0];
  for (const render::PacketSize packet : kPackets) {
    const render::TraceStats stats = trace_with_stats(scene, camera, surfaces, packet).stats;
    EXPECT_EQ(stats.rays, 64u * 48u);
    EXPECT_EQ(stats.hits, 0u);
    EXPECT_EQ(stats.isopolygon_extractions, 0u);
    EXPECT_EQ(stats.ray_isopolygon_tests, 0u);
  }
}

TEST(TraceStats, CollectingDoesNotChangeTheImage) {
  const RenderScene scene = gyroid_scene();
  const double isovalues[] = {-0.3, 0.4};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  for (const render::Camera& camera : standard_cameras(100, 37)) {
    for (const render::PacketSize packet : kPackets) {
      const render::Framebuffer plain = trace_image(scene, camera, surfaces, packet);
      EXPECT_EQ(image_difference(plain, trace_with_stats(scene, camera, surfaces, packet).image),
                "");
    }
  }
}

}  // namespace
}  // namespace tetray::test
