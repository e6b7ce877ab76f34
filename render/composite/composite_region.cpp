#include "render/composite/composite_region.hpp"

#include <algorithm>
#include <bit>

namespace tetray::render {
namespace {

constexpr std::uint32_t kScanBlock = 16;

// Active pixels among the kScanBlock pixels from `at`: a branch-free count the compiler
// vectorizes, so a block is all active, all background or mixed after one comparison. (Kept a
// loop: unrolled into the scans, GCC leaves the sixteen tests scalar.)
std::uint32_t active_in_block(const Framebuffer& image, std::uint32_t at) {
  const float* depth = image.depth.data() + at;
  const std::uint32_t* hit = image.hit.data() + at;
  std::uint32_t count = 0;
#pragma GCC unroll 1
  for (std::uint32_t k = 0; k < kScanBlock; ++k) count += is_active(depth[k], hit[k]) ? 1u : 0u;
  return count;
}

bool active_at(const Framebuffer& image, std::uint32_t p) {
  return is_active(image.depth[p], image.hit[p]);
}

}  // namespace

std::uint32_t run_end(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                      bool active) {
  const std::uint32_t uniform = active ? kScanBlock : 0;
  while (end - begin >= kScanBlock && active_in_block(image, begin) == uniform) {
    begin += kScanBlock;
  }
  while (begin < end && active_at(image, begin) == active) ++begin;
  return begin;
}

std::uint32_t run_start(const Framebuffer& image, std::uint32_t begin, std::uint32_t end,
                        bool active) {
  const std::uint32_t uniform = active ? kScanBlock : 0;
  while (end - begin >= kScanBlock && active_in_block(image, end - kScanBlock) == uniform) {
    end -= kScanBlock;
  }
  while (end > begin && active_at(image, end - 1) == active) --end;
  return end;
}

PixelSpan split_span(PixelSpan span, int parts, int part) {
  const std::uint64_t size = span.size();
  const auto boundary = [&](int k) {
    return span.begin + static_cast<std::uint32_t>(size * static_cast<std::uint64_t>(k) /
                                                   static_cast<std::uint64_t>(parts));
  };
  return {boundary(part), boundary(part + 1)};
}

std::vector<std::uint32_t> interlaced_rows(int height) {
  std::vector<std::uint32_t> rows;
  if (height <= 0) return rows;
  rows.reserve(static_cast<std::size_t>(height));
  const auto bits = static_cast<int>(std::bit_width(static_cast<std::uint32_t>(height - 1)));
  for (std::uint32_t k = 0; k < (std::uint32_t{1} << bits); ++k) {
    std::uint32_t reversed = 0;
    for (int b = 0; b < bits; ++b) reversed |= ((k >> b) & 1u) << (bits - 1 - b);
    if (reversed < static_cast<std::uint32_t>(height)) rows.push_back(reversed);
  }
  return rows;
}

PixelRect united(PixelRect a, PixelRect b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

PixelRect active_rect(const Framebuffer& image, PixelRect within) {
  const int x0 = std::max(within.x0, 0), x1 = std::min(within.x1, image.width);
  const int y0 = std::max(within.y0, 0), y1 = std::min(within.y1, image.height);
  PixelRect rect;
  for (int j = y0; j < y1; ++j) {
    const auto row = static_cast<std::uint32_t>(image.index(0, j));
    const std::uint32_t begin = row + static_cast<std::uint32_t>(x0);
    const std::uint32_t end = row + static_cast<std::uint32_t>(x1);
    const std::uint32_t first = run_end(image, begin, end, false);
    if (first == end) continue;
    const std::uint32_t last_end = run_start(image, first, end, false);
    rect =
        united(rect, {static_cast<int>(first - row), j, static_cast<int>(last_end - row), j + 1});
  }
  return rect;
}

}  // namespace tetray::render
