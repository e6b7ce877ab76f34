// tetray-bench's error-against-time studies on a tiny mesh, and the generic log-log plot script
// on their CSVs. --dvr-study: the CSV has the exact integral and five fixed steps, the exact
// integral has the smallest error against the dense reference, the error of fixed-step sampling
// falls as the step shrinks (and is not zero: the reference is not any of the images).
// --lod-study: a row per threshold with sane figures, exact at the finest and approximate at the
// coarsest, plotted one series per mesh size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "plane_scene.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

double number(const std::vector<std::vector<std::string>>& csv, std::size_t row,
              const std::string& column) {
  return std::stod(cell(csv, row, column));
}

TEST(DvrStudy, ExactIsBestAndFixedStepErrorFallsWithTheStep) {
  ScratchDir dir;
  const fs::path table = dir.path() / "study.csv", plot = dir.path() / "study.png";
  const std::string bench = std::string(TETRAY_BENCH_EXECUTABLE) +
                            " --sizes 4 --size-px 32 --threads 2 --dvr-study " + table.string() +
                            " > /dev/null";
  ASSERT_EQ(std::system(bench.c_str()), 0) << bench;
  const auto csv = read_csv(table.string());
  ASSERT_EQ(csv.size(), 7u);
  EXPECT_EQ(csv[0], (std::vector<std::string>{"step", "ms", "mean_error", "max_error"}));
  EXPECT_EQ(cell(csv, 1, "step"), "exact");
  const double exact_mean = number(csv, 1, "mean_error"), exact_max = number(csv, 1, "max_error");
  EXPECT_GT(exact_mean, 0);  // the reference is an independent image
  double previous = INFINITY;
  for (std::size_t r = 2; r < csv.size(); ++r) {
    EXPECT_EQ(number(csv, r, "step"), std::ldexp(1.0, -static_cast<int>(r - 2)));
    EXPECT_GT(number(csv, r, "ms"), 0);
    const double mean = number(csv, r, "mean_error");
    EXPECT_LT(mean, previous) << "row " << r;
    EXPECT_GT(mean, exact_mean) << "row " << r;
    EXPECT_GT(number(csv, r, "max_error"), exact_max) << "row " << r;
    previous = mean;
  }
  const std::string plot_command = "/usr/bin/python3 " + std::string(TETRAY_LOGLOG_PLOT) + " " +
                                   table.string() +
                                   " --x ms --y mean_error max_error --label step --alone exact "
                                   "--out " +
                                   plot.string();
  ASSERT_EQ(std::system(plot_command.c_str()), 0) << plot_command;
  const PngPixels png = read_png_rgba8(plot.string());
  ASSERT_TRUE(png.error.empty()) << png.error;
  EXPECT_EQ(png.width, 640);
  EXPECT_EQ(png.height, 480);
}

TEST(LodStudy, ExactAtTheFinestThresholdApproximateAtTheCoarsest) {
  ScratchDir dir;
  const fs::path table = dir.path() / "lod.csv", plot = dir.path() / "lod.png";
  const std::string bench = std::string(TETRAY_BENCH_EXECUTABLE) +
                            " --sizes 4,6 --size-px 64 --threads 2 --lod-study " + table.string() +
                            " > /dev/null";
  ASSERT_EQ(std::system(bench.c_str()), 0) << bench;
  const auto csv = read_csv(table.string());
  ASSERT_EQ(csv.size(), 15u);  // the header and 7 thresholds per size
  for (std::size_t r = 1; r < csv.size(); ++r) {
    const double n = number(csv, r, "n");
    EXPECT_EQ(number(csv, r, "tets"), 6 * n * n * n);
    for (const char* positive : {"frame_ms", "exact_ms", "embree_trace_ms", "node_fit_ms"})
      EXPECT_GT(number(csv, r, positive), 0) << positive << " in row " << r;
    const double fraction = number(csv, r, "hit_miss_fraction");
    EXPECT_GE(fraction, 0);
    EXPECT_LE(fraction, 1);
  }
  // At 1 pixel no node of these meshes is narrow enough; at 64 the whole mesh is (64 pixels).
  EXPECT_EQ(number(csv, 1, "node_pixels"), 1);
  EXPECT_EQ(number(csv, 1, "hit_miss_fraction"), 0);
  EXPECT_EQ(number(csv, 1, "depth_error_median_px"), 0);
  EXPECT_EQ(number(csv, 7, "node_pixels"), 64);
  EXPECT_GT(number(csv, 7, "color_error_mean"), 0);
  const std::string plot_command = "/usr/bin/python3 " + std::string(TETRAY_LOGLOG_PLOT) + " " +
                                   table.string() +
                                   " --x frame_ms --y hit_miss_fraction color_error_mean "
                                   "--label node_pixels --group tets --out " +
                                   plot.string() + " 2> /dev/null";
  ASSERT_EQ(std::system(plot_command.c_str()), 0) << plot_command;
  const PngPixels png = read_png_rgba8(plot.string());
  ASSERT_TRUE(png.error.empty()) << png.error;
  EXPECT_EQ(png.width, 640);
}

}  // namespace
}  // namespace tetray::testing
