// VTK files of tet grids: write_vtu -> read_grid round trips, .pvtu pieces (empty ones too), the
// error for cells that are not tets, ParaView .pvd collections, and VTK's error text kept off
// stderr.
#include <gtest/gtest.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridWriter.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <fstream>

#include "scenes/box_mesh.hpp"
#include "support/pvtu_summary.hpp"
#include "support/scratch_dir.hpp"
#include "support/text_edit.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::vtkio {
namespace {

using testing::ScratchDir;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The gyroid-twist scene of docs/architecture.md §6 as a TetGrid, with a second field and ghost
// flags.
TetGrid gyroid_grid(int n) {
  const GyroidTwist scene = make_gyroid_twist(n, 0.2);
  TetGrid grid;
  grid.points = scene.mesh.points;
  grid.tets = scene.mesh.tets;
  grid.point_fields["gyroid"] = scene.field;
  std::vector<double>& height = grid.point_fields["height"];
  for (std::size_t p = 0; p < grid.points.size() / 3; ++p) height.push_back(grid.points[3 * p + 1]);
  grid.ghost.assign(grid.tets.size() / 4, 0);
  for (std::size_t t = 0; t < grid.ghost.size(); t += 7) grid.ghost[t] = 1;
  return grid;
}

void expect_same_grid(const TetGrid& a, const TetGrid& b) {
  EXPECT_EQ(a.points, b.points);  // exact: doubles travel as raw binary
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.ghost, b.ghost);
  EXPECT_EQ(a.point_fields, b.point_fields);
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(VtkGrid, WriteThenReadGivesTheSameGrid) {
  ScratchDir dir;
  const TetGrid grid = gyroid_grid(4);
  std::string error;
  ASSERT_TRUE(write_vtu(dir / "grid.vtu", grid, error)) << error;
  TetGrid read;
  ASSERT_TRUE(read_grid(dir / "grid.vtu", read, error)) << error;
  EXPECT_EQ(read.tets.size(), 4u * 6 * 4 * 4 * 4);
  expect_same_grid(grid, read);
}

TEST(VtkGrid, ReadsPiecesOfAParallelFile) {
  ScratchDir dir;
  const TetGrid a = gyroid_grid(2);
  TetGrid b = gyroid_grid(3);
  b.ghost.clear();
  b.ghost.assign(b.tets.size() / 4, 0);
  std::string error;
  ASSERT_TRUE(write_vtu(dir / "part_0.vtu", a, error)) << error;
  ASSERT_TRUE(write_vtu(dir / "part_1.vtu", b, error)) << error;
  write_text(dir / "whole.pvtu",
             testing::pvtu_summary({"part_0.vtu", "part_1.vtu"}, {"gyroid", "height"}, true));
  TetGrid read;
  ASSERT_TRUE(read_grid(dir / "whole.pvtu", read, error)) << error;

  // The pieces are appended: b's point indices shift by a's point count.
  const auto shift = static_cast<std::int64_t>(a.points.size() / 3);
  TetGrid expected = a;
  expected.points.insert(expected.points.end(), b.points.begin(), b.points.end());
  for (std::int64_t v : b.tets) expected.tets.push_back(v + shift);
  expected.ghost.insert(expected.ghost.end(), b.ghost.begin(), b.ghost.end());
  for (auto& [name, values] : expected.point_fields) {
    const std::vector<double>& more = b.point_fields.at(name);
    values.insert(values.end(), more.begin(), more.end());
  }
  expect_same_grid(expected, read);
}

// VTK keeps no cell offsets for a grid without cells; such a piece (a rank that had no cells)
// adds nothing. The pieces are written as two ranks write them with VTK 9.1's own parallel
// writer: rank 0 its grid as piece 0, rank 1 as piece 1 a grid with a point and its fields but no
// cells (VTK writes no file for a piece without points). Without MPI each writer's summary lists
// only its own piece, so the summary of both is the one VTK writes with a controller.
TEST(VtkGrid, AnEmptyPieceWrittenByVtkAddsNothing) {
  ScratchDir dir;
  const TetGrid whole = gyroid_grid(2);
  std::string error;
  ASSERT_TRUE(write_vtu(dir / "whole.vtu", whole, error)) << error;
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir / "whole.vtu").c_str());
  reader->Update();
  vtkNew<vtkUnstructuredGrid> no_cells;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(5, 5, 5);
  no_cells->SetPoints(points);
  for (const char* name : {"gyroid", "height"}) {
    vtkNew<vtkDoubleArray> values;
    values->SetName(name);
    values->InsertNextValue(7);
    no_cells->GetPointData()->AddArray(values);
  }
  for (int rank : {0, 1}) {
    vtkNew<vtkXMLPUnstructuredGridWriter> writer;
    writer->SetInputData(rank == 0 ? reader->GetOutput() : no_cells.Get());
    writer->SetFileName((dir / "pieces.pvtu").c_str());
    writer->SetNumberOfPieces(2);
    writer->SetStartPiece(rank);
    writer->SetEndPiece(rank);
    writer->SetWriteSummaryFile(rank == 0);
    ASSERT_EQ(writer->Write(), 1) << rank;
  }
  TetGrid piece;
  ASSERT_FALSE(read_grid(dir / "pieces_1.vtu", piece, error));
  EXPECT_TRUE(contains(error, "pieces_1.vtu': the grid is empty (no cells)")) << error;

  const std::string text = testing::slurp(dir / "pieces.pvtu");
  const std::string first = "<Piece Source=\"pieces_0.vtu\"/>";
  ASSERT_NE(text.find(first), std::string::npos) << text;
  write_text(dir / "both.pvtu",
             testing::replaced_once(text, first, first + "<Piece Source=\"pieces_1.vtu\"/>"));
  TetGrid read;
  ASSERT_TRUE(read_grid(dir / "both.pvtu", read, error)) << error;
  EXPECT_EQ(read.tets, whole.tets);
  std::vector<double> field = whole.point_fields.at("gyroid");
  field.push_back(7);  // the empty piece's point, which no tet uses
  EXPECT_EQ(read.point_fields.at("gyroid"), field);
}

