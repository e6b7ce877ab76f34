#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>

#include "render/bvh/bounds.hpp"
#include "render/update/step_store.hpp"
#include "render/update/volume_update.hpp"
#include "support/reference_comparison.hpp"

namespace tetray::test {
namespace {

using render::BvhUpdateKind;
using render::Camera;
using render::Framebuffer;
using render::IsoSurface;
using render::PointSource;
using render::ScalarKind;

PointSource points_of(const std::vector<double>& xyz) {
  return {xyz.data(), ScalarKind::f64, nullptr, ScalarKind::f64, xyz.size() / 3};
}

render::FieldSource field_of(const std::vector<double>& f) {
  return {f.data(), ScalarKind::f64, f.size()};
}

const IsoSurface kSurfaces[] = {{0.0f, {0.9f, 0.6f, 0.3f}}, {0.5f, {0.3f, 0.6f, 0.9f}}};

// Hit/miss must agree and depth within 1e-6 relative; returns the number of pixels that don't.
std::size_t count_differences(const Framebuffer& a, const Framebuffer& b) {
  std::size_t bad = 0;
  for (std::size_t p = 0; p < a.pixel_count(); ++p) {
    const bool ha = a.hit[p] != render::kNoHit, hb = b.hit[p] != render::kNoHit;
    if (ha != hb) {
      ++bad;
    } else if (ha && std::abs(a.depth[p] - b.depth[p]) > 1e-6 * std::abs(b.depth[p])) {
      ++bad;
    }
  }
  return bad;
}

// The gyroid-twist steps of docs/architecture.md §6, deformed from the undeformed jittered box.
struct Series {
  BoxMesh box;
  std::vector<double> points, field;
  explicit Series(int n) : box(jittered_box(n)) {}
  void at(double t) { deform_gyroid_twist(box, t, points, field); }
};

// After a build each leaf lists the distinct vertices of its tets, once each, and inner nodes
// list none; a refit from the lists gives every leaf the bound of its tets.
TEST(Refit, LeafVertexListsHoldEachLeafsDistinctVertices) {
  Series series(10);
  series.at(0.2);
  const RenderScene scene = load_scene(series.points, series.box.tets, series.field);
  const render::Bvh& bvh = scene.bvh;
  ASSERT_EQ(bvh.leaf_vertex_begin.size(), bvh.nodes.size() + 1);
  ASSERT_EQ(bvh.leaf_vertex_begin.back(), bvh.leaf_vertices.size());
  std::size_t leaves = 0;
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const render::BvhNode& node = bvh.nodes[i];
    std::vector<std::uint32_t> listed(bvh.leaf_vertices.begin() + bvh.leaf_vertex_begin[i],
                                      bvh.leaf_vertices.begin() + bvh.leaf_vertex_begin[i + 1]);
    if (!node.is_leaf()) {
      EXPECT_TRUE(listed.empty()) << "inner node " << i;
      continue;
    }
    ++leaves;
    std::vector<std::uint32_t> used;
    render::Bounds4 walked = render::tet_bounds(scene.volume, scene.volume.tets[node.first]);
    for (std::uint32_t t = node.first; t < node.first + node.count; ++t) {
      for (std::int32_t v : scene.volume.tets[t].v) used.push_back(static_cast<std::uint32_t>(v));
      const render::Bounds4 b = render::tet_bounds(scene.volume, scene.volume.tets[t]);
      for (int a = 0; a < 4; ++a) {
        walked.lo[a] = std::min(walked.lo[a], b.lo[a]);
        walked.hi[a] = std::max(walked.hi[a], b.hi[a]);
      }
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, used) << "leaf " << i;
    for (int a = 0; a < 4; ++a) {
      EXPECT_EQ(node.bounds.lo[a], walked.lo[a]) << "leaf " << i << " axis " << a;
      EXPECT_EQ(node.bounds.hi[a], walked.hi[a]) << "leaf " << i << " axis " << a;
    }
  }
  EXPECT_GT(leaves, 1u);
}

// A new step is read in the caller's point order and scattered to the vertices the points
// became: with the points shuffled and some left unused, every used point's new position and
// value land on its vertex, and unused points on none.
TEST(Refit, NewStepLandsOnEachPointsVertex) {
  Series series(6);
  series.at(0.0);
  const std::size_t used_points = series.points.size() / 3;
  // Shuffled order, plus unused points in between.
  std::vector<std::int64_t> slot(used_points);
  std::iota(slot.begin(), slot.end(), 0);
  std::mt19937 rng(7);
  std::shuffle(slot.begin(), slot.end(), rng);
  for (auto& s : slot) s = 2 * s + 1;  // even slots stay unused
  const std::size_t point_count = 2 * used_points + 1;
  auto placed = [&](const std::vector<double>& xyz, const std::vector<double>& f) {
    std::pair<std::vector<double>, std::vector<double>> out{
        std::vector<double>(3 * point_count, 0.5), std::vector<double>(point_count, -7.0)};
    for (std::size_t p = 0; p < used_points; ++p) {
      for (int a = 0; a < 3; ++a) out.first[3 * slot[p] + a] = xyz[3 * p + a];
      out.second[slot[p]] = f[p];
    }
    return out;
  };
  std::vector<std::int64_t> tets = series.box.tets;
  for (auto& v : tets) v = slot[v];
  const auto [points0, field0] = placed(series.points, series.field);
  RenderScene scene = load_scene(points0, tets, field0);
  const auto& map = scene.volume.point_vertex;
  ASSERT_EQ(map.size(), point_count);
  series.at(0.3);
  const auto [points1, field1] = placed(series.points, series.field);
  render::update_volume(scene.volume, scene.bvh, points_of(points1), field_of(field1), {true, true},
                        {});
  std::size_t mapped = 0;
  for (std::size_t p = 0; p < point_count; ++p) {
    if (p % 2 == 0) {
      EXPECT_EQ(map[p], render::kNoVertex) << "unused point " << p;
      continue;
    }
    ASSERT_LT(map[p], scene.volume.vertices.size()) << "point " << p;
    ++mapped;
    const render::Vertex& v = scene.volume.vertices[map[p]];
    const double local[3] = {v.x, v.y, v.z};
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(scene.volume.origin[a] + local[a], points1[3 * p + a], 1e-6) << "point " << p;
    EXPECT_NEAR(v.f, field1[p], 1e-6) << "point " << p;
  }
  EXPECT_EQ(mapped, scene.volume.vertices.size());
  // A step whose arrays end early (here before the last used point) is read only as far as
  // it goes: the cut-off point's vertex keeps its value, the others take the new one.
  const std::size_t cut = point_count - 2;  // the last used point
  ASSERT_NE(map[cut], render::kNoVertex);
  series.at(0.4);
  const auto [points2, field2] = placed(series.points, series.field);
  const std::vector<double> shorter_points(points2.begin(), points2.begin() + 3 * cut);
  const std::vector<double> shorter_field(field2.begin(), field2.begin() + cut);
  render::update_volume(scene.volume, scene.bvh, points_of(shorter_points), field_of(shorter_field),
                        {true, true}, {});
  EXPECT_NEAR(scene.volume.vertices[map[cut]].f, field1[cut], 1e-6);
  EXPECT_NEAR(scene.volume.vertices[map[1]].f, field2[1], 1e-6);
}

TEST(Refit, RefitMatchesRebuildOverGyroidTwistSteps) {
  Series series(12);
  series.at(0.0);
  render::TetVolume volume;
  render::Bvh bvh;
  render::UpdatePolicy never_rebuild;
  never_rebuild.rebuild_ratio = 1e30;
  const auto& tets = series.box.tets;
  render::load_volume(volume, bvh, tets, {}, {}, points_of(series.points), field_of(series.field),
                      never_rebuild);
  const Camera camera = benchmark_camera(scaled_side(200));
  for (double t : {0.1, 0.2, 0.3, 0.4}) {
    series.at(t);
    const auto update = render::update_volume(volume, bvh, points_of(series.points),
                                              field_of(series.field), {true, true}, never_rebuild);
    EXPECT_EQ(update.kind, BvhUpdateKind::refit);
    EXPECT_LT(update.quality_ratio, 1.2) << "t = " << t;
    const Framebuffer refit = render::trace(volume, bvh, camera, kSurfaces, {});
    const RenderScene rebuilt = load_scene(series.points, tets, series.field);
    const Framebuffer fresh = render::trace(rebuilt.volume, rebuilt.bvh, camera, kSurfaces, {});
    EXPECT_EQ(count_differences(refit, fresh), 0u) << "t = " << t;
    std::size_t hits = 0;
    for (auto h : fresh.hit) hits += h != render::kNoHit;
    EXPECT_GT(hits, fresh.pixel_count() / 10) << "the scene must show a surface";
  }
}

TEST(Refit, FieldOnlyUpdateMatchesRebuild) {
  Series series(10);
  series.at(0.0);
  const auto& tets = series.box.tets;
  RenderScene scene = load_scene(series.points, tets, series.field);
  const std::vector<double> old_points = series.points;
  const Camera camera = benchmark_camera(scaled_side(160));
  // New values on the same geometry: the field of a later time, sampled at the old points.
  std::vector<double> later(series.field.size());
  for (std::size_t p = 0; p < later.size(); ++p)
    later[p] = std::sin(4 * old_points[3 * p] + 1.3) * std::cos(4 * old_points[3 * p + 1]) + 0.2;
  const auto before = scene.bvh.nodes;
  const auto update = render::update_volume(scene.volume, scene.bvh, points_of(old_points),
                                            field_of(later), {false, true}, {});
  EXPECT_EQ(update.kind, BvhUpdateKind::field_only);
  for (std::size_t i = 0; i < before.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(before[i].bounds.lo[a], scene.bvh.nodes[i].bounds.lo[a]) << "geometry touched";
      ASSERT_EQ(before[i].bounds.hi[a], scene.bvh.nodes[i].bounds.hi[a]) << "geometry touched";
    }
  const RenderScene rebuilt = load_scene(old_points, tets, later);
  const Framebuffer a = render::trace(scene.volume, scene.bvh, camera, kSurfaces, {});
  const Framebuffer b = render::trace(rebuilt.volume, rebuilt.bvh, camera, kSurfaces, {});
  EXPECT_EQ(count_differences(a, b), 0u);
}

TEST(Refit, NothingChangedSkipsTheBvh) {
  Series series(6);
  series.at(0.0);
  RenderScene scene = load_scene(series.points, series.box.tets, series.field);
  const auto before = scene.bvh.nodes;
  const auto update = render::update_volume(scene.volume, scene.bvh, points_of(series.points),
                                            field_of(series.field), {false, false}, {});
  EXPECT_EQ(update.kind, BvhUpdateKind::none);
  EXPECT_EQ(update.ingest_refit_ms, 0.0);
  EXPECT_EQ(
      std::memcmp(before.data(), scene.bvh.nodes.data(), before.size() * sizeof(render::BvhNode)),
      0);
}

// Twists the box by several turns, folds it over itself (inverting tets) and moves it far
// across the domain: the refit tree degrades, the policy rebuilds, and the image still matches
// the brute-force reference.
TEST(Refit, ExtremeDeformationRebuildsAndStaysExact) {
  const BoxMesh box = jittered_box(7);
  std::vector<double> points = box.points, field(box.point_count());
  for (std::size_t p = 0; p < field.size(); ++p) {
    const double x = points[3 * p], y = points[3 * p + 1], z = points[3 * p + 2];
    field[p] = x * x + 0.7 * y * y + 0.4 * z * z;
  }
  RenderScene scene = load_scene(points, box.tets, field);
  for (std::size_t p = 0; p < field.size(); ++p) {
    const double x = points[3 * p], y = points[3 * p + 1], z = points[3 * p + 2];
    const double turn = 6.0 * z, c = std::cos(turn), s = std::sin(turn);
    const double folded = x > 0 ? -0.3 * x : x;  // folds the half x > 0 back over the rest
    points[3 * p] = c * folded - s * y;
    points[3 * p + 1] = s * folded + c * y + 8.0;
  }
  const auto update = render::update_volume(scene.volume, scene.bvh, points_of(points),
                                            field_of(field), {true, true}, {});
  EXPECT_GT(update.quality_ratio, 1.5);
  EXPECT_EQ(update.kind, BvhUpdateKind::rebuild);
  EXPECT_EQ(scene.bvh.sah_cost_now, scene.bvh.sah_cost_at_build) << "a fresh tree";
  Camera camera;
  camera.eye = {6.0, 12.0, 9.0};
  camera.look_at = {0.0, 8.0, 0.0};
  camera.width = camera.height = scaled_side(96);
  const IsoSurface surfaces[] = {{0.6f, {1, 1, 1}}};
  const AgreementCounts counts = expect_agreement(scene, camera, surfaces, "folded");
  EXPECT_EQ(counts.failures(), 0u) << counts.summary();
  EXPECT_GT(counts.reference_hits, counts.pixels / 50) << "the surface must be in view";
}

// The node bounds after a refit, and the tree of a build, are bitwise the same for any
// number of threads.
TEST(Refit, ThreadCountDoesNotChangeBuildOrRefit) {
  Series series(14);
  series.at(0.0);
  const auto& tets = series.box.tets;
  std::vector<render::LargeArray<render::BvhNode>> results;
  std::vector<render::LargeArray<std::uint32_t>> leaf_lists;
  for (int threads : {1, 2, 8}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      RenderScene scene = load_scene(series.points, tets, series.field);
      Series next(14);
      next.at(0.3);
      render::update_volume(scene.volume, scene.bvh, points_of(next.points), field_of(next.field),
                            {true, true}, {});
      results.push_back(scene.bvh.nodes);
      leaf_lists.push_back(scene.bvh.leaf_vertices);
    });
  }
  for (std::size_t k = 1; k < results.size(); ++k) {
    ASSERT_EQ(results[k].size(), results[0].size());
    EXPECT_EQ(std::memcmp(results[k].data(), results[0].data(),
                          results[0].size() * sizeof(render::BvhNode)),
              0)
        << "thread count changed the BVH";
    EXPECT_EQ(leaf_lists[k], leaf_lists[0]) << "thread count changed the leaf vertex lists";
  }
}

