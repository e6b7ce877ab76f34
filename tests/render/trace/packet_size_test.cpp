// Packet sizes: single rays and 8x8, 16x16 and 32x32 packets give bitwise identical
// images, also for image sizes that leave partial packets at the right and bottom edges.
#include <gtest/gtest.h>

#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

void expect_same_image_for_every_packet_size(const RenderScene& scene,
                                             std::span<const double> isovalues,
                                             const std::string& label) {
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const int sizes[][2] = {{100, 37}, {64, 64}, {17, 129}, {1, 1}};
  for (const auto& size : sizes) {
    const std::vector<render::Camera> cameras = standard_cameras(size[0], size[1]);
    for (std::size_t c = 0; c < cameras.size(); ++c) {
      const std::string where = label + " " + std::to_string(size[0]) + "x" +
                                std::to_string(size[1]) + " camera " + std::to_string(c);
      const render::Framebuffer single =
          trace_image(scene, cameras[c], surfaces, render::PacketSize::single);
      EXPECT_EQ(malformed_pixels(single), 0u) << where;
      for (const render::PacketSize packet : render::kPacketSizes) {
        if (packet == render::PacketSize::single) continue;
        EXPECT_EQ(image_difference(single, trace_image(scene, cameras[c], surfaces, packet)), "")
            << where << ": single vs " << render::to_string(packet);
      }
    }
  }
}

TEST(PacketSizes, SameImageOnTheGyroid) {
  const GyroidTwist data = gyroid(6);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const double isovalues[] = {0.0, 0.5};
  expect_same_image_for_every_packet_size(scene, isovalues, "gyroid");
}

TEST(PacketSizes, SameImageOnARandomField) {
  const BoxMesh mesh = jittered_box(5);
  const std::vector<double> field = random_field(mesh.point_count(), 3);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {-0.3, 0.2, 0.6};
  expect_same_image_for_every_packet_size(scene, isovalues, "random");
}

// Vertex values on a grid of eighths put isovalues on vertices, and cameras with the eye on a
// grid plane send rays along tet faces and through shared isopolygon edges, where the tie rule
// (nearest, then smaller id) must pick the same tet in every packet layout. No surface is seen
// edge-on from the axis-aligned camera.
TEST(PacketSizes, SameImageOnFacesAndVertices) {
  const BoxMesh mesh = jittered_box(4, 0.0);
  const std::vector<double> field =
      sample_field(mesh.points, [](Vec3d p) { return p.x + 0.5 * p.y + 0.25 * p.z; });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {0.0, 0.75};
  expect_same_image_for_every_packet_size(scene, isovalues, "faces");
}

}  // namespace
}  // namespace tetray::test
