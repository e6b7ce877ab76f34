// Empty-space skipping and the entry bins of a view against independent answers: which tets are
// busy against the transfer function sampled densely over each tet's range and the surfaces'
// isovalues; images rendered with skipping (jumps included) against the same images walking every
// tet, on a box, a box with holes (re-entries), from an eye inside the mesh and with surfaces of a
// second field; and each pixel's entries through the binned faces against the tree's.
#include "render/walk/empty_space.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/walk/entry_bins.hpp"
#include "render/walk/volume_render.hpp"
#include "walk_meshes.hpp"

namespace tetray::test {
namespace {

const render::Colormap kGray{{0.2f, 0.2f, 0.2f, 1, 1, 1}};

// Clear but for two thin slabs of the field: [-0.9, -0.8] and [0.75, 0.9].
render::TransferFunction slabs() {
  return {&kGray, -1, 1, {{-0.9, 0}, {-0.85, 2}, {-0.8, 0}, {0.75, 0}, {0.8, 3}, {0.9, 0}}, 0.5};
}

// Whether the transfer function is non-zero anywhere in [lo, hi], sampled densely.
bool opacity_somewhere(const render::TransferFunction& tf, double lo, double hi) {
  constexpr int kSamples = 4000;
  for (int k = 0; k <= kSamples; ++k) {
    if (tf.at(lo + (hi - lo) * k / kSamples).extinction > 0) return true;
  }
  return false;
}

TEST(BusyTets, FollowTheTransferFunctionAndTheSurfaces) {
  const BoxMesh mesh = jittered_box(6, 0.2);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, random_field(mesh.point_count(), 4));
  const std::vector<double> g = sample_field(mesh.points, [](Vec3d x) { return x.x + 0.5 * x.z; });
  const std::vector<float> second = per_vertex(scene.volume, g);
  const std::vector<render::IsoSurface> surfaces = {{0.3f, {}, 0.5f}};
  const render::TransferFunction tf = slabs();
  const render::BusyTets busy =
      render::find_busy_tets(scene.volume, scene.bvh, tf, surfaces, second);
  std::size_t busy_count = 0, empty_count = 0;
  for (std::uint32_t t = 0; t < scene.volume.tets.size(); ++t) {
    double f_lo = 1e30, f_hi = -1e30, g_lo = 1e30, g_hi = -1e30;
    for (const std::int32_t v : scene.volume.tets[t].v) {
      f_lo = std::min<double>(f_lo, scene.volume.vertices[v].f);
      f_hi = std::max<double>(f_hi, scene.volume.vertices[v].f);
      g_lo = std::min<double>(g_lo, second[v]);
      g_hi = std::max<double>(g_hi, second[v]);
    }
    const bool wanted = opacity_somewhere(tf, f_lo, f_hi) || (g_lo <= 0.3 && 0.3 <= g_hi);
    EXPECT_EQ(busy.busy(t), wanted) << "tet " << t << " f in [" << f_lo << ", " << f_hi << "]";
    (wanted ? busy_count : empty_count) += 1;
  }
  EXPECT_EQ(busy.busy_count, busy_count);
  // Both kinds are common, so the comparison above tests something.
  EXPECT_GT(busy_count, scene.volume.tets.size() / 10);
  EXPECT_GT(empty_count, scene.volume.tets.size() / 10);
  // A node is busy exactly when a tet below it is.
  for (std::uint32_t i = 0; i < scene.bvh.nodes.size(); ++i) {
    const render::BvhNode& node = scene.bvh.nodes[i];
    if (!node.is_leaf()) {
      EXPECT_EQ(busy.node[i], busy.node[node.first] | busy.node[node.first + 1]);
      continue;
    }
    bool any = false;
    for (std::uint32_t t = node.first; t < node.first + node.count; ++t) any |= busy.busy(t);
    EXPECT_EQ(busy.node[i] != 0, any);
  }
}

struct SkipCase {
  MeshShape shape;
  render::Camera camera;
  bool eye_inside = false;
  bool surfaces = false;
  double most_walked = 0.75;  // tets walked skipping, at most this share of the whole walk's
};

// The field rises along x, so a ray along x crosses long clear stretches between the slabs.
void expect_skipping_changes_nothing(const SkipCase& c) {
  const BoxMesh mesh = make_walk_mesh(c.shape);
  const RenderScene scene =
      load_scene(mesh.points, mesh.tets,
                 sample_field(mesh.points, [](Vec3d x) { return 0.95 * x.x + 0.04 * x.y * x.z; }));
  const render::WalkStructure walk = render::build_walk_structure(scene.volume);
  const std::vector<double> g = sample_field(mesh.points, [](Vec3d x) { return x.y; });
  const std::vector<float> second = per_vertex(scene.volume, g);
  render::VolumeRenderOptions options;
  options.transfer = slabs();
  options.termination = 1;
  if (c.surfaces) {
    options.surfaces = {{0.4f, {0.9f, 0.5f, 0.2f}, 0.5f}};
    options.surface_field = second;
  }
  if (c.eye_inside) {
    options.eye_tet = render::locate_eye(scene.volume, scene.bvh, c.camera);
    ASSERT_NE(options.eye_tet, render::kBoundaryFace);
  }
  render::VolumeRenderStats all_stats, skip_stats;
  render::VolumeFragmentImage all =
      render::render_volume(scene.volume, walk, c.camera, options, &all_stats);
  options.bvh = &scene.bvh;
  render::VolumeFragmentImage skipped =
      render::render_volume(scene.volume, walk, c.camera, options, &skip_stats);
  const render::Framebuffer want = render::resolve(all), got = render::resolve(skipped);
  double seen = 0;
  for (std::size_t k = 0; k < want.rgba.size(); ++k) {
    ASSERT_NEAR(got.rgba[k], want.rgba[k], 1e-6) << "pixel " << k / 4 << " channel " << k % 4;
    seen = std::max<double>(seen, want.rgba[k]);
  }
  for (std::size_t p = 0; p < want.depth.size(); ++p) {
    if (std::isfinite(want.depth[p])) {
      ASSERT_NEAR(got.depth[p], want.depth[p], 1e-5) << p;
    }
  }
  EXPECT_GT(seen, 0.05);  // the slabs show
  // Skipping happened: fewer tets walked, and some rays jumped over empty space.
  EXPECT_LT(static_cast<double>(skip_stats.tets_visited),
            c.most_walked * static_cast<double>(all_stats.tets_visited));
  EXPECT_GT(skip_stats.jumps, 0u);
}

// Sides that are no multiple of the entry bins' tiles: the last row and column of tiles are
// partial.
render::Camera along_x(Vec3d eye, int side) {
  return look_at(eye, {eye.x + 3, eye.y * 0.6, eye.z * 0.6}, 30, side, side - 5);
}

TEST(EmptySpace, SkippingGivesTheImageOfTheWholeWalk) {
  expect_skipping_changes_nothing({{.cells = 20, .jitter = 0.2}, along_x({-3, 0.2, 0.1}, 24)});
}

TEST(EmptySpace, SkippingGivesTheImageOfTheWholeWalkWithHolesAndSurfaces) {
  expect_skipping_changes_nothing(
      {{.cells = 20, .jitter = 0.2, .removed_fraction = 0.05, .seed = 3},
       along_x({-3, -0.1, 0.25}, 24),
       false,
       true});
}

TEST(EmptySpace, SkippingGivesTheImageOfTheWholeWalkFromInside) {
  // The eye where the field is clear: its tet is empty, so the walk leaves it without a visit.
  expect_skipping_changes_nothing(
      {{.cells = 20, .jitter = 0.2}, along_x({-0.5, 0.05, -0.1}, 29), true, true, 0.9});
}

// Every pixel's entries, first and after each exit, through its tile's faces and through the
// tree: the same faces at the same t.
void expect_bins_match_the_tree(const BoxMesh& mesh, const render::Camera& camera,
                                bool plane_cuts_mesh) {
  const RenderScene scene = load_walk_scene(mesh);
  const render::WalkStructure walk = render::build_walk_structure(scene.volume);
  const render::EntryBins bins = render::bin_entry_faces(scene.volume, walk.boundary, camera);
  ASSERT_TRUE(bins.usable());
  // Where the eye's plane cuts the mesh, faces cross it; every ray tests those.
  EXPECT_EQ(plane_cuts_mesh, !bins.everywhere.empty());
  const render::CameraFrame frame = render::make_frame(camera);
  int entries = 0;
  for (int j = 0; j < camera.height; ++j) {
    for (int i = 0; i < camera.width; ++i) {
      const render::RayFrame ray(camera.eye - scene.volume.origin,
                                 render::pixel_direction(frame, camera, i, j));
      const render::EntryCandidates candidates = bins.at(i, j);
      render::EntryCursor cursor;
      double t_from = 0;
      for (int k = 0; k < 64; ++k) {
        const auto tree = render::next_entry(scene.volume, walk.boundary, ray, t_from, cursor);
        const auto binned =
            render::next_entry(scene.volume, walk.boundary, ray, t_from, cursor, {}, &candidates);
        ASSERT_EQ(tree.has_value(), binned.has_value()) << "pixel " << i << ", " << j;
        if (!tree) break;
        ASSERT_EQ(tree->face, binned->face) << "pixel " << i << ", " << j;
        ASSERT_EQ(tree->crossing.t, binned->crossing.t);
        ++entries;
        cursor = {tree->crossing.t, tree->face, true};
        t_from = tree->crossing.t;
      }
    }
  }
  EXPECT_GT(entries, camera.width * camera.height / 4);
}

TEST(EntryBins, GiveTheTreesEntries) {
  const BoxMesh holes = make_walk_mesh({.cells = 7, .removed_fraction = 0.3, .seed = 5});
  expect_bins_match_the_tree(holes, look_at({2.1, 1.7, 3.3}, {0, 0, 0}, 45, 45, 37), false);
  // Eye inside the domain: faces cross the eye's plane and are tested by every ray; those wholly
  // behind it are left out.
  expect_bins_match_the_tree(holes, look_at({0.1, -0.2, 0.3}, {1, 0.3, 0.2}, 80, 43, 38), true);
}

}  // namespace
}  // namespace tetray::test
