// Level of detail: the per-node linear fits, the proxy isopolygons of a node, the footprint
// test, and images against the exact ones. A planar isosurface is one the proxies represent
// exactly, so there the LOD image must equal the exact one up to rounding while the traversal
// does far less; on a curved surface the depth error is bounded by the node widths allowed and
// shrinks with the threshold.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "render/bvh/node_planes.hpp"
#include "render/trace/level_of_detail.hpp"
#include "support/render_fixtures.hpp"
#include "tools/bench_common/image_error.hpp"

namespace tetray::test {
namespace {

using bench::ImageError;
using render::Bounds4;
using render::NodePlane;

std::vector<NodePlane> planes_of(const RenderScene& scene) {
  std::vector<NodePlane> planes;
  render::fit_node_planes(scene.volume, scene.bvh, planes);
  return planes;
}

TEST(NodePlanes, ExactForALinearFieldAtEveryNode) {
  const BoxMesh box = jittered_box(6);
  const Vec3d g{0.4, -1.1, 0.7};
  const auto f = sample_field(box.points, [&](Vec3d p) { return dot(g, p) + 0.25; });
  const RenderScene scene = load_scene(box.points, box.tets, f);
  const std::vector<NodePlane> planes = planes_of(scene);
  ASSERT_EQ(planes.size(), scene.bvh.nodes.size());
  const Vec3d origin = scene.volume.origin;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const Bounds4& b = scene.bvh.nodes[i].bounds;
    const Vec3d centre =
        origin + Vec3d{0.5 * (double(b.lo[0]) + b.hi[0]), 0.5 * (double(b.lo[1]) + b.hi[1]),
                       0.5 * (double(b.lo[2]) + b.hi[2])};
    EXPECT_NEAR(planes[i].gradient[0], g.x, 1e-4) << "node " << i;
    EXPECT_NEAR(planes[i].gradient[1], g.y, 1e-4) << "node " << i;
    EXPECT_NEAR(planes[i].gradient[2], g.z, 1e-4) << "node " << i;
    EXPECT_NEAR(planes[i].value, dot(g, centre) + 0.25, 1e-4) << "node " << i;
  }
}

TEST(NodePlanes, IndependentOfTheThreadCount) {
  const GyroidTwist scene_data = gyroid(12);
  const RenderScene scene =
      load_scene(scene_data.mesh.points, scene_data.mesh.tets, scene_data.field);
  std::vector<NodePlane> one, two;
  tbb::task_arena(1).execute([&] { one = planes_of(scene); });
  tbb::task_arena(2).execute([&] { two = planes_of(scene); });
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].value, two[i].value);
    EXPECT_EQ(one[i].gradient[0], two[i].gradient[0]);
  }
}

// 2D point-in-convex-polygon for the proxies' corners projected along the plane normal.
bool inside_polygon(const render::Isopolygon& poly, Vec3d p, int drop_axis) {
  alignas(16) float c[3][4];
  for (int a = 0; a < 3; ++a) poly.xyz[a].store_aligned(c[a]);
  const int u = (drop_axis + 1) % 3, v = (drop_axis + 2) % 3;
  int positive = 0, negative = 0;
  for (int k = 0; k < 4; ++k) {
    const int j = (k + 1) % 4;
    const double ex = c[u][j] - c[u][k], ey = c[v][j] - c[v][k];
    if (ex == 0 && ey == 0) continue;  // a triangle's repeated corner
    const double side = ex * (p[v] - c[v][k]) - ey * (p[u] - c[u][k]);
    positive += side > 1e-9;
    negative += side < -1e-9;
  }
  return positive == 0 || negative == 0;
}

