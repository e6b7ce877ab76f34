// The frame's shared record of which tets of each leaf straddle (render/trace/leaf_straddles.hpp):
// a leaf's tets are tested once per frame, a new frame knows nothing of the last, a frame
// started inside another keeps its own record, and a leaf whose every tet straddles (the word
// that also means "unknown") still reads its true bits. Every copy of the record's code is
// checked: the baseline's and each instruction-set variant's (culling_copies.hpp).
#include <gtest/gtest.h>

#include <cstdint>

#include "culling_copies.hpp"

namespace tetray::test {
namespace {

// find() for a leaf: counts its calls and gives `bits`.
struct CountingFind {
  std::uint64_t bits;
  int calls = 0;
  std::uint64_t operator()() {
    ++calls;
    return bits;
  }
};

// One frame's record, made, read and ended by one copy of the code.
class Frame {
 public:
  Frame(const render::CullingKernels& kernels, std::size_t nodes)
      : kernels_(kernels), straddles_(kernels.start_frame(nodes)) {}
  ~Frame() { kernels_.end_frame(straddles_); }
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;

  std::uint64_t of(std::size_t leaf, CountingFind& find) {
    return kernels_.leaf_straddles_of(
        *straddles_, leaf, [](void* f) { return (*static_cast<CountingFind*>(f))(); }, &find);
  }
  std::uint64_t of(std::size_t leaf, std::uint64_t bits) {
    CountingFind find{bits};
    return of(leaf, find);
  }

 private:
  const render::CullingKernels& kernels_;
  render::LeafStraddles* straddles_;
};

class LeafStraddles : public CullingCopies {};
TETRAY_FOR_EACH_CULLING_COPY(LeafStraddles);

TEST_P(LeafStraddles, EachLeafIsTestedOncePerFrame) {
  Frame straddles(kernels(), 8);
  CountingFind leaf3{0b1011}, leaf5{0};
  for (int visit = 0; visit < 3; ++visit) {
    EXPECT_EQ(straddles.of(3, leaf3), 0b1011u);
    EXPECT_EQ(straddles.of(5, leaf5), 0u);
  }
  EXPECT_EQ(leaf3.calls, 1);
  EXPECT_EQ(leaf5.calls, 1);
}

TEST_P(LeafStraddles, ANewFrameKnowsNothingOfTheLast) {
  {
    Frame first(kernels(), 8);
    EXPECT_EQ(first.of(2, 0b110), 0b110u);
  }
  Frame second(kernels(), 8);  // the same thread: its kept storage again
  CountingFind leaf2{0b1};
  EXPECT_EQ(second.of(2, leaf2), 0b1u);
  EXPECT_EQ(leaf2.calls, 1);
}

TEST_P(LeafStraddles, AFrameStartedInsideAnotherKeepsItsOwnRecord) {
  Frame outer(kernels(), 4);
  EXPECT_EQ(outer.of(1, 0b10), 0b10u);
  {
    Frame inner(kernels(), 4);
    EXPECT_EQ(inner.of(1, 0b01), 0b01u);
  }
  CountingFind again{0b11};
  EXPECT_EQ(outer.of(1, again), 0b10u) << "the inner frame wrote the outer's";
  EXPECT_EQ(again.calls, 0);
}

TEST_P(LeafStraddles, AFullLeafOfStraddlingTetsReadsItsBits) {
  Frame straddles(kernels(), 2);
  constexpr std::uint64_t kAll = ~std::uint64_t{0};
  CountingFind full{kAll};
  EXPECT_EQ(straddles.of(0, full), kAll);
  EXPECT_EQ(straddles.of(0, full), kAll);
}

}  // namespace
}  // namespace tetray::test
