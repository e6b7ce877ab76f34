// Meshes given as cells (CellsView) end to end: for every kind of cell tetray splits (hexahedra,
// wedges, pyramids, a mix of hexahedra and pyramids, quadratic tets and hexahedra), the ball
// level set of the distance to the centre covers as many pixels as geometry and interpolation
// error allow (tests/support/ball_image.h), and the image of the mesh split among the ranks,
// each numbering its own points in its own shuffled order, is that of one rank holding it all.
// A split decided by rank-local point numbers would cut the quadrilaterals of the partition
// boundaries differently on each side and change the image.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "ball_image.h"
#include "shared_dir.hpp"
#include "support/cell_meshes.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

constexpr int kCubes = 12, kSide = 64;
constexpr double kRadius = 0.6, kEye = 3, kFov = 40;

// One rank's share of a cell mesh: its cells, over only the points they use, numbered locally.
struct RankCells {
  std::vector<double> xyz, distance;
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets{0}, connectivity;
};

// The cells [first, last) of `mesh` (on [-1, 1]^3), their points in the order of `seed`'s
// shuffle (seed 0: the mesh's own order).
RankCells share(const CellMesh& mesh, std::size_t first, std::size_t last, unsigned seed) {
  std::vector<std::int64_t> used;
  for (auto c = first; c < last; ++c) {
    used.insert(used.end(), mesh.connectivity.begin() + mesh.offsets[c],
                mesh.connectivity.begin() + mesh.offsets[c + 1]);
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  if (seed != 0) std::shuffle(used.begin(), used.end(), std::mt19937(seed));
  std::vector<std::int64_t> local(mesh.points.size(), -1);
  RankCells out;
  const std::vector<double> xyz = mesh.xyz(-1, 1);
  for (std::size_t k = 0; k < used.size(); ++k) {
    local[used[k]] = static_cast<std::int64_t>(k);
    const double* p = &xyz[3 * used[k]];
    out.xyz.insert(out.xyz.end(), p, p + 3);
    out.distance.push_back(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
  }
  for (auto c = first; c < last; ++c) {
    out.types.push_back(mesh.types[c]);
    for (auto v = mesh.offsets[c]; v < mesh.offsets[c + 1]; ++v) {
      out.connectivity.push_back(local[mesh.connectivity[v]]);
    }
    out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
  }
  return out;
}

std::string config(const std::string& directory) {
  return "output: {directory: " + directory + ", formats: [png], quiet: true}\n" +
         "scenes:\n"
         "  - name: ball\n"
         "    field: distance\n"
         "    isovalues: [" +
         std::to_string(kRadius) + "]\n    camera: {eye: [0, 0, " + std::to_string(kEye) +
         "], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: " + std::to_string(kFov) +
         "}\n    image: {width: " + std::to_string(kSide) + ", height: " + std::to_string(kSide) +
         "}\n";
}

void render(MPI_Comm comm, const std::string& directory, const RankCells& cells) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, config(directory), status);
  ASSERT_TRUE(adaptor) << status.message;
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(cells.xyz));
  mesh.cells = {cells.types.data(), cells.offsets.data(), cells.connectivity.data(),
                IndexType::int64, cells.types.size()};
  const FieldView fields[] = {FieldView::of("distance", std::span<const double>(cells.distance))};
  status = adaptor->execute(0, 0, mesh, fields);
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

}  // namespace
}  // namespace tetray::testing
