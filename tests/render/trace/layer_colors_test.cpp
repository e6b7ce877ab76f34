// The color of transparent layers as the tracer blends them (trace_layers, then flatten_layers, as
// the adaptor runs them on one rank) against the closed form of front-to-back "over",
//   C = sum_i c_i a_i prod_{j<i} (1 - a_j),   A = 1 - prod_i (1 - a_i),
// for surfaces whose colors, opacities and order are known here, not taken from the code.
// The scene is the cube [-1, 1]^3 of six tets twice over, each copy with its own points: copy A
// carries f = z, copy B f = z + 1/2. Looking down -z, a ray meets A's 0.5 surface at z = 1/2, then
// two surfaces in the one plane z = 0 (A's 0 and B's 0.5: equal depths, different tie keys and
// colors), then B's 0 at z = -1/2. B's tets come first, so their keys (their positions) are the
// smaller, and by the tie rule of docs/architecture.md §3 B's layer lies in front of A's at z = 0.
// With ambient 1 a layer's shade is its surface's color exactly, whatever the angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "render/trace/layer_shading.hpp"
#include "support/over_reference.hpp"
#include "support/reference_camera.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr double kColorTolerance = 1e-6;
// Rays this close (world units) to an edge of the tets' isopolygons are left out: such a ray may
// meet two tets of one copy, a layer each.
constexpr double kEdgeMargin = 0.03;
constexpr double kPlanes[] = {0.5, 0.0, -0.5};

struct Surface {
  std::array<float, 3> color;
  float alpha;
};
const Surface kRed{{0.9f, 0.15f, 0.1f}, 0.5f};    // isovalue 0
const Surface kBlue{{0.1f, 0.3f, 0.95f}, 0.35f};  // isovalue 0.5
// Front to back, by the tie rule: A's 0.5, then at z = 0 B's 0.5 (smaller key) before A's 0, then
// B's 0. Ties the other way round would give blue, red, blue, red.
const Surface kFrontToBack[] = {kBlue, kBlue, kRed, kRed};

// The closed form of "over" for surfaces listed front to back.
std::array<double, 4> over(std::span<const Surface> front_to_back) {
  return ::tetray::testing::over_front_to_back(front_to_back);
}

// Copy B's tets first (points 8..15, f = z + 1/2), then copy A's (points 0..7, f = z).
RenderScene two_copies_of_a_cube() {
  const BoxMesh cube = make_box_mesh({{1, 1, 1}});
  const std::size_t n = cube.point_count();
  std::vector<double> points = cube.points;
  points.insert(points.end(), cube.points.begin(), cube.points.end());
  std::vector<double> field;
  for (double shift : {0.0, 0.5})
    for (std::size_t p = 0; p < n; ++p) field.push_back(cube.points[3 * p + 2] + shift);
  std::vector<std::int64_t> tets;
  for (std::int64_t v : cube.tets) tets.push_back(v + static_cast<std::int64_t>(n));
  tets.insert(tets.end(), cube.tets.begin(), cube.tets.end());
  return load_scene(points, tets, field);
}

// Whether the ray crosses every plane well inside the cube and away from the lines where the
// plane z = c meets the tets' shared faces (x = y, x = c, y = c: the cube's Kuhn split).
bool clear_of_edges(Vec3d eye, Vec3d direction) {
  for (const double z : kPlanes) {
    const double t = (z - eye.z) / direction.z;
    const double x = eye.x + t * direction.x, y = eye.y + t * direction.y;
    if (std::abs(x) > 1 - kEdgeMargin || std::abs(y) > 1 - kEdgeMargin) return false;
    for (const double d : {x - y, x - z, y - z})
      if (std::abs(d) < kEdgeMargin) return false;
  }
  return true;
}

TEST(LayerColors, TiedLayersBlendInTheTieOrderAsTheClosedForm) {
  const RenderScene scene = two_copies_of_a_cube();
  std::vector<render::IsoSurface> surfaces(2);
  surfaces[0] = {0.0f, {kRed.color[0], kRed.color[1], kRed.color[2]}, kRed.alpha};
  surfaces[1] = {0.5f, {kBlue.color[0], kBlue.color[1], kBlue.color[2]}, kBlue.alpha};
  render::TraceOptions options;
  options.ambient = 1;
  options.max_layers = 8;
  const render::Camera camera = look_at({0, 0, 6}, {0, 0, 0}, 25, 32, 32);
  render::LayerImage layers;
  render::trace_layers(layers, scene.volume, scene.bvh, camera, surfaces, options);
  // The peeled layers, before flatten_layers sorts them for the blend.
  const ReferenceCamera rays(camera);
  std::vector<std::size_t> compared;
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      if (!clear_of_edges(rays.eye(), rays.pixel_direction(i, j))) continue;
      const std::size_t p = static_cast<std::size_t>(j) * camera.width + i;
      const auto pixel = layers.color.pixel(p);
      ASSERT_EQ(pixel.size(), 4u) << "pixel (" << i << ", " << j << ")";
      // The scene makes the tie this test is about: equal depths, different keys.
      ASSERT_EQ(pixel[1].depth_in, pixel[2].depth_in) << "pixel (" << i << ", " << j << ")";
      ASSERT_NE(pixel[1].key, pixel[2].key) << "pixel (" << i << ", " << j << ")";
      compared.push_back(p);
    }
  EXPECT_GT(compared.size(), 100u);
  render::Framebuffer image;
  render::flatten_layers(layers.color, camera, image);
  const std::array<double, 4> expected = over(kFrontToBack);
  std::size_t wrong = 0;
  for (const std::size_t p : compared) {
    double error = 0;
    for (int c = 0; c < 4; ++c)
      error = std::max(error, std::abs(image.rgba[4 * p + c] - expected[c]));
    if (error > kColorTolerance && ++wrong <= 3)
      ADD_FAILURE() << "pixel " << p << ": RGBA " << image.rgba[4 * p] << " "
                    << image.rgba[4 * p + 1] << " " << image.rgba[4 * p + 2] << " "
                    << image.rgba[4 * p + 3] << ", the closed form " << expected[0] << " "
                    << expected[1] << " " << expected[2] << " " << expected[3];
  }
  EXPECT_EQ(wrong, 0u) << "of " << compared.size() << " pixels";
}

}  // namespace
}  // namespace tetray::test
