// The renderer on the tets the adaptor splits other cells into (adaptor/input/cell_split.hpp): on
// meshes of hexahedra, wedges, pyramids, hexahedra mixed with pyramids, quadratic tets and
// quadratic hexahedra, a sphere level set is watertight from random cameras (docs/architecture.md
// §5: zero pinholes with every packet size) and tetray's image agrees with the double-precision
// reference intersector on the standard cameras. The split's points are ordered by their positions'
// hash, as the adaptor orders them.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "adaptor/input/cell_split.hpp"
#include "support/cell_meshes.hpp"
#include "support/reference_comparison.hpp"
#include "support/watertight.hpp"

namespace tetray::test {
namespace {

constexpr int kCubes = 5;
const Vec3d kCenter{0.06, -0.04, 0.09};
constexpr double kIso = 0.62;

struct SplitMesh {
  std::vector<double> points, field;
  std::vector<std::int64_t> tets;
};

SplitMesh split_mesh(const testing::CellKind& kind, bool use_hanging_nodes = true) {
  const testing::CellMesh cells = testing::lattice(kCubes, kind.make);
  SplitMesh mesh;
  mesh.points = cells.xyz(-1, 1);
  const std::vector<std::uint64_t> keys = position_keys(mesh.points);
  SplitCells split = split_cells(cells.types, cells.offsets, cells.connectivity, keys,
                                 use_hanging_nodes ? mesh.points : std::vector<double>());
  EXPECT_EQ(split.error, "") << kind.name;
  mesh.tets = std::move(split.tets);
  mesh.field = sample_field(mesh.points, [](Vec3d x) { return length(x - kCenter); });
  testing::constrain_hanging_values(cells, mesh.field);
  return mesh;
}

// The sphere level set of `kind`'s mesh, split with or without its hanging nodes, checked for
// pinholes from random cameras.
void expect_watertight(const testing::CellKind& kind, bool use_hanging_nodes = true) {
  const SplitMesh mesh = split_mesh(kind, use_hanging_nodes);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, mesh.field);
  expect_sphere_watertight(scene, kCenter, kIso, 12, 100'000u / kSanitizerSlowdown, kind.name);
}

TEST(SplitCells, SphereLevelSetIsWatertight) {
  for (const testing::CellKind& kind : testing::kCellKinds) expect_watertight(kind);
}

TEST(SplitCells, ImagesAgreeWithTheReference) {
  const double isovalues[] = {0.35, kIso, 0.9};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  for (const testing::CellKind& kind : testing::kCellKinds) {
    const SplitMesh mesh = split_mesh(kind);
    const RenderScene scene = load_scene(mesh.points, mesh.tets, mesh.field);
    AgreementCounts total;
    for (const render::Camera& camera : standard_cameras(scaled_side(96), scaled_side(80))) {
      total += expect_agreement(scene, camera, surfaces, kind.name);
    }
    EXPECT_GT(total.reference_hits, total.pixels / 10) << kind.name;
    EXPECT_EQ(total.failures(), 0u) << kind.name << ": " << total.summary();
  }
}

// A solver's adaptively refined mesh (coarse hexahedra against refined ones, the field at the
// hanging nodes constrained as the solver gives it): the isosurface has no pinhole along the
// refinement interfaces. The same split without the hanging nodes leaves cracks there, which the
// same check finds: it can fail.
TEST(SplitCells, LevelSetIsWatertightAcrossRefinementInterfaces) {
  for (const testing::CellKind& kind : testing::kHangingKinds) expect_watertight(kind);
}

TEST(SplitCells, IgnoringTheHangingNodesCracksTheSurface) {
  for (const testing::CellKind& kind : testing::kHangingKinds) {
    ::testing::TestPartResultArray failures;
    {
      const ::testing::ScopedFakeTestPartResultReporter capture(
          ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
      expect_watertight(kind, false);
    }
    int pinholes = 0;
    for (int k = 0; k < failures.size(); ++k) {
      pinholes +=
          std::string(failures.GetTestPartResult(k).message()).find("pinhole") != std::string::npos;
    }
    EXPECT_GT(pinholes, 0) << kind.name;
  }
}

}  // namespace
}  // namespace tetray::test
