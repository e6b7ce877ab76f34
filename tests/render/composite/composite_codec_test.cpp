// The wire format: its layout word by word, a piece composited into an empty image gives back
// exactly the piece's active pixels, compositing keeps the pixel the depth rule picks, copying
// writes exactly the message's pixels, and bad messages are refused without touching the image.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "render/composite/composite_codec.hpp"
#include "run_images.hpp"

namespace tetray::render {
namespace {

using testing::differs_from_background;
using testing::run_image;

constexpr float kInf = std::numeric_limits<float>::infinity();

std::size_t active_count(const Framebuffer& image, PixelSpan span) {
  std::size_t count = 0;
  for (std::uint32_t p = span.begin; p < span.end; ++p) count += differs_from_background(image, p);
  return count;
}

bool same_pixel(const Framebuffer& a, const Framebuffer& b, std::size_t p) {
  bool same =
      std::bit_cast<std::uint32_t>(a.depth[p]) == std::bit_cast<std::uint32_t>(b.depth[p]) &&
      a.hit[p] == b.hit[p];
  for (int c = 0; c < 4; ++c) same = same && a.rgba[4 * p + c] == b.rgba[4 * p + c];
  return same;
}

std::size_t count_differences(const Framebuffer& a, const Framebuffer& b) {
  std::size_t differences = 0;
  for (std::size_t p = 0; p < a.pixel_count(); ++p) differences += same_pixel(a, b, p) ? 0 : 1;
  return differences;
}

void set_pixel(Framebuffer& image, std::size_t p, float depth, std::uint32_t hit, float color) {
  image.depth[p] = depth;
  image.hit[p] = hit;
  for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = color + 0.125f * static_cast<float>(c);
}

std::uint32_t bits(float value) { return std::bit_cast<std::uint32_t>(value); }

TEST(CompositeCodec, LaysOutEachRunAsColorsThenDepthsThenKeys) {
  // 5 x 3: pixels 3, 4 (row 0) and 5, 6 (row 1) make one run across the rows; pixel 13 another.
  Framebuffer image(5, 3);
  for (std::size_t p : {3u, 4u, 5u, 6u, 13u}) {
    set_pixel(image, p, static_cast<float>(p), 100u + static_cast<std::uint32_t>(p),
              static_cast<float>(p));
  }
  const PieceMessage message = encode_piece(image, {1, 15}, {0, 0, 5, 3});
  std::vector<std::uint32_t> expected = {1, 2, 5, 0, 0, 5, 3};  // start, runs, pixels, rect
  expected.insert(expected.end(), {2, 4});                      // skip 3 - 1, 4 pixels
  for (std::size_t p : {3u, 4u, 5u, 6u}) {
    for (int c = 0; c < 4; ++c)
      expected.push_back(bits(static_cast<float>(p) + 0.125f * static_cast<float>(c)));
  }
  for (std::size_t p : {3u, 4u, 5u, 6u}) expected.push_back(bits(static_cast<float>(p)));
  for (std::uint32_t p : {3u, 4u, 5u, 6u}) expected.push_back(100u + p);
  expected.insert(expected.end(), {6, 1});  // skip 13 - 7, 1 pixel
  for (int c = 0; c < 4; ++c) expected.push_back(bits(13.0f + 0.125f * static_cast<float>(c)));
  expected.insert(expected.end(), {bits(13.0f), 113u});
  EXPECT_EQ(std::vector<std::uint32_t>(message.begin(), message.end()), expected);
}

// Spans of an image of `pixels` pixels: all of it, one pixel, its end, an empty one, one across
// rows, and 20 random ones.
std::vector<PixelSpan> test_spans(std::uint32_t pixels, std::mt19937& rng) {
  std::vector<PixelSpan> spans = {
      {0, pixels}, {40, 41}, {pixels - 7, pixels}, {500, 500}, {60, 170}};
  for (int k = 0; k < 20; ++k) {
    const auto a = static_cast<std::uint32_t>(rng() % (pixels + 1));
    const auto b = static_cast<std::uint32_t>(rng() % (pixels + 1));
    spans.push_back({std::min(a, b), std::max(a, b)});
  }
  return spans;
}

TEST(CompositeCodec, RoundTripRestoresTheSpanAndNothingElse) {
  std::mt19937 rng(3);
  for (int longest : {2, 20, 200}) {
    const Framebuffer image = run_image(57, 31, static_cast<std::uint32_t>(longest), longest);
    const auto pixels = static_cast<std::uint32_t>(image.pixel_count());
    const Framebuffer empty(57, 31);
    const std::vector<PixelSpan> spans = test_spans(pixels, rng);
    for (const PixelSpan span : spans) {
      const PieceMessage message = encode_piece(image, span, active_rect(image));
      Framebuffer received(57, 31);
      ASSERT_TRUE(composite_piece(received, message).has_value());
      std::size_t wrong = 0;
      for (std::uint32_t p = 0; p < pixels; ++p) {
        const bool inside = p >= span.begin && p < span.end;
        wrong += same_pixel(received, inside ? image : empty, p) ? 0 : 1;
      }
      EXPECT_EQ(wrong, 0u) << "runs up to " << longest << ", span " << span.begin << " "
                           << span.end;
    }
  }
}

// Interlaced (RowOrder): a span of schedule indices carries the pixels of the image rows its
// schedule rows stand for, and composites exactly those back, with a loose hint or a tight one.
TEST(CompositeCodec, InterlacedRoundTripRestoresTheImageRowsOfTheSpan) {
  std::mt19937 rng(5);
  constexpr int kWidth = 57, kHeight = 31;
  const std::vector<std::uint32_t> rows = interlaced_rows(kHeight);
  const RowOrder order{rows};
  for (int longest : {2, 20, 200}) {
    const Framebuffer image =
        run_image(kWidth, kHeight, static_cast<std::uint32_t>(longest), longest);
    const auto pixels = static_cast<std::uint32_t>(image.pixel_count());
    const Framebuffer empty(kWidth, kHeight);
    const std::vector<PixelSpan> spans = test_spans(pixels, rng);
    for (const PixelSpan span : spans) {
      for (const PixelRect hint : {active_rect(image), PixelRect{0, 0, kWidth, kHeight}}) {
        const PieceMessage message = encode_piece(image, span, hint, order);
        Framebuffer received(kWidth, kHeight);
        ASSERT_TRUE(composite_piece(received, message, order).has_value());
        std::vector<bool> inside(pixels, false);
        for (std::uint32_t s = span.begin; s < span.end; ++s) {
          inside[rows[s / kWidth] * kWidth + s % kWidth] = true;
        }
        std::size_t wrong = 0;
        for (std::uint32_t p = 0; p < pixels; ++p) {
          wrong += same_pixel(received, inside[p] ? image : empty, p) ? 0 : 1;
        }
        EXPECT_EQ(wrong, 0u) << "runs up to " << longest << ", span " << span.begin << " "
                             << span.end;
      }
    }
  }
}

// Interlaced rows are not neighbours in the image: a run ends with its row, and a message whose
// run crosses a row is refused in that order (taken in natural order, where it is well formed).
TEST(CompositeCodec, InterlacedRunsEndWithTheirRow) {
  Framebuffer image(37, 40);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    set_pixel(image, p, 2.0f, static_cast<std::uint32_t>(p), 0.5f);
  }
  const std::vector<std::uint32_t> rows = interlaced_rows(40);
  const PixelSpan span{30, 1300};  // schedule rows 0 to 35
  const PieceMessage interlaced = encode_piece(image, span, active_rect(image), {rows});
  EXPECT_EQ(interlaced[1], 36u);
  EXPECT_EQ(interlaced[2], span.size());
  EXPECT_LE(interlaced.size(), piece_capacity(image, span));
  const PieceMessage natural = encode_piece(image, span, active_rect(image));
  ASSERT_EQ(natural[1], 1u);
  Framebuffer received(37, 40);
  EXPECT_FALSE(composite_piece(received, natural, {rows}).has_value());
  EXPECT_EQ(count_differences(received, Framebuffer(37, 40)), 0u);
  EXPECT_TRUE(composite_piece(received, natural).has_value());
}

TEST(CompositeCodec, MessageHoldsOnlyActivePixelsAndTheirRuns) {
  const Framebuffer image = run_image(64, 20, 5, 9);
  const PixelSpan span{70, 1000};
  const PieceMessage message = encode_piece(image, span, active_rect(image));
  const std::size_t runs = message[1];
  EXPECT_EQ(message[2], active_count(image, span));
  EXPECT_EQ(message.size(), kPieceHeaderWords + kRunHeaderWords * runs + kPixelWords * message[2]);
  // Runs are maximal: at least one background pixel separates two of them.
  EXPECT_LE(runs, span.size() - message[2] + 1);
}

TEST(CompositeCodec, AnAllActiveSpanIsOneRunAcrossItsRows) {
  Framebuffer image(37, 40);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    set_pixel(image, p, 2.0f, static_cast<std::uint32_t>(p), 0.5f);
  }
  const PixelSpan span{30, 1300};
  const PieceMessage message = encode_piece(image, span, active_rect(image));
  EXPECT_EQ(message[1], 1u);
  EXPECT_EQ(message[2], span.size());
  EXPECT_EQ(message.size(), kPieceHeaderWords + kRunHeaderWords + kPixelWords * span.size());
  Framebuffer received(37, 40);
  const auto rect = composite_piece(received, message);
  ASSERT_TRUE(rect.has_value());
  EXPECT_EQ(*rect, (PixelRect{0, 0, 37, 36}));
  for (std::uint32_t p = span.begin; p < span.end; ++p) EXPECT_TRUE(same_pixel(received, image, p));
}

