// The mesh split among the ranks, traced per rank with the global camera and composited, gives
// the image of one rank tracing the whole mesh: identical hit/miss, depth within 1e-6
// relative, and hit keys that differ only where two tets tie in depth, on under 0.01% of the
// pixels. Partitions: slabs by tet centroid x, a random one, and slabs that leave the root
// empty. Each rank ingests only its own tets and points, as the adaptor does, with the origin
// shared through the global bounds.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "render/composite/composite.hpp"
#include "render/parallel/global_reduce.hpp"
#include "render/parallel/scene_shadows.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "scenes/box_mesh.hpp"
#include "support/mpi_world.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::render {
namespace {

using testing::World;
using testing::world;

constexpr int kImageSide = 256;

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(12, 0.2);
  return gyroid;
}

// One rank's share of the mesh: its tets renumbered onto its own points, with global tet ids.
struct MeshPiece {
  std::vector<double> points, field;
  std::vector<std::int64_t> tets;
  std::vector<std::uint32_t> ids;
};

using Partition = std::function<int(std::size_t tet)>;  // the rank that owns a tet

MeshPiece piece_of(const GyroidTwist& gyroid, const Partition& owner, int rank) {
  MeshPiece piece;
  std::unordered_map<std::int64_t, std::int64_t> local_of;
  for (std::size_t t = 0; t < gyroid.mesh.tet_count(); ++t) {
    if (owner(t) != rank) continue;
    piece.ids.push_back(static_cast<std::uint32_t>(t));
    for (int k = 0; k < 4; ++k) {
      const std::int64_t global = gyroid.mesh.tets[4 * t + k];
      auto [at, inserted] = local_of.try_emplace(global, std::ssize(piece.field));
      if (inserted) {
        for (int a = 0; a < 3; ++a) piece.points.push_back(gyroid.mesh.points[3 * global + a]);
        piece.field.push_back(gyroid.field[global]);
      }
      piece.tets.push_back(at->second);
    }
  }
  return piece;
}

double centroid_x(const GyroidTwist& gyroid, std::size_t t) {
  double x = 0;
  for (int k = 0; k < 4; ++k) x += gyroid.mesh.points[3 * gyroid.mesh.tets[4 * t + k]];
  return x / 4;
}

// Slabs of equal width in x among ranks [first, first + count).
Partition slabs(int first, int count) {
  return [first, count](std::size_t t) {
    const double u = (centroid_x(scene(), t) + 1) / 2;
    return first + std::clamp(static_cast<int>(u * count), 0, count - 1);
  };
}

Partition random_partition(int ranks) {
  auto owners = std::make_shared<std::vector<int>>(scene().mesh.tet_count());
  std::mt19937 rng(2024);
  for (int& owner : *owners) owner = std::uniform_int_distribution<int>(0, ranks - 1)(rng);
  return [owners](std::size_t t) { return (*owners)[t]; };
}

// Loads a piece of the mesh (its field as the volume's), vertices relative to `origin`.
void load_piece(const MeshPiece& piece, Vec3d origin, TetVolume& volume, Bvh& bvh) {
  const PointSource points{piece.points.data(), ScalarKind::f64, nullptr, ScalarKind::f64,
                           piece.field.size()};
  const FieldSource field{piece.field.data(), ScalarKind::f64, piece.field.size()};
  load_volume(volume, bvh, piece.tets, {}, piece.ids, points, field, {}, &origin);
}

// Traces a piece of the mesh with the global camera at isovalue 0, vertices relative to
// `origin`.
Framebuffer trace_piece(const MeshPiece& piece, Vec3d origin) {
  TetVolume volume;
  Bvh bvh;
  load_piece(piece, origin, volume, bvh);
  const IsoSurface surfaces[] = {IsoSurface{0.0f, {}}};
  return trace(volume, bvh, test::benchmark_camera(kImageSide), surfaces, {});
}

struct Comparison {
  std::size_t hits = 0;
  std::size_t hit_miss_differences = 0;
  std::size_t depth_differences = 0;  // beyond 1e-6 relative
  std::size_t key_differences = 0;    // same depth, another tet: the tie rule
};

Comparison compare(const Framebuffer& split, const Framebuffer& whole) {
  Comparison c;
  for (std::size_t p = 0; p < whole.pixel_count(); ++p) {
    const bool hit_whole = whole.hit[p] != kNoHit, hit_split = split.hit[p] != kNoHit;
    c.hits += hit_whole;
    if (hit_whole != hit_split) {
      ++c.hit_miss_differences;
    } else if (hit_whole) {
      const double d = whole.depth[p];
      c.depth_differences += std::abs(split.depth[p] - d) > 1e-6 * std::abs(d);
      c.key_differences += split.hit[p] != whole.hit[p];
    }
  }
  return c;
}

// The whole mesh, as one rank holds it.
MeshPiece whole_mesh() {
  return piece_of(
      scene(), [](std::size_t) { return 0; }, 0);
}

// The origin every rank shares: the centre of the pieces' global bounds (collective).
Vec3d shared_origin(const MeshPiece& piece) {
  BoundingBox box = local_bounds<double>(piece.points);
  EXPECT_EQ(global_bounds_and_ranges(box, {}, MPI_COMM_WORLD), MPI_SUCCESS);
  return 0.5 * (box.lo() + box.hi());
}

