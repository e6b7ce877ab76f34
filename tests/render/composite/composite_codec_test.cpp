// The wire format: a piece composited into an empty image gives back exactly the piece's
// active pixels, the message holds those and nothing else, and bad messages are refused.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "render/composite/composite_codec.hpp"

namespace tetray::render {
namespace {

// Active pixels in scattered runs: roughly a third of the image.
Framebuffer speckled_image(int width, int height, std::uint32_t seed) {
  Framebuffer image(width, height);
  std::mt19937 rng(seed);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    if (rng() % 3 != 0) continue;
    // Now and then infinite depth with a key: it still wins over the background, so it travels.
    const bool far = rng() % 10 == 0;
    image.depth[p] =
        far ? std::numeric_limits<float>::infinity() : static_cast<float>(rng() % 100) * 0.01f;
    image.hit[p] = static_cast<std::uint32_t>(rng() % 1000);
    for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = static_cast<float>(rng() % 256) / 255.0f;
  }
  return image;
}

std::size_t active_count(const Framebuffer& image, PixelSpan span) {
  std::size_t count = 0;
  for (std::uint32_t p = span.begin; p < span.end; ++p)
    count += is_active(image.depth[p], image.hit[p]);
  return count;
}

TEST(CompositeCodec, RoundTripRestoresTheSpanAndNothingElse) {
  const Framebuffer image = speckled_image(57, 31, 3);
  const auto pixels = static_cast<std::uint32_t>(image.pixel_count());
  for (const PixelSpan span : {PixelSpan{0, pixels}, PixelSpan{40, 41}, PixelSpan{100, 1200},
                               PixelSpan{pixels - 7, pixels}, PixelSpan{500, 500}}) {
    const PieceMessage message = encode_piece(image, span, active_rect(image));
    Framebuffer received(57, 31);
    ASSERT_TRUE(composite_piece(received, message).has_value());
    for (std::uint32_t p = 0; p < pixels; ++p) {
      const bool inside = p >= span.begin && p < span.end;
      EXPECT_EQ(received.depth[p], inside ? image.depth[p] : Framebuffer(1, 1).depth[0]);
      EXPECT_EQ(received.hit[p], inside ? image.hit[p] : kNoHit);
      EXPECT_EQ(received.rgba[4 * p + 2], inside ? image.rgba[4 * p + 2] : 0.0f);
    }
  }
}

TEST(CompositeCodec, MessageHoldsOnlyActivePixelsAndTheirRuns) {
  const Framebuffer image = speckled_image(64, 20, 5);
  const PixelSpan span{70, 1000};
  const PieceMessage message = encode_piece(image, span, active_rect(image));
  const std::size_t runs = message[1];
  EXPECT_EQ(message[2], active_count(image, span));
  EXPECT_EQ(message.size(), kPieceHeaderWords + kRunHeaderWords * runs + kPixelWords * message[2]);
  // Runs are maximal: at least one background pixel separates two of them.
  EXPECT_LE(runs, span.size() - message[2] + 1);
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

TEST(CompositeCodec, RefusesTruncatedAndOutOfRangeMessages) {
  const Framebuffer image = speckled_image(16, 16, 9);
  PieceMessage message = encode_piece(image, {0, 256}, active_rect(image));
  Framebuffer small(8, 8);
  EXPECT_FALSE(composite_piece(small, message).has_value());
  message.pop_back();
  Framebuffer target(16, 16);
  EXPECT_FALSE(composite_piece(target, message).has_value());
  EXPECT_FALSE(
      composite_piece(target, std::span<const std::uint32_t>(message).first(3)).has_value());
}

}  // namespace
}  // namespace tetray::render
