// The wire format of the compositor: a piece of an image (a span of pixels) sent as its active
// pixels only. Background runs are skipped (run-length encoded) and only the rows and columns
// of the piece's active rectangle are scanned, so a rank whose part of the mesh covers little of
// the screen sends, and reads, little.
//
// Layout, in 32-bit words: start, run count, pixel count, the rectangle of the pixels sent (x0,
// y0, x1, y1, in the image), then per run: pixels skipped since the previous run, pixel count n,
// and the run's pixels as three arrays, as the framebuffer holds them: 4 n words r, g, b, a, n
// depths (float bits), n hit keys. Positions are the schedule's indices (RowOrder,
// composite_region.hpp), the image's own in natural order. A run continues across rows where
// the active pixels do and the order is natural (a full-width region is one run). So encoding is a
// scan for runs and three copies per run, decoding works on arrays (the compositing loop
// vectorizes), and a pixel costs 24 bytes.
//
// A piece whose active pixels are one run (a span of a dense image, full-width rows) is sent
// without the copies (outgoing_piece, isend_piece): its nine header words, then its three arrays
// straight from the framebuffer, one MPI datatype over the four blocks. The receiver sees the
// same words either way.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "render/composite/composite.hpp"
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

// The most words a piece of `span` can take: every pixel active, in one run (natural order) or
// one run per row of the span (interlaced, RowOrder).
inline std::size_t piece_capacity(std::uint32_t width, PixelSpan span) {
  const std::size_t rows =
      span.size() == 0 || width == 0 ? 0 : (span.end - 1) / width - span.begin / width + 1;
  return kPieceHeaderWords + kRunHeaderWords * (rows + 1) + kPixelWords * std::size_t{span.size()};
}

inline std::size_t piece_capacity(const Framebuffer& image, PixelSpan span) {
  return piece_capacity(static_cast<std::uint32_t>(image.width), span);
}

// The bytes of a received piece.
inline std::uint64_t piece_bytes(const Framebuffer&, std::span<const std::uint32_t> piece) {
  return piece.size() * sizeof(std::uint32_t);
}

// Encodes the active pixels of `span` (of schedule indices in `order`, composite_region.hpp);
// `hint` must hold every active pixel of the span (a looser rectangle costs scanning time, never
// correctness).
PieceMessage encode_piece(const Framebuffer& image, PixelSpan span, PixelRect hint,
                          const RowOrder& order = {});

// Where a piece's pixels lie in the image, a run each: image index and pixel count.
struct Segment {
  std::size_t at = 0;
  std::size_t count = 0;
};

// The segments of the pixels of `span` (schedule indices): the span itself where it is
// consecutive in the image (RowOrder::consecutive), else one per schedule row.
std::vector<Segment> span_segments(PixelSpan span, std::uint32_t width, const RowOrder& order);

// A piece as the compositor sends it: the encoded words, or, where the span's active pixels are
// one run, or interlaced every pixel of the span, the header and run headers alone, the runs'
// pixels to follow from `image`. Holds the MPI
// datatype of its send until it is destroyed, which must come after the send completes; the
// image's run must not change until then either.
class OutgoingPiece {
 public:
  OutgoingPiece() = default;
  // `segments`: where the runs' pixels are in `image`, one per run of `words`.
  OutgoingPiece(PieceMessage words, const Framebuffer* image, std::vector<Segment> segments)
      : words_(std::move(words)), image_(image), segments_(std::move(segments)) {}
  OutgoingPiece(OutgoingPiece&& other) noexcept;
  OutgoingPiece& operator=(OutgoingPiece&& other) noexcept;
  ~OutgoingPiece();

