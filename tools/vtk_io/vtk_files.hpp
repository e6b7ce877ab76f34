// VTK XML files of tet grids for the tools and tests: .vtu and .pvtu in through VTK's readers,
// ParaView .pvd collections, .vtu out (binary, appended). VTK's printed errors come back as the
// error message.
#pragma once

#include <string>
#include <vector>

#include "tetray/vtk_bridge.hpp"

namespace tetray::vtkio {

// Reads a .vtu or .pvtu file into the arrays the VTK bridge takes. Pieces without cells add
// nothing; a file with no cell at all is an error that says it is empty.
bool read_grid(const std::string& path, TetGrid& out, std::string& error);

// The .vtu/.pvtu files and times listed by a ParaView .pvd collection, in time order.
struct SeriesEntry {
  double time = 0;
  std::string path;
};
bool read_pvd(const std::string& path, std::vector<SeriesEntry>& out, std::string& error);

// Writes a .vtu (binary, appended), atomically like the images.
bool write_vtu(const std::string& path, const TetGrid& grid, std::string& error);

}  // namespace tetray::vtkio
