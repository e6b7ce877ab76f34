#include "render/composite/composite_codec.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace tetray::render {
namespace {

// Appends runs of active pixels in increasing index order; a run that continues the previous
// one (a full-width active region crosses rows) extends it.
class PieceWriter {
 public:
  // Reserving the expected size once keeps the appends cheap.
  PieceWriter(const Framebuffer& image, PixelSpan span, std::size_t expected_words)
      : image_(image), cursor_(span.begin) {
    words_.reserve(expected_words);
    words_.assign(kPieceHeaderWords, 0);
    words_[0] = span.begin;
  }

  // Pixels [begin, end) of row j, which starts at index `row`.
  void add_run(std::uint32_t begin, std::uint32_t end, std::uint32_t row, int j) {
    if (run_header_ == 0 || begin != cursor_) {
      run_header_ = words_.size();
      words_.push_back(begin - cursor_);
      words_.push_back(0);
      ++run_count_;
    }
    const std::uint32_t count = end - begin;
    words_[run_header_ + 1] += count;
    pixel_count_ += count;
    cursor_ = end;
    copy_pixels(begin, end);
    const int i0 = static_cast<int>(begin - row), i1 = static_cast<int>(end - row);
    if (pixel_count_ == count) rect_ = {i0, j, i1, j + 1};
    rect_ = {std::min(rect_.x0, i0), rect_.y0, std::max(rect_.x1, i1), j + 1};
  }

  PieceMessage finish() && {
    words_[1] = run_count_;
    words_[2] = pixel_count_;
    words_[3] = static_cast<std::uint32_t>(rect_.x0);
    words_[4] = static_cast<std::uint32_t>(rect_.y0);
    words_[5] = static_cast<std::uint32_t>(rect_.x1);
    words_[6] = static_cast<std::uint32_t>(rect_.y1);
    return std::move(words_);
  }

 private:
  void copy_pixels(std::uint32_t begin, std::uint32_t end) {
    const std::size_t at = words_.size();
    words_.resize(at + kPixelWords * (end - begin));
    std::uint32_t* out = words_.data() + at;
    for (std::uint32_t p = begin; p < end; ++p, out += kPixelWords) {
      std::memcpy(out, &image_.rgba[4 * std::size_t{p}], 4 * sizeof(float));
      std::memcpy(out + 4, &image_.depth[p], sizeof(float));
      out[5] = image_.hit[p];
    }
  }

  const Framebuffer& image_;
  PieceMessage words_;
  std::uint32_t cursor_;        // index just after the last pixel written
  std::size_t run_header_ = 0;  // word index of the open run's header (0: none yet)
  std::uint32_t run_count_ = 0;
  std::uint32_t pixel_count_ = 0;
  PixelRect rect_{};
};

bool fits(std::span<const std::uint32_t> message, std::size_t at, std::size_t words) {
  return at <= message.size() && words <= message.size() - at;
}

}  // namespace

PieceMessage encode_piece(const Framebuffer& image, PixelSpan span, PixelRect hint) {
  if (span.size() == 0 || hint.empty() || image.width == 0) {
    return PieceWriter(image, span, kPieceHeaderWords).finish();
  }
  const auto width = static_cast<std::uint32_t>(image.width);
  const int first_row = std::max(hint.y0, static_cast<int>(span.begin / width));
  const int last_row = std::min(hint.y1 - 1, static_cast<int>((span.end - 1) / width));
  const auto rows = static_cast<std::size_t>(std::max(0, last_row - first_row + 1));
  const std::size_t scanned_at_most =
      std::min<std::size_t>(span.size(), rows * static_cast<std::size_t>(hint.x1 - hint.x0));
  PieceWriter writer(image, span,
                     kPieceHeaderWords + kPixelWords * scanned_at_most + kRunHeaderWords * rows);
  const auto active_at = [&](std::uint32_t p) { return is_active(image.depth[p], image.hit[p]); };
  for (int j = first_row; j <= last_row; ++j) {
    const std::uint32_t row = static_cast<std::uint32_t>(j) * width;
    std::uint32_t index = std::max(row + static_cast<std::uint32_t>(hint.x0), span.begin);
    const std::uint32_t end = std::min(row + static_cast<std::uint32_t>(hint.x1), span.end);
    while (index < end) {
      while (index < end && !active_at(index)) ++index;
      const std::uint32_t run_begin = index;
      while (index < end && active_at(index)) ++index;
      if (index > run_begin) writer.add_run(run_begin, index, row, j);
    }
  }
  return std::move(writer).finish();
}

std::optional<PixelRect> composite_piece(Framebuffer& image,
                                         std::span<const std::uint32_t> message) {
  if (!fits(message, 0, kPieceHeaderWords)) return std::nullopt;
  const std::uint32_t run_count = message[1];
  const std::uint32_t pixel_count = message[2];
  if (message.size() != kPieceHeaderWords + kRunHeaderWords * std::size_t{run_count} +
                            kPixelWords * std::size_t{pixel_count}) {
    return std::nullopt;
  }
  std::size_t position = message[0];
  std::size_t at = kPieceHeaderWords;
  for (std::uint32_t run = 0; run < run_count; ++run) {
    position += message[at];
    const std::size_t count = message[at + 1];
    at += kRunHeaderWords;
    if (!fits(message, at, kPixelWords * count) || position + count > image.pixel_count()) {
      return std::nullopt;
    }
    for (std::size_t end = position + count; position < end; ++position, at += kPixelWords) {
      const float depth = std::bit_cast<float>(message[at + 4]);
      const std::uint32_t hit = message[at + 5];
      if (!wins_over(depth, hit, image.depth[position], image.hit[position])) continue;
      for (int c = 0; c < 4; ++c)
        image.rgba[4 * position + c] = std::bit_cast<float>(message[at + c]);
      image.depth[position] = depth;
      image.hit[position] = hit;
    }
  }
  return PixelRect{static_cast<int>(message[3]), static_cast<int>(message[4]),
                   static_cast<int>(message[5]), static_cast<int>(message[6])};
}

}  // namespace tetray::render
