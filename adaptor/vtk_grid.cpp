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

// Empty when every cell is a tet; otherwise names the first cell that is not. A file may
// declare fewer cell types than cells: those cells have no type.
std::string first_non_tet(vtkUnstructuredGrid* grid) {
  const vtkIdType cell_count = grid->GetNumberOfCells();
  vtkUnsignedCharArray* types = grid->GetCellTypesArray();
  const vtkIdType typed = types ? types->GetNumberOfTuples() : 0;
  if (typed < cell_count) {
    return "cell " + std::to_string(typed) + " has no cell type (" + std::to_string(typed) +
           " types for " + std::to_string(cell_count) + " cells)";
  }
  for (vtkIdType cell = 0; cell < cell_count; ++cell) {
    const int type = types->GetValue(cell);
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

// The 4 ids of every tet. The type array says "tet" but only the offsets say how many ids a
// cell has: a file whose offsets do not step by 4 from 0 to the end of the connectivity is
// refused (a cell with 3 ids would otherwise borrow its neighbour's).
template <typename Ids>
std::string copy_tet_ids(const Ids* offsets, vtkIdType cells, const Ids* ids, vtkIdType id_count,
                         std::vector<std::int64_t>& tets) {
  if (offsets[0] != 0 || offsets[cells] != id_count) {
    return "the cell offsets span [" + std::to_string(offsets[0]) + ", " +
           std::to_string(offsets[cells]) + ") of a connectivity of " + std::to_string(id_count) +
           " point ids";
  }
  for (vtkIdType cell = 0; cell < cells; ++cell) {
    if (offsets[cell + 1] - offsets[cell] != 4) {
      return "cell " + std::to_string(cell) + " is a tet with " +
             std::to_string(offsets[cell + 1] - offsets[cell]) + " point ids (a tet has 4)";
    }
  }
  tets.assign(ids, ids + id_count);
  return {};
}

std::string copy_tets(vtkUnstructuredGrid* grid, std::vector<std::int64_t>& tets) {
  vtkCellArray* cells = grid->GetCells();
  if (!cells || cells->GetNumberOfCells() == 0) return {};
  const vtkIdType count = cells->GetNumberOfCells();
  if (cells->IsStorage64Bit()) {
    return copy_tet_ids(cells->GetOffsetsArray64()->GetPointer(0), count,
                        cells->GetConnectivityArray64()->GetPointer(0),
                        cells->GetNumberOfConnectivityIds(), tets);
  }
  return copy_tet_ids(cells->GetOffsetsArray32()->GetPointer(0), count,
                      cells->GetConnectivityArray32()->GetPointer(0),
                      cells->GetNumberOfConnectivityIds(), tets);
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
  error = copy_tets(grid, out.tets);
  if (!error.empty()) return false;
  out.points = copy_points(grid);
  out.ghost = copy_ghosts(grid);
  out.point_fields = copy_point_fields(grid);
  error = size_mismatch(out);
  return error.empty();
}

}  // namespace tetray::vtkio
