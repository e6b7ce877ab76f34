// The tie rule of docs/architecture.md §3 on scenes built so that different tets' isopolygons
// meet a ray at exactly the same depth: the surface along a face seen from both tets sharing it,
// two isosurfaces lying on one face of a mesh whose two sides do not share vertices, and rays
// through the edges between the faces of a plane made of tet faces. The coordinates are small
// dyadic numbers, so every product the renderer forms for these planes is exact and the ties are
// exact in float too. The expected winner is computed here in double with its own ray-polygon
// test: the nearest isopolygon of non-zero area, equal depths going to the smaller tet id. It is
// computed on the rays the renderer traces: the direction of docs/architecture.md §3 rounded to
// float, a component of exactly zero tilted to 1e-20 of its sign (render/trace/ray_packet.cpp:
// a ray in a grid plane counts as just off it), so a ray meets an edge exactly where the
// renderer's ray does.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "support/reference_camera.hpp"
#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr double kTieTolerance = 1e-12;  // relative: the ties built here are exact

struct ExpectedPixel {
  double t = ReferenceHit::kNone;
  std::uint32_t key = render::kNoHit;
  int surface = -1;
  int tied = 0;  // isopolygons at the nearest depth
};

// Where the ray meets the polygon's plane, if inside the polygon or on its boundary (a point on
// an edge belongs to both polygons that share the edge).
std::optional<double> hit_polygon(const Isopolygon& polygon, const Ray& ray) {
  if (polygon.size < 3) return std::nullopt;
  const std::array<Vec3d, 4>& c = polygon.corners;
  const Vec3d normal =
      polygon.size == 3 ? cross(c[1] - c[0], c[2] - c[0]) : cross(c[2] - c[0], c[3] - c[1]);
  const double facing = dot(normal, ray.direction);
  if (facing == 0) return std::nullopt;  // also a polygon of zero area, which holds no surface
  const double t = dot(normal, c[0] - ray.origin) / facing;
  if (!(t > 0)) return std::nullopt;
  const Vec3d x = ray.origin + t * ray.direction;
  bool positive = false, negative = false;
  for (int k = 0; k < polygon.size; ++k) {
    const double side = dot(cross(c[(k + 1) % polygon.size] - c[k], x - c[k]), normal);
    positive = positive || side > 0;
    negative = negative || side < 0;
  }
  if (positive && negative) return std::nullopt;
  return t;
}

Vec3d traced_direction(const ReferenceCamera& rays, int i, int j) {
  const Vec3d exact = rays.pixel_direction(i, j);
  Vec3d traced;
  for (int axis = 0; axis < 3; ++axis) {
    const float component = static_cast<float>(exact[axis]);
    traced[axis] = component == 0 ? std::copysign(1e-20f, component) : component;
  }
  return traced;
}

ExpectedPixel expected_pixel(std::span<const ReferenceTet> tets, std::span<const double> isovalues,
                             const Ray& ray) {
  struct Candidate {
    double t;
    std::uint32_t key;
    int surface;
  };
  std::vector<Candidate> candidates;
  for (const ReferenceTet& tet : tets) {
    for (std::size_t s = 0; s < isovalues.size(); ++s) {
      if (const auto t = hit_polygon(tet.isopolygon(isovalues[s]), ray)) {
        candidates.push_back({*t, tet.id(), static_cast<int>(s)});
      }
    }
  }
  ExpectedPixel pixel;
  for (const Candidate& c : candidates) pixel.t = std::min(pixel.t, c.t);
  for (const Candidate& c : candidates) {
    if (c.t > pixel.t * (1 + kTieTolerance)) continue;
    ++pixel.tied;
    if (c.key < pixel.key) {
      pixel.key = c.key;
      pixel.surface = c.surface;
    }
  }
  return pixel;
}

// Traces the scene with every packet size and checks each pixel's winner; returns the number of
// pixels where two or more isopolygons tied.
int expect_tie_winners(const RenderScene& scene, std::span<const render::IsoSurface> surfaces,
                       const render::Camera& camera, const std::string& label) {
  const std::vector<ReferenceTet> tets = reference_tets(scene.volume);
  const std::vector<double> isovalues = isovalues_of(surfaces);
  const ReferenceCamera rays(camera);
  std::vector<ExpectedPixel> expected;
  for (int j = 0; j < camera.height; ++j) {
    for (int i = 0; i < camera.width; ++i) {
      const Ray ray{camera.eye - scene.volume.origin, traced_direction(rays, i, j)};
      expected.push_back(expected_pixel(tets, isovalues, ray));
    }
  }
  const int ties = static_cast<int>(std::count_if(
      expected.begin(), expected.end(), [](const ExpectedPixel& p) { return p.tied > 1; }));
  for (const render::PacketSize packet : render::kPacketSizes) {
    const render::Framebuffer image = trace_image(scene, camera, surfaces, packet);
    int wrong = 0;
    for (std::size_t p = 0; p < expected.size(); ++p) {
      const ExpectedPixel& want = expected[p];
      if (image.hit[p] == want.key && (want.surface < 0 || image.rgba[4 * p + want.surface] > 0)) {
        continue;
      }
      if (wrong++ < 5) {
        ADD_FAILURE() << label << " packet " << render::to_string(packet) << ": pixel ("
                      << p % camera.width << ", " << p / camera.width << ") has tet "
                      << image.hit[p] << " at depth " << image.depth[p] << ", expected tet "
                      << want.key << " (surface " << want.surface << ", " << want.tied
                      << " isopolygons at t " << want.t << ")";
      }
    }
    EXPECT_EQ(wrong, 0) << label << " packet " << render::to_string(packet);
  }
  return ties;
}

