// Meshes given as cells (CellsView) end to end: for every kind of cell tetray splits (hexahedra,
// wedges, pyramids, a mix of hexahedra and pyramids, quadratic tets and hexahedra), the ball
// level set of the distance to the centre covers as many pixels as geometry and interpolation
// error allow (tests/support/ball_image.h), and the image of the mesh split among the ranks,
// each numbering its own points in its own shuffled order, is that of one rank holding it all.
// A split decided by rank-local point numbers would cut the quadrilaterals of the partition
// boundaries differently on each side and change the image.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>
#include <vector>

#include "ball_image.h"
#include "rank_cells.hpp"
#include "shared_dir.hpp"
#include "support/cell_meshes.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

constexpr int kCubes = 12, kSide = 64;
constexpr double kRadius = 0.6, kEye = 3, kFov = 40;

std::string config(const std::string& directory) {
  return ball_config(directory, kRadius, "[0, 0, " + std::to_string(kEye) + "]", kFov, kSide);
}

void render(MPI_Comm comm, const std::string& directory, const RankCells& cells) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, config(directory), status);
  ASSERT_TRUE(adaptor) << status.message;
  status = adaptor->execute(0, 0, cells.view(), cells.fields());
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(adaptor->finalize().ok());
}

TEST(Cells, EveryKindRendersTheBallAndTheSameImageOnAnyRankCount) {
  const SharedDir shared("cells");
  for (const CellKind& kind : kCellKinds) {
    const CellMesh mesh = lattice(kCubes, kind.make);
    const std::string name = std::string(kind.name);
    const std::string one = shared.path() + "/one_" + std::to_string(&kind - kCellKinds);
    const std::string split = shared.path() + "/split_" + std::to_string(&kind - kCellKinds);
    if (rank() == 0) render(MPI_COMM_SELF, one, share(mesh, 0, mesh.types.size(), 0));
    const std::size_t cells = mesh.types.size();
    const auto bound = [&](int r) { return cells * static_cast<std::size_t>(r) / world_size(); };
    render(MPI_COMM_WORLD, split, share(mesh, bound(rank()), bound(rank() + 1), 11 + rank()));
    if (rank() != 0) continue;
    const std::string png = one + "/ball/ball_000000.png";
    std::int64_t fewest = 0, most = 0;
    tetray_ball_pixel_bounds(kCubes, kRadius, kEye, kFov, kSide, kSide, &fewest, &most);
    const std::int64_t covered = tetray_png_covered_pixels(png.c_str());
    EXPECT_GE(covered, fewest) << name;
    EXPECT_LE(covered, most) << name;
    const std::string whole = slurp(png);
    ASSERT_FALSE(whole.empty()) << name;
    EXPECT_EQ(whole, slurp(split + "/ball/ball_000000.png")) << name << " on " << world_size();
  }
}

// Adaptively refined meshes (coarse hexahedra against refined ones, the field constrained at the
// hanging nodes as the solver gives it) split among the ranks with the ghost layer a solver such
// as deal.II passes: every rank finds the hanging nodes of its cells, and the image is that of one
// rank holding every cell. The cells are ordered by x, so each rank's block meets the refined
// half or the alternate cubes along its partition boundaries.
TEST(Cells, HangingNodesGiveTheSameImageOnAnyRankCountWithAGhostLayer) {
  const SharedDir shared("cells_hanging");
  for (const CellKind& kind : kHangingKinds) {
    const CellMesh mesh = lattice(8, kind.make);
    std::vector<double> values;
    for (const double x : mesh.xyz(-1, 1)) values.push_back(x);  // x, y, z of each point
    std::vector<double> distance(mesh.points.size());
    for (std::size_t p = 0; p < distance.size(); ++p) {
      distance[p] = std::hypot(values[3 * p] - 0.06, values[3 * p + 1] + 0.04, values[3 * p + 2]);
    }
    constrain_hanging_values(mesh, distance);
    const std::string index = std::to_string(&kind - kHangingKinds);
    const std::string one = shared.path() + "/one_" + index,
                      split = shared.path() + "/split_" + index;
    const std::size_t cells = mesh.types.size();
    if (rank() == 0) render(MPI_COMM_SELF, one, share_with_ghosts(mesh, 0, cells, 0, distance));
    const auto bound = [&](int r) { return cells * static_cast<std::size_t>(r) / world_size(); };
    render(MPI_COMM_WORLD, split,
           share_with_ghosts(mesh, bound(rank()), bound(rank() + 1), 11 + rank(), distance));
    if (rank() != 0) continue;
    const std::string whole = slurp(one + "/ball/ball_000000.png");
    ASSERT_FALSE(whole.empty()) << kind.name;
    EXPECT_GT(tetray_png_covered_pixels((one + "/ball/ball_000000.png").c_str()), kSide * kSide / 8)
        << kind.name;
    EXPECT_EQ(whole, slurp(split + "/ball/ball_000000.png")) << kind.name << " on " << world_size();
  }
}

}  // namespace
}  // namespace tetray::testing
