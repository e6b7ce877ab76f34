// Clip caps (Wald et al. 2007, §7) against a double-precision reference: on a box mesh whose
// boundary is exactly the cube [-1, 1]^3, with a cap field linear in x (barycentric
// interpolation is exact for it), a pixel shows the cap exactly where the reference says the
// ray's entry point into the kept region (ReferenceClip::entry) lies in the mesh and in front of
// every kept isosurface hit (ReferenceIntersector), and its color is the colormap of the
// analytic value there, lit with the plane's normal.
#include <gtest/gtest.h>

#include <random>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "render/walk/clip_cap.hpp"
#include "render/walk/point_locate.hpp"
#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

const int kWidth = scaled_side(80);
const int kHeight = scaled_side(60);
constexpr float kAmbient = 0.15f;  // TraceOptions' default
const Vec3d kSlope{0.7, -0.4, 0.25};
constexpr double kOffset = 0.3;
// Relative to the mesh's size: decisions closer than this to a plane, an edge of the region,
// the mesh's boundary or an isosurface are float rounding, and exempt.
constexpr double kMargin = 1e-5;
// Per color channel: the renderer interpolates in float at a float point (seen: below 1e-6).
constexpr double kColorTolerance = 1e-5;

double cap_value(Vec3d world) { return dot(kSlope, world) + kOffset; }

struct CapScene {
  RenderScene scene;
  std::vector<float> cap_field;
  std::vector<render::IsoSurface> surfaces;
  render::FaceAdjacency<render::Tet20> adjacency;
};

CapScene cap_scene() {
  const BoxMesh mesh = jittered_box(7);
  // A field whose level set 0 is a few closed and open sheets through the cube.
  const auto iso_field = sample_field(mesh.points, [](Vec3d p) {
    return std::sin(3 * p.x) * std::cos(3 * p.y) + std::sin(3 * p.z) * std::cos(2 * p.x);
  });
  CapScene s{load_scene(mesh.points, mesh.tets, iso_field),
             {},
             make_surfaces(std::vector<double>{0.0}),
             {}};
  const std::vector<double> linear = sample_field(mesh.points, cap_value);
  render::load_vertex_field(
      s.scene.volume, {linear.data(), render::ScalarKind::f64, mesh.point_count()}, s.cap_field);
  s.adjacency = render::build_face_adjacency<render::Tet20>(s.scene.volume);
  return s;
}

render::ClipRegion tilted_plane() {
  render::ClipRegion clip;
  clip.planes[0] = {{0.1, 0.0, 0.2}, {1, 0.8, 1.1}};  // cuts away the corner towards the eye
  clip.plane_count = 1;
  return clip;
}

render::ClipRegion box_and_plane() {
  render::ClipRegion clip;
  clip.has_box = true;
  clip.box_lo = {-0.8, -1.5, -0.7};
  clip.box_hi = {0.6, 0.55, 1.5};
  clip.planes[0] = {{0.0, -0.3, 0.0}, {0, -1, 0.3}};
  clip.plane_count = 1;
  return clip;
}

double cube_margin(Vec3d world) {
  double margin = 1e300;
  for (int a = 0; a < 3; ++a) margin = std::min(margin, 1 - std::abs(world[a]));
  return margin;  // < 0 outside the mesh
}

// What the reference says one pixel shows.
struct ExpectedCap {
  bool cap = false;
  bool ambiguous = false;  // too close to call
  double depth = 0;
  float rgb[3] = {0, 0, 0};
};

ExpectedCap expected_cap(const ReferenceCamera& rc, const ReferenceClip& clip, Vec3d origin,
                         const ReferenceHit& surface, const render::Colormap& colormap, double lo,
                         double hi, int i, int j) {
  ExpectedCap e;
  const Vec3d d = rc.pixel_direction(i, j);
  const auto entry = clip.entry(rc.eye() - origin, d);
  if (!entry) return e;
  const Vec3d world = rc.eye() + entry->t * d;
  const double scale = 2 * std::sqrt(3.0);
  const double inside = cube_margin(world);
  const bool near_surface = surface.hit && std::abs(surface.t - entry->t) < kMargin * scale;
  e.ambiguous = entry->margin < kMargin * scale || std::abs(inside) < kMargin * scale ||
                near_surface || surface.isopolygon_edge_distance < kGrazingDistance;
  e.cap = inside > 0 && (!surface.hit || entry->t < surface.t);
  e.depth = rc.depth(world);
  colormap.lookup(static_cast<float>((cap_value(world) - lo) / (hi - lo)), e.rgb);
  const double light = kAmbient + (1 - kAmbient) * std::abs(dot(entry->normal, d));
  for (float& c : e.rgb) c = static_cast<float>(c * light);
  return e;
}

struct CapCounts {
  std::size_t caps = 0, checked = 0, ambiguous = 0, wrong_place = 0, wrong_color = 0;
  double worst_color = 0;
};

