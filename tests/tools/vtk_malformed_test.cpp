// Malformed VTK files and grids that once crashed the readers or were read wrong: a tet whose
// cell has fewer than 4 point ids (it borrowed its neighbour's, a heap over-read at the end),
// cells with no cell type, cells on a grid with no points, XML nested so deep that VTK's
// recursive element tree overflows the stack (.vtu, a .pvtu's piece, a .pvd series), and headers
// that announce sizes the file cannot hold (VTK loops over or allocates them before it reads a
// value), points of 2 components. Each must be refused with a message naming the file and the
// cause.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "support/pvtu_summary.hpp"
#include "support/scratch_dir.hpp"
#include "support/text_edit.hpp"
#include "tools/vtk_io/vtk_files.hpp"
#include "tools/vtk_io/xml_header.hpp"

namespace tetray::vtkio {
namespace {

using testing::ScratchDir;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Point field f = 0, 1, 2, 3 of a 4-point piece.
const std::string kFieldF =
    "<PointData><DataArray type=\"Float64\" Name=\"f\" format=\"ascii\">0 1 2 3</DataArray>"
    "</PointData>\n";

// A one-piece ASCII .vtu with the unit tet's points (or `points_xml`) and the given cells; with
// 4 points also the field f.
std::string vtu_text(const std::string& connectivity, const std::string& offsets,
                     const std::string& types, int cells, std::int64_t points = 4,
                     const std::string& points_xml =
                         "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                         "format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>") {
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <UnstructuredGrid>
    <Piece NumberOfPoints=")" +
         std::to_string(points) + "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n" +
         (points == 4 ? kFieldF : "") + points_xml + R"(
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">)" +
         connectivity + R"(</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">)" +
         offsets + R"(</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">)" +
         types + R"(</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";
}

// `depth` nested elements inside `outer_open` ... `outer_close`.
std::string deeply_nested(const std::string& outer_open, const std::string& outer_close,
                          int depth) {
  std::string text = "<?xml version=\"1.0\"?>\n" + outer_open;
  for (int k = 0; k < depth; ++k) text += "<a>";
  for (int k = 0; k < depth; ++k) text += "</a>";
  return text + outer_close;
}

std::string read_error(const std::string& path) {
  TetGrid out;
  std::string error;
  EXPECT_FALSE(read_grid(path, out, error)) << path;
  EXPECT_TRUE(out.tets.empty() && out.points.empty()) << path;
  EXPECT_TRUE(contains(error, path)) << error;
  return error;
}

TEST(VtkMalformed, ATetCellWithThreeIdsIsRefused) {
  ScratchDir dir;
  write_text(dir / "three.vtu", vtu_text("0 1 2", "3", "10", 1));
  write_text(dir / "three_then_four.vtu", vtu_text("0 1 2 0 1 2 3", "3 7", "10 10", 2));
  EXPECT_TRUE(
      contains(read_error(dir / "three.vtu"), "cell 0 (VTK cell type 10) has 3 nodes, not 4"));
  EXPECT_TRUE(contains(read_error(dir / "three_then_four.vtu"),
                       "cell 0 (VTK cell type 10) has 3 nodes, not 4"));
}

TEST(VtkMalformed, ATetCellWithFiveIdsIsRefused) {
  ScratchDir dir;
  write_text(dir / "five.vtu", vtu_text("0 1 2 3 0 1 2 3", "5 8", "10 10", 2));
  EXPECT_TRUE(
      contains(read_error(dir / "five.vtu"), "cell 0 (VTK cell type 10) has 5 nodes, not 4"));
}

// The bridge gets grids from solvers too: a cell array whose cells do not hold 4 ids each is
// refused, not copied 4 ids at a time past the end of the connectivity.
TEST(VtkMalformed, BridgeRefusesTetsOfTheWrongSize) {
  vtkNew<vtkPoints> points;
  for (int p = 0; p < 4; ++p) points->InsertNextPoint(p == 1, p == 2, p == 3);
  vtkNew<vtkCellArray> cells;
  const vtkIdType triangle[3] = {0, 1, 2};
  cells->InsertNextCell(3, triangle);
  vtkNew<vtkUnsignedCharArray> types;
  types->InsertNextValue(VTK_TETRA);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(types, cells);
  TetGrid out;
  std::string error;
  EXPECT_FALSE(from_vtk(grid, out, error));
  EXPECT_TRUE(contains(error, "cell 0 (VTK cell type 10) has 3 nodes, not 4")) << error;
}