TEST(CompositeCodec, AnAllBackgroundSpanIsTheHeaderAlone) {
  Framebuffer image(37, 40);
  image.depth[0] = 1.0f;  // active, but outside the span
  const PieceMessage message = encode_piece(image, {1, 1480}, {0, 0, 37, 40});
  EXPECT_EQ(std::vector<std::uint32_t>(message.begin(), message.end()),
            (std::vector<std::uint32_t>{1, 0, 0, 0, 0, 0, 0}));
  Framebuffer received(37, 40);
  const auto rect = composite_piece(received, message);
  ASSERT_TRUE(rect.has_value());
  EXPECT_TRUE(rect->empty());
  EXPECT_EQ(count_differences(received, Framebuffer(37, 40)), 0u);
}

TEST(CompositeCodec, ReportsTheTightRectangleOfTheActivePixelsSent) {
  Framebuffer image(20, 10);
  for (auto [i, j] : {std::pair{3, 2}, std::pair{15, 4}, std::pair{7, 8}}) {
    image.depth[image.index(i, j)] = 1.0f;
  }
  Framebuffer received(20, 10);
  const auto rect = composite_piece(received, encode_piece(image, {0, 200}, {0, 0, 20, 10}));
  ASSERT_TRUE(rect.has_value());
  EXPECT_EQ(*rect, (PixelRect{3, 2, 16, 9}));
}

