// The schedule: for every rank count up to a large machine, the rounds multiply out to the
// ranks that take part, the folded ranks each have a partner, and binary swap is pure radix 2.
#include <gtest/gtest.h>

#include <bit>
#include <functional>
#include <numeric>

#include "render/composite/composite_plan.hpp"

namespace tetray::render {
namespace {

int product(const std::vector<int>& radices) {
  return std::accumulate(radices.begin(), radices.end(), 1, std::multiplies<>());
}

TEST(CompositePlan, RoundsCoverTheTakingPartRanksForEveryCount) {
  for (CompositeAlgorithm algorithm :
       {CompositeAlgorithm::automatic, CompositeAlgorithm::binary_swap,
        CompositeAlgorithm::radix_k}) {
    for (int ranks = 1; ranks <= 17000; ++ranks) {
      const CompositePlan plan = make_plan(ranks, algorithm);
      ASSERT_EQ(plan.rank_count, ranks);
      ASSERT_EQ(product(plan.radices), plan.swap_count) << ranks;
      // Each folded rank needs its own partner among the taking-part ranks.
      ASSERT_LE(plan.folded_count(), plan.swap_count) << ranks;
      for (int k : plan.radices) {
        ASSERT_GE(k, 2);
        ASSERT_LE(k, kMaxRadix);
      }
    }
  }
}

TEST(CompositePlan, AutomaticIsRadixKWithRadicesOfAtMostEightAndFoldsNothingForSmoothCounts) {
  // Powers of two: as many radices of 8 as fit, the rest in one smaller radix.
  for (int ranks : {2, 4, 8, 64, 1024, 4096, 16384}) {
    const CompositePlan plan = make_plan(ranks, CompositeAlgorithm::automatic);
    const int log2 = std::countr_zero(unsigned(ranks));
    std::vector<int> expected(static_cast<std::size_t>(log2 / 3), 8);
    if (log2 % 3 != 0) expected.push_back(1 << (log2 % 3));
    EXPECT_EQ(plan.radices, expected) << ranks;
    EXPECT_EQ(plan.folded_count(), 0);
  }
  for (int ranks : {3, 5, 6, 7, 12, 1000}) {
    EXPECT_EQ(make_plan(ranks, CompositeAlgorithm::automatic).folded_count(), 0) << ranks;
  }
  EXPECT_EQ(make_plan(11, CompositeAlgorithm::automatic).swap_count, 10);
  EXPECT_EQ(make_plan(5, CompositeAlgorithm::binary_swap).swap_count, 4);
  EXPECT_EQ(make_plan(16, CompositeAlgorithm::binary_swap).radices, std::vector<int>(4, 2));
}

TEST(CompositePlan, GatherHasNoRoundsBeforeTheFinalOne) {
  const CompositePlan plan = make_plan(6, CompositeAlgorithm::gather);
  EXPECT_TRUE(plan.radices.empty());
  EXPECT_EQ(plan.swap_count, 6);
  EXPECT_EQ(plan.round_count(), 1);
}

TEST(CompositePlan, GroupMembersShareEveryOtherDigit) {
  const CompositePlan plan = make_plan(60, CompositeAlgorithm::radix_k);
  for (std::size_t round = 0; round < plan.radices.size(); ++round) {
    for (int v = 0; v < plan.swap_count; ++v) {
      const RoundPosition position = round_position(plan, static_cast<int>(round), v);
      const int first_member = v - position.digit * position.stride;
      for (int d = 0; d < plan.radices[round]; ++d) {
        const int member = first_member + d * position.stride;
        ASSERT_EQ(round_position(plan, static_cast<int>(round), member).digit, d);
      }
    }
  }
}

}  // namespace
}  // namespace tetray::render
