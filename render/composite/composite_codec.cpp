#include "render/composite/composite_codec.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

namespace tetray::render {
namespace {

// Appends runs of active pixels in increasing index order. A run stays open while the next
// pixels continue it (a full-width active region crosses rows) and is copied, three arrays,
// when it closes.
class PieceWriter {
 public:
  // `most_words` bounds the message, so that the runs' appends never move it.
  PieceWriter(const Framebuffer& image, PixelSpan span, std::size_t most_words)
      : image_(image), cursor_(span.begin) {
    words_.reserve(most_words);
    words_.assign(kPieceHeaderWords, 0);
    words_[0] = span.begin;
  }

  // Pixels [begin, end) of row j, which starts at index `row`.
  void add_run(std::uint32_t begin, std::uint32_t end, std::uint32_t row, int j) {
    if (open_.size() > 0 && begin == open_.end) {
      open_.end = end;
    } else {
      close_run();
      open_ = {begin, end};
    }
    const int i0 = static_cast<int>(begin - row), i1 = static_cast<int>(end - row);
    rect_ = united(rect_, {i0, j, i1, j + 1});
  }

  PieceMessage finish() && {
    close_run();
    words_[1] = run_count_;
    words_[2] = pixel_count_;
    words_[3] = static_cast<std::uint32_t>(rect_.x0);
    words_[4] = static_cast<std::uint32_t>(rect_.y0);
    words_[5] = static_cast<std::uint32_t>(rect_.x1);
    words_[6] = static_cast<std::uint32_t>(rect_.y1);
    return std::move(words_);
  }

 private:
  void close_run() {
    const std::size_t count = open_.size();
    if (count == 0) return;
    const std::size_t at = words_.size();
    words_.resize(at + kRunHeaderWords + kPixelWords * count);
    std::uint32_t* out = words_.data() + at;
    out[0] = open_.begin - cursor_;
    out[1] = static_cast<std::uint32_t>(count);
    out += kRunHeaderWords;
    std::memcpy(out, image_.rgba.data() + 4 * std::size_t{open_.begin}, 4 * count * sizeof(float));
    std::memcpy(out + 4 * count, image_.depth.data() + open_.begin, count * sizeof(float));
    std::memcpy(out + 5 * count, image_.hit.data() + open_.begin, count * sizeof(std::uint32_t));
    cursor_ = open_.end;
    ++run_count_;
    pixel_count_ += static_cast<std::uint32_t>(count);
    open_ = {};
  }

