// Smooth shading's vertex gradients on a split mesh (docs/architecture.md, "Smooth shading
// across ranks"): the per-vertex gradients of the tets split into slabs, each rank's exact
// partial sums combined by the real protocol (render/parallel/shared_gradients.hpp) over the
// ranks that share a vertex, are bit for bit those of one rank holding every tet; and a vertex
// whose gradient needs its tet count over all ranks (the counts exchanged) gets it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstring>
#include <vector>

#include "render/parallel/shared_gradients.hpp"
#include "render/update/vertex_gradients.hpp"
#include "render/update/volume_update.hpp"
#include "scenes/box_mesh.hpp"
#include "support/count_star.hpp"
#include "support/mesh_slabs.hpp"
#include "support/mpi_world.hpp"

namespace tetray::testing {
namespace {

using render::testing::world;

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  return gyroid;
}

struct Loaded {
  render::TetVolume volume;
  render::Bvh bvh;
};

// The volume of `tets` over `points` and `field` with every rank's origin, gradients left to the
// caller.
void load(const std::vector<double>& points, const std::vector<double>& field,
          const std::vector<std::int64_t>& tets, Loaded& out) {
  const render::PointSource source{points.data(), render::ScalarKind::f64, nullptr,
                                   render::ScalarKind::f64, points.size() / 3};
  const render::FieldSource values{field.data(), render::ScalarKind::f64, field.size()};
  const render::Vec3d origin{0, 0, 0};
  render::load_volume(out.volume, out.bvh, tets, {}, {}, source, values, {}, &origin);
}

void load(const std::vector<std::int64_t>& tets, Loaded& out) {
  load(scene().mesh.points, scene().field, tets, out);
}

// The shared vertices of `slab` over `points`, matched and their gradients computed by the
// protocol; a failure fails the test.
void compute_shared(const std::vector<double>& points, Loaded& slab) {
  render::SharedGradients shared;
  const render::PointSource source{points.data(), render::ScalarKind::f64, nullptr,
                                   render::ScalarKind::f64, points.size() / 3};
  ASSERT_EQ(shared.match(slab.volume, source, MPI_COMM_WORLD).message, "");
  ASSERT_EQ(shared.compute(slab.volume).message, "");
}

// Points of `slab` whose gradient differs (in any bit) from the whole mesh's.
std::size_t differing_gradients(const Loaded& whole, const Loaded& slab) {
  std::size_t count = 0;
  for (std::size_t p = 0; p < slab.volume.point_vertex.size(); ++p) {
    const std::uint32_t k = slab.volume.point_vertex[p];
    if (k == render::kNoVertex) continue;
    const render::Vec3f& a = slab.volume.gradients[k];
    const render::Vec3f& b = whole.volume.gradients[whole.volume.point_vertex[p]];
    count += std::memcmp(&a, &b, sizeof a) != 0;
  }
  return count;
}

TEST(SmoothAcrossRanks, VertexGradientsAreThoseOfOneRankBitForBit) {
  Loaded whole, slab;
  load(scene().mesh.tets, whole);
  render::compute_vertex_gradients(whole.volume);
  load(x_slab(scene().mesh, world().rank, world().size).tets, slab);
  // Alone, a rank's boundary vertices miss the other ranks' tets.
  render::compute_vertex_gradients(slab.volume);
  const std::size_t alone = differing_gradients(whole, slab);
  if (world().size > 1) {
    EXPECT_GT(alone, 0u) << "the slabs must share vertices";
  }
  compute_shared(scene().mesh.points, slab);
  EXPECT_EQ(differing_gradients(whole, slab), 0u)
      << "on rank " << world().rank << " of " << world().size << " (" << alone << " alone)";
}

// The grid a shared vertex's terms are rounded to is that of its tets on all ranks
// (support/count_star.hpp): vertex 0's nine tets split three (rank 0) to six (the others) give
// the gradient of one rank holding all nine, (0, -1, 0) / S, not the (1, -1, 0) / S of rank 0's
// three tets' finer grid.
TEST(SmoothAcrossRanks, ASharedVertexIsRoundedOnTheGridOfAllItsTets) {
  const CountStar star = count_star();
  Loaded whole, part;
  load(star.points, star.field, star.tets, whole);
  render::compute_vertex_gradients(whole.volume);
  const render::Vec3f at_origin = whole.volume.gradients[whole.volume.point_vertex[0]];
  EXPECT_EQ(at_origin.x, 0.0f);
  EXPECT_FLOAT_EQ(at_origin.y, -1 / (4 + 27 / 256.0f));
  load(star.points, star.field, star.tets_of(world().rank, world().size), part);
  compute_shared(star.points, part);
  EXPECT_EQ(differing_gradients(whole, part), 0u)
      << "on rank " << world().rank << " of " << world().size;
}

}  // namespace
}  // namespace tetray::testing
