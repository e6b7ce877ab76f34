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

}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> make_grid(const std::vector<std::int64_t>& tets) {
  vtkNew<vtkCellArray> cells;
  if (!cells->SetData(4, view_array<vtkAOSDataArrayTemplate<long>>(tets, 1)))
    throw std::runtime_error("VTK rejected the tet connectivity");
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetCells(VTK_TETRA, cells);
  return grid;
}

void set_grid_step(vtkUnstructuredGrid& grid, const std::vector<double>& points,
                   const std::vector<double>& field) {
  vtkNew<vtkPoints> grid_points;
  grid_points->SetData(view_array<vtkDoubleArray>(points, 3));
  grid.SetPoints(grid_points);
  auto scalars = view_array<vtkDoubleArray>(field, 1);
  scalars->SetName("f");
  grid.GetPointData()->SetScalars(scalars);
}

namespace {

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

struct Contour::State {
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  vtkNew<vtkContour3DLinearGrid> filter;
};

Contour::Contour(const std::vector<std::int64_t>& tets, double iso)
    : state_(std::make_unique<State>()) {
  state_->grid = make_grid(tets);
  vtkContour3DLinearGrid& filter = *state_->filter;
  filter.SetInputData(state_->grid);
  filter.SetValue(0, iso);
  filter.SetMergePoints(false);
  filter.SetInterpolateAttributes(false);
  filter.SetComputeNormals(false);
  filter.SetComputeScalars(false);
  filter.SetSequentialProcessing(false);
  filter.SetOutputPointsPrecision(vtkAlgorithm::SINGLE_PRECISION);
}

Contour::~Contour() = default;

void Contour::set_step(const std::vector<double>& points, const std::vector<double>& field) {
  set_grid_step(*state_->grid, points, field);
}

double Contour::run_ms() {
  state_->filter->Modified();
  return time_ms([&] { state_->filter->Update(); });
}

TriangleSoup Contour::triangles() const {
  auto* surface = vtkPolyData::SafeDownCast(state_->filter->GetOutputDataObject(0));
  if (surface == nullptr) throw std::runtime_error("the contour filter gave no polydata");
  return to_soup(*surface);
}

ContourRun contour_with_vtk(const BoxMesh& mesh, const std::vector<double>& field, double iso) {
  Contour contour(mesh.tets, iso);
  contour.set_step(mesh.points, field);
  contour.run_ms();
  ContourRun run;
  run.contour_ms = best_of_ms(kRepetitions, [&] { return contour.run_ms(); });
  run.triangles = contour.triangles();
  return run;
}

}  // namespace tetray::bench
