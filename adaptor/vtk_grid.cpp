// vtkUnstructuredGrid -> TetGrid: the conversion behind the VTK bridge, tetray-render and
// tetray-replay. Only VTK_TETRA cells are accepted; everything is copied into plain arrays so
// that the renderer never sees a VTK type.
#include "tetray/vtk_bridge.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>

namespace tetray::vtkio {
namespace {

// Empty when every cell is a tet; otherwise names the first cell that is not.
std::string first_non_tet(vtkUnstructuredGrid* grid) {
  const vtkIdType cell_count = grid->GetNumberOfCells();
  for (vtkIdType cell = 0; cell < cell_count; ++cell) {
    const int type = grid->GetCellType(cell);
    if (type == VTK_TETRA) continue;
    const char* name = vtkCellTypes::GetClassNameFromTypeId(type);
    return "cell " + std::to_string(cell) + " is a " + (name ? name : "cell of unknown type") +
           " (VTK cell type " + std::to_string(type) + "); tetray renders only VTK_TETRA (" +
           std::to_string(VTK_TETRA) + ") cells";
  }
  return {};
}

std::vector<double> copy_points(vtkUnstructuredGrid* grid) {
  vtkPoints* points = grid->GetPoints();
  if (!points) return {};
  const vtkIdType count = points->GetNumberOfPoints();
  std::vector<double> xyz(3 * static_cast<std::size_t>(count));
  for (vtkIdType p = 0; p < count; ++p) points->GetPoint(p, &xyz[3 * static_cast<std::size_t>(p)]);
  return xyz;
}

// All cells are tets, so the connectivity array is the 4-per-tet list itself.
std::vector<std::int64_t> copy_tets(vtkUnstructuredGrid* grid) {
  vtkCellArray* cells = grid->GetCells();
  if (!cells) return {};
  std::vector<std::int64_t> tets(4 * static_cast<std::size_t>(cells->GetNumberOfCells()));
  if (cells->IsStorage64Bit()) {
    const auto* ids = cells->GetConnectivityArray64()->GetPointer(0);
    std::copy(ids, ids + tets.size(), tets.begin());
  } else {
    const auto* ids = cells->GetConnectivityArray32()->GetPointer(0);
    std::copy(ids, ids + tets.size(), tets.begin());
  }
  return tets;
}

std::vector<std::uint8_t> copy_ghosts(vtkUnstructuredGrid* grid) {
  vtkDataArray* ghosts = grid->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  if (!ghosts || ghosts->GetNumberOfComponents() != 1) return {};
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(ghosts->GetNumberOfTuples()));
  for (std::size_t t = 0; t < flags.size(); ++t) {
    flags[t] = static_cast<std::uint8_t>(ghosts->GetComponent(static_cast<vtkIdType>(t), 0));
  }
  return flags;
}

// Numeric one-component point arrays with a name; vectors, strings and ghost flags are skipped.
std::map<std::string, std::vector<double>> copy_point_fields(vtkUnstructuredGrid* grid) {
  std::map<std::string, std::vector<double>> fields;
  vtkPointData* data = grid->GetPointData();
  for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = data->GetArray(a);
    if (!array || !array->GetName() || array->GetNumberOfComponents() != 1) continue;
    if (std::string(array->GetName()) == vtkDataSetAttributes::GhostArrayName()) continue;
    std::vector<double>& values = fields[array->GetName()];
    values.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
    for (std::size_t p = 0; p < values.size(); ++p) {
      values[p] = array->GetComponent(static_cast<vtkIdType>(p), 0);
    }
  }
  return fields;
}

// Empty when the ghost flags and every field have one value per cell and per point.
std::string size_mismatch(const TetGrid& grid) {
  const std::size_t tets = grid.tets.size() / 4;
  const std::size_t points = grid.points.size() / 3;
  if (!grid.ghost.empty() && grid.ghost.size() != tets) {
    return "cell array vtkGhostType has " + std::to_string(grid.ghost.size()) + " values for " +
           std::to_string(tets) + " cells";
  }
  for (const auto& [name, values] : grid.point_fields) {
    if (values.size() != points) {
      return "point array '" + name + "' has " + std::to_string(values.size()) + " values for " +
             std::to_string(points) + " points";
    }
  }
  return {};
}

}  // namespace

bool from_vtk(vtkUnstructuredGrid* grid, TetGrid& out, std::string& error) {
  out = {};
  if (!grid) {
    error = "no grid (null vtkUnstructuredGrid)";
    return false;
  }
  error = first_non_tet(grid);
  if (!error.empty()) return false;
  out.points = copy_points(grid);
  out.tets = copy_tets(grid);
  out.ghost = copy_ghosts(grid);
  out.point_fields = copy_point_fields(grid);
  error = size_mismatch(out);
  return error.empty();
}

}  // namespace tetray::vtkio
