#include "render/composite/composite_codec.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <utility>

namespace tetray::render {
namespace {

// Appends the headers of runs of active pixels in increasing index order: the message without
// its pixels (with_pixels adds them). A run stays open while the next pixels continue it (a
// full-width active region crosses rows).
class RunWriter {
 public:
  // `most_words` bounds the headers, so that the runs' appends never move them. `join`: a run
  // may continue into the next row (natural order, where that row follows in the image).
  RunWriter(PixelSpan span, std::size_t most_words, bool join) : cursor_(span.begin), join_(join) {
    words_.reserve(most_words);
    words_.assign(kPieceHeaderWords, 0);
    words_[0] = span.begin;
  }

  // Pixels [begin, end) of the schedule row that starts at index `row`, image row j.
  void add_run(std::uint32_t begin, std::uint32_t end, std::uint32_t row, int j) {
    if (open_.size() > 0 && begin == open_.end && (join_ || begin != row)) {
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
    words_.push_back(open_.begin - cursor_);
    words_.push_back(static_cast<std::uint32_t>(count));
    cursor_ = open_.end;
    ++run_count_;
    pixel_count_ += static_cast<std::uint32_t>(count);
    open_ = {};
  }

  PieceMessage words_;
  std::uint32_t cursor_;  // index just after the last run written
  bool join_;
  PixelSpan open_;  // the run not written yet (empty: none)
  std::uint32_t run_count_ = 0;
  std::uint32_t pixel_count_ = 0;
  PixelRect rect_{};
};

// The schedule rows of `span` that reach `hint`'s image rows, first to last; a row outside the
// hint has no active pixel. Natural order: the range itself; interlaced: every row of the span,
// each tested.
struct ScannedRows {
  int first = 0, last = -1;
  std::size_t count = 0;  // of them within the hint
};

ScannedRows scanned_rows(PixelSpan span, PixelRect hint, std::uint32_t width,
                         const RowOrder& order) {
  ScannedRows rows{static_cast<int>(span.begin / width), static_cast<int>((span.end - 1) / width)};
  if (order.natural()) {
    rows.first = std::max(rows.first, hint.y0);
    rows.last = std::min(rows.last, hint.y1 - 1);
    rows.count = static_cast<std::size_t>(std::max(0, rows.last - rows.first + 1));
    return rows;
  }
  for (int v = rows.first; v <= rows.last; ++v) {
    const auto j = static_cast<int>(order.image_row(static_cast<std::uint32_t>(v)));
    rows.count += j >= hint.y0 && j < hint.y1 ? 1 : 0;
  }
  return rows;
}

// The header and run headers of the active pixels of `span` (encode_piece without the pixels).
PieceMessage scan_runs(const Framebuffer& image, PixelSpan span, PixelRect hint,
                       const RowOrder& order) {
  if (span.size() == 0 || hint.empty() || image.width == 0) {
    return RunWriter(span, kPieceHeaderWords, true).finish();
  }
  const auto width = static_cast<std::uint32_t>(image.width);
  const ScannedRows rows = scanned_rows(span, hint, width, order);
  const std::size_t scanned_at_most =
      std::min<std::size_t>(span.size(), rows.count * static_cast<std::size_t>(hint.x1 - hint.x0));
  // A row's runs are separated by background pixels: at most (its pixels + 1) / 2 of them.
  const std::size_t runs_at_most = (scanned_at_most + rows.count) / 2 + 1;
  RunWriter writer(span, kPieceHeaderWords + kRunHeaderWords * runs_at_most, order.natural());
  for (int v = rows.first; v <= rows.last; ++v) {
    const auto j = static_cast<int>(order.image_row(static_cast<std::uint32_t>(v)));
    if (j < hint.y0 || j >= hint.y1) continue;
    const std::uint32_t row = static_cast<std::uint32_t>(v) * width;
    // Scanned where the pixels are: image index = schedule index + shift.
    const std::uint32_t shift = static_cast<std::uint32_t>(j) * width - row;
    std::uint32_t index = std::max(row + static_cast<std::uint32_t>(hint.x0), span.begin) + shift;
    const std::uint32_t end = std::min(row + static_cast<std::uint32_t>(hint.x1), span.end) + shift;
    while (index < end) {
      const std::uint32_t run_begin = run_end(image, index, end, false);
      index = run_end(image, run_begin, end, true);
      if (index > run_begin) writer.add_run(run_begin - shift, index - shift, row, j);
    }
  }
  return std::move(writer).finish();
}

// Copies `count` pixels of `image` from image index `at` as three arrays: colors, depths, keys.
void copy_pixels_out(const Framebuffer& image, std::size_t at, std::size_t count,
                     std::uint32_t* out) {
  std::memcpy(out, image.rgba.data() + 4 * at, 4 * count * sizeof(float));
  std::memcpy(out + 4 * count, image.depth.data() + at, count * sizeof(float));
  std::memcpy(out + 5 * count, image.hit.data() + at, count * sizeof(std::uint32_t));
}

// The whole message of `runs` (scan_runs): each run's header, then its pixels as three arrays,
// copied from image index image_at(r, position) for run r at schedule index `position`.
template <typename ImageAt>
PieceMessage with_pixels(const Framebuffer& image, const PieceMessage& runs, ImageAt&& image_at) {
  const std::size_t run_count = runs[1], pixels = runs[2];
  PieceMessage words;
  words.resize(kPieceHeaderWords + kRunHeaderWords * run_count + kPixelWords * pixels);
  std::copy(runs.begin(), runs.begin() + kPieceHeaderWords, words.begin());
  std::size_t position = runs[0], at = kPieceHeaderWords;
  for (std::size_t r = 0; r < run_count; ++r) {
    const std::uint32_t skip = runs[kPieceHeaderWords + kRunHeaderWords * r];
    const std::uint32_t count = runs[kPieceHeaderWords + kRunHeaderWords * r + 1];
    position += skip;
    words[at] = skip;
    words[at + 1] = count;
    copy_pixels_out(image, image_at(r, position), count, words.data() + at + kRunHeaderWords);
    at += kRunHeaderWords + kPixelWords * count;
    position += count;
  }
  return words;
}

PieceMessage with_pixels(const Framebuffer& image, const PieceMessage& runs,
                         const RowOrder& order) {
  const auto width = static_cast<std::uint32_t>(image.width);
  return with_pixels(image, runs, [&](std::size_t, std::size_t position) {
    return order.image_index(position, width);
  });
}

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

// Calls `write` for each run of `message` (whose header is checked), at its image index, and
// says whether every run lies whole in the message and in the image's `pixel_count` pixels (in
// one row where the order is interlaced), and the runs fill the message exactly. With a `write`
// that does nothing, it checks the message.
template <typename Write>
bool for_each_run(std::span<const std::uint32_t> message, std::size_t pixel_count,
                  std::uint32_t width, const RowOrder& order, Write&& write) {
  std::size_t position = message[0];
  std::size_t at = kPieceHeaderWords;
  for (std::uint32_t run = 0; run < message[1]; ++run) {
    if (!fits(message, at, kRunHeaderWords)) return false;
    position += message[at];
    const std::size_t count = message[at + 1];
    at += kRunHeaderWords;
    if (!fits(message, at, kPixelWords * count) || position > pixel_count ||
        count > pixel_count - position ||
        (!order.natural() && count > 0 && position % width + count > width)) {
      return false;
    }
    const std::uint32_t* rgba = message.data() + at;
    const std::size_t image_at = count > 0 ? order.image_index(position, width) : 0;
    write(Run{image_at, count, rgba, rgba + 4 * count, rgba + 5 * count});
    position += count;
    at += kPixelWords * count;
  }
  return at == message.size();
}

// Applies `write` to every run once the whole message is checked: a malformed message changes
// nothing.
template <typename Write>
std::optional<PixelRect> decode(Framebuffer& image, std::span<const std::uint32_t> message,
                                const RowOrder& order, Write&& write) {
  const std::optional<PixelRect> rect = header_rect(message, image);
  const auto width = static_cast<std::uint32_t>(image.width);
  if (!rect || !for_each_run(message, image.pixel_count(), width, order, [](const Run&) {})) {
    return std::nullopt;
  }
  for_each_run(message, image.pixel_count(), width, order, write);
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
void composite_pixels(Framebuffer& image, const Run& run) {
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

// composite_pixels over a long run in blocks on the rank's threads (each pixel is its own).
void composite_run(Framebuffer& image, const Run& run) {
  constexpr std::size_t kBlock = std::size_t{1} << 15;
  if (run.count <= kBlock) return composite_pixels(image, run);
  tbb::parallel_for(std::size_t{0}, (run.count + kBlock - 1) / kBlock, [&](std::size_t b) {
    const std::size_t first = b * kBlock, count = std::min(kBlock, run.count - first);
    composite_pixels(image, {run.position + first, count, run.rgba + 4 * first, run.depth + first,
                             run.hit + first});
  });
}

void copy_run(Framebuffer& image, const Run& run) {
  std::memcpy(image.rgba.data() + 4 * run.position, run.rgba, 4 * run.count * sizeof(float));
  std::memcpy(image.depth.data() + run.position, run.depth, run.count * sizeof(float));
  std::memcpy(image.hit.data() + run.position, run.hit, run.count * sizeof(std::uint32_t));
}

// One committed datatype of 32-bit words at their distances from `base`: the `first_words`
// words at `first` (none when null), then each segment's colors, depths and keys where the image
// holds them, every segment after the first preceded by its two run-header words, those of
// segment k at run_headers + 2 (k - 1). What a piece sent or received in place travels as.
int segments_type(const std::uint32_t* first, std::size_t first_words,
                  const std::uint32_t* run_headers, const Framebuffer& image,
                  std::span<const Segment> segments, const void* base, MPI_Datatype& type) {
  std::vector<const void*> blocks;
  std::vector<int> lengths;
  blocks.reserve(1 + 4 * segments.size());
  lengths.reserve(blocks.capacity());
  const auto add = [&](const void* block, std::size_t words) {
    blocks.push_back(block);
    lengths.push_back(static_cast<int>(words));
  };
  if (first != nullptr) add(first, first_words);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const auto [at, n] = segments[k];
    if (k > 0) add(run_headers + kRunHeaderWords * (k - 1), kRunHeaderWords);
    add(image.rgba.data() + 4 * at, 4 * n);
    add(image.depth.data() + at, n);
    add(image.hit.data() + at, n);
  }
  MPI_Aint origin = 0;
  MPI_Get_address(base, &origin);
  std::vector<MPI_Aint> displacements(blocks.size());
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    MPI_Get_address(blocks[k], &displacements[k]);
    displacements[k] -= origin;
  }
  if (int rc = MPI_Type_create_hindexed(static_cast<int>(blocks.size()), lengths.data(),
                                        displacements.data(), MPI_UINT32_T, &type);
      rc != MPI_SUCCESS)
    return rc;
  return MPI_Type_commit(&type);
}

// Whether a piece's header (its first kFirstPartWords words) says it holds every pixel of
// `span`, in the runs span_segments gives: in place, its runs are the image's own segments.
bool covers_whole_span(const std::uint32_t* header, PixelSpan span,
                       std::span<const Segment> segments) {
  if (segments.empty() || header[0] != span.begin || header[1] != segments.size()) return false;
  // Every pixel, the first run from the span's start: the runs are then the segments.
  const bool every_pixel = header[2] == span.size();
  return every_pixel && header[kPieceHeaderWords] == 0 &&
         header[kPieceHeaderWords + 1] == segments[0].count;
}

}  // namespace

PieceMessage encode_piece(const Framebuffer& image, PixelSpan span, PixelRect hint,
                          const RowOrder& order) {
  return with_pixels(image, scan_runs(image, span, hint, order), order);
}

std::vector<Segment> span_segments(PixelSpan span, std::uint32_t width, const RowOrder& order) {
  std::vector<Segment> segments;
  if (span.size() == 0) return segments;
  if (order.consecutive(span, width)) {
    segments.push_back({order.image_index(span.begin, width), span.size()});
    return segments;
  }
  for (std::uint32_t at = span.begin; at < span.end;) {
    const std::uint32_t row_end = std::min(span.end, (at / width + 1) * width);
    segments.push_back({order.image_index(at, width), std::size_t{row_end - at}});
    at = row_end;
  }
  return segments;
}

OutgoingPiece outgoing_piece(const Framebuffer& image, PixelSpan span, PixelRect hint,
                             const RowOrder& order) {
  PieceMessage runs = scan_runs(image, span, hint, order);
  const auto width = static_cast<std::uint32_t>(image.width);
  // In place: one run (consecutive in the image: a run stays in its row unless the order is
  // natural), or every pixel of the span (interlaced, a run per row: the span's segments).
  if (runs[1] == 1) {
    const std::size_t at = order.image_index(span.begin + runs[kPieceHeaderWords], width);
    std::vector<Segment> run{{at, runs[kPieceHeaderWords + 1]}};
    return {std::move(runs), &image, std::move(run)};
  }
  if (runs[1] > 1 && runs[2] == span.size()) {
    std::vector<Segment> segments = span_segments(span, width, order);
    return {std::move(runs), &image, std::move(segments)};
  }
  return {with_pixels(image, runs, order), nullptr, {}};
}

OutgoingPiece::OutgoingPiece(OutgoingPiece&& other) noexcept
    : words_(std::move(other.words_)),
      image_(other.image_),
      segments_(std::move(other.segments_)),
      type_(std::exchange(other.type_, MPI_DATATYPE_NULL)) {}

OutgoingPiece& OutgoingPiece::operator=(OutgoingPiece&& other) noexcept {
  if (this != &other) {
    if (type_ != MPI_DATATYPE_NULL) MPI_Type_free(&type_);
    words_ = std::move(other.words_);
    image_ = other.image_;
    segments_ = std::move(other.segments_);
    type_ = std::exchange(other.type_, MPI_DATATYPE_NULL);
  }
  return *this;
}

OutgoingPiece::~OutgoingPiece() {
  if (type_ != MPI_DATATYPE_NULL) MPI_Type_free(&type_);
}

std::size_t OutgoingPiece::pixel_count() const {
  std::size_t pixels = 0;
  for (const Segment& segment : segments_) pixels += segment.count;
  return pixels;
}

std::size_t OutgoingPiece::wire_words() const {
  return words_.size() + (in_place() ? kPixelWords * pixel_count() : 0);
}

PieceMessage OutgoingPiece::wire() const {
  if (!in_place()) return words_;
  return with_pixels(*image_, words_, [&](std::size_t r, std::size_t) { return segments_[r].at; });
}

int OutgoingPiece::make_run_type(const std::uint32_t* first, const void* base) {
  if (type_ != MPI_DATATYPE_NULL) MPI_Type_free(&type_);
  return segments_type(first, kFirstPartWords, words_.data() + kFirstPartWords, *image_, segments_,
                       base, type_);
}

int OutgoingPiece::isend(int peer, int tag, MPI_Comm comm, MPI_Request* request) {
  if (!in_place()) {
    return MPI_Isend(words_.data(), static_cast<int>(words_.size()), MPI_UINT32_T, peer, tag, comm,
                     request);
  }
  if (int rc = make_run_type(words_.data(), words_.data()); rc != MPI_SUCCESS) return rc;
  return MPI_Isend(words_.data(), 1, type_, peer, tag, comm, request);
}

int OutgoingPiece::isend_parts(int peer, int tag, MPI_Comm comm, MPI_Request requests[2]) {
  const std::size_t first = std::min(words_.size(), kFirstPartWords);
  if (int rc = MPI_Isend(words_.data(), static_cast<int>(first), MPI_UINT32_T, peer, tag, comm,
                         &requests[0]);
      rc != MPI_SUCCESS)
    return rc;
  if (in_place()) {
    const void* base = image_->rgba.data() + 4 * segments_.front().at;
    if (int rc = make_run_type(nullptr, base); rc != MPI_SUCCESS) return rc;
    return MPI_Isend(base, 1, type_, peer, tag, comm, &requests[1]);
  }
  if (words_.size() == first) return MPI_SUCCESS;
  return MPI_Isend(words_.data() + first, static_cast<int>(words_.size() - first), MPI_UINT32_T,
                   peer, tag, comm, &requests[1]);
}

int post_piece_body(Framebuffer& image, PixelSpan span, ReceiveBuffer& buffer,
                    std::size_t header_words, int peer, int tag, MPI_Comm comm,
                    MPI_Request* request, PartsArrival& arrival, const RowOrder& order) {
  const auto width = static_cast<std::uint32_t>(image.width);
  const std::uint32_t* header = buffer.words.get();
  if (header_words < kPieceHeaderWords) return MPI_ERR_OTHER;
  const std::size_t total = kPieceHeaderWords + kRunHeaderWords * std::size_t{header[1]} +
                            kPixelWords * std::size_t{header[2]};
  if (total > buffer.capacity || total < header_words ||
      (header_words < kFirstPartWords && total != header_words))
    return MPI_ERR_OTHER;
  arrival.header_words = header_words;
  arrival.body_words = total - header_words;
  std::vector<Segment> segments;
  if (header_words == kFirstPartWords && span.end <= image.pixel_count()) {
    segments = span_segments(span, width, order);
  }
  arrival.in_place = header_words == kFirstPartWords && covers_whole_span(header, span, segments);
  if (arrival.body_words == 0) return MPI_SUCCESS;
  std::uint32_t* const after_header = buffer.words.get() + header_words;
  if (!arrival.in_place) {
    return MPI_Irecv(after_header, static_cast<int>(arrival.body_words), MPI_UINT32_T, peer, tag,
                     comm, request);
  }
  // The pixels into the image, the run headers after the first into the buffer (checked when
  // the piece is taken).
  arrival.segments = std::move(segments);
  float* const colors = image.rgba.data() + 4 * arrival.segments.front().at;
  if (int rc =
          segments_type(nullptr, 0, after_header, image, arrival.segments, colors, arrival.type);
      rc != MPI_SUCCESS)
    return rc;
  return MPI_Irecv(colors, 1, arrival.type, peer, tag, comm, request);
}

std::optional<PixelRect> take_piece_body(Framebuffer& image, PixelSpan, const ReceiveBuffer& buffer,
                                         PartsArrival& arrival, std::size_t body_words,
                                         const RowOrder& order) {
  if (body_words != arrival.body_words) return std::nullopt;
  const std::span<const std::uint32_t> message(buffer.words.get(),
                                               arrival.header_words + arrival.body_words);
  if (!arrival.in_place) return copy_piece(image, message, order);
  // The pixels are in place; the buffer holds the runs' headers after the first, each of which
  // must continue the span without a gap. The header's rectangle must lie in the image.
  const std::uint32_t* run_headers = buffer.words.get() + arrival.header_words;
  for (std::size_t k = 1; k < arrival.segments.size(); ++k, run_headers += kRunHeaderWords) {
    if (run_headers[0] != 0 || run_headers[1] != arrival.segments[k].count) return std::nullopt;
  }
  return header_rect(message, image);
}

std::optional<PixelRect> composite_piece(Framebuffer& image, std::span<const std::uint32_t> message,
                                         const RowOrder& order) {
  return decode(image, message, order, [&](const Run& run) { composite_run(image, run); });
}

std::optional<PixelRect> copy_piece(Framebuffer& image, std::span<const std::uint32_t> message,
                                    const RowOrder& order) {
  return decode(image, message, order, [&](const Run& run) { copy_run(image, run); });
}

}  // namespace tetray::render
