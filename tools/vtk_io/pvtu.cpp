// Parallel .pvtu files: <VTKFile type="PUnstructuredGrid"><PUnstructuredGrid><PPointData>
// <PDataArray Name="f"/>...<Piece Source="part_0.vtu"/>... The pieces are read one by one as
// .vtu files and appended here rather than by VTK's vtkXMLPUnstructuredGridReader, which copies
// each piece's raw arrays into arrays typed by the summary: a summary whose types or component
// counts differ from its pieces' (Float32 points over Float64 pieces, no NumberOfComponents)
// made it write past its buffers or through a null pointer.
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <filesystem>
#include <string_view>
#include <vector>

#include "tools/vtk_io/grid_readers.hpp"
#include "tools/vtk_io/vtk_message_capture.hpp"
#include "tools/vtk_io/xml_header.hpp"

namespace tetray::vtkio {
namespace {

// What the summary says: the pieces (resolved against its directory) and the arrays it names.
struct Summary {
  std::vector<std::string> pieces;
  std::vector<std::string> point_fields;
  bool ghost = false;  // PCellData names vtkGhostType
};

bool named(vtkXMLDataElement* element, std::string_view name) {
  return element->GetName() && std::string_view(element->GetName()) == name;
}

// The Name attributes of the PDataArray elements of `data` (PPointData or PCellData).
std::vector<std::string> array_names(vtkXMLDataElement* data) {
  std::vector<std::string> names;
  for (int k = 0; k < data->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* array = data->GetNestedElement(k);
    const char* name = array->GetAttribute("Name");
    if (named(array, "PDataArray") && name && *name) names.emplace_back(name);
  }
  return names;
}

std::string read_summary(const std::string& path, Summary& summary) {
  if (std::string problem = xml_header_problem(path); !problem.empty()) return problem;
  VtkMessageCapture capture;
  vtkNew<vtkXMLDataParser> parser;
  capture.watch(parser.Get());
  parser->SetFileName(path.c_str());
  if (parser->Parse() != 1 || !parser->GetRootElement()) {
    return "not a readable XML file" +
           (capture.errors().empty() ? "" : " (" + capture.errors() + ")");
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  vtkXMLDataElement* grid = root->FindNestedElementWithName("PUnstructuredGrid");
  if (!named(root, "VTKFile") || !grid) return "not a parallel unstructured grid (.pvtu)";
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();
  for (int k = 0; k < grid->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* element = grid->GetNestedElement(k);
    if (named(element, "PPointData")) {
      // Point ghost flags (DOLFINx writes them) are not a field: the pieces' reader skips them.
      for (std::string& name : array_names(element)) {
        if (name != "vtkGhostType") summary.point_fields.push_back(std::move(name));
      }
    }
    if (named(element, "PCellData")) {
      for (const std::string& name : array_names(element)) summary.ghost |= name == "vtkGhostType";
    }
    if (!named(element, "Piece")) continue;
    const char* source = element->GetAttribute("Source");
    if (!source || !*source) {
      return "Piece " + std::to_string(summary.pieces.size()) + " has no Source attribute";
    }
    summary.pieces.push_back((directory / source).lexically_normal().string());
  }
  if (summary.pieces.empty()) return "lists no Piece";
  return {};
}

// Appends `piece` to `out`, keeping the fields the summary names; empty or what is missing.
std::string append_piece(const Summary& summary, TetGrid& piece, TetGrid& out) {
  for (const std::string& name : summary.point_fields) {
    auto field = piece.point_fields.find(name);
    if (field == piece.point_fields.end()) return "has no scalar point array '" + name + "'";
    std::vector<double>& values = out.point_fields[name];
    values.insert(values.end(), field->second.begin(), field->second.end());
  }
  // A piece without cells has no cell arrays to flag.
  if (summary.ghost && piece.ghost.empty() && !piece.tets.empty()) {
    return "has no vtkGhostType cell array";
  }
  const auto shift = static_cast<std::int64_t>(out.points.size() / 3);
  out.points.insert(out.points.end(), piece.points.begin(), piece.points.end());
  for (const std::int64_t v : piece.tets) out.tets.push_back(v + shift);
  out.ghost.insert(out.ghost.end(), piece.ghost.begin(), piece.ghost.end());
  return {};
}

}  // namespace

std::string read_pvtu(const std::string& path, TetGrid& out) {
  Summary summary;
  if (std::string error = read_summary(path, summary); !error.empty()) return error;
  for (const std::string& source : summary.pieces) {
    std::error_code ec;
    TetGrid piece;
    std::string error = std::filesystem::is_regular_file(source, ec) ? read_vtu(source, piece)
                                                                     : std::string("no such file");
    if (error.empty()) error = append_piece(summary, piece, out);
    if (!error.empty()) return "piece '" + source + "': " + error;
  }
  return {};
}

}  // namespace tetray::vtkio