TEST(VtkGrid, AFileWhoseEveryPieceIsEmptySaysSo) {
  ScratchDir dir;
  std::string error;
  ASSERT_TRUE(write_vtu(dir / "empty.vtu", TetGrid{}, error)) << error;
  write_text(dir / "empty.pvtu", testing::pvtu_summary({"empty.vtu", "empty.vtu"}));
  TetGrid read;
  EXPECT_FALSE(read_grid(dir / "empty.pvtu", read, error));
  EXPECT_TRUE(contains(error, "empty.pvtu': every piece is empty (no cells)")) << error;
  EXPECT_FALSE(read_grid(dir / "empty.vtu", read, error));
  EXPECT_TRUE(contains(error, "empty.vtu': the grid is empty (no cells)")) << error;
}

// A solver's rank with no cells hands the bridge an empty grid: empty, not an error.
TEST(VtkGrid, TheBridgeTakesAGridWithoutCells) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  grid->SetPoints(points);
  TetGrid out;
  std::string error;
  EXPECT_TRUE(from_vtk(grid, out, error)) << error;
  EXPECT_TRUE(out.tets.empty());
  EXPECT_TRUE(out.points.empty());
}

// Two tets and, in between, cell 1 of `type`: the unit cube as a hexahedron, or a triangle.
vtkNew<vtkUnstructuredGrid> grid_with_cell_1(int type) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 8; ++k) points->InsertNextPoint(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  grid->SetPoints(points);
  const vtkIdType tet[4] = {0, 1, 2, 4};
  const vtkIdType hex[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  grid->InsertNextCell(VTK_TETRA, 4, tet);
  grid->InsertNextCell(type, type == VTK_HEXAHEDRON ? 8 : 3, hex);
  grid->InsertNextCell(VTK_TETRA, 4, tet);
  return grid;
}

double tet_volume(const TetGrid& grid, std::size_t t) {
  double e[3][3];
  const double* a = &grid.points[3 * grid.tets[4 * t]];
  for (int k = 0; k < 3; ++k) {
    const double* p = &grid.points[3 * grid.tets[4 * t + k + 1]];
    for (int c = 0; c < 3; ++c) e[k][c] = p[c] - a[c];
  }
  return std::abs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                  e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                  e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6;
}

// The cube becomes six tets that fill it, between the two tets as they were.
TEST(VtkGrid, AHexahedronIsSplitIntoTetsThatFillIt) {
  vtkNew<vtkUnstructuredGrid> grid = grid_with_cell_1(VTK_HEXAHEDRON);
  ScratchDir dir;
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName((dir / "hex.vtu").c_str());
  ASSERT_EQ(writer->Write(), 1);
  for (const bool from_file : {false, true}) {
    TetGrid out;
    std::string error;
    ASSERT_TRUE(from_file ? read_grid(dir / "hex.vtu", out, error) : from_vtk(grid, out, error))
        << error;
    ASSERT_EQ(out.tets.size(), 4u * 8);
    const std::vector<std::int64_t> tet = {0, 1, 2, 4};
    EXPECT_TRUE(std::equal(tet.begin(), tet.end(), out.tets.begin()));
    EXPECT_TRUE(std::equal(tet.begin(), tet.end(), out.tets.end() - 4));
    double cube = 0;
    for (std::size_t t = 1; t < 7; ++t) {
      EXPECT_GT(tet_volume(out, t), 0.1) << "tet " << t;
      cube += tet_volume(out, t);
    }
    EXPECT_NEAR(cube, 1.0, 1e-12);
  }
}

TEST(VtkGrid, ACellTetrayDoesNotSplitIsAnErrorNamingTypeAndCell) {
  vtkNew<vtkUnstructuredGrid> grid = grid_with_cell_1(VTK_TRIANGLE);
  TetGrid out;
  std::string error;
  EXPECT_FALSE(from_vtk(grid, out, error));
  EXPECT_TRUE(contains(error, "cell 1 (VTK cell type 5) is not a cell tetray renders")) << error;

  ScratchDir dir;
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName((dir / "triangle.vtu").c_str());
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_FALSE(read_grid(dir / "triangle.vtu", out, error));
  EXPECT_TRUE(contains(error, dir / "triangle.vtu")) << error;
  EXPECT_TRUE(contains(error, "VTK cell type 5")) << error;
}

TEST(VtkGrid, KeepsOnlyScalarPointArrays) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 4; ++k) points->InsertNextPoint(k == 1, k == 2, k == 3);
  grid->SetPoints(points);
  const vtkIdType tet[4] = {0, 1, 2, 3};
  grid->InsertNextCell(VTK_TETRA, 4, tet);
  vtkNew<vtkDoubleArray> scalar, vector;
  scalar->SetName("temperature");
  vector->SetName("velocity");
  vector->SetNumberOfComponents(3);
  for (int k = 0; k < 4; ++k) {
    scalar->InsertNextValue(10.0 + k);
    vector->InsertNextTuple3(k, k, k);
  }
  grid->GetPointData()->AddArray(scalar);
  grid->GetPointData()->AddArray(vector);

  TetGrid out;
  std::string error;
  ASSERT_TRUE(from_vtk(grid, out, error)) << error;
  EXPECT_EQ(out.tets, (std::vector<std::int64_t>{0, 1, 2, 3}));
  EXPECT_EQ(out.points.size(), 12u);
  ASSERT_EQ(out.point_fields.size(), 1u);
  EXPECT_EQ(out.point_fields.at("temperature"), (std::vector<double>{10, 11, 12, 13}));
  EXPECT_TRUE(out.ghost.empty());
}

