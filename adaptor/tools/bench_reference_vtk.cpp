#include "bench_reference_vtk.hpp"

#include <vtkAOSDataArrayTemplate.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellType.h>
#include <vtkContour3DLinearGrid.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <stdexcept>

#include "bench_timing.hpp"

namespace tetray::bench {
namespace {

// VTK arrays that view the bench's own arrays (save = 1: VTK never frees them), so building
// the grid costs no copy.
template <typename Array, typename T>
vtkSmartPointer<Array> view_array(const std::vector<T>& values, int components) {
  auto array = vtkSmartPointer<Array>::New();
  array->SetNumberOfComponents(components);
  array->SetArray(const_cast<T*>(values.data()), static_cast<vtkIdType>(values.size()), 1);
  return array;
}

vtkSmartPointer<vtkUnstructuredGrid> make_grid(const BoxMesh& mesh,
                                               const std::vector<double>& field) {
  vtkNew<vtkPoints> points;
  points->SetData(view_array<vtkDoubleArray>(mesh.points, 3));
  vtkNew<vtkCellArray> cells;
  if (!cells->SetData(4, view_array<vtkAOSDataArrayTemplate<long>>(mesh.tets, 1)))
    throw std::runtime_error("VTK rejected the tet connectivity");
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_TETRA, cells);
  auto scalars = view_array<vtkDoubleArray>(field, 1);
  scalars->SetName("f");
  grid->GetPointData()->SetScalars(scalars);
  return grid;
}

TriangleSoup to_soup(vtkPolyData& surface) {
  TriangleSoup soup;
  auto* coordinates = vtkFloatArray::SafeDownCast(surface.GetPoints()->GetData());
  if (coordinates == nullptr) throw std::runtime_error("contour points are not float");
  const float* first = coordinates->GetPointer(0);
  soup.xyz.assign(first, first + 3 * surface.GetNumberOfPoints());
  soup.xyz.push_back(0.0f);
  soup.indices.reserve(3 * static_cast<std::size_t>(surface.GetNumberOfPolys()));
  auto cell = vtk::TakeSmartPointer(surface.GetPolys()->NewIterator());
  for (cell->GoToFirstCell(); !cell->IsDoneWithTraversal(); cell->GoToNextCell()) {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cell->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k) soup.indices.push_back(static_cast<std::uint32_t>(ids[k]));
  }
  return soup;
}

}  // namespace

ContourRun contour_with_vtk(const BoxMesh& mesh, const std::vector<double>& field, double iso) {
  const auto grid = make_grid(mesh, field);
  vtkNew<vtkContour3DLinearGrid> contour;
  contour->SetInputData(grid);
  contour->SetValue(0, iso);
  contour->SetMergePoints(false);
  contour->SetInterpolateAttributes(false);
  contour->SetComputeNormals(false);
  contour->SetComputeScalars(false);
  contour->SetSequentialProcessing(false);
  contour->SetOutputPointsPrecision(vtkAlgorithm::SINGLE_PRECISION);
  contour->Update();
  ContourRun run;
  run.contour_ms = best_ms(
      kRepetitions, [&] { contour->Modified(); }, [&] { contour->Update(); });
  auto* surface = vtkPolyData::SafeDownCast(contour->GetOutputDataObject(0));
  if (surface == nullptr) throw std::runtime_error("the contour filter gave no polydata");
  run.triangles = to_soup(*surface);
  return run;
}

}  // namespace tetray::bench
