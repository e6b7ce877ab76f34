// The two grid readers behind read_grid (vtk_files.hpp), for the files of this folder only.
// Each returns an empty string on success, else what is wrong (without the path, which
// read_grid puts in front).
#pragma once

#include <string>

#include "tetray/vtk_bridge.hpp"

namespace tetray::vtkio {

// One .vtu through VTK's reader and the VTK bridge (cell types, sizes), after the XML header
// check (xml_header.hpp).
std::string read_vtu(const std::string& path, TetGrid& out);

// A .pvtu as its pieces appended in order (pvtu.cpp).
std::string read_pvtu(const std::string& path, TetGrid& out);

}  // namespace tetray::vtkio