TEST(VtkMalformed, BridgeRefusesCellsWithoutATypeArray) {
  vtkNew<vtkPoints> points;
  for (int p = 0; p < 4; ++p) points->InsertNextPoint(p == 1, p == 2, p == 3);
  vtkNew<vtkCellArray> cells;
  const vtkIdType tet[4] = {0, 1, 2, 3};
  cells->InsertNextCell(4, tet);
  cells->InsertNextCell(4, tet);
  vtkNew<vtkUnsignedCharArray> types;
  types->InsertNextValue(VTK_TETRA);  // one type for two cells
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(types, cells);
  TetGrid out;
  std::string error;
  EXPECT_FALSE(from_vtk(grid, out, error));
  EXPECT_TRUE(contains(error, "cell 1 has no cell type")) << error;
}

TEST(VtkMalformed, CellsOnAGridWithoutPointsAreRefused) {
  ScratchDir dir;
  const std::string no_points =
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
      "</DataArray></Points>";
  write_text(dir / "no_points.vtu", vtu_text("0 1 2 3", "4", "10", 1, 0, no_points));
  EXPECT_TRUE(contains(read_error(dir / "no_points.vtu"), "outside [0, 0)"));
  write_text(dir / "no_points_element.vtu", vtu_text("0 1 2 3", "4", "10", 1, 4, ""));
  read_error(dir / "no_points_element.vtu");
}

TEST(VtkMalformed, DeeplyNestedFilesAreRefusedBeforeVtkReadsThem) {
  ScratchDir dir;
  const int depth = 200000;  // enough to overflow VTK's recursive element destructor
  write_text(dir / "deep.vtu",
             deeply_nested("<VTKFile type=\"UnstructuredGrid\">", "</VTKFile>\n", depth));
  EXPECT_TRUE(contains(read_error(dir / "deep.vtu"), "nest deeper than"));

  write_text(dir / "deep_piece.vtu",
             deeply_nested("<VTKFile type=\"UnstructuredGrid\">", "</VTKFile>\n", depth));
  write_text(dir / "whole.pvtu", testing::pvtu_summary({"deep_piece.vtu"}));
  const std::string piece_error = read_error(dir / "whole.pvtu");
  EXPECT_TRUE(contains(piece_error, "deep_piece.vtu")) << piece_error;
  EXPECT_TRUE(contains(piece_error, "nest deeper than")) << piece_error;

  write_text(dir / "deep.pvd", deeply_nested("<VTKFile type=\"Collection\"><Collection>",
                                             "</Collection></VTKFile>\n", depth));
  std::vector<SeriesEntry> series;
  std::string error;
  EXPECT_FALSE(read_pvd(dir / "deep.pvd", series, error));
  EXPECT_TRUE(contains(error, "nest deeper than")) << error;
}

// A .pvtu summary whose array types or component counts differ from its pieces' (found by the
// .pvtu fuzzer) made VTK's parallel reader write through a null pointer or past its buffers.
// The pieces are read as they are and appended, whatever the summary says of their types.
TEST(VtkMalformed, ASummaryThatMisdescribesItsPiecesReadsThePieces) {
  ScratchDir dir;
  write_text(dir / "piece.vtu", vtu_text("0 1 2 3", "4", "10", 1));
  const std::pair<const char*, const char*> summaries[] = {
      {"<PDataArray type=\"Float64\" Name=\"f\"/>", "<PDataArray type=\"Float64\"/>"},
      {"<PDataArray type=\"Float64\" Name=\"f\"/>",
       "<PDataArray type=\"Float64\" NumberOfComponents=\"2\"/>"},
      {"<PDataArray type=\"Float64\" Name=\"f\"/>",
       "<PDataArray type=\"Float32\" NumberOfComponents=\"3\"/>"},
      {"<PDataArray type=\"Int8\" Name=\"f\"/>",
       "<PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>"},
  };
  for (const auto& [point_data, points] : summaries) {
    write_text(dir / "whole.pvtu", std::string(R"(<?xml version="1.0"?>
<VTKFile type="PUnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PUnstructuredGrid GhostLevel="0">
    <PPointData>)") + point_data + "</PPointData>\n    <PPoints>" +
                                       points +
                                       R"(</PPoints>
    <Piece Source="piece.vtu"/>
    <Piece Source="piece.vtu"/>
  </PUnstructuredGrid>
</VTKFile>
)");
    TetGrid out;
    std::string error;
    ASSERT_TRUE(read_grid(dir / "whole.pvtu", out, error)) << point_data << points << error;
    EXPECT_EQ(out.points, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1,
                                               0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}));
    EXPECT_EQ(out.tets, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7}));
    EXPECT_EQ(out.point_fields.at("f"), (std::vector<double>{0, 1, 2, 3, 0, 1, 2, 3}));
  }
}