TEST(CompositeCodec, KeepsTheNearerPixelAndBreaksTiesByTheSmallerKey) {
  Framebuffer mine(3, 1), theirs(3, 1);
  const float depths_mine[] = {1.0f, 2.0f, 2.0f}, depths_theirs[] = {2.0f, 1.0f, 2.0f};
  const std::uint32_t keys_mine[] = {9, 9, 9}, keys_theirs[] = {1, 1, 4};
  for (int p = 0; p < 3; ++p) {
    mine.depth[p] = depths_mine[p];
    mine.hit[p] = keys_mine[p];
    theirs.depth[p] = depths_theirs[p];
    theirs.hit[p] = keys_theirs[p];
  }
  ASSERT_TRUE(composite_piece(mine, encode_piece(theirs, {0, 3}, {0, 0, 3, 1})).has_value());
  EXPECT_EQ(mine.hit[0], 9u);
  EXPECT_EQ(mine.hit[1], 1u);
  EXPECT_EQ(mine.hit[2], 4u);
}

TEST(CompositeCodec, CompositesRandomRunsAsTheDepthOrderSays) {
  for (int longest : {3, 30, 300}) {
    const auto seed = static_cast<std::uint32_t>(longest);
    const Framebuffer theirs = run_image(131, 23, seed, longest);
    Framebuffer mine = run_image(131, 23, seed + 1, longest);
    // The rule of docs/architecture.md §3 as the order of (depth, key) pairs, pixel by pixel.
    Framebuffer expected = mine;
    for (std::size_t p = 0; p < mine.pixel_count(); ++p) {
      if (std::pair{theirs.depth[p], theirs.hit[p]} < std::pair{mine.depth[p], mine.hit[p]}) {
        expected.depth[p] = theirs.depth[p];
        expected.hit[p] = theirs.hit[p];
        for (int c = 0; c < 4; ++c) expected.rgba[4 * p + c] = theirs.rgba[4 * p + c];
      }
    }
    const auto pixels = static_cast<std::uint32_t>(mine.pixel_count());
    ASSERT_TRUE(
        composite_piece(mine, encode_piece(theirs, {0, pixels}, active_rect(theirs))).has_value());
    EXPECT_EQ(count_differences(mine, expected), 0u) << "runs up to " << longest;
  }
}

