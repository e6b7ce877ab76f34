// The distance from a ray to an isopolygon (render/trace/isopolygon_intersect.hpp) down to grazing
// incidence: the set-up's bounds hold the distance of every point of the polygon from the eye,
// tightly, a computed distance never leaves them, and a well-conditioned ray's distance is the
// plane's within float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "render/trace/isopolygon_intersect.hpp"

namespace tetray::test {
namespace {

using render::Vec3f;

// The square of half side `half` centred at `center`, spanned by the unit vectors u and v.
render::Isopolygon square(Vec3f center, Vec3f u, Vec3f v, float half) {
  const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  alignas(16) float xyz[3][4];
  for (int k = 0; k < 4; ++k) {
    const Vec3f corner = center + (half * su[k]) * u + (half * sv[k]) * v;
    for (int c = 0; c < 3; ++c) xyz[c][k] = corner[c];
  }
  render::Isopolygon poly;
  poly.vertex_count = 4;
  for (int c = 0; c < 3; ++c) poly.xyz[c] = render::simd::Float4::load_aligned(xyz[c]);
  return poly;
}

struct OneHit {
  float t;                     // the ray's distance to the polygon
  render::PolygonSetup setup;  // the polygon's set-up for the ray's eye
};

// One ray from `eye` along the unit direction d (its view axis d itself) against the polygon, or
// nothing where it misses.
std::optional<OneHit> intersect_one(const render::Isopolygon& poly, Vec3f eye, Vec3f d) {
  render::RayPacket<1> ray;
  ray.eye = eye;
  ray.dx[0] = d.x;
  ray.dy[0] = d.y;
  ray.dz[0] = d.z;
  ray.tmax[0] = std::numeric_limits<float>::infinity();
  ray.projection.forward = d;
  render::prepare_rays(ray);
  render::TraceStats stats;
  render::IsopolygonIntersector<1, false> intersector(ray, stats);
  if (!intersector.intersect(poly, {1, 0, 0}, 0)) return std::nullopt;
  OneHit hit{ray.tmax[0], {}};
  render::CoveredPixels covered;
  EXPECT_TRUE(
      render::set_up_polygon(poly, eye, nullptr, ray.projection, 0, 0, false, hit.setup, covered));
  return hit;
}

Vec3f unit(Vec3f v) { return (1.0f / length(v)) * v; }

double squared(double x) { return x * x; }

// Squares of side 1 to 20 and eyes at random, some close to them: every point of a square lies
// between the set-up's bounds, which are within its diameter of the distances its points take.
TEST(PolygonDistance, BoundsHoldEveryPointOfThePolygon) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f), size(0.5f, 10.0f),
      weight(0.0f, 1.0f);
  int in_front = 0;
  for (int n = 0; n < 1000; ++n) {
    const Vec3f center{coordinate(random), coordinate(random), coordinate(random)};
    const Vec3f u = unit({coordinate(random), coordinate(random), coordinate(random)});
    const Vec3f v = unit(cross(u, unit({coordinate(random), coordinate(random), 1.0f})));
    const float half = size(random);
    const render::Isopolygon poly = square(center, u, v, half);
    // Anywhere, or just beyond an edge, almost in the square's plane (grazing views).
    const Vec3f eye = n % 2 ? Vec3f{coordinate(random), coordinate(random), coordinate(random)}
                            : center + (half + 0.01f * std::abs(coordinate(random))) * u +
                                  (1e-3f * weight(random)) * unit(cross(u, v));
    render::PolygonSetup s;
    render::CoveredPixels covered;
    render::RowProjection projection;
    projection.forward = unit(center - eye);
    ASSERT_TRUE(render::set_up_polygon(poly, eye, nullptr, projection, 0, 0, false, s, covered));
    alignas(16) float corner[3][4];
    for (int c = 0; c < 3; ++c) poly.xyz[c].store_aligned(corner[c]);
    auto distance_at = [&](const double(&w)[4]) {
      double p[3] = {0, 0, 0};
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) p[c] += w[k] * corner[c][k];
      const float e[3] = {eye.x, eye.y, eye.z};
      return std::sqrt(squared(p[0] - e[0]) + squared(p[1] - e[1]) + squared(p[2] - e[2]));
    };
    double corners[4];
    for (int k = 0; k < 4; ++k) {
      double w[4] = {0, 0, 0, 0};
      w[k] = 1;
      corners[k] = distance_at(w);
    }
    double farthest = 0;
    for (int sample = 0; sample < 200; ++sample) {
      double w[4] = {0, 0, 0, 0};
      if (sample < 4) {
        w[sample] = 1;  // the corners themselves
      } else {
        double sum = 0;
        for (double& x : w) sum += x = weight(random);
        for (double& x : w) x /= sum;
      }
      const double d = distance_at(w);
      EXPECT_LE(s.closest, d) << "polygon " << n << ", sample " << sample;
      EXPECT_GE(s.far_ceiling, d) << "polygon " << n << ", sample " << sample;
      farthest = std::max(farthest, d);
    }
    // For a square in front of the eye the floor is the root of m^2 - 3/8 D^2 (m its nearest
    // corner's distance), less the margins; the distance floor otherwise.
    const double diameter_squared = 8.0 * half * half;
    const double m = *std::min_element(corners, corners + 4);
    if (s.near_floor > 0 && m * m > 0.375 * diameter_squared) {
      EXPECT_GE(s.closest, std::sqrt(m * m - 0.375 * diameter_squared) - 0x1p-14 * farthest)
          << "polygon " << n;
    }
    EXPECT_GE(s.closest, s.near_floor) << "polygon " << n;
    in_front += s.near_floor > 0;
    EXPECT_LE(s.far_ceiling, farthest * (1 + 0x1p-14)) << "polygon " << n;
  }
  EXPECT_GT(in_front, 600);
}

