// vtkUnstructuredGrid -> TetGrid: the conversion behind the VTK bridge, tetray-render and
// tetray-replay. Tets, hexahedra, wedges, pyramids and quadratic tets and hexahedra are accepted
// and split into tets (cell_split.hpp); everything is copied into plain arrays so that the
// renderer never sees a VTK type.
#include "tetray/vtk_bridge.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
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

#include "adaptor/input/cell_split.hpp"

namespace tetray::vtkio {
namespace {

// The cells as VTK stores them: cell c has type types[c] and the point ids
// connectivity[offsets[c], offsets[c + 1]).
struct VtkCells {
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets, connectivity;
};

// A file may declare fewer cell types than cells, or offsets that do not span the connectivity
// from its start to its end: such cells are refused (a cell would borrow its neighbour's ids).
template <typename Ids>
std::string copy_ids(const Ids* offsets, vtkIdType cells, const Ids* ids, vtkIdType id_count,
                     VtkCells& out) {
  if (offsets[0] != 0 || offsets[cells] != id_count) {
    return "the cell offsets span [" + std::to_string(offsets[0]) + ", " +
           std::to_string(offsets[cells]) + ") of a connectivity of " + std::to_string(id_count) +
           " point ids";
  }
  out.offsets.assign(offsets, offsets + cells + 1);
  out.connectivity.assign(ids, ids + id_count);
  return {};
}

std::string copy_cells(vtkUnstructuredGrid* grid, VtkCells& out) {
  vtkCellArray* cells = grid->GetCells();
  const vtkIdType count = cells ? cells->GetNumberOfCells() : 0;
  if (count == 0) return {};
  vtkUnsignedCharArray* types = grid->GetCellTypesArray();
  const vtkIdType typed = types ? types->GetNumberOfTuples() : 0;
  if (typed < count) {
    return "cell " + std::to_string(typed) + " has no cell type (" + std::to_string(typed) +
           " types for " + std::to_string(count) + " cells)";
  }
  out.types.assign(types->GetPointer(0), types->GetPointer(0) + count);
  if (cells->IsStorage64Bit()) {
    return copy_ids(cells->GetOffsetsArray64()->GetPointer(0), count,
                    cells->GetConnectivityArray64()->GetPointer(0),
                    cells->GetNumberOfConnectivityIds(), out);
  }
  return copy_ids(cells->GetOffsetsArray32()->GetPointer(0), count,
                  cells->GetConnectivityArray32()->GetPointer(0),
                  cells->GetNumberOfConnectivityIds(), out);
}

// The cells as tets (cell_split.hpp), with their ghost flags; the order of the points is that of
// their positions, so that every rank and file splits a shared face alike.
std::string split_into_tets(const VtkCells& cells, TetGrid& grid) {
  const std::vector<std::uint64_t> keys = position_keys(grid.points);
  SplitCells split = split_cells(cells.types, cells.offsets, cells.connectivity, keys, grid.points);
  if (!split.error.empty()) return split.error;
  grid.tets = std::move(split.tets);
  if (!grid.ghost.empty()) {
    std::vector<std::uint8_t> ghost(split.tet_cell.size());
    for (std::size_t t = 0; t < ghost.size(); ++t) ghost[t] = grid.ghost[split.tet_cell[t]];
    grid.ghost = std::move(ghost);
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
std::string size_mismatch(const TetGrid& grid, std::size_t cells) {
  const std::size_t points = grid.points.size() / 3;
  if (!grid.ghost.empty() && grid.ghost.size() != cells) {
    return "cell array vtkGhostType has " + std::to_string(grid.ghost.size()) + " values for " +
           std::to_string(cells) + " cells";
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
  VtkCells cells;
  error = copy_cells(grid, cells);
  if (!error.empty()) return false;
  out.points = copy_points(grid);
  out.ghost = copy_ghosts(grid);
  out.point_fields = copy_point_fields(grid);
  error = size_mismatch(out, cells.types.size());
  if (error.empty()) error = split_into_tets(cells, out);
  return error.empty();
}

}  // namespace tetray::vtkio
