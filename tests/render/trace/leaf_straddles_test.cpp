// The frame's shared record of which tets of each leaf straddle (render/trace/leaf_straddles.hpp):
// a leaf's tets are tested once per frame, a new frame knows nothing of the last, a frame
// started inside another keeps its own record, and a leaf whose every tet straddles (the word
// that also means "unknown") still reads its true bits.
#include <gtest/gtest.h>

#include <cstdint>

#include "render/trace/leaf_straddles.hpp"

namespace tetray::test {
namespace {

using render::LeafStraddles;

// find() for a leaf: counts its calls and gives `bits`.
struct CountingFind {
  std::uint64_t bits;
  int calls = 0;
  std::uint64_t operator()() {
    ++calls;
    return bits;
  }
};

TEST(LeafStraddles, EachLeafIsTestedOncePerFrame) {
  LeafStraddles straddles(8);
  CountingFind leaf3{0b1011}, leaf5{0};
  for (int visit = 0; visit < 3; ++visit) {
    EXPECT_EQ(straddles.of(3, [&] { return leaf3(); }), 0b1011u);
    EXPECT_EQ(straddles.of(5, [&] { return leaf5(); }), 0u);
  }
  EXPECT_EQ(leaf3.calls, 1);
  EXPECT_EQ(leaf5.calls, 1);
}

TEST(LeafStraddles, ANewFrameKnowsNothingOfTheLast) {
  {
    LeafStraddles first(8);
    EXPECT_EQ(first.of(2, [] { return std::uint64_t{0b110}; }), 0b110u);
  }
  LeafStraddles second(8);  // the same thread: its kept storage again
  CountingFind leaf2{0b1};
  EXPECT_EQ(second.of(2, [&] { return leaf2(); }), 0b1u);
  EXPECT_EQ(leaf2.calls, 1);
}

TEST(LeafStraddles, AFrameStartedInsideAnotherKeepsItsOwnRecord) {
  LeafStraddles outer(4);
  EXPECT_EQ(outer.of(1, [] { return std::uint64_t{0b10}; }), 0b10u);
  {
    LeafStraddles inner(4);
    EXPECT_EQ(inner.of(1, [] { return std::uint64_t{0b01}; }), 0b01u);
  }
  CountingFind again{0b11};
  EXPECT_EQ(outer.of(1, [&] { return again(); }), 0b10u) << "the inner frame wrote the outer's";
  EXPECT_EQ(again.calls, 0);
}

TEST(LeafStraddles, AFullLeafOfStraddlingTetsReadsItsBits) {
  LeafStraddles straddles(2);
  constexpr std::uint64_t kAll = ~std::uint64_t{0};
  CountingFind full{kAll};
  EXPECT_EQ(straddles.of(0, [&] { return full(); }), kAll);
  EXPECT_EQ(straddles.of(0, [&] { return full(); }), kAll);
}

}  // namespace
}  // namespace tetray::test