TEST(VtkMalformed, ASummaryNamingAnArrayAPieceLacksIsAnError) {
  ScratchDir dir;
  write_text(dir / "piece.vtu", vtu_text("0 1 2 3", "4", "10", 1));
  write_text(dir / "whole.pvtu", testing::pvtu_summary({"piece.vtu"}, {"g"}));
  const std::string error = read_error(dir / "whole.pvtu");
  EXPECT_TRUE(contains(error, "piece.vtu': has no scalar point array 'g'")) << error;
  write_text(dir / "empty.pvtu", "<VTKFile><PUnstructuredGrid/></VTKFile>");
  EXPECT_TRUE(contains(read_error(dir / "empty.pvtu"), "lists no Piece"));
}

// The depth scan counts elements, not text that looks like them, and stops at raw data.
TEST(VtkMalformed, DepthScanSkipsCommentsQuotesAndRawData) {
  ScratchDir dir;
  std::string fine = "<?xml version=\"1.0\"?>\n<!-- <a><a><a> -->\n<r attr=\"<a>\">";
  for (int k = 0; k < kMaxXmlDepth - 1; ++k) fine += "<a><b/>";
  fine += "<![CDATA[<a><a>]]>";
  for (int k = 0; k < kMaxXmlDepth - 1; ++k) fine += "</a>";
  fine += "</r>";
  write_text(dir / "fine.xml", fine);
  EXPECT_EQ(xml_header_problem(dir / "fine.xml"), "");

  std::string raw = "<VTKFile><AppendedData encoding=\"raw\">_";
  for (int k = 0; k < 2 * kMaxXmlDepth; ++k) raw += "<a>";
  write_text(dir / "raw.vtu", raw);
  EXPECT_EQ(xml_header_problem(dir / "raw.vtu"), "");

  std::string deep = "<r>";
  for (int k = 0; k < kMaxXmlDepth; ++k) deep += "<a>";
  write_text(dir / "deep.xml", deep);
  EXPECT_TRUE(contains(xml_header_problem(dir / "deep.xml"), "nest deeper than"));
}

// A Points array of 2 components: VTK's vtkPoints refuses it and its reader then reads the
// coordinates into an array with no room (VTK 9.1 reports that, and leaks its array iterator:
// tests/fuzz/lsan.supp). Refused by the header scan before VTK reads the file.
TEST(VtkMalformed, PointsOfTwoComponentsAreRefused) {
  ScratchDir dir;
  write_text(dir / "flat.vtu",
             vtu_text("0 1 2 3", "4", "10", 1, 4,
                      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"2\" "
                      "format=\"ascii\">0 0 1 0 0 1 1 1</DataArray></Points>"));
  const std::string error = read_error(dir / "flat.vtu");
  EXPECT_TRUE(contains(error, dir / "flat.vtu")) << error;
  EXPECT_TRUE(contains(error,
                       "point coordinates (<Points><DataArray>) have "
                       "NumberOfComponents=\"2\", not 3"))
      << error;
  // Only the coordinates: a two-component field elsewhere is VTK's to judge, and nothing after
  // </Points> counts as inside.
  write_text(dir / "fine.vtu",
             "<VTKFile><Piece><Points><DataArray NumberOfComponents=\"3\"/></Points>"
             "<PointData><DataArray NumberOfComponents=\"2\"/></PointData></Piece></VTKFile>");
  EXPECT_EQ(xml_header_problem(dir / "fine.vtu"), "");
}

