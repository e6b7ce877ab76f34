// VTK XML files of tet grids: .vtu in (VTK's reader; .pvtu in pvtu.cpp), .vtu out (binary
// appended).
// VTK's printed errors are captured and returned as the error message.
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <filesystem>
#include <span>

#include "render/image/image_write.hpp"
#include "tools/vtk_io/grid_readers.hpp"
#include "tools/vtk_io/vtk_files.hpp"
#include "tools/vtk_io/vtk_message_capture.hpp"
#include "tools/vtk_io/xml_header.hpp"

namespace tetray::vtkio {
namespace {

// Empty when the arrays are consistent: whole tuples, indices in range, one value per point
// and per tet.
std::string grid_problem(const TetGrid& grid) {
  if (grid.points.size() % 3 != 0) return "point coordinates are not a multiple of 3";
  if (grid.tets.size() % 4 != 0) return "tet connectivity is not a multiple of 4";
  const auto points = static_cast<std::int64_t>(grid.points.size() / 3);
  const auto bad = std::find_if(grid.tets.begin(), grid.tets.end(),
                                [points](std::int64_t v) { return v < 0 || v >= points; });
  if (bad != grid.tets.end()) {
    return "tet " + std::to_string((bad - grid.tets.begin()) / 4) + " has point index " +
           std::to_string(*bad) + " outside [0, " + std::to_string(points) + ")";
  }
  if (!grid.ghost.empty() && grid.ghost.size() != grid.tets.size() / 4) {
    return "ghost flags do not match the tet count";
  }
  for (const auto& [name, values] : grid.point_fields) {
    if (values.size() != grid.points.size() / 3) {
      return "field '" + name + "' does not have one value per point";
    }
  }
  return {};
}

template <typename Array, typename T>
vtkSmartPointer<Array> vtk_array(std::span<const T> values, int components, const char* name) {
  auto array = vtkSmartPointer<Array>::New();
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  if (name) array->SetName(name);
  return array;
}

vtkSmartPointer<vtkCellArray> tet_cells(const std::vector<std::int64_t>& tets) {
  const std::size_t count = tets.size() / 4;
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(count + 1));
  for (std::size_t t = 0; t <= count; ++t) {
    offsets->SetValue(static_cast<vtkIdType>(t), static_cast<vtkIdType>(4 * t));
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, vtk_array<vtkIdTypeArray>(std::span(tets), 1, nullptr));
  return cells;
}

vtkSmartPointer<vtkUnstructuredGrid> to_vtk(const TetGrid& grid) {
  auto out = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetData(vtk_array<vtkDoubleArray>(std::span(grid.points), 3, nullptr));
  out->SetPoints(points);
  out->SetCells(VTK_TETRA, tet_cells(grid.tets));
  for (const auto& [name, values] : grid.point_fields) {
    out->GetPointData()->AddArray(vtk_array<vtkDoubleArray>(std::span(values), 1, name.c_str()));
  }
  if (!grid.ghost.empty()) {
    out->GetCellData()->AddArray(vtk_array<vtkUnsignedCharArray>(
        std::span(grid.ghost), 1, vtkDataSetAttributes::GhostArrayName()));
  }
  return out;
}

}  // namespace

std::string read_vtu(const std::string& path, TetGrid& out) {
  if (std::string problem = xml_header_problem(path); !problem.empty()) return problem;
  VtkMessageCapture capture;
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  capture.watch(reader.Get());
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (!capture.errors().empty() || reader->GetErrorCode() != 0 || !grid) {
    return capture.errors().empty() ? "the VTK reader failed" : capture.errors();
  }
  std::string error;
  from_vtk(grid, out, error);
  return error;
}

bool read_grid(const std::string& path, TetGrid& out, std::string& error) {
  out = {};
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension != ".vtu" && extension != ".pvtu") {
    error = "'" + path + "': unsupported file type (tetray reads .vtu and .pvtu)";
    return false;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = "'" + path + "': no such file";
    return false;
  }
  error = extension == ".vtu" ? read_vtu(path, out) : read_pvtu(path, out);
  // Indices are checked here, so that a grid read from a file is whole whatever it is used for.
  if (error.empty()) error = grid_problem(out);
  // A piece without cells is a rank that had none; a file with no cell at all has nothing to
  // draw, which is said as such rather than rendered as an empty image.
  if (error.empty() && out.tets.empty()) {
    error = extension == ".pvtu" ? "every piece is empty (no cells): nothing to render"
                                 : "the grid is empty (no cells): nothing to render";
  }
  if (error.empty()) return true;
  out = {};
  error = "'" + path + "': " + error;
  return false;
}

bool write_vtu(const std::string& path, const TetGrid& grid, std::string& error) {
  error = grid_problem(grid);
  if (!error.empty()) {
    error = "cannot write '" + path + "': " + error;
    return false;
  }
  VtkMessageCapture capture;
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  capture.watch(writer.Get());
  writer->SetInputData(to_vtk(grid));
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary, not base64
  writer->WriteToOutputStringOn();  // then written atomically like the images
  if (writer->Write() != 1) {
    error = "cannot write '" + path + "': " + capture.errors();
    return false;
  }
  const std::string& bytes = writer->GetOutputString();
  const render::WriteResult written = render::write_file_atomically(
      path, std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()));
  error = written.message;
  return written.ok;
}

}  // namespace tetray::vtkio
