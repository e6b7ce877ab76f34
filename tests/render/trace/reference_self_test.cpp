// The reference intersector against analytic answers, on volumes built without the renderer:
// a linear field is reproduced exactly by linear tets, so its level set is a known plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

struct LinearField {
  Vec3d gradient;
  double offset;
  double operator()(Vec3d x) const { return dot(gradient, x) + offset; }
};

struct PlaneCase {
  const char* name;
  double jitter;
  LinearField field;
  double isovalue;
};

// Generic position, along tet faces (f = x at a grid plane), through vertices only.
const PlaneCase kPlaneCases[] = {
    {"generic", 0.15, {{0.3, -0.5, 0.8}, 0.1}, 0.27},
    {"along faces", 0.0, {{1, 0, 0}, 0}, 0.0},
    {"through vertices", 0.0, {{1, 1, 1}, 0}, 0.5},
};

constexpr int kCells = 4;  // grid planes of [-1, 1]^3 at multiples of 0.5

// The ray parameter interval inside [-1, 1]^3 (slab method); empty when it misses.
struct Interval {
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  bool empty() const { return !(lo <= hi); }
};
Interval clip_to_cube(Vec3d eye, Vec3d direction) {
  Interval interval;
  for (int axis = 0; axis < 3; ++axis) {
    const double a = (-1 - eye[axis]) / direction[axis], b = (1 - eye[axis]) / direction[axis];
    interval.lo = std::max(interval.lo, std::min(a, b));
    interval.hi = std::min(interval.hi, std::max(a, b));
  }
  return interval;
}

bool inside_cube(Vec3d x, double margin) {
  return std::abs(x.x) <= 1 - margin && std::abs(x.y) <= 1 - margin && std::abs(x.z) <= 1 - margin;
}
bool outside_cube(Vec3d x, double margin) {
  return std::abs(x.x) > 1 + margin || std::abs(x.y) > 1 + margin || std::abs(x.z) > 1 + margin;
}

render::TetVolume linear_volume(const PlaneCase& c) {
  const BoxMesh mesh = jittered_box(kCells, c.jitter);
  const std::vector<double> field = sample_field(mesh.points, c.field);
  return volume_by_hand(mesh.points, mesh.tets, field);
}

TEST(ReferenceSelfTest, LinearFieldGivesItsExactPlane) {
  for (const PlaneCase& c : kPlaneCases) {
    const ReferenceIntersector reference(linear_volume(c), {c.isovalue});
    int checked_hits = 0, checked_misses = 0;
    for (const render::Camera& camera : standard_cameras(40, 30)) {
      const ReferenceCamera rays(camera);
      for (int j = 0; j < camera.height; ++j) {
        for (int i = 0; i < camera.width; ++i) {
          const Vec3d d = rays.pixel_direction(i, j);
          const ReferenceHit got = reference.trace_ray(rays, d);
          const double margin = 1e-6 * got.length_scale;
          const double t = (c.isovalue - c.field(camera.eye)) / dot(c.field.gradient, d);
          const Vec3d x = camera.eye + t * d;
          if (t > 0 && inside_cube(x, margin)) {
            ++checked_hits;
            ASSERT_TRUE(got.hit) << c.name << " pixel " << i << "," << j;
            EXPECT_NEAR(got.t, t, margin) << c.name;
            EXPECT_NEAR(got.abs_cos, std::abs(dot(c.field.gradient, d)) / length(c.field.gradient),
                        1e-5);
          } else if (!(t > 0) || outside_cube(x, margin)) {
            ++checked_misses;
            EXPECT_FALSE(got.hit) << c.name << " pixel " << i << "," << j;
          }
        }
      }
    }
    EXPECT_GT(checked_hits, 1000) << c.name;
    EXPECT_GT(checked_misses, 1000) << c.name;
  }
}

TEST(ReferenceSelfTest, BelowLevelProbeMatchesTheClippedLinearField) {
  const PlaneCase& c = kPlaneCases[0];
  const BelowLevelProbe probe(linear_volume(c), c.isovalue);
  int below = 0, not_below = 0;
  for (const render::Camera& camera : standard_cameras(40, 30)) {
    const ReferenceCamera rays(camera);
    for (int j = 0; j < camera.height; ++j) {
      for (int i = 0; i < camera.width; ++i) {
        const Vec3d d = rays.pixel_direction(i, j);
        const Interval inside = clip_to_cube(camera.eye, d);
        const bool passes = probe.passes_below(camera.eye, d);
        if (inside.empty()) {
          EXPECT_FALSE(passes);
          continue;
        }
        // Linear along the ray, so the minimum is at an end of the stretch inside the cube.
        const double lowest =
            std::min(c.field(camera.eye + inside.lo * d), c.field(camera.eye + inside.hi * d));
        if (std::abs(lowest - c.isovalue) < 1e-6 || inside.hi - inside.lo < 1e-6) continue;
        EXPECT_EQ(passes, lowest < c.isovalue) << "pixel " << i << "," << j;
        (passes ? below : not_below) += 1;
      }
    }
  }
  EXPECT_GT(below, 300);
  EXPECT_GT(not_below, 300);
}

// f = x with the isovalue at the grid plane x = 0: the surface is made of tet faces, whose
// edges lie on the grid lines; the distances to them are known.
TEST(ReferenceSelfTest, GrazingDistancesToKnownEdges) {
  const PlaneCase& c = kPlaneCases[1];
  const ReferenceIntersector reference(linear_volume(c), {c.isovalue});
  const double h = 2.0 / kCells;
  const double length_scale = std::sqrt(12.0);  // the mesh diagonal exceeds |eye| below
  struct Probe {
    double y, z, edge_distance;
  };
  // Off a grid line by 0.1 h (farther from both face diagonals), and on a grid line.
  const Probe probes[] = {{0.1 * h, 0.5 * h, 0.1 * h}, {0.0, 0.5 * h, 0.0}};
  for (const Probe& probe : probes) {
    render::Camera camera = look_at({-3, probe.y, probe.z}, {0, probe.y, probe.z}, 30, 1, 1);
    const ReferenceHit got = reference.trace_ray(ReferenceCamera(camera), {1, 0, 0});
    ASSERT_TRUE(got.hit);
    EXPECT_NEAR(got.depth, 3.0, 1e-12);
    EXPECT_DOUBLE_EQ(got.length_scale, length_scale);
    EXPECT_NEAR(got.isopolygon_edge_distance * length_scale, probe.edge_distance, 1e-12);
    EXPECT_NEAR(got.tet_edge_distance * length_scale, probe.edge_distance, 1e-12);
  }
}

}  // namespace
}  // namespace tetray::test