// A message of one run of 12 pixels (pixels 2 to 13 of a 16 x 1 image).
PieceMessage twelve_pixel_message() {
  Framebuffer image(16, 1);
  for (std::size_t p = 2; p < 14; ++p)
    set_pixel(image, p, 1.0f, static_cast<std::uint32_t>(p), 0.25f);
  return encode_piece(image, {0, 16}, {0, 0, 16, 1});
}

// Decodes `message` with both decoders into an image that is not empty and says whether either
// accepted it; a refusal must leave the image as it was.
bool accepted(std::span<const std::uint32_t> message) {
  const Framebuffer before = run_image(16, 1, 7, 3);
  Framebuffer composited = before, copied = before;
  const bool either =
      composite_piece(composited, message).has_value() || copy_piece(copied, message).has_value();
  if (!either) {
    EXPECT_EQ(count_differences(composited, before), 0u);
    EXPECT_EQ(count_differences(copied, before), 0u);
  }
  return either;
}

TEST(CompositeCodec, RefusesAMessageCutInsideEachArray) {
  const PieceMessage whole = twelve_pixel_message();
  ASSERT_EQ(whole.size(), kPieceHeaderWords + kRunHeaderWords + 12 * kPixelWords);
  EXPECT_TRUE(accepted(whole));
  const std::size_t colors = kPieceHeaderWords + kRunHeaderWords;
  const std::size_t depths = colors + 4 * 12, keys = depths + 12;
  // Cut one word after the start of, or one word into, each array: the length gives it away.
  for (std::size_t cut : {colors + 1, colors + 30, depths + 1, depths + 7, keys + 1, keys + 11}) {
    EXPECT_FALSE(accepted(std::span<const std::uint32_t>(whole).first(cut))) << cut;
  }
  // Cut by whole pixels with the header's pixel count lowered to match: the length agrees, and
  // the run, still of 12 pixels, ends past the message. 6, 18 and 30 words end inside the keys,
  // the depths and the colors.
  for (std::size_t pixels_cut : {1u, 3u, 5u}) {
    PieceMessage cut = whole;
    cut.resize(whole.size() - kPixelWords * pixels_cut);
    cut[2] -= static_cast<std::uint32_t>(pixels_cut);
    EXPECT_FALSE(accepted(cut)) << pixels_cut;
  }
}