TEST(ProxyIsopolygons, CoverThePlaneWithinTheBoxAndNothingElse) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Bounds4 box{{-1, -0.5, 0, 0}, {2, 1, 0.25, 1}};
  int planes_with_polygons = 0;
  for (int trial = 0; trial < 300; ++trial) {
    NodePlane plane;
    for (float& g : plane.gradient) g = static_cast<float>(unit(rng));
    plane.value = static_cast<float>(0.5 * unit(rng));
    render::Isopolygon polys[2];
    const int count = render::proxy_isopolygons(box, plane, 0.0f, polys);
    planes_with_polygons += count > 0;
    const Vec3d g{plane.gradient[0], plane.gradient[1], plane.gradient[2]};
    const Vec3d centre{0.5, 0.25, 0.125};
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(g[a]) > std::abs(g[drop])) drop = a;
    // Every corner lies on the plane and in the box.
    for (int j = 0; j < count; ++j) {
      alignas(16) float c[3][4];
      for (int a = 0; a < 3; ++a) polys[j].xyz[a].store_aligned(c[a]);
      for (int k = 0; k < 4; ++k) {
        const Vec3d p{c[0][k], c[1][k], c[2][k]};
        EXPECT_NEAR(plane.value + dot(g, p - centre), 0.0, 1e-5);
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(p[a], box.lo[a] - 1e-6);
          EXPECT_LE(p[a], box.hi[a] + 1e-6);
        }
      }
    }
    // Random points of the plane around the box: those inside it fall in a polygon, those
    // outside it in none.
    for (int s = 0; s < 50; ++s) {
      Vec3d p{};
      double off_drop = plane.value;
      for (int a = 0; a < 3; ++a) {
        if (a == drop) continue;
        p[a] = box.lo[a] + (0.5 + 0.6 * unit(rng)) * (box.hi[a] - box.lo[a]);
        off_drop += g[a] * (p[a] - centre[a]);
      }
      p[drop] = centre[drop] - off_drop / g[drop];
      bool inside = true, near_or_inside = true;
      for (int a = 0; a < 3; ++a) {
        inside &= p[a] > box.lo[a] + 1e-4 && p[a] < box.hi[a] - 1e-4;
        near_or_inside &= p[a] >= box.lo[a] - 1e-4 && p[a] <= box.hi[a] + 1e-4;
      }
      bool covered = false;
      for (int j = 0; j < count; ++j) covered |= inside_polygon(polys[j], p, drop);
      if (inside) {
        EXPECT_TRUE(covered) << "trial " << trial;
      }
      if (!near_or_inside) {
        EXPECT_FALSE(covered) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(planes_with_polygons, 100);
}

TEST(FootprintLod, StopsAtNodesNarrowerThanTheFootprintOnly) {
  NodePlane sloped;
  sloped.gradient[0] = 1;
  const NodePlane flat;
  const std::vector<NodePlane> planes{sloped, flat};
  const render::FootprintLod lod({2.0f, planes}, 0.05f);  // 0.1 per unit distance
  render::BvhNode node{{{10, 0, 0, 0}, {11, 1, 1, 1}}, 0, 1};
  EXPECT_TRUE(lod.stops_at(0, node, {0, 0.5f, 0.5f}));       // width 1 at distance 10
  EXPECT_FALSE(lod.stops_at(0, node, {5, 0.5f, 0.5f}));      // at distance 5
  EXPECT_FALSE(lod.stops_at(1, node, {0, 0.5f, 0.5f}));      // no surface plane
  EXPECT_FALSE(lod.stops_at(0, node, {10.5f, 0.5f, 0.5f}));  // eye inside
}

ImageError compare(const render::Framebuffer& exact, const render::Framebuffer& lod,
                   const render::Camera& camera) {
  return bench::image_error(exact, lod, camera);
}

render::Framebuffer trace_lod(const RenderScene& scene, const render::Camera& camera,
                              std::span<const render::IsoSurface> surfaces, float node_pixels,
                              const std::vector<NodePlane>& planes, render::TraceStats* stats,
                              render::PacketSize packet = render::PacketSize::p16x16) {
  render::TraceOptions options;
  options.packet = packet;
  options.collect_stats = stats != nullptr;
  options.lod = {node_pixels, planes};
  return render::trace(scene.volume, scene.bvh, camera, surfaces, options, stats);
}

TEST(LevelOfDetail, ThresholdFarBelowTheNodesGivesTheExactImage) {
  const GyroidTwist g = gyroid(10);
  const RenderScene scene = load_scene(g.mesh.points, g.mesh.tets, g.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  const std::vector<NodePlane> planes = planes_of(scene);
  const render::Camera camera = benchmark_camera(scaled_side(256));
  const render::Framebuffer exact = trace_image(scene, camera, surfaces);
  const render::Framebuffer lod = trace_lod(scene, camera, surfaces, 1e-6f, planes, nullptr);
  EXPECT_EQ(exact.depth, lod.depth);
  EXPECT_EQ(exact.rgba, lod.rgba);
  EXPECT_EQ(exact.hit, lod.hit);
}

// Leaves of 16 tets: on this small mesh, leaves of the default 64 already project to about the
// threshold, so the proxies would stand in for leaves rather than for subtrees.
TEST(LevelOfDetail, PlanarSurfaceDrawnByProxiesWithFarLessTraversal) {
  const BoxMesh box = jittered_box(24);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.x + 0.3 * p.y - 0.2 * p.z; });
  render::UpdatePolicy leaves_of_16;
  leaves_of_16.build.leaf_size = 16;
  const RenderScene scene = load_scene(box.points, box.tets, f, leaves_of_16);
  const auto surfaces = make_surfaces(std::vector<double>{0.1});
  const std::vector<NodePlane> planes = planes_of(scene);
  const render::Camera camera =
      look_at({2.5, 1.5, 3.5}, {0, 0, 0}, 40, scaled_side(256), scaled_side(256));
  render::TraceStats exact_stats, lod_stats;
  render::TraceOptions exact_options;
  exact_options.packet = render::PacketSize::p16x16;
  exact_options.collect_stats = true;
  const render::Framebuffer exact =
      render::trace(scene.volume, scene.bvh, camera, surfaces, exact_options, &exact_stats);
  const render::Framebuffer lod = trace_lod(scene, camera, surfaces, 16.0f, planes, &lod_stats);
  const ImageError e = compare(exact, lod, camera);
  EXPECT_LT(e.hit_miss_fraction, 0.002);
  EXPECT_LT(e.depth_p99_px, 0.05);  // rounding only: the proxies lie in the same plane
  EXPECT_LT(lod_stats.isopolygon_extractions, exact_stats.isopolygon_extractions / 2);
  EXPECT_LT(lod_stats.packet_box_tests, exact_stats.packet_box_tests);
}