// Surface 0 is pure red and surface 1 pure green, so a pixel's color names its surface.
std::vector<render::IsoSurface> red_and_green(std::span<const double> isovalues) {
  std::vector<render::IsoSurface> surfaces;
  const render::Rgb colors[] = {{1, 0, 0}, {0, 1, 0}};
  for (std::size_t s = 0; s < isovalues.size(); ++s) {
    surfaces.push_back({static_cast<float>(isovalues[s]), colors[s]});
  }
  return surfaces;
}

const render::Camera kAboveTheFace = look_at({0.25, 0.25, 3}, {0.25, 0.25, 0}, 40, 33, 33);

// The face z = 0 of corners (0,0,0), (1,0,0), (0,1,0), with a tet on each side.
constexpr double kFace[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
constexpr double kApexAbove[] = {0.25, 0.25, 1};
constexpr double kApexBelow[] = {0.25, 0.25, -1};

TEST(TieRule, FaceOnTheIsovalueSeenFromBothSidesGoesToTheSmallerId) {
  // Field 0 on the face and -1 at both apexes: each tet's isopolygon for 0 is the face itself.
  std::vector<double> points(kFace, kFace + 9);
  points.insert(points.end(), kApexAbove, kApexAbove + 3);
  points.insert(points.end(), kApexBelow, kApexBelow + 3);
  const std::vector<double> field = {0, 0, 0, -1, -1};
  const std::vector<std::vector<std::int64_t>> orders = {{0, 1, 2, 3, 0, 2, 1, 4},
                                                         {0, 2, 1, 4, 0, 1, 2, 3}};
  const double isovalues[] = {0.0};
  for (std::size_t o = 0; o < orders.size(); ++o) {
    const RenderScene scene = load_scene(points, orders[o], field);
    const std::string label = "face seen from both sides, order " + std::to_string(o);
    EXPECT_GT(expect_tie_winners(scene, red_and_green(isovalues), kAboveTheFace, label), 100)
        << label;
  }
}

TEST(TieRule, TwoIsosurfacesOnOneFaceGoToTheSmallerId) {
  // The two sides of the face have their own copies of its corners, with the values 0 (tet
  // above, apex -1) and 0.5 (tet below, apex -0.5): isovalue 0 lies on the face from above,
  // isovalue 0.5 from below, and the two surfaces coincide.
  std::vector<double> points(kFace, kFace + 9);
  points.insert(points.end(), kApexAbove, kApexAbove + 3);
  points.insert(points.end(), kFace, kFace + 9);
  points.insert(points.end(), kApexBelow, kApexBelow + 3);
  const std::vector<double> field = {0, 0, 0, -1, 0.5, 0.5, 0.5, -0.5};
  const std::vector<std::vector<std::int64_t>> orders = {{0, 1, 2, 3, 4, 6, 5, 7},
                                                         {4, 6, 5, 7, 0, 1, 2, 3}};
  const double isovalues[] = {0.0, 0.5};
  for (std::size_t o = 0; o < orders.size(); ++o) {
    const RenderScene scene = load_scene(points, orders[o], field);
    const std::string label = "two isosurfaces on one face, order " + std::to_string(o);
    EXPECT_GT(expect_tie_winners(scene, red_and_green(isovalues), kAboveTheFace, label), 100)
        << label;
  }
}

TEST(TieRule, RaysThroughSharedEdgesGoToTheSmallerId) {
  // f = z on an unjittered grid of spacing 0.5: isovalue 0 is the grid plane z = 0, made of the
  // top faces of the tets below it, right triangles of one area split along x = y. Seen straight
  // down in a square image, the pixels of the image diagonal have rays with equal x and y
  // components, which meet those diagonal edges exactly, each shared by two faces; the middle
  // row and column, tilted off the grid lines, check the other side of the convention.
  const BoxMesh mesh = jittered_box(4, 0.0);
  const std::vector<double> field = sample_field(mesh.points, [](Vec3d p) { return p.z; });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {0.0};
  const render::Camera camera = look_at({0, 0, 4}, {0, 0, 0}, 40, 41, 41);
  EXPECT_GT(expect_tie_winners(scene, red_and_green(isovalues), camera, "plane of faces"), 20);
}

}  // namespace
}  // namespace tetray::test
