// The walk against the brute force: on random rays through jittered boxes, slivers, non-convex
// boxes with holes and a box a million units from the origin, the walk visits exactly the tets
// that testing every tet finds, in order, with the same stretches and field values; rays through
// vertices and edges (exactly, on an unjittered grid) neither lose nor repeat a stretch. Where a
// ray crosses a face, the point and the fields are the same bits whichever corner the face is
// held from, so an isosurface lying in faces is met the same way on every ray and rank count.
#include "render/walk/tet_walk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "render/walk/surface_crossing.hpp"
#include "walk_meshes.hpp"

namespace tetray::test {
namespace {

struct WalkedMesh {
  RenderScene scene;
  render::FaceAdjacency<render::Tet20> tet20;
  render::FaceAdjacency<render::Tet16> tet16;
  render::BoundaryFaces boundary;

  explicit WalkedMesh(const BoxMesh& mesh)
      : scene(load_walk_scene(mesh)),
        tet20(render::build_face_adjacency<render::Tet20>(scene.volume)),
        tet16(render::build_face_adjacency<render::Tet16>(scene.volume)),
        boundary(render::build_boundary_faces(scene.volume, tet20.boundary)) {}
};

template <typename Layout>
std::vector<render::WalkSegment> walk(const WalkedMesh& mesh,
                                      const render::FaceAdjacency<Layout>& adjacency,
                                      const render::RayFrame& frame,
                                      render::WalkCounters& counters) {
  return render::walk_segments(
      render::WalkMesh<Layout>{mesh.scene.volume, adjacency, mesh.boundary}, frame,
      std::numeric_limits<double>::infinity(), std::numeric_limits<std::size_t>::max(), counters);
}

// The walk's stretches longer than `min_length` are the brute force's, tet for tet in order.
void expect_walk_matches_brute_force(const WalkedMesh& mesh, Vec3d origin, Vec3d direction,
                                     double scale) {
  const double min_length = 1e-7 * scale;
  const render::RayFrame frame(origin, direction);
  const std::vector<CrossedTet> expected =
      crossed_by_brute_force(mesh.scene.volume, origin, direction, min_length);
  render::WalkCounters counters;
  const std::vector<render::WalkSegment> walked20 = walk(mesh, mesh.tet20, frame, counters);
  const std::vector<render::WalkSegment> walked16 = walk(mesh, mesh.tet16, frame, counters);
  ASSERT_EQ(counters.lost_rays, 0u);
  ASSERT_EQ(walked20.size(), walked16.size());
  std::vector<render::WalkSegment> walked;
  for (std::size_t s = 0; s < walked20.size(); ++s) {
    ASSERT_EQ(walked20[s].tet, walked16[s].tet) << "Tet20 and Tet16 walk the same tets";
    if (walked20[s].t_out - walked20[s].t_in > min_length) walked.push_back(walked20[s]);
  }
  ASSERT_EQ(walked.size(), expected.size());
  for (std::size_t s = 0; s < walked.size(); ++s) {
    ASSERT_EQ(walked[s].tet, expected[s].tet) << "stretch " << s;
    EXPECT_NEAR(walked[s].t_in, expected[s].t_in, 1e-6 * scale);
    EXPECT_NEAR(walked[s].t_out, expected[s].t_out, 1e-6 * scale);
    EXPECT_NEAR(walked[s].f_in, expected[s].f_in, 1e-5 + 1e-12 * std::abs(expected[s].f_in));
    EXPECT_NEAR(walked[s].f_out, expected[s].f_out, 1e-5 + 1e-12 * std::abs(expected[s].f_out));
  }
}

// Rays from a sphere of radius 3 around the local origin to random points of [-1.2, 1.2]^3
// (scaled along z like the mesh), and rays through vertices and edge midpoints of the mesh.
void expect_random_rays_match(const MeshShape& shape, int ray_count) {
  const WalkedMesh mesh(make_walk_mesh(shape));
  const render::TetVolume& volume = mesh.scene.volume;
  std::mt19937 rng(shape.seed + 17);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> box(-1.2, 1.2);
  std::uniform_int_distribution<std::size_t> pick_tet(0, volume.tets.size() - 1);
  std::uniform_int_distribution<int> pick_corner(0, 3);
  for (int r = 0; r < ray_count; ++r) {
    const Vec3d origin = (3.0 / 1.0) * normalize(Vec3d{gauss(rng), gauss(rng), gauss(rng)});
    Vec3d target{box(rng), box(rng), shape.squash_z * box(rng)};
    const render::Tet& tet = volume.tets[pick_tet(rng)];
    const Vec3d a = render::vertex_position(volume, tet.v[pick_corner(rng)]);
    const Vec3d b = render::vertex_position(volume, tet.v[pick_corner(rng)]);
    if (r % 3 == 1) target = a;              // through a vertex
    if (r % 3 == 2) target = 0.5 * (a + b);  // through an edge's midpoint (or a vertex)
    SCOPED_TRACE(testing::Message() << "ray " << r);
    expect_walk_matches_brute_force(mesh, origin, target - origin, 1.0);
    if (testing::Test::HasFatalFailure()) return;
  }
}

constexpr int kRays = 240 / kSanitizerSlowdown;

TEST(TetWalk, VisitsTheTetsOfTheBruteForceOnAJitteredBox) { expect_random_rays_match({}, kRays); }

TEST(TetWalk, VisitsTheTetsOfTheBruteForceOnSlivers) {
  MeshShape shape;
  shape.squash_z = 1e-3;
  shape.jitter = 0.2;
  expect_random_rays_match(shape, kRays);
}

TEST(TetWalk, ReentersANonConvexDomain) {
  MeshShape shape;
  shape.removed_fraction = 0.35;
  shape.seed = 5;
  expect_random_rays_match(shape, kRays);
}

TEST(TetWalk, VisitsTheTetsOfTheBruteForceFarFromTheOrigin) {
  MeshShape shape;
  shape.offset = {1e6, 1e6, 1e6};
  shape.removed_fraction = 0.2;
  expect_random_rays_match(shape, kRays);
}

// Rays along z through the vertices, edges and faces of an unjittered grid meet the mesh's
// vertices and edges exactly (the projected points are exactly zero), where the exit-face test
// ties (the lines are inside the box: one on its surface may pass either side). The walk then
// decides as for a ray moved by an infinitesimal: its stretches are contiguous, cover the box from
// z = -1 to z = 1 once, and are each a tet the ray touches.
TEST(TetWalk, RaysThroughVerticesAndEdgesCoverTheBoxOnce) {
  MeshShape shape;
  shape.cells = 4;
  shape.jitter = 0;
  const WalkedMesh mesh(make_walk_mesh(shape));
  const Vec3d shift = -1.0 * mesh.scene.volume.origin;  // world (x, y) to local
  int rays = 0;
  for (int i = 1; i < 8; ++i) {
    for (int j = 1; j < 8; ++j) {
      for (const Vec3d direction : {Vec3d{0, 0, 1}, Vec3d{0, 0, -1}}) {
        const Vec3d origin = Vec3d{-1 + 0.25 * i, -1 + 0.25 * j, -4 * direction.z} + shift;
        const render::RayFrame frame(origin, direction);
        render::WalkCounters counters;
        const std::vector<render::WalkSegment> segments = walk(mesh, mesh.tet20, frame, counters);
        EXPECT_EQ(counters.lost_rays, 0u);
        ASSERT_FALSE(segments.empty());
        const std::vector<CrossedTet> touched =
            crossed_by_brute_force(mesh.scene.volume, origin, direction, -1.0);
        std::set<std::uint32_t> touched_tets;
        for (const CrossedTet& c : touched) touched_tets.insert(c.tet);
        std::set<std::uint32_t> visited;
        for (std::size_t s = 0; s < segments.size(); ++s) {
          EXPECT_TRUE(touched_tets.count(segments[s].tet)) << "a tet the ray does not touch";
          EXPECT_TRUE(visited.insert(segments[s].tet).second) << "a tet visited twice";
          if (s > 0) {
            EXPECT_EQ(segments[s].t_in, segments[s - 1].t_out);
          }
        }
        EXPECT_NEAR(segments.front().t_in, 3.0, 1e-6);
        EXPECT_NEAR(segments.back().t_out, 5.0, 1e-6);
        ++rays;
      }
    }
  }
  EXPECT_EQ(rays, 98);
}

TEST(FaceCrossing, TheSameBitsFromEveryCornerOrder) {
  const BoxMesh box = jittered_box(4, 0.2);
  const RenderScene scene = load_scene(box.points, box.tets, random_field(box.point_count(), 2));
  const render::TetVolume& volume = scene.volume;
  const std::vector<float> second = per_vertex(volume, random_field(box.point_count(), 8));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.05, 0.95);
  int compared = 0;
  for (std::uint32_t t = 0; t < volume.tets.size(); t += 3) {
    const render::Tet& tet = volume.tets[t];
    std::uint32_t v[3];
    for (int c = 0; c < 3; ++c) v[c] = static_cast<std::uint32_t>(tet.v[c]);
    // A ray from outside through a point inside the face.
    double a = unit(rng), b = unit(rng) * (1 - a);
    const Vec3d x0 = render::vertex_position(volume, v[0]),
                x1 = render::vertex_position(volume, v[1]),
                x2 = render::vertex_position(volume, v[2]);
    const Vec3d target = x0 + a * (x1 - x0) + b * (x2 - x0);
    const render::RayFrame frame(target + Vec3d{3.1, -1.7, 2.3}, Vec3d{-3.1, 1.7, -2.3});
    render::ProjectedFace face{};
    for (int c = 0; c < 3; ++c) {
      face.vertex[c] = v[c];
      face.point[c] = frame.project(render::vertex_position(volume, v[c]));
    }
    if (render::ray_side(face.point[0], v[0], face.point[1], v[1]) < 0) {
      std::swap(face.vertex[1], face.vertex[2]);
      std::swap(face.point[1], face.point[2]);
    }
    const render::FaceCrossing first = render::cross_face(volume, frame, face, second);
    for (int turn = 1; turn < 3; ++turn) {
      render::ProjectedFace turned{};
      for (int c = 0; c < 3; ++c) {
        turned.vertex[c] = face.vertex[(c + turn) % 3];
        turned.point[c] = face.point[(c + turn) % 3];
      }
      const render::FaceCrossing other = render::cross_face(volume, frame, turned, second);
      ASSERT_EQ(other.t, first.t) << "tet " << t;
      ASSERT_EQ(other.f, first.f) << "tet " << t;
      ASSERT_EQ(other.g, first.g) << "tet " << t;
    }
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

// g = 0.5 - |z| peaks at 0.5 on the grid's plane z = 0, so the isosurface 0.5 lies in faces:
// every ray through the plane meets it the same number of times.
TEST(FaceCrossing, ASurfaceLyingInFacesIsMetAlikeByEveryRay) {
  const BoxMesh grid = jittered_box(6, 0.0);
  const RenderScene scene = load_walk_scene(grid);
  const std::vector<float> ridge = per_vertex(
      scene.volume, sample_field(grid.points, [](Vec3d x) { return 0.5 - std::abs(x.z); }));
  const render::FaceAdjacency<render::Tet20> adjacency =
      render::build_face_adjacency<render::Tet20>(scene.volume);
  const render::BoundaryFaces boundary =
      render::build_boundary_faces(scene.volume, adjacency.boundary);
  const std::vector<render::IsoSurface> surfaces = {{0.5f, {}, 0.5f}};
  std::set<int> met;
  int rays = 0;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> across(-0.9, 0.9);
  for (int k = 0; k < 400; ++k) {
    const Vec3d at{across(rng), across(rng), 0.0};
    const Vec3d origin = at + Vec3d{0.37, -0.21, 2.0} - scene.volume.origin;
    const render::RayFrame frame(origin, Vec3d{-0.37, 0.21, -2.0});
    render::WalkCounters counters;
    int crossings = 0;
    for (const render::WalkSegment& s : render::walk_segments(
             render::WalkMesh<render::Tet20>{scene.volume, adjacency, boundary, ridge}, frame,
             std::numeric_limits<double>::infinity(), std::numeric_limits<std::size_t>::max(),
             counters)) {
      render::SurfaceCrossing found[render::kMaxIsovalues];
      crossings += render::surface_crossings(surfaces, s.g_in, s.g_out, found);
    }
    met.insert(crossings);
    ++rays;
  }
  EXPECT_EQ(rays, 400);
  // The ridge is met where g rises to 0.5 and again where it falls from it (surface_crossing.hpp:
  // below to at-or-above, or back), at the same depth: twice on every ray.
  EXPECT_EQ(met.size(), 1u) << "rays met the surface " << *met.begin() << " to " << *met.rbegin()
                            << " times";
  EXPECT_EQ(*met.begin(), 2);
}

TEST(TetWalk, EarlyStopEndsTheWalk) {
  const WalkedMesh mesh(make_walk_mesh({}));
  const render::RayFrame frame({0.1, 0.2, -3}, {0, 0.05, 1});
  render::WalkCounters counters;
  const std::vector<render::WalkSegment> segments = render::walk_segments(
      render::WalkMesh<render::Tet20>{mesh.scene.volume, mesh.tet20, mesh.boundary}, frame,
      std::numeric_limits<double>::infinity(), 3, counters);
  EXPECT_EQ(segments.size(), 3u);
  EXPECT_EQ(counters.tets_visited, 3u);
}

}  // namespace
}  // namespace tetray::test
