// The screen bound of a box against brute force: every pixel whose center ray meets the box
// (a slab test in double precision, apart from the projection screen_bound inverts) lies in
// the bound, for random boxes and cameras; a box reaching behind the eye has no bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "render/scene/camera.hpp"
#include "render/scene/screen_bound.hpp"

namespace tetray::render {
namespace {

bool ray_meets_box(const Vec3d& origin, const Vec3d& direction, const Vec3d& lo, const Vec3d& hi) {
  double near = 0, far = INFINITY;
  const double o[] = {origin.x, origin.y, origin.z}, d[] = {direction.x, direction.y, direction.z};
  const double l[] = {lo.x, lo.y, lo.z}, h[] = {hi.x, hi.y, hi.z};
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < l[a] || o[a] > h[a]) return false;
      continue;
    }
    double t0 = (l[a] - o[a]) / d[a], t1 = (h[a] - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far;
}

TEST(ScreenBound, HoldsEveryPixelWhoseRayMeetsTheBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int boxes_seen = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Camera camera;
    camera.eye = {4 * unit(rng), 4 * unit(rng), 6 + 2 * unit(rng)};
    camera.look_at = {unit(rng), unit(rng), unit(rng)};
    camera.fov_deg = 40 + 20 * unit(rng);
    camera.width = 61 + trial % 7;
    camera.height = 47 + trial % 5;
    const Vec3d a{unit(rng), unit(rng), unit(rng)}, b{unit(rng), unit(rng), unit(rng)};
    const Vec3d lo{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
    const Vec3d hi{std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
    const auto bound = screen_bound(camera, lo, hi);
    ASSERT_TRUE(bound) << trial;  // the eye is at least 3 units in front of every box
    const CameraFrame frame = make_frame(camera);
    int covered = 0;
    for (int j = 0; j < camera.height; ++j) {
      for (int i = 0; i < camera.width; ++i) {
        if (!ray_meets_box(camera.eye, pixel_direction(frame, camera, i, j), lo, hi)) continue;
        ++covered;
        ASSERT_TRUE(i >= bound->x0 && i < bound->x1 && j >= bound->y0 && j < bound->y1)
            << "trial " << trial << " pixel " << i << "," << j;
      }
    }
    boxes_seen += covered > 0;
    // Not loose beyond the margin: the bound's area stays within a small factor of the
    // covered pixels for boxes that cover many.
    if (covered > 400) {
      EXPECT_LT((bound->x1 - bound->x0) * (bound->y1 - bound->y0), 4 * covered + 400) << trial;
    }
  }
  EXPECT_GT(boxes_seen, 150);
}

TEST(ScreenBound, NothingForABoxReachingBehindTheEye) {
  Camera camera;  // at z = 5 looking at the origin
  EXPECT_FALSE(screen_bound(camera, {-1, -1, -1}, {1, 1, 6}));
  EXPECT_FALSE(screen_bound(camera, {-1, -1, 5}, {1, 1, 5.5}));
  EXPECT_TRUE(screen_bound(camera, {-1, -1, -1}, {1, 1, 1}));
}

}  // namespace
}  // namespace tetray::render
