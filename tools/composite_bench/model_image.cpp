#include "tools/composite_bench/model_image.hpp"

#include <algorithm>
#include <cstring>

#ifdef TETRAY_SMPI
#include <smpi/smpi.h>
#endif

#include "render/composite/composite_codec.hpp"

namespace tetray::composite_bench {
namespace {

constexpr std::size_t kAddressWords = sizeof(ModelPiece*) / sizeof(std::uint32_t);

// The first and last row of `span` and where in them it starts and ends.
struct SpanRows {
  int first_row, first_x, last_row, last_x;  // pixels [first_x, width) of the first row ...
};

SpanRows rows_of(render::PixelSpan span, int width) {
  const auto w = static_cast<std::uint32_t>(width);
  return {static_cast<int>(span.begin / w), static_cast<int>(span.begin % w),
          static_cast<int>((span.end - 1) / w), static_cast<int>((span.end - 1) % w + 1)};
}

// Pixels of row y of `rect` inside the span.
int row_pixels(const SpanRows& rows, render::PixelRect rect, int y) {
  int lo = rect.x0, hi = rect.x1;
  if (y == rows.first_row) lo = std::max(lo, rows.first_x);
  if (y == rows.last_row) hi = std::min(hi, rows.last_x);
  return std::max(0, hi - lo);
}

// Rows of `rect` the span reaches, [y0, y1]; empty when y0 > y1.
std::pair<int, int> reached_rows(const SpanRows& rows, render::PixelRect rect) {
  return {std::max(rect.y0, rows.first_row), std::min(rect.y1 - 1, rows.last_row)};
}

bool empty_input(render::PixelSpan span, render::PixelRect rect, int width) {
  return span.size() == 0 || rect.empty() || width <= 0;
}

// Words on the wire for a real message of `words`.
std::size_t scaled_words(std::uint64_t words, int byte_scale) {
  const auto scale = static_cast<std::uint64_t>(std::max(byte_scale, 1));
  return std::max<std::size_t>(kAddressWords, (words + scale - 1) / scale);
}

// The piece's footprints join the image's, at `seconds_per_pixel`.
std::optional<render::PixelRect> take_in(ModelImage& image, std::span<const std::uint32_t> message,
                                         double seconds_per_pixel) {
  const std::unique_ptr<ModelPiece> piece = take_piece(message);
  if (!piece) return std::nullopt;
  inject_compute(static_cast<double>(piece->pixels) * seconds_per_pixel);
  for (const render::PixelRect& footprint : piece->footprints) {
    if (std::find(image.footprints.begin(), image.footprints.end(), footprint) ==
        image.footprints.end()) {
      image.footprints.push_back(footprint);
    }
  }
  return piece->rect;
}

}  // namespace

void inject_compute(double seconds) {
#ifdef TETRAY_SMPI
  if (seconds > 0) smpi_execute(seconds);
#else
  (void)seconds;
#endif
}

SpanCover span_cover(render::PixelSpan span, render::PixelRect rect, int width,
                     const render::RowOrder& order) {
  SpanCover cover;
  if (empty_input(span, rect, width)) return cover;
  const SpanRows rows = rows_of(span, width);
  if (order.natural()) {
    const auto [y0, y1] = reached_rows(rows, rect);
    if (y0 > y1) return cover;
    cover.rect = {rect.x0, y0, rect.x1, y1 + 1};
    const auto first = static_cast<std::uint64_t>(row_pixels(rows, rect, y0));
    if (y0 == y1) {
      cover.pixels = first;
      cover.rows = first > 0;
      return cover;
    }
    const auto last = static_cast<std::uint64_t>(row_pixels(rows, rect, y1));
    const auto inner = static_cast<std::uint64_t>(y1 - y0 - 1);
    cover.pixels = inner * static_cast<std::uint64_t>(rect.x1 - rect.x0) + first + last;
    cover.rows = inner + (first > 0) + (last > 0);
    return cover;
  }
  // Interlaced: each schedule row of the span is one image row, wherever it lies.
  for (int v = rows.first_row; v <= rows.last_row; ++v) {
    const auto j = static_cast<int>(order.image_row(static_cast<std::uint32_t>(v)));
    if (j < rect.y0 || j >= rect.y1) continue;
    const int pixels = row_pixels(rows, rect, v);
    if (pixels <= 0) continue;
    cover.pixels += static_cast<std::uint64_t>(pixels);
    ++cover.rows;
    cover.rect = render::united(cover.rect, {rect.x0, j, rect.x1, j + 1});
  }
  return cover;
}

ModelMessage::ModelMessage(std::unique_ptr<ModelPiece> piece, int byte_scale)
    : words_(new std::uint32_t[scaled_words(piece->words, byte_scale)]),
      size_(scaled_words(piece->words, byte_scale)) {
  ModelPiece* address = piece.release();
  std::memcpy(words_.get(), &address, sizeof address);
}

std::unique_ptr<ModelPiece> take_piece(std::span<const std::uint32_t> message) {
  if (message.size() < kAddressWords) return nullptr;
  ModelPiece* address = nullptr;
  std::memcpy(&address, message.data(), sizeof address);
  return std::unique_ptr<ModelPiece>(address);
}

const ModelPiece& peek_piece(std::span<const std::uint32_t> message) {
  ModelPiece* address = nullptr;
  std::memcpy(&address, message.data(), sizeof address);
  return *address;
}

std::uint64_t message_bytes(const ModelMessage& message) {
  return peek_piece({message.data(), message.size()}).words * sizeof(std::uint32_t);
}

std::size_t piece_capacity(const ModelImage& image, render::PixelSpan span) {
  return scaled_words(render::piece_capacity(static_cast<std::uint32_t>(image.width), span),
                      image.settings->byte_scale);
}

std::uint64_t piece_bytes(const ModelImage&, std::span<const std::uint32_t> piece) {
  return peek_piece(piece).words * sizeof(std::uint32_t);
}

render::PixelRect active_rect(const ModelImage& image, render::PixelRect within) {
  const auto width = static_cast<double>(std::clamp(within.x1, 0, image.width) -
                                         std::clamp(within.x0, 0, image.width));
  const auto height = static_cast<double>(std::clamp(within.y1, 0, image.height) -
                                          std::clamp(within.y0, 0, image.height));
  inject_compute(std::max(width, 0.0) * std::max(height, 0.0) * image.settings->costs.scan);
  render::PixelRect rect;
  for (const render::PixelRect& footprint : image.footprints)
    rect = render::united(rect, footprint);
  return rect;
}

ModelMessage outgoing_piece(const ModelImage& image, render::PixelSpan span, render::PixelRect hint,
                            const render::RowOrder& order) {
  auto piece = std::make_unique<ModelPiece>();
  std::uint64_t runs = 0;
  render::PixelRect sent_rect;
  for (const render::PixelRect& footprint : image.footprints) {
    const SpanCover cover = span_cover(span, footprint, image.width, order);
    if (cover.pixels == 0) continue;
    piece->footprints.push_back(footprint);
    piece->pixels += cover.pixels;
    // A footprint as wide as the image is one run in natural order: the encoder joins its rows.
    const bool joined = order.natural() && footprint.x1 - footprint.x0 == image.width;
    runs += joined ? 1 : cover.rows;
    sent_rect = render::united(sent_rect, cover.rect);
  }
  piece->rect = sent_rect;
  // Runs of neighbouring footprints in one row are joined by the encoder and counted apart
  // here; no real piece exceeds one run per pixel row of the span, nor the span's capacity.
  piece->words =
      std::min<std::uint64_t>(render::kPieceHeaderWords + render::kRunHeaderWords * runs +
                                  render::kPixelWords * piece->pixels,
                              render::kPieceHeaderWords + render::kRunHeaderWords +
                                  render::kPixelWords * std::uint64_t{span.size()});
  const PixelCosts& costs = image.settings->costs;
  const std::uint64_t scanned = span_cover(span, hint, image.width, order).pixels;
  // One run, or interlaced every pixel of the span, goes from the image itself: its pixels are
  // scanned, not copied (outgoing_piece).
  const bool in_place = runs == 1 || (!order.natural() && piece->pixels == span.size());
  const double encode = in_place ? costs.scan : costs.encode;
  inject_compute(static_cast<double>(scanned - std::min(scanned, piece->pixels)) * costs.scan +
                 static_cast<double>(piece->pixels) * encode);
  return ModelMessage(std::move(piece), image.settings->byte_scale);
}

int isend_piece(ModelMessage& message, int peer, int tag, MPI_Comm comm, MPI_Request* request) {
  return MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_UINT32_T, peer, tag, comm,
                   request);
}