// Schema I: steps stored while the series runs render afterwards exactly as they did live, and
// the store refuses a step past its memory budget. A stored step leaves out what only a refit
// reads (the leaf vertex lists, the point -> vertex map).
TEST(StepStore, ReplaysStoredStepsAndKeepsToItsBudget) {
  Series series(8);
  series.at(0.0);
  RenderScene scene = load_scene(series.points, series.box.tets, series.field);
  const Camera camera = benchmark_camera(scaled_side(96));
  render::StepStore probe(std::numeric_limits<std::size_t>::max());
  ASSERT_TRUE(probe.store(0, scene.volume, scene.bvh));
  const std::size_t step_bytes = probe.bytes();
  const std::size_t refit_only_bytes =
      (scene.volume.point_vertex.size() + scene.bvh.leaf_vertex_begin.size() +
       scene.bvh.leaf_vertices.size()) *
      sizeof(std::uint32_t);
  EXPECT_LE(step_bytes, scene.volume.bytes() + scene.bvh.bytes() - refit_only_bytes);
  render::StepStore store(3 * step_bytes);
  std::vector<Framebuffer> live;
  for (int step = 0; step < 4; ++step) {
    series.at(0.1 * step);
    render::update_volume(scene.volume, scene.bvh, points_of(series.points), field_of(series.field),
                          {true, true}, {});
    live.push_back(render::trace(scene.volume, scene.bvh, camera, kSurfaces, {}));
    EXPECT_EQ(store.store(step, scene.volume, scene.bvh), step < 3) << "step " << step;
  }
  EXPECT_EQ(store.steps(), 3u);
  EXPECT_EQ(store.bytes(), 3 * step_bytes);
  EXPECT_EQ(store.find(3), nullptr);
  for (int step = 0; step < 3; ++step) {
    const auto* entry = store.find(step);
    ASSERT_NE(entry, nullptr);
    const Framebuffer replay = render::trace(entry->volume, entry->bvh, camera, kSurfaces, {});
    EXPECT_EQ(image_difference(replay, live[step]), "") << "step " << step;
  }
  EXPECT_NE(image_difference(live[0], live[2]), "") << "the steps must differ";
}

}  // namespace
}  // namespace tetray::test
