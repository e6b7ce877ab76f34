// The text of a .pvtu summary as VTK writes one: Float64 points, the point fields it names
// (Float64), the vtkGhostType cell array if `ghost`, and its pieces' sources in order.
#pragma once

#include <string>
#include <vector>

namespace tetray::testing {

inline std::string pvtu_summary(const std::vector<std::string>& pieces,
                                const std::vector<std::string>& point_fields = {},
                                bool ghost = false) {
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
      "byte_order=\"LittleEndian\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n";
  if (!point_fields.empty()) {
    text += "    <PPointData>\n";
    for (const std::string& name : point_fields) {
      text += "      <PDataArray type=\"Float64\" Name=\"" + name + "\"/>\n";
    }
    text += "    </PPointData>\n";
  }
  if (ghost)
    text += "    <PCellData><PDataArray type=\"UInt8\" Name=\"vtkGhostType\"/></PCellData>\n";
  text += "    <PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>\n";
  for (const std::string& piece : pieces) text += "    <Piece Source=\"" + piece + "\"/>\n";
  return text + "  </PUnstructuredGrid>\n</VTKFile>\n";
}

}  // namespace tetray::testing