int isend_piece_parts(ModelMessage& message, int peer, int tag, MPI_Comm comm,
                      MPI_Request requests[2]) {
  if (int rc = MPI_Isend(message.data(), static_cast<int>(kAddressWords), MPI_UINT32_T, peer, tag,
                         comm, &requests[0]);
      rc != MPI_SUCCESS)
    return rc;
  if (message.size() == kAddressWords) return MPI_SUCCESS;
  return MPI_Isend(message.data() + kAddressWords, static_cast<int>(message.size() - kAddressWords),
                   MPI_UINT32_T, peer, tag, comm, &requests[1]);
}

int post_piece_body(ModelImage& image, render::PixelSpan span, render::ReceiveBuffer& buffer,
                    std::size_t header_words, int peer, int tag, MPI_Comm comm,
                    MPI_Request* request, render::PartsArrival& arrival, const render::RowOrder&) {
  if (header_words != kAddressWords) return MPI_ERR_OTHER;
  const ModelPiece& piece = peek_piece({buffer.words.get(), header_words});
  arrival.header_words = header_words;
  arrival.body_words = scaled_words(piece.words, image.settings->byte_scale) - kAddressWords;
  arrival.in_place = piece.pixels == span.size();
  if (arrival.body_words == 0) return MPI_SUCCESS;
  return MPI_Irecv(buffer.words.get() + header_words, static_cast<int>(arrival.body_words),
                   MPI_UINT32_T, peer, tag, comm, request);
}

std::optional<render::PixelRect> take_piece_body(ModelImage& image, render::PixelSpan,
                                                 const render::ReceiveBuffer& buffer,
                                                 render::PartsArrival& arrival,
                                                 std::size_t body_words, const render::RowOrder&) {
  if (body_words != arrival.body_words) return std::nullopt;
  return take_in(image, {buffer.words.get(), arrival.header_words + arrival.body_words},
                 arrival.in_place ? 0.0 : image.settings->costs.copy);
}

std::optional<render::PixelRect> composite_piece(ModelImage& image,
                                                 std::span<const std::uint32_t> message,
                                                 const render::RowOrder&) {
  return take_in(image, message, image.settings->costs.composite);
}

}  // namespace tetray::composite_bench
