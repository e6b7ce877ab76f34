#include "tetray/vtk_bridge.hpp"

#include <new>

#include "grid_views.hpp"
#include "vtk_grid.hpp"

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
    return execute_grid(adaptor, step, time, converted, changes, report);
  } catch (const std::bad_alloc&) {
    return {StatusCode::internal_error, "VTK bridge: out of memory"};
  } catch (const std::exception& e) {
    return {StatusCode::internal_error, std::string("VTK bridge: ") + e.what()};
  }
}

}  // namespace tetray
