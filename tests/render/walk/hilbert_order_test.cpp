// Hilbert order: the curve's index visits every grid point once with each step to a neighbour,
// and a volume in Hilbert order holds the same tets and renders the same image.
#include "render/walk/hilbert_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <vector>

#include "render/walk/volume_render.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

TEST(HilbertIndex, StepsToANeighbourAndVisitsEveryPointOnce) {
  for (int bits = 1; bits <= 4; ++bits) {
    const std::uint32_t side = 1u << bits;
    std::vector<std::array<std::uint32_t, 3>> at(std::size_t{side} * side * side, {side, 0, 0});
    for (std::uint32_t x = 0; x < side; ++x)
      for (std::uint32_t y = 0; y < side; ++y)
        for (std::uint32_t z = 0; z < side; ++z) {
          const std::uint64_t index = render::hilbert_index(x, y, z, bits);
          ASSERT_LT(index, at.size());
          EXPECT_EQ(at[index][0], side) << "index " << index << " visited twice";
          at[index] = {x, y, z};
        }
    EXPECT_EQ(at[0], (std::array<std::uint32_t, 3>{0, 0, 0}));
    for (std::size_t k = 1; k < at.size(); ++k) {
      int distance = 0;
      for (int a = 0; a < 3; ++a)
        distance += std::abs(static_cast<int>(at[k][a]) - static_cast<int>(at[k - 1][a]));
      EXPECT_EQ(distance, 1) << "bits " << bits << ", step " << k;
    }
  }
}

std::array<float, 12> corners(const render::TetVolume& v, std::size_t t) {
  std::array<float, 12> c;
  for (int k = 0; k < 4; ++k) {
    const render::Vertex& p = v.vertices[v.tets[t].v[k]];
    c[3 * k] = p.x;
    c[3 * k + 1] = p.y;
    c[3 * k + 2] = p.z;
  }
  return c;
}

TEST(HilbertOrder, SameTetsAndTheSameVolumeImage) {
  const BoxMesh box = jittered_box(6);
  const RenderScene scene = load_scene(box.points, box.tets, random_field(box.point_count(), 5));
  const render::TetVolume sorted = render::hilbert_ordered(scene.volume);
  ASSERT_EQ(sorted.tets.size(), scene.volume.tets.size());
  std::vector<std::size_t> of_id(scene.volume.tets.size());
  for (std::size_t t = 0; t < scene.volume.tets.size(); ++t) of_id[scene.volume.tet_ids[t]] = t;
  for (std::size_t t = 0; t < sorted.tets.size(); ++t)
    EXPECT_EQ(corners(sorted, t), corners(scene.volume, of_id[sorted.tet_ids[t]]));
  EXPECT_NE(sorted.tet_ids, scene.volume.tet_ids);  // the order did change
  for (std::size_t p = 0; p < box.point_count(); ++p) {
    const render::Vertex& a = sorted.vertices[sorted.point_vertex[p]];
    EXPECT_EQ(a.x, static_cast<float>(box.points[3 * p] - sorted.origin.x)) << "point " << p;
  }
  static const render::Colormap kGray{{0, 0, 0, 1, 1, 1}};
  render::VolumeRenderOptions options;
  options.transfer = {&kGray, -1, 1, {{-1, 0.2}, {0, 2}, {1, 0.5}}, 1};
  options.termination = 1;
  const render::Camera camera = look_at({-2.2, 1.4, 3.1}, {0, 0, 0}, 40, 24, 24);
  render::VolumeFragmentImage a = render::render_volume(
      scene.volume, render::build_walk_structure(scene.volume), camera, options);
  render::VolumeFragmentImage b =
      render::render_volume(sorted, render::build_walk_structure(sorted), camera, options);
  const render::Framebuffer ia = render::resolve(a), ib = render::resolve(b);
  ASSERT_EQ(ia.rgba.size(), ib.rgba.size());
  for (std::size_t k = 0; k < ia.rgba.size(); ++k) EXPECT_NEAR(ia.rgba[k], ib.rgba[k], 1e-6);
}

}  // namespace
}  // namespace tetray::test
