#include "tetray/vtk_bridge.hpp"

#include <new>
#include <vector>

namespace tetray {

Status execute(Adaptor& adaptor, std::int64_t step, double time, vtkUnstructuredGrid* grid,
               const Changes& changes, ExecuteReport* report) {
  if (!adaptor.will_render(step, time)) return adaptor.execute(step, time, {}, {}, changes, report);
  try {
    // A failure here is this rank's alone: execute_failed keeps the other ranks from waiting.
    if (grid == nullptr) {
      return adaptor.execute_failed(step, time,
                                    {StatusCode::invalid_argument, "VTK bridge: the grid is null"},
                                    changes, report);
    }
    vtkio::TetGrid converted;
    std::string error;
    if (!vtkio::from_vtk(grid, converted, error)) {
      return adaptor.execute_failed(
          step, time, {StatusCode::invalid_argument, "VTK bridge: " + error}, changes, report);
    }
    return execute(adaptor, step, time, converted, changes, report);
  } catch (const std::bad_alloc&) {
    return adaptor.execute_failed(
        step, time, {StatusCode::internal_error, "VTK bridge: out of memory"}, changes, report);
  } catch (const std::exception& e) {
    return adaptor.execute_failed(
        step, time, {StatusCode::internal_error, std::string("VTK bridge: ") + e.what()}, changes,
        report);
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
