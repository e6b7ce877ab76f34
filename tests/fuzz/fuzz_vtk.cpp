// The VTK readers on arbitrary bytes: VTK reads files, so each input is written to a file with
// the extension TETRAY_FUZZ_EXTENSION (.vtu, .pvtu or .pvd) in a private directory that also
// holds a valid piece, piece.vtu, and one without cells, empty.vtu (a rank that had none), for
// .pvtu and .pvd inputs to refer to (fuzz_vtk_files.hpp). Every input must give a grid (or
// series) or an error message; a series' entries are read as replay reads them.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_vtk_files.hpp"

using tetray::fuzz::fuzz_directory;
using tetray::fuzz::read_one;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = (fuzz_directory() / ("input" TETRAY_FUZZ_EXTENSION)).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  if (std::string_view(TETRAY_FUZZ_EXTENSION) != ".pvd") {
    read_one(path);
    return 0;
  }
  std::vector<tetray::vtkio::SeriesEntry> series;
  std::string error;
  if (!tetray::vtkio::read_pvd(path, series, error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  // The first few entries, as tetray-replay would read them (an entry naming the input
  // itself is a .pvd and is refused by read_grid).
  for (std::size_t k = 0; k < series.size() && k < 4; ++k) read_one(series[k].path);
  return 0;
}
