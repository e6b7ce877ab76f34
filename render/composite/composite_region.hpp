// Screen regions the compositor works with: spans of linear pixel indices (the pieces that
// binary swap and radix-k split the image into) and rectangles bounding the active pixels
// (what a rank actually has to send when its part of the mesh covers little of the screen).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

// A pixel is active when it can win over the background; only active pixels are exchanged.
// This is wins_over(depth, hit, +infinity, kNoHit) spelled without short-circuits (a NaN depth
// is not active), so that the scans over blocks of pixels vectorize.
inline bool is_active(float depth, std::uint32_t hit) {
  constexpr float kFar = std::numeric_limits<float>::infinity();
  return (depth < kFar) | ((depth == kFar) & (hit != kNoHit));
}

// Where a run of pixels of one activity ends: the first pixel of [begin, end) whose activity is
// not `active`, or `end`. Pixels are tested 16 at a time and the per-pixel test runs only in the
// block where the activity changes, so long runs of active or background pixels (the common
// case) cost a fraction of a nanosecond per pixel.
std::uint32_t run_end(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                      bool active);

// The same backwards: the start of the run of pixels of activity `active` that ends at `end`, no
// earlier than `begin` (`end` when pixel end - 1 is not of that activity).
std::uint32_t run_start(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                        bool active);

// Linear pixel indices [begin, end), row-major (index = j * width + i).
struct PixelSpan {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;

  std::uint32_t size() const { return end - begin; }
};

// Part `part` of `parts` near-equal consecutive parts of `span`.
PixelSpan split_span(PixelSpan span, int parts, int part);

// Where the schedule's rows lie in the image. The compositor's spans are of row-major indices
// p = v w + i over schedule rows v: in natural order schedule row v is image row v; interlaced,
// it is image row rows[v], the rows taken in the order of their bit-reversed numbers, so that
// any run of consecutive schedule rows samples the whole image evenly. A rank whose hits cover
// a small part of the screen then has about as many pixels in every part a group splits its
// span into, instead of all of them in one part (IceT's interlaced images, Moreland et al.,
// SC 2011). A run of a piece stays in one schedule row there, so that its pixels are
// consecutive in the image.
struct RowOrder {
  std::span<const std::uint32_t> rows;  // image row of each schedule row; empty: natural order

  bool natural() const { return rows.empty(); }
  std::uint32_t image_row(std::uint32_t schedule_row) const {
    return natural() ? schedule_row : rows[schedule_row];
  }
  // The image index of schedule index `position` in an image `width` pixels wide.
  std::size_t image_index(std::size_t position, std::uint32_t width) const {
    if (natural()) return position;
    return std::size_t{rows[position / width]} * width + position % width;
  }
  // Whether the span's pixels are consecutive in the image: in natural order, or within one row.
  bool consecutive(PixelSpan span, std::uint32_t width) const {
    return natural() || span.size() == 0 || span.begin / width == (span.end - 1) / width;
  }
};

// The interlaced order of `height` rows (RowOrder::rows): 0, h/2, h/4, 3h/4, ... for a power
// of two, the rows whose bit-reversed numbers are in range otherwise.
std::vector<std::uint32_t> interlaced_rows(int height);

// Half-open pixel rectangle [x0, x1) x [y0, y1); empty when it holds no pixel.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x0 >= x1 || y0 >= y1; }
  bool operator==(const PixelRect&) const = default;
};

// The smallest rectangle holding both.
PixelRect united(PixelRect a, PixelRect b);

// The smallest rectangle holding every active pixel of `image` inside `within` (clipped to the
// image); only `within` is scanned.
PixelRect active_rect(const Framebuffer& image, PixelRect within);

// The whole image as a rectangle.
inline PixelRect image_rect(const Framebuffer& image) { return {0, 0, image.width, image.height}; }

// The smallest rectangle holding every active pixel of `image`.
inline PixelRect active_rect(const Framebuffer& image) {
  return active_rect(image, image_rect(image));
}

}  // namespace tetray::render