CapCounts compare_caps(const CapScene& s, const render::ClipRegion& clip,
                       const render::Camera& camera) {
  const render::Colormap& colormap = *render::find_colormap("viridis");
  const double lo = kOffset - 1.35, hi = kOffset + 1.35;  // |kSlope|_1 = 1.35
  render::TraceOptions options;
  options.clip = clip;
  render::Framebuffer image =
      render::trace(s.scene.volume, s.scene.bvh, camera, s.surfaces, options);
  const render::ClipCap cap{&colormap, static_cast<float>(lo), static_cast<float>(hi), s.cap_field};
  // Located through the BVH alone, and walking from the previous pixel's tet as the adaptor
  // does: the same image, bit for bit.
  render::Framebuffer walked = image;
  render::draw_clip_cap(image, s.scene.volume, s.scene.bvh, camera, options, cap);
  render::draw_clip_cap(walked, s.scene.volume, s.scene.bvh, camera, options, cap, nullptr,
                        &s.adjacency);
  EXPECT_TRUE(std::equal(image.rgba.begin(), image.rgba.end(), walked.rgba.begin()));
  EXPECT_TRUE(std::equal(image.hit.begin(), image.hit.end(), walked.hit.begin()));
  const ReferenceIntersector reference(s.scene.volume, isovalues_of(s.surfaces), clip);
  const std::vector<ReferenceHit> surfaces = reference.trace_image(camera);
  const ReferenceCamera rc(camera);
  const ReferenceClip reference_clip(clip, s.scene.volume.origin);
  CapCounts counts;
  for (int j = 0; j < camera.height; ++j) {
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      const ExpectedCap e = expected_cap(rc, reference_clip, s.scene.volume.origin, surfaces[p],
                                         colormap, lo, hi, i, j);
      if (e.ambiguous) {
        ++counts.ambiguous;
        continue;
      }
      ++counts.checked;
      const bool shows_cap =
          image.hit[p] != render::kNoHit &&
          std::abs(image.depth[p] - e.depth) <= kMargin * std::max(1.0, std::abs(e.depth));
      if (shows_cap != e.cap) {
        ++counts.wrong_place;
        continue;
      }
      if (!e.cap) continue;
      ++counts.caps;
      double worst = 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(double(image.rgba[4 * p + c]) - e.rgb[c]));
      counts.worst_color = std::max(counts.worst_color, worst);
      counts.wrong_color += worst > kColorTolerance || image.rgba[4 * p + 3] != 1.0f;
    }
  }
  return counts;
}

void expect_caps_agree(const render::ClipRegion& clip, const std::string& label) {
  const CapScene s = cap_scene();
  std::size_t caps = 0;
  int index = 0;
  for (const render::Camera& camera : standard_cameras(kWidth, kHeight)) {
    const std::string name = label + " camera " + std::to_string(index++);
    const CapCounts c = compare_caps(s, clip, camera);
    std::cout << "[ cap ] " << name << ": " << c.caps << " cap pixels of " << c.checked
              << " checked, " << c.ambiguous << " ambiguous, worst color error " << c.worst_color
              << "\n";
    EXPECT_EQ(c.wrong_place, 0u) << name;
    EXPECT_EQ(c.wrong_color, 0u) << name << ": worst " << c.worst_color;
    // Few pixels too close to call (rays along a box face, at the small sanitizer images too).
    EXPECT_LT(c.ambiguous, c.checked / 20 + 1) << name;
    caps += c.caps;
  }
  EXPECT_GT(caps, static_cast<std::size_t>(kWidth * kHeight / 4)) << label;
}

// From the tet of a point a fraction of a cell away, the walk ends where the BVH's search does,
// weights included, or gives up (then the cap asks the BVH).
TEST(PointLocate, WalkingFindsTheTetOfTheBvhsSearch) {
  const CapScene s = cap_scene();
  const render::TetVolume& volume = s.scene.volume;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> inside(-0.95, 0.95), step(-0.2, 0.2);
  int found = 0, tried = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3d a{inside(rng), inside(rng), inside(rng)};
    const Vec3d b = a + Vec3d{step(rng), step(rng), step(rng)};
    const auto from = render::locate_point(volume, s.scene.bvh, a - volume.origin);
    const auto want = render::locate_point(volume, s.scene.bvh, b - volume.origin);
    if (!from || !want) continue;
    ++tried;
    const auto got = render::locate_by_walking(volume, s.adjacency, from->tet, b - volume.origin);
    if (!got) continue;
    ++found;
    ASSERT_EQ(got->tet, want->tet) << "point " << k;
    for (int c = 0; c < 4; ++c) ASSERT_EQ(got->weight[c], want->weight[c]) << "point " << k;
  }
  EXPECT_GT(tried, 1500);
  EXPECT_GT(found, tried * 3 / 4);  // the walk does the work, not the fallback
}

TEST(ClipCap, PlaneCapAgreesWithTheReference) { expect_caps_agree(tilted_plane(), "plane"); }

TEST(ClipCap, BoxAndPlaneCapsAgreeWithTheReference) {
  expect_caps_agree(box_and_plane(), "box and plane");
}

TEST(ClipCap, EntryIsTheNearestPointOfTheRegion) {
  const render::ClipRegion clip = box_and_plane();
  // From x = 3 along -x: enters the box through its face x = 0.6, outward normal +x.
  const auto entry = render::enter_region(clip, {0, 0, 0}, {3, 0.1, 0.2}, {-1, 0, 0});
  ASSERT_TRUE(entry.has_value());
  EXPECT_DOUBLE_EQ(entry->t, 2.4);
  EXPECT_EQ(entry->normal.x, 1);
  // From inside the region nothing is cut in front of the eye; a ray past the box misses it.
  EXPECT_FALSE(render::enter_region(clip, {0, 0, 0}, {0, 0, 0}, {1, 0, 0}).has_value());
  EXPECT_FALSE(render::enter_region(clip, {0, 0, 0}, {3, 2, 0}, {-1, 0, 0}).has_value());
  // Crosses the face x = 0.6 (at y = 2.52) and leaves through x = -0.8 before it comes down to
  // the top face y = 0.55: it enters no point of the region.
  const Vec3d d = normalize(Vec3d{-1, -0.2, 0});
  EXPECT_FALSE(render::enter_region(clip, {0, 0, 0}, {3, 3, 0.2}, d).has_value());
  EXPECT_FALSE(ReferenceClip(clip, {0, 0, 0}).entry({3, 3, 0.2}, d).has_value());
}

}  // namespace
}  // namespace tetray::test
