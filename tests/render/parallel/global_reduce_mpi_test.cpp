// Global bounds and value ranges: each rank contributes known values (rank 1 none at all), and
// the unions are checked against their closed forms.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "render/parallel/global_reduce.hpp"

namespace tetray::render {
namespace {

int rank_count() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Rank r holds the points (r, -r, 2r) and (r + 0.5, 0, 0) and the values r - 1 and 3r; rank 1
// holds nothing.
TEST(GlobalReduce, UnionOfBoundsAndRangesOverRanks) {
  const int r = rank();
  const int last = rank_count() - 1;
  std::vector<double> xyz;
  std::vector<float> values;
  if (r != 1) {
    xyz = {double(r), double(-r), 2.0 * r, r + 0.5, 0.0, 0.0};
    values = {float(r - 1), float(3 * r)};
  }
  BoundingBox box = local_bounds<double>(xyz);
  std::array<ValueRange, 2> ranges = {local_range<float>(values), ValueRange{}};
  ASSERT_EQ(global_bounds_and_ranges(box, ranges, MPI_COMM_WORLD), MPI_SUCCESS);
  // With two ranks, rank 1 (the last) holds nothing.
  const int top = last == 1 ? 0 : last;
  EXPECT_EQ(box.lo().x, 0.0);
  EXPECT_EQ(box.hi().x, top + 0.5);
  EXPECT_EQ(box.lo().y, double(-top));
  EXPECT_EQ(box.hi().y, 0.0);
  EXPECT_EQ(box.lo().z, 0.0);
  EXPECT_EQ(box.hi().z, 2.0 * top);
  EXPECT_EQ(ranges[0].lo, -1.0);
  EXPECT_EQ(ranges[0].hi, 3.0 * top);
  EXPECT_TRUE(ranges[1].empty());
}

TEST(GlobalReduce, AllRanksEmptyStayEmpty) {
  std::array<ValueRange, 3> ranges{};
  ASSERT_EQ(global_ranges(ranges, MPI_COMM_WORLD), MPI_SUCCESS);
  for (const ValueRange& range : ranges) EXPECT_TRUE(range.empty());
}

TEST(GlobalReduce, NonFiniteValuesAreIgnored) {
  const std::vector<double> values = {std::nan(""), 2.0, INFINITY, -1.0, -INFINITY};
  const ValueRange range = local_range<double>(values);
  EXPECT_EQ(range.lo, -1.0);
  EXPECT_EQ(range.hi, 2.0);
}

}  // namespace
}  // namespace tetray::render
