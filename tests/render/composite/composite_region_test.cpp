// Spans and active rectangles against direct definitions.
#include <gtest/gtest.h>

#include <random>

#include "render/composite/composite_region.hpp"

namespace tetray::render {
namespace {

TEST(SplitSpan, PartsTileTheSpanInOrderWithSizesDifferingByAtMostOne) {
  for (std::uint32_t size : {0u, 1u, 5u, 131u, 257u * 131u}) {
    for (int parts = 1; parts <= 9; ++parts) {
      const PixelSpan span{100, 100 + size};
      std::uint32_t expected_begin = span.begin;
      for (int part = 0; part < parts; ++part) {
        const PixelSpan piece = split_span(span, parts, part);
        EXPECT_EQ(piece.begin, expected_begin);
        EXPECT_LE(piece.size(), size / parts + 1);
        EXPECT_GE(piece.size(), size / parts);
        expected_begin = piece.end;
      }
      EXPECT_EQ(expected_begin, span.end);
    }
  }
}

TEST(ActiveRect, IsTheTightBoundOfActivePixels) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    Framebuffer image(37, 23);
    const int active = trial % 5;  // 0 to 4 active pixels
    PixelRect expected;
    for (int k = 0; k < active; ++k) {
      const int i = static_cast<int>(rng() % 37), j = static_cast<int>(rng() % 23);
      image.depth[image.index(i, j)] = 2.0f;
      expected = united(expected, {i, j, i + 1, j + 1});
    }
    EXPECT_EQ(active_rect(image), expected);
  }
}

TEST(ActiveRect, InfiniteDepthWithAKeyStillCountsAsActive) {
  // wins_over puts (inf, key) ahead of the background (inf, kNoHit), so it must travel.
  Framebuffer image(4, 4);
  image.hit[image.index(2, 3)] = 5;
  EXPECT_EQ(active_rect(image), (PixelRect{2, 3, 3, 4}));
}

}  // namespace
}  // namespace tetray::render