TEST(VtkGrid, UnreadableFilesGiveErrorsAndNoVtkNoise) {
  ScratchDir dir;
  write_text(dir / "garbage.vtu", "this is not XML at all");
  write_text(dir / "truncated.vtu", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"");
  write_text(dir / "missing_piece.pvtu", testing::pvtu_summary({"nowhere.vtu"}));
  const std::pair<std::string, std::string> cases[] = {
      {dir / "absent.vtu", "no such file"},
      {dir / "grid.vtk", "unsupported file type"},
      {dir / "garbage.vtu", ""},
      {dir / "truncated.vtu", ""},
      {dir / "missing_piece.pvtu", ""},
  };
  for (const auto& [path, cause] : cases) {
    ::testing::internal::CaptureStderr();
    TetGrid out;
    std::string error;
    const bool read = read_grid(path, out, error);
    const std::string noise = ::testing::internal::GetCapturedStderr();
    EXPECT_FALSE(read) << path;
    EXPECT_TRUE(contains(error, path)) << error;
    EXPECT_TRUE(contains(error, cause)) << error;
    EXPECT_GT(error.size(), path.size() + 4) << "no cause given: " << error;
    EXPECT_EQ(noise, "") << path;
  }
}

TEST(VtkGrid, WriteRejectsInconsistentGrids) {
  ScratchDir dir;
  TetGrid bad_index = gyroid_grid(2);
  bad_index.tets[9] = 1000;
  TetGrid short_field = gyroid_grid(2);
  short_field.point_fields["gyroid"].pop_back();
  for (const TetGrid& grid : {bad_index, short_field}) {
    std::string error;
    EXPECT_FALSE(write_vtu(dir / "bad.vtu", grid, error));
    EXPECT_TRUE(contains(error, dir / "bad.vtu")) << error;
  }
  std::string error;
  EXPECT_FALSE(write_vtu(dir / "no_dir/grid.vtu", gyroid_grid(2), error));
  EXPECT_TRUE(contains(error, "No such file or directory")) << error;
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
}

