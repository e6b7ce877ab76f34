// Spans, the activity scans and active rectangles against direct definitions.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <limits>
#include <random>

#include "render/composite/composite_region.hpp"
#include "run_images.hpp"

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

// Every row once; in bit-reversed order for a power of two, so that each aligned run of 2^k
// schedule rows holds one row of each of the image's 2^k bands; any height keeps its rows in
// the order of their reversed numbers.
TEST(InterlacedRows, TakeEveryRowOnceInTheOrderOfTheirReversedBits) {
  for (int height = 1; height <= 70; ++height) {
    const std::vector<std::uint32_t> rows = interlaced_rows(height);
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(height));
    std::vector<std::uint32_t> sorted = rows;
    std::sort(sorted.begin(), sorted.end());
    for (int j = 0; j < height; ++j) EXPECT_EQ(sorted[static_cast<std::size_t>(j)], j);
  }
  const std::vector<std::uint32_t> rows = interlaced_rows(64);
  for (const int bands : {2, 4, 8, 16}) {
    const int band = 64 / bands;
    for (int first = 0; first < 64; first += bands) {
      std::vector<int> per_band(static_cast<std::size_t>(bands), 0);
      for (int v = first; v < first + bands; ++v)
        ++per_band[rows[static_cast<std::size_t>(v)] / band];
      for (int count : per_band) EXPECT_EQ(count, 1) << bands << " bands from row " << first;
    }
  }
  EXPECT_EQ(interlaced_rows(6), (std::vector<std::uint32_t>{0, 4, 2, 1, 5, 3}));
  EXPECT_TRUE(interlaced_rows(0).empty());
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

TEST(IsActive, IsWinningOverTheBackground) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (float depth :
       {-kInf, -1.0f, -0.0f, 0.0f, 3.5f, std::numeric_limits<float>::max(), kInf, std::nanf("")}) {
    for (std::uint32_t hit : {0u, 5u, kNoHit - 1, kNoHit}) {
      EXPECT_EQ(is_active(depth, hit), wins_over(depth, hit, kInf, kNoHit))
          << "depth " << depth << " key " << hit;
    }
  }
}

// The first pixel of [begin, end) whose activity is not `active`, one pixel at a time.
std::uint32_t run_end_by_pixels(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                                bool active) {
  while (begin < end && testing::differs_from_background(image, begin) == active) ++begin;
  return begin;
}

std::uint32_t run_start_by_pixels(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                                  bool active) {
  while (end > begin && testing::differs_from_background(image, end - 1) == active) --end;
  return end;
}

TEST(ActivityScan, FindsTheEndsOfRunsAsAPixelByPixelScanDoes) {
  std::mt19937 rng(11);
  for (int longest : {3, 40, 300}) {
    const Framebuffer image =
        testing::run_image(311, 17, 5u + static_cast<std::uint32_t>(longest), longest);
    const auto pixels = static_cast<std::uint32_t>(image.pixel_count());
    for (int trial = 0; trial < 2000; ++trial) {
      std::uint32_t begin = static_cast<std::uint32_t>(rng() % (pixels + 1));
      std::uint32_t end = static_cast<std::uint32_t>(rng() % (pixels + 1));
      if (begin > end) std::swap(begin, end);
      for (bool active : {false, true}) {
        EXPECT_EQ(run_end(image, begin, end, active), run_end_by_pixels(image, begin, end, active))
            << begin << " " << end << " " << active;
        EXPECT_EQ(run_start(image, begin, end, active),
                  run_start_by_pixels(image, begin, end, active))
            << begin << " " << end << " " << active;
      }
    }
  }
}

TEST(ActivityScan, CrossesWholeBlocksOfOneKind) {
  Framebuffer image(100, 1);
  EXPECT_EQ(run_end(image, 3, 100, false), 100u);
  EXPECT_EQ(run_start(image, 0, 97, false), 0u);
  image.hit[70] = 1;  // infinitely far with a key: active
  EXPECT_EQ(run_end(image, 3, 100, false), 70u);
  EXPECT_EQ(run_start(image, 0, 100, false), 71u);
  for (std::size_t p = 0; p < 100; ++p) image.depth[p] = 1.0f;
  EXPECT_EQ(run_end(image, 1, 99, true), 99u);
  EXPECT_EQ(run_start(image, 1, 99, true), 1u);
  image.depth[20] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(run_end(image, 1, 99, true), 20u);
  EXPECT_EQ(run_start(image, 1, 99, true), 21u);
}

TEST(ActiveRect, BoundsRandomRuns) {
  for (int longest : {2, 50, 900}) {
    const Framebuffer image =
        testing::run_image(203, 9, 3u * static_cast<std::uint32_t>(longest), longest);
    PixelRect expected;
    for (int j = 0; j < image.height; ++j) {
      for (int i = 0; i < image.width; ++i) {
        if (testing::differs_from_background(image, image.index(i, j))) {
          expected = united(expected, {i, j, i + 1, j + 1});
        }
      }
    }
    EXPECT_EQ(active_rect(image), expected) << longest;
  }
}

}  // namespace
}  // namespace tetray::render