TEST(LevelOfDetail, CurvedSurfaceErrorBoundedByTheThresholdAndShrinkingWithIt) {
  const BoxMesh box = jittered_box(32);
  const auto f = sample_field(box.points, [](Vec3d p) { return std::sqrt(dot(p, p)); });
  const RenderScene scene = load_scene(box.points, box.tets, f);
  const auto surfaces = make_surfaces(std::vector<double>{0.7});
  const std::vector<NodePlane> planes = planes_of(scene);
  const render::Camera camera = look_at({0, 0, 4}, {0, 0, 0}, 30, 96, 96);
  const render::Framebuffer exact = trace_image(scene, camera, surfaces);
  std::vector<ImageError> errors;
  for (float node_pixels : {32.0f, 16.0f, 8.0f}) {
    const ImageError e =
        compare(exact, trace_lod(scene, camera, surfaces, node_pixels, planes, nullptr), camera);
    EXPECT_LE(e.depth_median_px, node_pixels) << "node_pixels " << node_pixels;
    EXPECT_LT(e.hit_miss_fraction, 0.1) << "node_pixels " << node_pixels;
    if (!errors.empty()) {
      EXPECT_LT(e.depth_median_px, errors.back().depth_median_px);
    }
    errors.push_back(e);
  }
  // The coarsest threshold did stop at nodes, and the finest misses less of the surface.
  EXPECT_GT(errors.front().depth_median_px, 0);
  EXPECT_LT(errors.back().hit_miss_fraction, errors.front().hit_miss_fraction);
}

TEST(LevelOfDetail, EveryPacketSizeGivesTheSameImage) {
  const GyroidTwist g = gyroid(10);
  const RenderScene scene = load_scene(g.mesh.points, g.mesh.tets, g.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  const std::vector<NodePlane> planes = planes_of(scene);
  const render::Camera camera = benchmark_camera(scaled_side(128));
  const render::Framebuffer reference =
      trace_lod(scene, camera, surfaces, 4.0f, planes, nullptr, render::PacketSize::single);
  for (render::PacketSize packet : render::kPacketSizes) {
    const render::Framebuffer image =
        trace_lod(scene, camera, surfaces, 4.0f, planes, nullptr, packet);
    EXPECT_EQ(image.depth, reference.depth) << render::to_string(packet);
    EXPECT_EQ(image.hit, reference.hit) << render::to_string(packet);
  }
}

}  // namespace
}  // namespace tetray::test
