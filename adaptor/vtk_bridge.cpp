#include "tetray/vtk_bridge.hpp"

#include <new>
#include <vector>

namespace tetray {

Status execute(Adaptor& adaptor, std::int64_t step, double time, vtkUnstructuredGrid* grid,
               const Changes& changes, ExecuteReport* report) {
  if (!adaptor.will_render(step, time)) return adaptor.execute(step, time, {}, {}, changes, report);
  try {
    if (grid == nullptr) return {StatusCode::invalid_argument, "VTK bridge: the grid is null"};
    vtkio::TetGrid converted;
    std::string error;
    if (!vtkio::from_vtk(grid, converted, error)) {
      return {StatusCode::invalid_argument, "VTK bridge: " + error};
    }
    return execute(adaptor, step, time, converted, changes, report);
  } catch (const std::bad_alloc&) {
    return {StatusCode::internal_error, "VTK bridge: out of memory"};
  } catch (const std::exception& e) {
    return {StatusCode::internal_error, std::string("VTK bridge: ") + e.what()};
  }
}

Status execute(Adaptor& adaptor, std::int64_t step, double time, const vtkio::TetGrid& grid,
               const Changes& changes, ExecuteReport* report) {
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(grid.points));
  mesh.tets = TetsView::of(std::span<const std::int64_t>(grid.tets));
  if (!grid.ghost.empty()) mesh.tets.ghost = grid.ghost.data();
  std::vector<FieldView> fields;
  for (const auto& [name, values] : grid.point_fields) {
    fields.push_back(FieldView::of(name, std::span<const double>(values)));
  }
  return adaptor.execute(step, time, mesh, fields, changes, report);
}

}  // namespace tetray