// A header's sizes must fit the file: billions of components made VTK loop for minutes, billions
// of points made it allocate tens of GB. The unit tet's own header passes; compressed data may
// announce more values than it has bytes.
TEST(VtkMalformed, HeaderSizesBeyondTheFileAreRefused) {
  ScratchDir dir;
  const std::string good = vtu_text("0 1 2 3", "4", "10", 1);
  write_text(dir / "good.vtu", good);
  EXPECT_EQ(xml_header_problem(dir / "good.vtu"), "");

  write_text(dir / "components.vtu", testing::replaced_once(good, "NumberOfComponents=\"3\"",
                                                            "NumberOfComponents = \"2000000000\""));
  EXPECT_TRUE(contains(read_error(dir / "components.vtu"),
                       "<DataArray> declares NumberOfComponents=\"2000000000\", more than 1024"));

  write_text(dir / "points.vtu", vtu_text("0 1 2 3", "4", "10", 1, 3000000000));
  EXPECT_TRUE(contains(read_error(dir / "points.vtu"),
                       "<Piece> declares NumberOfPoints=\"3000000000\", more values than"));
  write_text(dir / "overflow.vtu", vtu_text("0 1 2 3", "4", "10", 1, 4) + "<a NumberOfTuples=\"" +
                                       std::string(40, '9') + "\"/>");
  EXPECT_TRUE(contains(read_error(dir / "overflow.vtu"), "NumberOfTuples"));

  const std::string compressed =
      "<VTKFile compressor=\"vtkZLibDataCompressor\"><Piece NumberOfPoints=\"5000\"/></VTKFile>";
  write_text(dir / "compressed.vtu", compressed);
  EXPECT_EQ(xml_header_problem(dir / "compressed.vtu"), "");
  write_text(dir / "plain.vtu", testing::replaced_once(compressed, "compressor", "compressee"));
  EXPECT_TRUE(contains(xml_header_problem(dir / "plain.vtu"), "NumberOfPoints=\"5000\""));
}

// A negative count made VTK 9.1's reader size a memset with it (NumberOfCells="-1" died with
// SIGSEGV in vtkXMLUnstructuredGridReader::SetupOutputData). Every count, and an appended data
// offset, is refused below zero (and the offset beyond the file) before VTK reads the file.
TEST(VtkMalformed, NegativeCountsAndOffsetsAreRefusedBeforeVtkReadsThem) {
  ScratchDir dir;
  const std::string good = vtu_text("0 1 2 3", "4", "10", 1);
  struct Change {
    std::string from, to, attribute;
  };
  const Change changes[] = {
      {"NumberOfCells=\"1\"", "NumberOfCells=\"-1\"", "NumberOfCells"},
      {"NumberOfCells=\"1\"", "NumberOfCells=\"-99999999999999999999999\"", "NumberOfCells"},
      {"NumberOfPoints=\"4\"", "NumberOfPoints=\" -4\"", "NumberOfPoints"},
      {"NumberOfComponents=\"3\"", "NumberOfComponents=\"-3\"", "NumberOfComponents"},
      {"Name=\"offsets\"", "Name=\"offsets\" NumberOfTuples=\"-2\"", "NumberOfTuples"},
      {"Name=\"offsets\"", "Name=\"offsets\" offset=\"-8\"", "offset"},
      {"<UnstructuredGrid>", "<UnstructuredGrid NumberOfPieces=\"-1\">", "NumberOfPieces"},
  };
  for (const Change& change : changes) {
    write_text(dir / "negative.vtu", testing::replaced_once(good, change.from, change.to));
    const std::string error = read_error(dir / "negative.vtu");
    EXPECT_TRUE(contains(error, "declares " + change.attribute + "="))
        << change.to << ": " << error;
    EXPECT_TRUE(contains(error, "a negative number")) << change.to << ": " << error;
  }
  write_text(dir / "beyond.vtu", testing::replaced_once(good, "Name=\"offsets\"",
                                                        "Name=\"offsets\" offset=\"100000\""));
  EXPECT_TRUE(contains(read_error(dir / "beyond.vtu"), "offset=\"100000\", beyond the end"));
}

// The same file through a .pvtu's piece: the piece is named with the cause.
TEST(VtkMalformed, ANegativeCountInAPieceNamesThePiece) {
  ScratchDir dir;
  write_text(dir / "piece.vtu",
             testing::replaced_once(vtu_text("0 1 2 3", "4", "10", 1), "NumberOfCells=\"1\"",
                                    "NumberOfCells=\"-1\""));
  write_text(dir / "whole.pvtu", testing::pvtu_summary({"piece.vtu"}));
  const std::string error = read_error(dir / "whole.pvtu");
  EXPECT_TRUE(contains(error, "piece.vtu': <Piece> declares NumberOfCells=\"-1\", a negative"))
      << error;
}

}  // namespace
}  // namespace tetray::vtkio
