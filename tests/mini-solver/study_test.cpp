// Study mode: the ladders show the expected orders (space and time errors fall together as
// h^2), and the CSV and the work-precision plot are written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "minisolver/raster.hpp"
#include "minisolver/study.hpp"

namespace minisolver {
namespace {

void expect_final_order_near_two(const std::vector<StudyRow>& rows, const std::string& scheme) {
  const std::vector<double> orders = l2_orders(rows, scheme);
  ASSERT_FALSE(orders.empty()) << scheme;
  EXPECT_NEAR(orders.back(), 2.0, 0.25) << scheme;
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Study, HeatLaddersConvergeAtSecondOrderAndAreWritten) {
  const SerialComm comm;
  std::string error;
  const std::vector<StudyRow> rows = run_study(StudyProblem::heat, comm, 3, error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(rows.size(), 6u);
  expect_final_order_near_two(rows, "backward_euler");
  expect_final_order_near_two(rows, "crank_nicolson");

  const auto dir = std::filesystem::temp_directory_path() / "tetray_study_test";
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(write_study_csv((dir / "heat.csv").string(), rows, error)) << error;
  ASSERT_TRUE(plot_study((dir / "heat.png").string(), rows, error)) << error;
  const std::string csv = read_all(dir / "heat.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
  EXPECT_EQ(csv.rfind("scheme,cells,h,dt,ranks,wall_seconds,l2_error,max_error", 0), 0u);
  EXPECT_EQ(read_all(dir / "heat.png").substr(1, 3), "PNG");
  std::filesystem::remove_all(dir);
}

TEST(Study, ElasticityLaddersConvergeAtSecondOrder) {
  const SerialComm comm;
  std::string error;
  const std::vector<StudyRow> rows = run_study(StudyProblem::elasticity, comm, 3, error);
  ASSERT_TRUE(error.empty()) << error;
  expect_final_order_near_two(rows, "newmark");
  expect_final_order_near_two(rows, "central_difference");
}

TEST(Raster, LinesAndGlyphsLandOnTheirPixels) {
  Raster r(20, 10, {255, 255, 255});
  r.line(1, 1, 18, 8, {0, 0, 0});
  EXPECT_EQ(r.at(1, 1), (Rgb{0, 0, 0}));
  EXPECT_EQ(r.at(18, 8), (Rgb{0, 0, 0}));
  EXPECT_EQ(r.at(18, 1), (Rgb{255, 255, 255}));
  Raster t(8, 8, {255, 255, 255});
  t.text(0, 0, "1", {0, 0, 0}, 1);  // 010 / 110 / 010 / 010 / 111
  EXPECT_EQ(t.at(1, 0), (Rgb{0, 0, 0}));
  EXPECT_EQ(t.at(0, 0), (Rgb{255, 255, 255}));
  EXPECT_EQ(t.at(0, 4), (Rgb{0, 0, 0}));
}

}  // namespace
}  // namespace minisolver