  bool in_place() const { return image_ != nullptr; }
  // Words on the wire: the header's and, in place, the run's pixels'.
  std::size_t wire_words() const;
  // The message as it travels (tests).
  PieceMessage wire() const;
  // MPI_Isend of the message: the words, or one datatype over the headers and the runs' arrays.
  int isend(int peer, int tag, MPI_Comm comm, MPI_Request* request);
  // The same as two messages, the first kFirstPartWords words (or fewer, all there are), then
  // the rest when there is any (requests[1] stays null otherwise).
  int isend_parts(int peer, int tag, MPI_Comm comm, MPI_Request requests[2]);

 private:
  // The runs' arrays and headers, after the first kFirstPartWords words when `first` is given, as
  // one datatype of words at their distances from `base` (into type_).
  int make_run_type(const std::uint32_t* first, const void* base);
  std::size_t pixel_count() const;

  PieceMessage words_;
  const Framebuffer* image_ = nullptr;
  std::vector<Segment> segments_;
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

// The assembly sends a piece as two messages: its first kFirstPartWords words (the piece's
// header and its first run's), then the rest, the body. Having read the header, the receiver
// takes a piece that is one run over its whole span straight into its image.
inline constexpr std::size_t kFirstPartWords = kPieceHeaderWords + kRunHeaderWords;

// What a receiver learnt from a piece's header: the words of each part, whether the body goes
// straight into the image (and where), and the datatype of that receive (freed with it).
struct PartsArrival {
  std::size_t header_words = 0;
  std::size_t body_words = 0;
  bool in_place = false;
  std::vector<Segment> segments;
  MPI_Datatype type = MPI_DATATYPE_NULL;

  PartsArrival() = default;
  PartsArrival(const PartsArrival&) = delete;
  PartsArrival& operator=(const PartsArrival&) = delete;
  ~PartsArrival() {
    if (type != MPI_DATATYPE_NULL) MPI_Type_free(&type);
  }
};

// encode_piece without the copies where the active pixels are one run.
OutgoingPiece outgoing_piece(const Framebuffer& image, PixelSpan span, PixelRect hint,
                             const RowOrder& order = {});

inline std::uint64_t message_bytes(const OutgoingPiece& piece) {
  return piece.wire_words() * sizeof(std::uint32_t);
}

inline int isend_piece(OutgoingPiece& piece, int peer, int tag, MPI_Comm comm,
                       MPI_Request* request) {
  return piece.isend(peer, tag, comm, request);
}

inline int isend_piece_parts(OutgoingPiece& piece, int peer, int tag, MPI_Comm comm,
                             MPI_Request requests[2]) {
  return piece.isend_parts(peer, tag, comm, requests);
}

// Posts the receive of a piece's body from the header that came (`header_words` words at the
// start of `buffer`): straight into `image` when the piece holds every pixel of `span` (one run,
// or interlaced one per row), into the buffer after the header otherwise; none when the piece
// has no body. MPI_ERR_OTHER when the header does not describe a piece of `span`.
int post_piece_body(Framebuffer& image, PixelSpan span, ReceiveBuffer& buffer,
                    std::size_t header_words, int peer, int tag, MPI_Comm comm,
                    MPI_Request* request, PartsArrival& arrival, const RowOrder& order = {});

// The piece once its body came (`body_words` of them): copied into `image` unless it came in
// place. Its rectangle, or nothing when the message is malformed.
std::optional<PixelRect> take_piece_body(Framebuffer& image, PixelSpan span,
                                         const ReceiveBuffer& buffer, PartsArrival& arrival,
                                         std::size_t body_words, const RowOrder& order = {});

// Composites an encoded piece into `image` by wins_over and returns the rectangle of its
// pixels, or nothing, leaving `image` as it was, when the message is malformed or does not fit
// the image.
std::optional<PixelRect> composite_piece(Framebuffer& image, std::span<const std::uint32_t> message,
                                         const RowOrder& order = {});

// Writes the piece's pixels over those of `image` (the assembly of the final image, whose
// pieces are already composited); otherwise as composite_piece.
std::optional<PixelRect> copy_piece(Framebuffer& image, std::span<const std::uint32_t> message,
                                    const RowOrder& order = {});

}  // namespace tetray::render
