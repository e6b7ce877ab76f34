// render::camera_problem, the one check of a camera a user gives (config, keyframes,
// tetray-render): every unusable part named, and directions taken at any scale.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "render/scene/camera.hpp"

namespace tetray::render {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Camera camera(Vec3d eye, Vec3d look_at, Vec3d up, double fov_deg = 40) {
  return Camera{eye, look_at, up, fov_deg, 64, 64};
}

bool names(const Camera& c, const std::string& part) {
  return camera_problem(c).find(part) != std::string::npos;
}

TEST(CameraProblem, AUsableCameraHasNone) {
  EXPECT_EQ(camera_problem(camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0})), "");
  EXPECT_EQ(camera_problem(camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 1)), "");
  EXPECT_EQ(camera_problem(camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 179)), "");
  // Scale-free: tiny and huge directions are directions.
  EXPECT_EQ(camera_problem(camera({0, 0, 1e-300}, {0, 0, 0}, {1e-300, 1e-300, 0})), "");
  EXPECT_EQ(camera_problem(camera({0, 0, 0}, {0, 0, 1e300}, {0, 1e300, 0})), "");
}

TEST(CameraProblem, EachUnusablePartIsNamed) {
  EXPECT_TRUE(names(camera({kNan, 0, 5}, {0, 0, 0}, {0, 1, 0}), "the eye is not a finite point"));
  EXPECT_TRUE(names(camera({0, 0, 5}, {0, kInf, 0}, {0, 1, 0}), "look_at is not a finite point"));
  EXPECT_TRUE(names(camera({0, 0, 5}, {0, 0, 0}, {0, kNan, 0}), "up is not a finite direction"));
  EXPECT_TRUE(names(camera({1, 1, 1}, {1, 1, 1}, {0, 1, 0}), "eye and look_at are the same point"));
  EXPECT_TRUE(names(camera({0, 0, 5}, {0, 0, 0}, {0, 0, 0}), "up must not be the zero vector"));
  EXPECT_TRUE(names(camera({0, 5, 0}, {0, 0, 0}, {0, 1, 0}), "parallel to up"));
  EXPECT_TRUE(names(camera({0, 5, 0}, {0, 0, 0}, {0, -1e-300, 0}), "parallel to up"));
  // Within 1e-6 rad of the view: rounding would dominate the frame.
  EXPECT_TRUE(names(camera({0, 0, 5}, {0, 0, 0}, {1e-7, 0, 1}), "parallel to up"));
  EXPECT_EQ(camera_problem(camera({0, 0, 5}, {0, 0, 0}, {1e-5, 0, 1})), "");
}

TEST(CameraProblem, TheFieldOfViewIsAFiniteNumberIn1To179) {
  for (double fov : {kNan, -kInf, kInf, 0.0, 0.999, 179.001, 180.0}) {
    EXPECT_TRUE(names(camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, fov), "outside [1, 179]")) << fov;
  }
}

TEST(CameraProblem, UnitDirectionKeepsTheDirectionAtAnyScale) {
  for (double scale : {1e-300, 1e-10, 1.0, 1e10, 1e300}) {
    const Vec3d v = unit_direction(scale * Vec3d{3, 0, 4});
    EXPECT_DOUBLE_EQ(v.x, 0.6) << scale;
    EXPECT_DOUBLE_EQ(v.z, 0.8) << scale;
  }
  const Vec3d zero = unit_direction({0, 0, 0});
  EXPECT_EQ(dot(zero, zero), 0);
}

}  // namespace
}  // namespace tetray::render
