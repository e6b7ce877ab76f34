#include "render/composite/composite_region.hpp"

#include <algorithm>

namespace tetray::render {

PixelSpan split_span(PixelSpan span, int parts, int part) {
  const std::uint64_t size = span.size();
  const auto boundary = [&](int k) {
    return span.begin + static_cast<std::uint32_t>(size * static_cast<std::uint64_t>(k) /
                                                   static_cast<std::uint64_t>(parts));
  };
  return {boundary(part), boundary(part + 1)};
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
    const std::size_t row = image.index(0, j);
    const auto active_at = [&](int i) {
      return is_active(image.depth[row + i], image.hit[row + i]);
    };
    int first = x0;
    while (first < x1 && !active_at(first)) ++first;
    if (first == x1) continue;
    int last = x1 - 1;
    while (!active_at(last)) --last;
    rect = united(rect, {first, j, last + 1, j + 1});
  }
  return rect;
}

}  // namespace tetray::render
