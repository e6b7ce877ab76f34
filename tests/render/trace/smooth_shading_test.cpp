// Smooth shading: normals from the field's vertex gradients, interpolated at the hit. For a
// linear field the vertex gradients are the field's gradient exactly; on the level set of
// |x| (a sphere) the shaded normal must follow the analytic sphere normal far more closely than
// the flat per-isopolygon normal, which shows the mesh as facets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <utility>

#include "render/update/vertex_gradients.hpp"
#include "support/reference_camera.hpp"
#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr double kRadius = 0.6;

TEST(VertexGradients, ExactForALinearField) {
  const BoxMesh box = jittered_box(4);
  const Vec3d g{0.3, -1.2, 2.5};
  const auto f = sample_field(box.points, [&](Vec3d p) { return dot(g, p) + 0.7; });
  RenderScene scene = load_scene(box.points, box.tets, f);
  render::compute_vertex_gradients(scene.volume);
  ASSERT_EQ(scene.volume.gradients.size(), scene.volume.vertices.size());
  for (const render::Vec3f& v : scene.volume.gradients) {
    EXPECT_NEAR(v.x, g.x, 1e-4);
    EXPECT_NEAR(v.y, g.y, 1e-4);
    EXPECT_NEAR(v.z, g.z, 1e-4);
  }
}

TEST(VertexGradients, KeptCurrentByTheUpdateWhenAsked) {
  const BoxMesh box = jittered_box(3);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.x; });
  render::UpdatePolicy policy;
  policy.vertex_gradients = true;
  RenderScene scene = load_scene(box.points, box.tets, f, policy);
  ASSERT_EQ(scene.volume.gradients.size(), scene.volume.vertices.size());
  EXPECT_NEAR(scene.volume.gradients[0].x, 1.0, 1e-5);
  const auto g = sample_field(box.points, [](Vec3d p) { return -2 * p.y; });
  render::update_volume(scene.volume, scene.bvh,
                        {box.points.data(), render::ScalarKind::f64, nullptr,
                         render::ScalarKind::f64, box.point_count()},
                        {g.data(), render::ScalarKind::f64, g.size()}, {false, true}, policy);
  for (const render::Vec3f& v : scene.volume.gradients) {
    EXPECT_NEAR(v.x, 0.0, 1e-5);
    EXPECT_NEAR(v.y, -2.0, 1e-5);
  }
}

bool same_bits(const std::vector<render::Vec3f>& a, const std::vector<render::Vec3f>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0;
}

// The exponents and sums of `volume` with its tets split in two parts, as two ranks holding the
// same vertices would find them: pass 1 on each, the maximum of their exponents and the sum of
// their tet counts, pass 2 on each with those, the sums added.
struct Sums {
  render::LargeArray<render::VertexExponents> exponents;
  render::LargeArray<render::VertexSums> sums;
};

Sums sums_of_two_parts(const render::TetVolume& volume, std::size_t split) {
  render::TetVolume first = volume, second = volume;
  first.tets.resize(split);
  second.tets.erase(second.tets.begin(), second.tets.begin() + static_cast<std::ptrdiff_t>(split));
  render::LargeArray<render::VertexExponents> e1, e2;
  render::LargeArray<std::int32_t> n1, n2;
  render::gradient_exponents(first, render::plan_gradients(first), e1, n1);
  render::gradient_exponents(second, render::plan_gradients(second), e2, n2);
  for (std::size_t k = 0; k < e1.size(); ++k) {
    for (int c = 0; c < 4; ++c) e1[k][c] = std::max(e1[k][c], e2[k][c]);
    n1[k] += n2[k];
  }
  render::LargeArray<render::VertexSums> s1, s2;
  render::gradient_sums(first, render::plan_gradients(first), e1, n1, s1);
  render::gradient_sums(second, render::plan_gradients(second), e1, n1, s2);
  for (std::size_t k = 0; k < s1.size(); ++k)
    for (int c = 0; c < 4; ++c) s1[k][c] += s2[k][c];
  return {e1, s1};
}

std::vector<render::Vec3f> gradients_of_two_parts(render::TetVolume volume, std::size_t split) {
  const Sums parts = sums_of_two_parts(volume, split);
  render::gradients_from_sums(volume, parts.exponents, parts.sums);
  return volume.gradients;
}

