// The VTK bridge: a vtkUnstructuredGrid of the plane scene renders like the raw views, ghost
// tets are not rendered, and a non-tet cell is a clear error.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/vtk_bridge.hpp"

namespace tetray::testing {
namespace {

vtkNew<vtkUnstructuredGrid> to_vtk(const PlaneScene& scene) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (std::size_t p = 0; p < scene.mesh.point_count(); ++p) {
    points->InsertNextPoint(&scene.mesh.points[3 * p]);
  }
  grid->SetPoints(points);
  for (std::size_t t = 0; t < scene.mesh.tet_count(); ++t) {
    vtkIdType ids[4];
    for (int k = 0; k < 4; ++k) ids[k] = scene.mesh.tets[4 * t + static_cast<std::size_t>(k)];
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  vtkNew<vtkDoubleArray> f;
  f->SetName("f");
  for (double v : scene.f) f->InsertNextValue(v);
  grid->GetPointData()->AddArray(f);
  return grid;
}

TEST(VtkBridge, RendersAGridAndDropsGhostTets) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(4);
  Status status;
  auto a = Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config(dir.path().string()), status);
  ASSERT_TRUE(a) << status.message;
  auto grid = to_vtk(scene);
  ASSERT_TRUE(execute(*a, 0, 0, grid).ok());
  // Every tet a ghost (DUPLICATECELL): nothing left to render.
  vtkNew<vtkUnsignedCharArray> ghost;
  ghost->SetName("vtkGhostType");
  for (std::size_t t = 0; t < scene.mesh.tet_count(); ++t) ghost->InsertNextValue(1);
  grid->GetCellData()->AddArray(ghost);
  ASSERT_TRUE(execute(*a, 1, 1, grid).ok());
  ASSERT_TRUE(a->finalize().ok());
  const auto log = read_csv(dir / "tetray_log.csv");
  ASSERT_EQ(log.size(), 3u);
  const ExpectedHits expected = expected_plane_hits();
  EXPECT_GE(std::stoull(cell(log, 1, "hits")), expected.sure);
  EXPECT_LE(std::stoull(cell(log, 1, "hits")), expected.sure + expected.edge);
  EXPECT_EQ(cell(log, 2, "kept_tets"), "0");
  EXPECT_EQ(cell(log, 2, "hits"), "0");
}

TEST(VtkBridge, NonTetCellIsAnError) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(2);
  Status status;
  auto a = Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config(dir.path().string()), status);
  ASSERT_TRUE(a) << status.message;
  auto grid = to_vtk(scene);
  vtkIdType triangle[3] = {0, 1, 2};
  grid->InsertNextCell(VTK_TRIANGLE, 3, triangle);
  status = execute(*a, 0, 0, grid);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("VTK bridge"), std::string::npos) << status.message;
  EXPECT_EQ(execute(*a, 1, 1, nullptr).code, StatusCode::invalid_argument);
}

}  // namespace
}  // namespace tetray::testing