  const Framebuffer& image_;
  PieceMessage words_;
  std::uint32_t cursor_;  // index just after the last run written
  PixelSpan open_;        // the run not written yet (empty: none)
  std::uint32_t run_count_ = 0;
  std::uint32_t pixel_count_ = 0;
  PixelRect rect_{};
};

// One run of a checked message: where its pixels go and its three arrays.
struct Run {
  std::size_t position;
  std::size_t count;
  const std::uint32_t* rgba;
  const std::uint32_t* depth;
  const std::uint32_t* hit;
};

bool fits(std::span<const std::uint32_t> message, std::size_t at, std::size_t words) {
  return at <= message.size() && words <= message.size() - at;
}

// The header's rectangle when the header is whole, its counts give the message's length and the
// rectangle lies in the image.
std::optional<PixelRect> header_rect(std::span<const std::uint32_t> message,
                                     const Framebuffer& image) {
  if (!fits(message, 0, kPieceHeaderWords)) return std::nullopt;
  if (message.size() != kPieceHeaderWords + kRunHeaderWords * std::size_t{message[1]} +
                            kPixelWords * std::size_t{message[2]}) {
    return std::nullopt;
  }
  const auto [x0, y0, x1, y1] = std::array{message[3], message[4], message[5], message[6]};
  const auto width = static_cast<std::uint32_t>(image.width);
  const auto height = static_cast<std::uint32_t>(image.height);
  if (x0 > x1 || x1 > width || y0 > y1 || y1 > height) return std::nullopt;
  return PixelRect{static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1),
                   static_cast<int>(y1)};
}

// Calls `write` for each run of `message` (whose header is checked) and says whether every run
// lies whole in the message and in the image's `pixel_count` pixels, and the runs fill the
// message exactly. With a `write` that does nothing, it checks the message.
template <typename Write>
bool for_each_run(std::span<const std::uint32_t> message, std::size_t pixel_count, Write&& write) {
  std::size_t position = message[0];
  std::size_t at = kPieceHeaderWords;
  for (std::uint32_t run = 0; run < message[1]; ++run) {
    if (!fits(message, at, kRunHeaderWords)) return false;
    position += message[at];
    const std::size_t count = message[at + 1];
    at += kRunHeaderWords;
    if (!fits(message, at, kPixelWords * count) || position > pixel_count ||
        count > pixel_count - position) {
      return false;
    }
    const std::uint32_t* rgba = message.data() + at;
    write(Run{position, count, rgba, rgba + 4 * count, rgba + 5 * count});
    position += count;
    at += kPixelWords * count;
  }
  return at == message.size();
}

// Applies `write` to every run once the whole message is checked: a malformed message changes
// nothing.
template <typename Write>
std::optional<PixelRect> decode(Framebuffer& image, std::span<const std::uint32_t> message,
                                Write&& write) {
  const std::optional<PixelRect> rect = header_rect(message, image);
  if (!rect || !for_each_run(message, image.pixel_count(), [](const Run&) {})) {
    return std::nullopt;
  }
  for_each_run(message, image.pixel_count(), write);
  return rect;
}

// `incoming` where `mask` is all ones, `old` where it is zero: a select of bits, so choosing
// this way gives the bits choosing pixel by pixel would.
std::uint32_t select_bits(std::uint32_t mask, std::uint32_t incoming, std::uint32_t old) {
  return (incoming & mask) | (old & ~mask);
}

float select_float(std::uint32_t mask, std::uint32_t incoming, float old) {
  return std::bit_cast<float>(select_bits(mask, incoming, std::bit_cast<std::uint32_t>(old)));
}

// Keeps, per pixel, the winner of wins_over. Every pixel is written through a select, without
// branches, over arrays that do not overlap, so that the compiler vectorizes the loop.
void composite_run(Framebuffer& image, const Run& run) {
  const std::uint32_t* __restrict in_rgba = run.rgba;
  const std::uint32_t* __restrict in_depth = run.depth;
  const std::uint32_t* __restrict in_hit = run.hit;
  float* __restrict rgba = image.rgba.data() + 4 * run.position;
  float* __restrict depth = image.depth.data() + run.position;
  std::uint32_t* __restrict hit = image.hit.data() + run.position;
  for (std::size_t k = 0; k < run.count; ++k) {
    const bool wins = wins_over(std::bit_cast<float>(in_depth[k]), in_hit[k], depth[k], hit[k]);
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(wins);
    depth[k] = select_float(mask, in_depth[k], depth[k]);
    hit[k] = select_bits(mask, in_hit[k], hit[k]);
    for (std::size_t c = 0; c < 4; ++c) {
      rgba[4 * k + c] = select_float(mask, in_rgba[4 * k + c], rgba[4 * k + c]);
    }
  }
}

void copy_run(Framebuffer& image, const Run& run) {
  std::memcpy(image.rgba.data() + 4 * run.position, run.rgba, 4 * run.count * sizeof(float));
  std::memcpy(image.depth.data() + run.position, run.depth, run.count * sizeof(float));
  std::memcpy(image.hit.data() + run.position, run.hit, run.count * sizeof(std::uint32_t));
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
  // A row's runs are separated by background pixels: at most (its pixels + 1) / 2 of them.
  const std::size_t runs_at_most = (scanned_at_most + rows) / 2 + 1;
  PieceWriter writer(
      image, span,
      kPieceHeaderWords + kPixelWords * scanned_at_most + kRunHeaderWords * runs_at_most);
  for (int j = first_row; j <= last_row; ++j) {
    const std::uint32_t row = static_cast<std::uint32_t>(j) * width;
    std::uint32_t index = std::max(row + static_cast<std::uint32_t>(hint.x0), span.begin);
    const std::uint32_t end = std::min(row + static_cast<std::uint32_t>(hint.x1), span.end);
    while (index < end) {
      const std::uint32_t run_begin = run_end(image, index, end, false);
      index = run_end(image, run_begin, end, true);
      if (index > run_begin) writer.add_run(run_begin, index, row, j);
    }
  }
  return std::move(writer).finish();
}

std::optional<PixelRect> composite_piece(Framebuffer& image,
                                         std::span<const std::uint32_t> message) {
  return decode(image, message, [&](const Run& run) { composite_run(image, run); });
}

std::optional<PixelRect> copy_piece(Framebuffer& image, std::span<const std::uint32_t> message) {
  return decode(image, message, [&](const Run& run) { copy_run(image, run); });
}

}  // namespace tetray::render