// 48000 tets: several of the parallel chunks, and in reversed order most of a chunk's vertices
// belong to others.
TEST(VertexGradients, IndependentOfTetOrderAndSplitBitForBit) {
  const BoxMesh box = jittered_box(20);
  const auto f =
      sample_field(box.points, [](Vec3d p) { return std::sin(3 * p.x) * p.y + p.z * p.z; });
  RenderScene scene = load_scene(box.points, box.tets, f);
  render::compute_vertex_gradients(scene.volume);
  const std::vector<render::Vec3f> whole = scene.volume.gradients;
  for (const std::size_t split :
       {std::size_t{1}, scene.volume.tets.size() / 3, scene.volume.tets.size() / 2}) {
    EXPECT_TRUE(same_bits(gradients_of_two_parts(scene.volume, split), whole)) << split;
  }
  std::reverse(scene.volume.tets.begin(), scene.volume.tets.end());
  std::rotate(scene.volume.tets.begin(), scene.volume.tets.begin() + 17, scene.volume.tets.end());
  render::compute_vertex_gradients(scene.volume);
  EXPECT_TRUE(same_bits(scene.volume.gradients, whole));
}

// Vertex 0's tets have x terms F, -F and 1: a double sum gives 1 or 0 depending on their order.
// The sums keep a term down to 2^-50 of the largest (3 tets: b = 3, see VertexSums) in every
// order: 1 for F = 2^40, so the gradient is (1/3, 0, 0); nothing for F = 1e20, so 0.
TEST(VertexGradients, ExactSumsKeepASmallTermOnTheGridInEveryOrder) {
  for (const auto& [f, x] : {std::pair{0x1p40f, 1.0f / 3}, std::pair{1e20f, 0.0f}}) {
    render::TetVolume volume;
    volume.vertices = {{0, 0, 0, 0},  {1, 0, 0, f}, {0, 1, 0, 0},  {0, 0, 1, 0},
                       {-1, 0, 0, f}, {1, 0, 0, 1}, {0, -1, 0, 0}, {0, 0, -1, 0}};
    const render::Tet up{{0, 1, 2, 3}}, down{{0, 4, 2, 3}}, small{{0, 5, 6, 7}};
    for (const std::vector<render::Tet>& order :
         {std::vector{up, down, small}, std::vector{small, up, down},
          std::vector{up, small, down}}) {
      volume.tets.assign(order.begin(), order.end());
      render::compute_vertex_gradients(volume);
      EXPECT_EQ(volume.gradients[0].x, x) << f;
      EXPECT_EQ(volume.gradients[0].y, 0.0f) << f;
    }
  }
}

// 5000 tets around one axis: its two end vertices have a tet count far above a mesh's, so their
// grid is coarser (b = 13), and their |det| terms, all positive and alike, sum to near 2^53 of
// its units. The field and the radii are random, so the terms use all their bits: a sum that
// rounded would differ in some order or split. The sums are compared, not the float gradients,
// whose rounding would hide a difference in the last bits of a double.
TEST(VertexGradients, SumsIndependentOfTetOrderAndSplitAtAHighTetCount) {
  constexpr int kTets = 5000;
  std::uint32_t state = 12345;
  const auto random = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / float(1 << 24);
  };
  render::TetVolume volume;
  volume.vertices = {{0, 0, -1, random()}, {0, 0, 1, random()}};
  for (int i = 0; i < kTets; ++i) {
    const double angle = 2 * std::numbers::pi * i / kTets, radius = 1 + 0.1 * random();
    volume.vertices.push_back({static_cast<float>(radius * std::cos(angle)),
                               static_cast<float>(radius * std::sin(angle)), random() - 0.5f,
                               random()});
  }
  for (std::int32_t i = 0; i < kTets; ++i) {
    volume.tets.push_back({{0, 1, 2 + i, 2 + (i + 1) % kTets}});
  }
  const render::LargeArray<render::VertexSums> whole = sums_of_two_parts(volume, 0).sums;
  for (const std::size_t split : {std::size_t{1}, std::size_t{1777}, std::size_t{2500}}) {
    EXPECT_EQ(sums_of_two_parts(volume, split).sums, whole) << split;
  }
  std::reverse(volume.tets.begin(), volume.tets.end());
  std::rotate(volume.tets.begin(), volume.tets.begin() + 1234, volume.tets.end());
  EXPECT_EQ(sums_of_two_parts(volume, 2000).sums, whole);
}

