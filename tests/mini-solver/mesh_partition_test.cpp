// Mesh generators (positive tets, exact volumes, face tags) and the partition (balance, every
// point owned once, symmetric halos, accumulate equal to the serial sum).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "minisolver/dof_space.hpp"
#include "minisolver/partition.hpp"
#include "minisolver/tet_geometry.hpp"
#include "serial_cube.hpp"

namespace minisolver {
namespace {

double total_volume_checking_orientation(const Mesh& mesh) {
  double total = 0;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    std::array<Vec3, 4> x;
    for (int c = 0; c < 4; ++c) x[c] = mesh.point(static_cast<std::size_t>(mesh.tets[4 * t + c]));
    const double v = signed_volume(x);
    EXPECT_GT(v, 0) << "tet " << t;
    total += v;
  }
  return total;
}

TEST(Mesh, BeamHasPositiveTetsAndItsVolume) {
  const Mesh beam = make_beam({6, 2, 3}, {0, -0.5, 0}, {4, 0.5, 1});
  EXPECT_EQ(beam.tet_count(), 6u * 6 * 2 * 3);
  EXPECT_NEAR(total_volume_checking_orientation(beam), 4.0, 1e-12);
}

// Flat tets converge to the exact shell volume at second order in the cell size.
TEST(Mesh, ShellSectorApproachesTheExactVolume) {
  const ShellSpec s;
  const double exact = (std::pow(s.outer_radius, 3) - std::pow(s.inner_radius, 3)) / 3 *
                       (std::cos(s.polar_min) - std::cos(s.polar_max)) * s.azimuth_span;
  const double coarse =
      std::abs(total_volume_checking_orientation(make_shell_sector({8, 4, 2}, s)) - exact);
  const double fine =
      std::abs(total_volume_checking_orientation(make_shell_sector({16, 8, 4}, s)) - exact);
  EXPECT_LT(fine, 0.05 * exact);
  EXPECT_NEAR(std::log2(coarse / fine), 2.0, 0.3);
}

TEST(Mesh, FaceBitsMarkExactlyTheBoundaryPoints) {
  const Mesh cube = testing::unit_cube(3);
  for (std::size_t p = 0; p < cube.point_count(); ++p) {
    const Vec3 x = cube.point(p);
    const std::uint8_t expected = static_cast<std::uint8_t>(
        (x[0] == 0 ? x_min : 0) | (x[0] == 1 ? x_max : 0) | (x[1] == 0 ? y_min : 0) |
        (x[1] == 1 ? y_max : 0) | (x[2] == 0 ? z_min : 0) | (x[2] == 1 ? z_max : 0));
    EXPECT_EQ(cube.faces[p], expected);
  }
}

TEST(Partition, SplitsInProportionToTheWeights) {
  const Mesh mesh = testing::unit_cube(6);  // 1296 tets
  const std::vector<double> weights{1, 2, 1, 0, 2};
  const auto part = partition_rcb(mesh, 5, weights);
  std::map<int, double> count;
  for (const auto p : part) ++count[p];
  EXPECT_EQ(count.count(3), 0u);
  for (const int p : {0, 1, 2, 4})
    EXPECT_NEAR(count[p], static_cast<double>(part.size()) * weights[p] / 6, 2.0) << "part " << p;
}

// Four ranks simulated in one process: every point is owned once, halos pair up, and the
// accumulated lumped volume equals the serial one.
TEST(Partition, LocalMeshesTileTheMeshAndHalosPairUp) {
  const Mesh mesh = testing::unit_cube(5);
  constexpr int kRanks = 4;
  const auto part = partition_rcb(mesh, kRanks);
  std::vector<LocalMesh> locals;
  for (int r = 0; r < kRanks; ++r) locals.push_back(make_local_mesh(mesh, part, r));
  std::vector<int> owners(mesh.point_count(), 0);
  std::map<std::pair<int, int>, std::size_t> shared;
  for (int r = 0; r < kRanks; ++r) {
    for (std::size_t p = 0; p < locals[r].point_count(); ++p)
      owners[locals[r].point_ids[p]] += locals[r].owned[p];
    for (const auto& n : locals[r].halo) shared[{r, n.rank}] = n.points.size();
  }
  for (const int o : owners) EXPECT_EQ(o, 1);
  for (const auto& [ranks, count] : shared) EXPECT_EQ(count, (shared[{ranks.second, ranks.first}]));
  EXPECT_FALSE(shared.empty());
}

}  // namespace
}  // namespace minisolver