// Splits the mesh by `owner`, composites on rank 0 and checks against the whole mesh there.
void check_split(const Partition& owner, const std::string& what) {
  const World w = world();
  const MeshPiece piece = piece_of(scene(), owner, w.rank);
  const Vec3d origin = shared_origin(piece);
  Framebuffer image = trace_piece(piece, origin);
  CompositeStats stats;
  ASSERT_EQ(composite(image, MPI_COMM_WORLD, {}, &stats), MPI_SUCCESS) << what;
  if (w.rank != 0) return;
  const Framebuffer whole = trace_piece(whole_mesh(), origin);
  const Comparison c = compare(image, whole);
  EXPECT_GT(c.hits, whole.pixel_count() / 10) << what << ": the view must show the surface";
  EXPECT_EQ(c.hit_miss_differences, 0u) << what;
  EXPECT_EQ(c.depth_differences, 0u) << what;
  EXPECT_LT(static_cast<double>(c.key_differences), 1e-4 * static_cast<double>(whole.pixel_count()))
      << what;
}

TEST(SplitMesh, SlabsByCentroidMatchTheWholeMesh) { check_split(slabs(0, world().size), "slabs"); }

TEST(SplitMesh, RandomTetPartitionMatchesTheWholeMesh) {
  check_split(random_partition(world().size), "random partition");
}

TEST(SplitMesh, EmptyRootMatchesTheWholeMesh) {
  const int size = world().size;
  check_split(size == 1 ? slabs(0, 1) : slabs(1, size - 1), "slabs leaving rank 0 empty");
}

}  // namespace
}  // namespace tetray::render

namespace tetray::render {
namespace {

// Shadows and clipping across ranks (render/parallel/shadow_visibility.hpp): each rank traces
// its piece with a shadowing point and directional light inside a clip region, the image and the
// lights' terms are composited, every rank traces the shadow rays of the composited hit points
// against its own tets, the occlusion bits are ORed onto the root, which shades. The result must
// be the image of one rank doing the same with the whole mesh.
TraceOptions lit_and_clipped() {
  TraceOptions options;
  options.clip.has_box = true;
  options.clip.box_lo = {-1.5, -1.5, -1.5};
  options.clip.box_hi = {0.3, 1.5, 1.5};
  options.clip.planes[0] = {{0, 0.5, 0}, {0.2, 1, 0.1}};
  options.clip.plane_count = 1;
  options.lights.count = 3;
  options.lights.light[0] = {LightKind::headlight, {}, false};
  options.lights.light[1] = {LightKind::point, {2.0, 3.0, 1.5}, true};
  options.lights.light[2] = {LightKind::directional, {-1.0, -0.4, -2.0}, true};
  return options;
}

struct ShadowedImage {
  Framebuffer image;
  std::vector<std::uint8_t> occluded;  // on the root
};

ShadowedImage shadowed_piece(const MeshPiece& piece, Vec3d origin, MPI_Comm comm) {
  TetVolume volume;
  Bvh bvh;
  load_piece(piece, origin, volume, bvh);
  const IsoSurface surfaces[] = {IsoSurface{0.0f, {0.9f, 0.6f, 0.3f}}, IsoSurface{0.5f, {}}};
  const Camera camera = test::benchmark_camera(kImageSide / 2);
  const TraceOptions options = lit_and_clipped();
  ShadowedImage out;
  std::vector<Framebuffer> terms;
  trace_into(out.image, volume, bvh, camera, surfaces, options, nullptr, &terms);
  EXPECT_EQ(terms.size(), 2u);
  EXPECT_EQ(composite(out.image, comm, {}), MPI_SUCCESS);
  const ShadowScene scene{volume, bvh, camera, surfaces, options};
  const ProtocolStatus shadowed =
      shadow_across_ranks(out.image, terms, scene, 0, comm, &out.occluded);
  EXPECT_TRUE(shadowed.ok()) << shadowed.message;
  return out;
}

void check_shadowed_split(const Partition& owner, const std::string& what) {
  const World w = world();
  const MeshPiece piece = piece_of(scene(), owner, w.rank);
  const Vec3d origin = shared_origin(piece);
  const ShadowedImage split = shadowed_piece(piece, origin, MPI_COMM_WORLD);
  if (w.rank != 0) return;
  const ShadowedImage whole = shadowed_piece(whole_mesh(), origin, MPI_COMM_SELF);
  std::size_t shadowed = 0, lit = 0, occlusion_differences = 0, color_differences = 0;
  for (std::size_t p = 0; p < whole.image.pixel_count(); ++p) {
    if (whole.image.hit[p] == kNoHit) continue;
    shadowed += whole.occluded[p] != 0;
    lit += whole.occluded[p] == 0;
    if (split.image.depth[p] != whole.image.depth[p]) continue;  // counted by check_split
    occlusion_differences += split.occluded[p] != whole.occluded[p];
    color_differences += split.image.hit[p] == whole.image.hit[p] &&
                         !std::equal(&split.image.rgba[4 * p], &split.image.rgba[4 * p + 4],
                                     &whole.image.rgba[4 * p]);
  }
  EXPECT_GT(shadowed, whole.image.pixel_count() / 50) << what << ": the view must show shadows";
  EXPECT_GT(lit, whole.image.pixel_count() / 50) << what;
  EXPECT_EQ(occlusion_differences, 0u) << what;
  EXPECT_EQ(color_differences, 0u) << what;
}

TEST(SplitMeshShadows, SlabsMatchTheWholeMesh) {
  check_shadowed_split(slabs(0, world().size), "slabs");
}

TEST(SplitMeshShadows, RandomTetPartitionMatchesTheWholeMesh) {
  check_shadowed_split(random_partition(world().size), "random partition");
}

}  // namespace
}  // namespace tetray::render