// A small square far from the eye, seen from any side: its floor lies within 2^-13 of its nearest
// point's distance, well within the margin by which the tiles' occlusion culling grows a box's
// distance (tile_occlusion.hpp), so a clamped distance never falls in front of the box around it.
TEST(PolygonDistance, FloorOfASmallPolygonIsTightForOcclusionCulling) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f), weight(0.0f, 1.0f);
  for (int n = 0; n < 1000; ++n) {
    const Vec3f center{coordinate(random), coordinate(random), coordinate(random)};
    const Vec3f u = unit({coordinate(random), coordinate(random), coordinate(random)});
    const Vec3f v = unit(cross(u, unit({coordinate(random), coordinate(random), 1.0f})));
    const render::Isopolygon poly = square(center, u, v, 0.005f);
    const Vec3f eye =
        center + 5.0f * unit({coordinate(random), coordinate(random), coordinate(random)});
    render::PolygonSetup s;
    render::CoveredPixels covered;
    render::RowProjection projection;
    projection.forward = unit(center - eye);
    ASSERT_TRUE(render::set_up_polygon(poly, eye, nullptr, projection, 0, 0, false, s, covered));
    ASSERT_GT(s.near_floor, 0.0f);
    // The nearest point: a dense grid over the square, in double.
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 100; ++i)
      for (int j = 0; j <= 100; ++j) {
        const double a = 0.005 * (i / 50.0 - 1), b = 0.005 * (j / 50.0 - 1);
        const double p[3] = {center.x + a * u.x + b * v.x - eye.x,
                             center.y + a * u.y + b * v.y - eye.y,
                             center.z + a * u.z + b * v.z - eye.z};
        nearest = std::min(nearest, std::sqrt(squared(p[0]) + squared(p[1]) + squared(p[2])));
      }
    EXPECT_GE(s.closest, nearest * (1 - 0x1p-13)) << "polygon " << n;
    EXPECT_LE(s.closest, nearest * (1 + 1e-6)) << "polygon " << n;
  }
}

// A ray aimed at the centre of a square from ever closer to its plane.
TEST(PolygonDistance, AimedRaysFindThePlaneDownToGrazing) {
  const Vec3f center{3.0f, -2.0f, 7.0f}, u = unit({1.0f, 0.2f, -0.3f});
  const Vec3f v = unit(cross(u, {0.1f, 0.3f, 1.0f}));
  const Vec3f normal = unit(cross(u, v));
  const render::Isopolygon poly = square(center, u, v, 1.0f);
  constexpr float kDistance = 10.0f;
  int hits = 0;
  for (double angle = 0.5; angle > 1e-9; angle *= 0.5) {
    // Aimed at the centre at `angle` from the polygon's plane, along a diagonal.
    const Vec3f along = unit(u + v);
    const Vec3f d = unit(static_cast<float>(std::cos(angle)) * along +
                         static_cast<float>(std::sin(angle)) * normal);
    const std::optional<OneHit> hit = intersect_one(poly, center - kDistance * d, d);
    if (!hit) continue;
    ++hits;
    EXPECT_GE(hit->t, hit->setup.closest) << "angle " << angle;
    EXPECT_LE(hit->t, hit->setup.far_ceiling) << "angle " << angle;
    // Well conditioned: the plane's distance. The square reaches 1.5 units along the ray
    // either side of its centre, so a grazing ray's distance is off by at most that.
    const double tolerance = angle > 1e-2 ? 1e-5 * kDistance : 1.5;
    EXPECT_NEAR(hit->t, kDistance, tolerance) << "angle " << angle;
  }
  EXPECT_GT(hits, 20);
}

// Rays from eyes within 1e-6 of the plane of a small square 10 units away, aimed at random points
// of it: their distances are ill-conditioned, and without the clamp many fall outside the
// square's bounds.
TEST(PolygonDistance, RandomGrazingRaysStayBetweenFloorAndCeiling) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit_interval(-1.0f, 1.0f), height(-1e-6f, 1e-6f);
  int hits = 0, outside = 0;
  for (int n = 0; n < 200000; ++n) {
    const Vec3f center{unit_interval(random), unit_interval(random), unit_interval(random)};
    const Vec3f u = unit({unit_interval(random), unit_interval(random), unit_interval(random)});
    const Vec3f v = unit(cross(u, unit({unit_interval(random), unit_interval(random), 1.0f})));
    const render::Isopolygon poly = square(center, u, v, 0.01f);
    // An eye almost in the polygon's plane, 10 units off, looking at a point of the polygon.
    const Vec3f normal = unit(cross(u, v));
    const Vec3f eye = center + 10.0f * unit(unit_interval(random) * u + unit_interval(random) * v) +
                      height(random) * normal;
    const Vec3f target =
        center + (0.01f * unit_interval(random)) * u + (0.01f * unit_interval(random)) * v;
    const std::optional<OneHit> hit = intersect_one(poly, eye, unit(target - eye));
    if (!hit) continue;
    ++hits;
    outside += !(hit->t >= hit->setup.closest && hit->t <= hit->setup.far_ceiling);
  }
  EXPECT_GT(hits, 1000);
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace tetray::test