// Every vertex's gradient against the linear field's, relative to its length.
double largest_relative_error(const render::TetVolume& volume, Vec3d g) {
  double worst = 0;
  for (const render::Vec3f& v : volume.gradients) {
    worst = std::max(worst, length(static_cast<Vec3d>(v) - g) / length(g));
  }
  return worst;
}

TEST(VertexGradients, ExactForALinearFieldOnTetsOfSizesFrom1eMinus6To1) {
  // x graded as sign(x) |x|^10: the cells next to x = 0 are 1e-6 wide, the outer ones 0.94,
  // and vertices at x = +-0.25^10 join both kinds. The field varies along x only, so its float
  // values keep their precision across the thinnest cells.
  BoxMesh box = make_box_mesh({.cells = {8, 4, 4}});
  for (std::size_t p = 0; p < box.point_count(); ++p) {
    double& x = box.points[3 * p];
    x = std::copysign(std::pow(std::abs(x), 10), x);
  }
  const Vec3d g{3, 0, 0};
  const auto f = sample_field(box.points, [&](Vec3d p) { return dot(g, p); });
  RenderScene scene = load_scene(box.points, box.tets, f);
  render::compute_vertex_gradients(scene.volume);
  EXPECT_LT(largest_relative_error(scene.volume, g), 1e-5);
}

TEST(VertexGradients, ExactForALinearFieldOnAMeshAt1e6) {
  BoxMesh box = jittered_box(6);
  for (double& c : box.points) c += 1e6;
  const Vec3d g{0.3, -1.2, 2.5};
  const auto f = sample_field(box.points, [&](Vec3d p) {
    return dot(g, p - Vec3d{1e6, 1e6, 1e6}) + 0.7;
  });
  RenderScene scene = load_scene(box.points, box.tets, f);
  render::compute_vertex_gradients(scene.volume);
  EXPECT_LT(largest_relative_error(scene.volume, g), 1e-5);
}

struct AngleErrors {
  double mean = 0, max = 0;
  std::size_t pixels = 0;
};

// With white surfaces and no ambient light a pixel shows |cos| of the angle between its ray and
// the shading normal; the difference to the angle the analytic sphere normal makes bounds the
// normal's angular error from below, pixel by pixel.
AngleErrors sphere_angle_errors(bool smooth) {
  const BoxMesh box = jittered_box(32);
  const auto f = sample_field(box.points, [](Vec3d p) { return length(p); });
  render::UpdatePolicy policy;
  policy.vertex_gradients = smooth;
  RenderScene scene = load_scene(box.points, box.tets, f, policy);
  const render::Camera camera = look_at({0.4, 0.9, 2.6}, {0, 0, 0}, 30, 96, 96);
  render::TraceOptions options;
  options.ambient = 0;
  options.smooth = smooth;
  const render::IsoSurface surfaces[] = {{static_cast<float>(kRadius), {1, 1, 1}}};
  const render::Framebuffer image =
      render::trace(scene.volume, scene.bvh, camera, surfaces, options);
  const ReferenceCamera rays(camera);
  AngleErrors errors;
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      if (image.hit[p] == render::kNoHit) continue;
      // The ray's nearest crossing of the analytic sphere, away from its silhouette.
      const Vec3d d = rays.pixel_direction(i, j), e = camera.eye;
      const double b = dot(e, d), c = dot(e, e) - kRadius * kRadius, disc = b * b - c;
      if (disc <= 0.05 * kRadius * kRadius) continue;
      const Vec3d hit = e + (-b - std::sqrt(disc)) * d;
      const double expected = std::acos(std::abs(dot(d, normalize(hit))));
      const double shown = std::acos(std::clamp(double(image.rgba[4 * p]), 0.0, 1.0));
      const double error = std::abs(shown - expected);
      errors.mean += error;
      errors.max = std::max(errors.max, error);
      ++errors.pixels;
    }
  errors.mean /= static_cast<double>(std::max<std::size_t>(errors.pixels, 1));
  return errors;
}

