// The BVH builders: a tree built by the SAH builder and one built by the BIH builder, at several
// leaf sizes, give bitwise identical images on the reference scenes. The tree only decides which
// tets a ray meets first; the hit kept (nearest, ties to the smaller tet id) must not depend on it.
// Neither builder makes a leaf larger than render::kMaxLeafSize, whatever leaf size is asked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

std::size_t hit_count(const render::Framebuffer& image) {
  return image.pixel_count() -
         static_cast<std::size_t>(std::count(image.hit.begin(), image.hit.end(), render::kNoHit));
}

render::UpdatePolicy built_with(render::BvhBuilder builder, int leaf_size) {
  render::UpdatePolicy policy;
  policy.build.builder = builder;
  policy.build.leaf_size = leaf_size;
  return policy;
}

void expect_same_image_for_both_builders(std::span<const double> points,
                                         std::span<const std::int64_t> tets,
                                         std::span<const double> field,
                                         std::span<const double> isovalues,
                                         const std::string& label) {
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const RenderScene bih = load_scene(points, tets, field, built_with(render::BvhBuilder::bih, 16));
  bool another_tree = false;
  for (const int leaf_size : {1, 4, 16}) {
    const RenderScene sah =
        load_scene(points, tets, field, built_with(render::BvhBuilder::sah, leaf_size));
    another_tree = another_tree || sah.volume.tet_ids != bih.volume.tet_ids;
    const std::vector<render::Camera> cameras = standard_cameras(96, 80);
    for (std::size_t c = 0; c < cameras.size(); ++c) {
      const render::Framebuffer expected = trace_image(bih, cameras[c], surfaces);
      EXPECT_GT(hit_count(expected), 0u) << label << " camera " << c;
      EXPECT_EQ(image_difference(expected, trace_image(sah, cameras[c], surfaces)), "")
          << label << ": SAH with leaves of " << leaf_size << " vs BIH, camera " << c;
    }
  }
  EXPECT_TRUE(another_tree) << label << ": every SAH tree put the tets in the BIH's leaf order";
}

TEST(BvhBuilders, NoLeafHoldsMoreThanTheMaximum) {
  const GyroidTwist data = gyroid(6);  // 1296 tets: a leaf of 1000 would hold most of them
  for (const render::BvhBuilder builder : {render::BvhBuilder::bih, render::BvhBuilder::sah}) {
    const RenderScene scene =
        load_scene(data.mesh.points, data.mesh.tets, data.field, built_with(builder, 1000));
    std::uint32_t largest = 0;
    for (const render::BvhNode& node : scene.bvh.nodes)
      if (node.is_leaf()) largest = std::max(largest, node.count);
    EXPECT_LE(largest, static_cast<std::uint32_t>(render::kMaxLeafSize));
    EXPECT_GT(largest, static_cast<std::uint32_t>(render::kMaxLeafSize / 4))
        << "the leaves are far below the maximum: the test no longer asks for large ones";
  }
}

TEST(BvhBuilders, SameImageOnTheGyroid) {
  const GyroidTwist data = gyroid(6);
  const double isovalues[] = {0.0, 0.5};
  expect_same_image_for_both_builders(data.mesh.points, data.mesh.tets, data.field, isovalues,
                                      "gyroid");
}

TEST(BvhBuilders, SameImageOnARandomField) {
  const BoxMesh mesh = jittered_box(5);
  const std::vector<double> field = random_field(mesh.point_count(), 7);
  const double isovalues[] = {-0.3, 0.2, 0.6};
  expect_same_image_for_both_builders(mesh.points, mesh.tets, field, isovalues, "random");
}

// Isovalues on vertices and rays along faces: the tie rule decides, whatever the tree.
TEST(BvhBuilders, SameImageOnFacesAndVertices) {
  const BoxMesh mesh = jittered_box(4, 0.0);
  const std::vector<double> field =
      sample_field(mesh.points, [](Vec3d p) { return p.x + 0.5 * p.y + 0.25 * p.z; });
  const double isovalues[] = {0.0, 0.75};
  expect_same_image_for_both_builders(mesh.points, mesh.tets, field, isovalues, "faces");
}

}  // namespace
}  // namespace tetray::test
