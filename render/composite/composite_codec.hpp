// The wire format of the compositor: a piece of an image (a span of pixels) sent as its active
// pixels only. Background runs are skipped (run-length encoded) and only the rows and columns
// of the piece's active rectangle are scanned, so a rank whose part of the mesh covers little of
// the screen sends, and reads, little.
//
// Layout, in 32-bit words: start, run count, pixel count, the rectangle of the pixels sent (x0,
// y0, x1, y1), then per run: pixels skipped since the previous run, pixel count n, and the
// run's pixels as three arrays, as the framebuffer holds them: 4 n words r, g, b, a, n depths
// (float bits), n hit keys. A run continues across rows where the active pixels do (a
// full-width region is one run). So encoding is a scan for runs and three copies per run,
// decoding works on arrays (the compositing loop vectorizes), and a pixel costs 24 bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "render/composite/composite_region.hpp"
#include "render/composite/message_memory.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::render {

using PieceMessage = std::vector<std::uint32_t, MessageAllocator<std::uint32_t>>;

inline constexpr std::size_t kPieceHeaderWords = 7;
inline constexpr std::size_t kRunHeaderWords = 2;
inline constexpr std::size_t kPixelWords = 6;

// The bytes of a message (the compositor's statistics).
inline std::uint64_t message_bytes(const PieceMessage& message) {
  return message.size() * sizeof(std::uint32_t);
}

// The most words a piece of `span` can take: every pixel active in one run.
inline std::size_t piece_capacity(const Framebuffer&, PixelSpan span) {
  return kPieceHeaderWords + kRunHeaderWords + kPixelWords * std::size_t{span.size()};
}

// The bytes of a received piece.
inline std::uint64_t piece_bytes(const Framebuffer&, std::span<const std::uint32_t> piece) {
  return piece.size() * sizeof(std::uint32_t);
}

// Encodes the active pixels of `span`; `hint` must hold every active pixel of the span (a
// looser rectangle costs scanning time, never correctness).
PieceMessage encode_piece(const Framebuffer& image, PixelSpan span, PixelRect hint);

// Composites an encoded piece into `image` by wins_over and returns the rectangle of its
// pixels, or nothing, leaving `image` as it was, when the message is malformed or does not fit
// the image.
std::optional<PixelRect> composite_piece(Framebuffer& image,
                                         std::span<const std::uint32_t> message);

// Writes the piece's pixels over those of `image` (the assembly of the final image, whose
// pieces are already composited); otherwise as composite_piece.
std::optional<PixelRect> copy_piece(Framebuffer& image, std::span<const std::uint32_t> message);

}  // namespace tetray::render
