// ParaView .pvd collections: <VTKFile type="Collection"><Collection><DataSet timestep="0.1"
// file="step_1.vtu"/>...</Collection></VTKFile>. ParaView's own vtkPVDReader is not part of VTK,
// so the XML is parsed with VTK's generic XML parser and the entries are read here.
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <algorithm>
#include <charconv>
#include <filesystem>

#include "tools/vtk_io/vtk_files.hpp"
#include "tools/vtk_io/vtk_message_capture.hpp"
#include "tools/vtk_io/xml_header.hpp"

namespace tetray::vtkio {
namespace {

bool parse_double(const char* text, double& value) {
  const char* end = text + std::char_traits<char>::length(text);
  while (text != end && std::isspace(static_cast<unsigned char>(*text))) ++text;
  while (end != text && std::isspace(static_cast<unsigned char>(end[-1]))) --end;
  const auto [stop, ec] = std::from_chars(text, end, value);
  return ec == std::errc() && stop == end && text != end;
}

// Relative file names in a collection are relative to the collection's own directory.
std::string resolve(const std::filesystem::path& directory, const char* file) {
  const std::filesystem::path path(file);
  return path.is_absolute() ? path.string() : (directory / path).lexically_normal().string();
}

// One <DataSet> entry; an empty string on success, else what is wrong with it.
std::string read_entry(vtkXMLDataElement* dataset, int index,
                       const std::filesystem::path& directory, SeriesEntry& entry) {
  const std::string where = "DataSet " + std::to_string(index);
  const char* file = dataset->GetAttribute("file");
  if (!file || !*file) return where + " has no file attribute";
  const char* timestep = dataset->GetAttribute("timestep");
  if (!timestep) return where + " (" + file + ") has no timestep attribute";
  if (!parse_double(timestep, entry.time)) {
    return where + " (" + file + ") has timestep '" + timestep + "', not a number";
  }
  entry.path = resolve(directory, file);
  return {};
}

vtkXMLDataElement* collection_of(vtkXMLDataElement* root) {
  if (!root || std::string_view(root->GetName()) != "VTKFile") return nullptr;
  const char* type = root->GetAttribute("type");
  if (type && std::string_view(type) != "Collection") return nullptr;
  return root->FindNestedElementWithName("Collection");
}

}  // namespace

bool read_pvd(const std::string& path, std::vector<SeriesEntry>& out, std::string& error) {
  out.clear();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = "'" + path + "': no such file";
    return false;
  }
  if (std::string problem = xml_header_problem(path); !problem.empty()) {
    error = "'" + path + "': " + problem;
    return false;
  }
  VtkMessageCapture capture;
  vtkNew<vtkXMLDataParser> parser;
  capture.watch(parser.Get());
  parser->SetFileName(path.c_str());
  if (parser->Parse() != 1) {
    error = "'" + path + "': not a readable XML file" +
            (capture.errors().empty() ? "" : " (" + capture.errors() + ")");
    return false;
  }
  vtkXMLDataElement* collection = collection_of(parser->GetRootElement());
  if (!collection) {
    error = "'" + path + "': not a ParaView collection (<VTKFile type=\"Collection\">)";
    return false;
  }
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();
  for (int k = 0; k < collection->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* element = collection->GetNestedElement(k);
    if (std::string_view(element->GetName()) != "DataSet") continue;
    SeriesEntry entry;
    error = read_entry(element, static_cast<int>(out.size()), directory, entry);
    if (!error.empty()) {
      error = "'" + path + "': " + error;
      out.clear();
      return false;
    }
    out.push_back(entry);
  }
  // Stable: parts of one time step (same timestep, several files) keep their listed order.
  std::stable_sort(out.begin(), out.end(),
                   [](const SeriesEntry& a, const SeriesEntry& b) { return a.time < b.time; });
  return true;
}

}  // namespace tetray::vtkio