// Gradients only where the surfaces need them: at every corner of every tet that straddles an
// isovalue they are the gradients of all tets to the bit, the other vertices are left at zero,
// and the image is the one of the gradients computed everywhere.
TEST(VertexGradients, AtTheSurfacesCornersTheSameBitsAsEverywhere) {
  const BoxMesh box = jittered_box(8);
  const auto f = sample_field(box.points, [](Vec3d p) { return length(p) + 0.2 * p.x * p.y; });
  RenderScene everywhere = load_scene(box.points, box.tets, f);
  RenderScene surfaces = load_scene(box.points, box.tets, f);
  render::compute_vertex_gradients(everywhere.volume);
  const float isovalues[] = {0.45f, 0.8f};
  render::compute_vertex_gradients(surfaces.volume, isovalues);
  const render::TetVolume& v = surfaces.volume;
  ASSERT_EQ(v.gradients.size(), everywhere.volume.gradients.size());
  std::vector<std::uint8_t> on_surface(v.vertices.size(), 0);
  for (const render::Tet& tet : v.tets) {
    float lo = v.vertices[tet.v[0]].f, hi = lo;
    for (int k = 1; k < 4; ++k) {
      lo = std::min(lo, v.vertices[tet.v[k]].f);
      hi = std::max(hi, v.vertices[tet.v[k]].f);
    }
    const bool straddles = std::any_of(std::begin(isovalues), std::end(isovalues),
                                       [&](float iso) { return lo < iso && iso <= hi; });
    if (straddles)
      for (const std::int32_t k : tet.v) on_surface[static_cast<std::size_t>(k)] = 1;
  }
  std::size_t flagged = 0, differing = 0, nonzero_elsewhere = 0;
  for (std::size_t k = 0; k < v.vertices.size(); ++k) {
    const render::Vec3f a = v.gradients[k], b = everywhere.volume.gradients[k];
    if (on_surface[k]) {
      ++flagged;
      differing += std::memcmp(&a, &b, sizeof a) != 0;
    } else {
      nonzero_elsewhere += a.x != 0 || a.y != 0 || a.z != 0;
    }
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(nonzero_elsewhere, 0u);
  // Both surfaces cross the box, and most vertices lie off them: the skip is real.
  EXPECT_GT(flagged, v.vertices.size() / 10);
  EXPECT_LT(flagged, v.vertices.size() / 2);

  const render::Camera camera = look_at({0.4, 0.9, 2.6}, {0, 0, 0}, 30, 64, 64);
  render::TraceOptions smooth;
  smooth.smooth = true;
  for (const float iso : isovalues) {  // the outer surface hides the inner one: one at a time
    const render::IsoSurface drawn[] = {{iso, {1, 1, 1}}};
    const auto a = render::trace(everywhere.volume, everywhere.bvh, camera, drawn, smooth);
    const auto b = render::trace(surfaces.volume, surfaces.bvh, camera, drawn, smooth);
    EXPECT_EQ(image_difference(a, b), "") << "isovalue " << iso;
  }
}

TEST(SmoothShading, SphereNormalsFollowTheAnalyticNormalFarBetterThanFlat) {
  const AngleErrors flat = sphere_angle_errors(false), smooth = sphere_angle_errors(true);
  constexpr double kDegree = std::numbers::pi / 180;
  std::printf(
      "sphere normal angle error: flat mean %.3f max %.3f deg, smooth mean %.3f max %.3f "
      "deg over %zu pixels\n",
      flat.mean / kDegree, flat.max / kDegree, smooth.mean / kDegree, smooth.max / kDegree,
      smooth.pixels);
  ASSERT_GT(smooth.pixels, 2000u);
  EXPECT_EQ(smooth.pixels, flat.pixels);
  // Measured: flat 1.34 mean, 5.4 max; smooth 0.34, 1.3 (the smooth error falls with h^2, the
  // flat one with h).
  EXPECT_GT(flat.mean, 1.0 * kDegree);  // the facets are there to be removed
  EXPECT_LT(smooth.mean, 0.5 * kDegree);
  EXPECT_LT(smooth.mean, 0.35 * flat.mean);
  EXPECT_LT(smooth.max, 0.35 * flat.max);
}

TEST(SmoothShading, WithoutGradientsItStaysFlat) {
  const BoxMesh box = jittered_box(4);
  const auto f = sample_field(box.points, [](Vec3d p) { return length(p); });
  RenderScene scene = load_scene(box.points, box.tets, f);
  const render::Camera camera = look_at({0.4, 0.9, 2.6}, {0, 0, 0}, 30, 32, 32);
  const render::IsoSurface surfaces[] = {{0.6f, {1, 1, 1}}};
  render::TraceOptions smooth;
  smooth.smooth = true;
  const auto a = render::trace(scene.volume, scene.bvh, camera, surfaces, {});
  const auto b = render::trace(scene.volume, scene.bvh, camera, surfaces, smooth);
  EXPECT_EQ(image_difference(a, b), "");
}

}  // namespace
}  // namespace tetray::test
