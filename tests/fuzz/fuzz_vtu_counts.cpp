// The VTK readers on .vtu files whose structure is right and whose counts are the fuzzer's: the
// bytes choose every count attribute of a one-piece ASCII .vtu (points, cells, components, tuples)
// and how many values each array really holds, so that negative, zero, huge and mismatched counts
// come up in the first inputs rather than after a byte-level mutation happens to form one (the
// plain .vtu target ran 41,000 inputs without writing NumberOfCells="-1", which killed VTK 9.1's
// reader). Every input must give a consistent grid or an error message. A file whose counts match
// its arrays and that has no cells is a rank without cells: as a piece of a .pvtu beside a valid
// one, it must be read, adding nothing.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "fuzz_vtk_files.hpp"

namespace {

namespace fs = std::filesystem;
using tetray::fuzz::check_grid;
using tetray::fuzz::fuzz_directory;

// A count as a file might declare it: mostly the values at the edges, else any 64-bit integer.
std::int64_t declared_count(FuzzedDataProvider& input, std::int64_t actual) {
  constexpr std::int64_t kEdges[] = {-1,
                                     0,
                                     1,
                                     2,
                                     std::numeric_limits<std::int32_t>::max(),
                                     std::int64_t{1} << 32,
                                     std::numeric_limits<std::int64_t>::min(),
                                     std::numeric_limits<std::int64_t>::max()};
  switch (input.ConsumeIntegralInRange(0, 3)) {
    case 0:
    case 1:
      return actual;
    case 2:
      return input.PickValueInArray(kEdges);
    default:
      return input.ConsumeIntegral<std::int64_t>();
  }
}

// `count` small integers from the input, separated by spaces.
std::string values(FuzzedDataProvider& input, std::int64_t count, int below) {
  std::string text;
  for (std::int64_t k = 0; k < count; ++k) {
    text += std::to_string(input.ConsumeIntegralInRange(0, below - 1)) + " ";
  }
  return text;
}

std::string repeated(const std::string& text, std::int64_t times) {
  std::string out;
  for (std::int64_t k = 0; k < times; ++k) out += text;
  return out;
}

// Tets of 4 points each: offsets 4, 8, ... (VTK's file leaves out the leading 0).
std::string offsets_text(std::int64_t cells) {
  std::string text;
  for (std::int64_t c = 1; c <= cells; ++c) text += std::to_string(4 * c) + " ";
  return text;
}

struct Counts {
  std::int64_t points = 0, cells = 0, components = 3, tuples = 0;
};

std::string vtu_text(FuzzedDataProvider& input, std::int64_t points, std::int64_t cells,
                     const Counts& declared) {
  const std::string data_array = "<DataArray type=\"Int64\" format=\"ascii\" Name=";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\"><UnstructuredGrid>\n"
         "<Piece NumberOfPoints=\"" +
         std::to_string(declared.points) + "\" NumberOfCells=\"" + std::to_string(declared.cells) +
         "\">\n<PointData><DataArray type=\"Float64\" Name=\"f\" format=\"ascii\" "
         "NumberOfTuples=\"" +
         std::to_string(declared.tuples) + "\">" + values(input, points, 100) +
         "</DataArray></PointData>\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"" +
         std::to_string(declared.components) + "\" format=\"ascii\">" +
         values(input, 3 * points, 4) + "</DataArray></Points>\n<Cells>" + data_array +
         "\"connectivity\">" + values(input, 4 * cells, static_cast<int>(points) + 1) +
         "</DataArray>" + data_array + "\"offsets\">" + offsets_text(cells) +
         "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" +
         repeated("10 ", cells) + "</DataArray></Cells>\n</Piece></UnstructuredGrid></VTKFile>\n";
}

// A rank without cells: its piece beside a valid one adds nothing.
void check_empty_piece_is_read(const fs::path& piece) {
  const fs::path summary = fuzz_directory() / "pieces.pvtu";
  std::ofstream(summary) << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" "
                            "version=\"1.0\"><PUnstructuredGrid GhostLevel=\"0\">"
                            "<PPointData><PDataArray type=\"Float64\" Name=\"f\"/></PPointData>"
                            "<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>"
                            "</PPoints><Piece Source=\"piece.vtu\"/><Piece Source=\""
                         << piece.filename().string() << "\"/></PUnstructuredGrid></VTKFile>\n";
  tetray::vtkio::TetGrid grid;
  std::string error;
  if (!tetray::vtkio::read_grid(summary.string(), grid, error)) std::abort();
  if (grid.tets != std::vector<std::int64_t>{0, 1, 2, 3}) std::abort();
  check_grid(grid);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider input(data, size);
  const std::int64_t points = input.ConsumeIntegralInRange(0, 8);
  const std::int64_t cells = points == 0 ? 0 : input.ConsumeIntegralInRange(0, 3);
  Counts declared;
  declared.points = declared_count(input, points);
  declared.cells = declared_count(input, cells);
  declared.components = declared_count(input, 3);
  declared.tuples = declared_count(input, points);
  const fs::path path = fuzz_directory() / "input.vtu";
  std::ofstream(path, std::ios::trunc) << vtu_text(input, points, cells, declared);

  tetray::fuzz::read_one(path.string());
  const bool truthful = declared.points == points && declared.cells == cells &&
                        declared.components == 3 && declared.tuples == points;
  if (truthful && cells == 0) check_empty_piece_is_read(path);
  return 0;
}