TEST(CompositeCodec, RefusesWordsBeyondItsRuns) {
  PieceMessage longer = twelve_pixel_message();
  longer.insert(longer.end(), kPixelWords, 0u);
  longer[2] += 1;  // the header counts a pixel that no run holds
  EXPECT_FALSE(accepted(longer));
}

TEST(CompositeCodec, RefusesARectangleOutsideTheImage) {
  for (std::size_t word : {3u, 4u, 5u, 6u}) {
    PieceMessage message = twelve_pixel_message();
    message[word] = word == 3 ? 15u : 17u;  // x0 past x1, or past the image's 16 x 1
    EXPECT_FALSE(accepted(message)) << word;
  }
}

TEST(CompositeCodec, RefusesTruncatedAndOutOfRangeMessages) {
  const Framebuffer image = run_image(16, 16, 9, 5);
  PieceMessage message = encode_piece(image, {0, 256}, active_rect(image));
  Framebuffer small(8, 8);
  EXPECT_FALSE(composite_piece(small, message).has_value());
  EXPECT_FALSE(copy_piece(small, message).has_value());
  message.pop_back();
  Framebuffer target(16, 16);
  EXPECT_FALSE(composite_piece(target, message).has_value());
  EXPECT_FALSE(
      composite_piece(target, std::span<const std::uint32_t>(message).first(3)).has_value());
  EXPECT_FALSE(copy_piece(target, std::span<const std::uint32_t>(message).first(3)).has_value());
  // A run that starts inside the image and ends past it.
  PieceMessage past_the_end = twelve_pixel_message();
  past_the_end[kPieceHeaderWords] = 5;  // pixels 5 to 16 of 16
  EXPECT_FALSE(accepted(past_the_end));
}

TEST(CopyPiece, WritesExactlyTheMessagesPixels) {
  for (int longest : {2, 25, 400}) {
    const Framebuffer theirs =
        run_image(93, 17, 40u + static_cast<std::uint32_t>(longest), longest);
    // Every pixel here is nearer than any of theirs: compositing would keep them all.
    Framebuffer mine(93, 17);
    for (std::size_t p = 0; p < mine.pixel_count(); ++p) set_pixel(mine, p, 0.0f, 0u, 0.75f);
    const Framebuffer before = mine;
    const PixelSpan span{150, 1400};
    const auto rect = copy_piece(mine, encode_piece(theirs, span, active_rect(theirs)));
    ASSERT_TRUE(rect.has_value());
    std::size_t wrong = 0;
    PixelRect written;
    for (std::uint32_t p = 0; p < mine.pixel_count(); ++p) {
      const bool sent = p >= span.begin && p < span.end && differs_from_background(theirs, p);
      wrong += same_pixel(mine, sent ? theirs : before, p) ? 0 : 1;
      const int i = static_cast<int>(p % 93), j = static_cast<int>(p / 93);
      if (sent) written = united(written, {i, j, i + 1, j + 1});
    }
    EXPECT_EQ(wrong, 0u) << "runs up to " << longest;
    EXPECT_EQ(*rect, written);
  }
}

TEST(CopyPiece, WritesInfinitelyFarPixelsWithAKey) {
  Framebuffer theirs(8, 1), mine(8, 1);
  theirs.hit[3] = 42;  // depth +infinity, but a key: active
  set_pixel(mine, 3, 1.0f, 1u, 0.5f);
  ASSERT_TRUE(copy_piece(mine, encode_piece(theirs, {0, 8}, {0, 0, 8, 1})).has_value());
  EXPECT_EQ(mine.depth[3], kInf);
  EXPECT_EQ(mine.hit[3], 42u);
  EXPECT_EQ(mine.rgba[12], 0.0f);
}

}  // namespace
}  // namespace tetray::render
