// Which way is up: a small ball (a level set of the distance to its centre on a tet mesh) placed
// right of and above the look-at point must land in the right half and the top half of the image
// (docs/architecture.md §3: i counts columns from the left, j rows from the top), at the column
// and row its centre projects to. Checked for the renderer and for the reference, whose camera
// shares no code with the renderer's, so a mirrored or flipped frame on either side fails here
// even when both sides agree with each other.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr double kRadius = 0.25;
constexpr double kFovDeg = 40;
constexpr double kEyeDistance = 4;
// The image is wider than tall, so a swap of the two axes or of width and height shows too.
constexpr int kWidth = 96, kHeight = 80;

struct Centroid {
  double column = 0, row = 0;  // pixel-centre coordinates, as (i + 0.5, j + 0.5)
  int pixels = 0;
};

Centroid centroid_of(int width, int height, const auto& is_hit) {
  Centroid c;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      if (!is_hit(i, j)) continue;
      c.column += i + 0.5;
      c.row += j + 0.5;
      ++c.pixels;
    }
  }
  if (c.pixels > 0) {
    c.column /= c.pixels;
    c.row /= c.pixels;
  }
  return c;
}

// Where the ball's centre projects: the pinhole of §3 solved for the pixel coordinates.
Centroid projected_centre(Vec3d centre) {
  const double tan_half = std::tan(kFovDeg / 2 * std::numbers::pi / 180);
  const double depth = kEyeDistance - centre.z;  // the eye is on +z looking down -z
  const double ndc_x = centre.x / depth / (tan_half * kWidth / kHeight);
  const double ndc_y = centre.y / depth / tan_half;
  return {kWidth * (ndc_x + 1) / 2, kHeight * (1 - ndc_y) / 2, 0};
}

void expect_ball_at(Vec3d centre, const std::string& label) {
  const BoxMesh mesh = jittered_box(12);
  const std::vector<double> field = sample_field(mesh.points, [&](Vec3d p) {
    return std::hypot(p.x - centre.x, p.y - centre.y, p.z - centre.z);
  });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {kRadius};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const render::Camera camera = look_at({0, 0, kEyeDistance}, {0, 0, 0}, kFovDeg, kWidth, kHeight);

  const render::Framebuffer image = trace_image(scene, camera, surfaces);
  const std::vector<ReferenceHit> reference =
      ReferenceIntersector(scene.volume, {kRadius}).trace_image(camera);
  const Centroid expected = projected_centre(centre);
  const Centroid traced = centroid_of(kWidth, kHeight, [&](int i, int j) {
    return image.hit[image.index(i, j)] != render::kNoHit;
  });
  const Centroid referenced = centroid_of(kWidth, kHeight, [&](int i, int j) {
    return reference[static_cast<std::size_t>(j) * kWidth + i].hit;
  });
  // The ball's image is a disk of about 7 pixels' radius; its centroid lies within a pixel of
  // the centre's projection (the perspective shift of a ball this small and this near the axis
  // is under 0.1 pixel).
  for (const auto& [name, got] :
       {std::pair{"tetray", traced}, std::pair{"reference", referenced}}) {
    EXPECT_GT(got.pixels, 100) << label << " " << name;
    EXPECT_NEAR(got.column, expected.column, 1.0) << label << " " << name;
    EXPECT_NEAR(got.row, expected.row, 1.0) << label << " " << name;
  }
  for (int j = 0; j < kHeight; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      if (image.hit[image.index(i, j)] == render::kNoHit) continue;
      if (centre.x > 0) {
        EXPECT_GE(i, kWidth / 2) << label << ": a hit in the left half";
      }
      if (centre.y > 0) {
        EXPECT_LT(j, kHeight / 2) << label << ": a hit in the bottom half";
      }
    }
  }
}

TEST(CameraOrientation, BallRightOfTheViewLandsInTheRightHalf) {
  expect_ball_at({0.5, 0, 0}, "ball at +x");
}

TEST(CameraOrientation, BallAboveTheViewLandsInTheTopHalf) {
  expect_ball_at({0, 0.5, 0}, "ball at +y");
}

}  // namespace
}  // namespace tetray::test