TEST(VtkGrid, ReadsAParaViewCollectionInTimeOrder) {
  ScratchDir dir;
  std::filesystem::create_directory(dir / "steps");
  write_text(dir / "series.pvd", R"(<?xml version="1.0"?>
<!-- written by hand, entries out of order -->
<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
  <Collection>
    <DataSet timestep="0.5" group="" part="0" file="steps/b.vtu"/>
    <DataSet timestep=" 0.25 " part="0" file="steps/a.pvtu"/>
    <DataSet timestep="1e-3" part="0" file="/abs/first.vtu"/>
    <DataSet timestep="0.5" group="" part="1" file="steps/../steps/c.vtu"/>
  </Collection>
</VTKFile>
)");
  std::vector<SeriesEntry> series;
  std::string error;
  ASSERT_TRUE(read_pvd(dir / "series.pvd", series, error)) << error;
  ASSERT_EQ(series.size(), 4u);
  EXPECT_EQ(series[0].time, 1e-3);
  EXPECT_EQ(series[0].path, "/abs/first.vtu");
  EXPECT_EQ(series[1].time, 0.25);
  EXPECT_EQ(series[1].path, dir / "steps/a.pvtu");
  EXPECT_EQ(series[2].time, 0.5);
  EXPECT_EQ(series[2].path, dir / "steps/b.vtu");
  EXPECT_EQ(series[3].time, 0.5);  // parts of one step keep their order
  EXPECT_EQ(series[3].path, dir / "steps/c.vtu");
}

TEST(VtkGrid, WrittenSeriesReadsBack) {
  ScratchDir dir;
  std::string collection = "<VTKFile type=\"Collection\"><Collection>\n";
  for (int step = 0; step < 3; ++step) {
    const std::string name = "step_" + std::to_string(step) + ".vtu";
    std::string error;
    ASSERT_TRUE(write_vtu(dir / name, gyroid_grid(2 + step), error)) << error;
    collection +=
        "<DataSet timestep=\"" + std::to_string(0.1 * step) + "\" file=\"" + name + "\"/>\n";
  }
  write_text(dir / "run.pvd", collection + "</Collection></VTKFile>\n");
  std::vector<SeriesEntry> series;
  std::string error;
  ASSERT_TRUE(read_pvd(dir / "run.pvd", series, error)) << error;
  ASSERT_EQ(series.size(), 3u);
  for (int step = 0; step < 3; ++step) {
    TetGrid read;
    ASSERT_TRUE(read_grid(series[step].path, read, error)) << error;
    expect_same_grid(gyroid_grid(2 + step), read);
  }
}

TEST(VtkGrid, BadCollectionsGiveErrors) {
  ScratchDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {"<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\"/></Collection></VTKFile>",
       "no file attribute"},
      {"<VTKFile type=\"Collection\"><Collection><DataSet file=\"a.vtu\"/></Collection></VTKFile>",
       "no timestep"},
      {"<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"soon\" file=\"a.vtu\"/>"
       "</Collection></VTKFile>",
       "'soon', not a number"},
      {"<VTKFile type=\"UnstructuredGrid\"></VTKFile>", "not a ParaView collection"},
      {"<VTKFile type=\"Collection\"><Collection>", "not a readable XML file"},
  };
  for (const auto& [text, cause] : cases) {
    write_text(dir / "bad.pvd", text);
    ::testing::internal::CaptureStderr();
    std::vector<SeriesEntry> series;
    std::string error;
    const bool read = read_pvd(dir / "bad.pvd", series, error);
    const std::string noise = ::testing::internal::GetCapturedStderr();
    EXPECT_FALSE(read) << text;
    EXPECT_TRUE(contains(error, dir / "bad.pvd")) << error;
    EXPECT_TRUE(contains(error, cause)) << error;
    EXPECT_TRUE(series.empty());
    EXPECT_EQ(noise, "") << text;
  }
  std::vector<SeriesEntry> series;
  std::string error;
  EXPECT_FALSE(read_pvd(dir / "absent.pvd", series, error));
  EXPECT_TRUE(contains(error, "no such file")) << error;
}

}  // namespace
}  // namespace tetray::vtkio
