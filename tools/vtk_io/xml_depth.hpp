// VTK's XML parser keeps the element tree it reads and frees it recursively, one stack frame
// per level: a file of some 100000 nested elements overflows the stack. The files are scanned
// for their nesting depth before VTK sees them.
#pragma once

#include <string>

namespace tetray::vtkio {

// Deeper than any VTK file (VTKFile > UnstructuredGrid > Piece > PointData > DataArray is 5).
inline constexpr int kMaxXmlDepth = 64;

// Empty when the elements of the XML file nest at most kMaxXmlDepth deep, else what is wrong.
// The scan stops at raw appended data (binary, not XML), so a large .vtu costs only its header.
std::string xml_depth_problem(const std::string& path);

}  // namespace tetray::vtkio
