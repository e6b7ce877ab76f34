// An image that knows only where its active pixels are, for running the compositor's real MPI
// schedule (render/composite/compositor.hpp) at thousands of simulated ranks, where real
// framebuffers would not fit this machine (a 64-megapixel image is 1.6 GB per rank).
//
// Its active pixels are a set of footprints: rectangles that are pairwise disjoint or equal, as
// the bench's dense and sparse layouts give (bench_images.hpp). A piece of a span carries,
// instead of pixels, the address of a ModelPiece (the simulator runs every rank in one
// process): the footprints it covers and the size of the real message, which the statistics
// count. On the wire it takes the real message's size divided by the byte scale; a run scaled
// so divides the network's bandwidth by the same factor (SMPI's bandwidth factor), which leaves
// every transfer time as it was while the host copies less.
//
// Computation between MPI calls is injected, not run: each kernel's pixels times the per-pixel
// cost measured on this machine (`PixelCosts`), as simulated time on the rank's host. Scanned
// pixels cost `scan`, active pixels written into a message `encode` (the copying encoder's cost,
// whose scanning is part of it), received ones `composite`, or `copy` in the assembly. A piece
// whose active pixels are one run, or interlaced every pixel of its span, is sent from the image
// without the copies, as the real compositor sends it (outgoing_piece): its pixels cost only
// their scan; an assembly piece holding every pixel of its span lands in the image uncopied.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "render/composite/composite_codec.hpp"
#include "render/composite/composite_region.hpp"

namespace tetray::composite_bench {

struct PixelCosts {
  double scan = 0;       // seconds per pixel scanned for activity
  double encode = 0;     // per active pixel written into a message, scanning included
  double composite = 0;  // per pixel of a message composited into the image
  double copy = 0;       // per pixel of a message copied into the image (the assembly)
};

// Computation of `seconds` on this rank: simulated time under SMPI; outside the simulator the
// model is not used for timing and this does nothing.
void inject_compute(double seconds);

// The real message a piece stands for.
struct ModelPiece {
  std::uint64_t words = 0;   // 32-bit words of the real message
  std::uint64_t pixels = 0;  // active pixels in it
  std::vector<render::PixelRect> footprints;
  render::PixelRect rect;  // holds its active pixels, as the real message's rectangle
};

class ModelMessage {
 public:
  ModelMessage() = default;
  // A message standing for `piece`, `byte_scale` times shorter on the wire (at least the two
  // words of the piece's address).
  ModelMessage(std::unique_ptr<ModelPiece> piece, int byte_scale);

  std::uint32_t* data() { return words_.get(); }
  const std::uint32_t* data() const { return words_.get(); }
  std::size_t size() const { return size_; }

 private:
  std::unique_ptr<std::uint32_t[]> words_;
  std::size_t size_ = 0;
};

// The piece a message carries; the receiver takes it over once.
std::unique_ptr<ModelPiece> take_piece(std::span<const std::uint32_t> message);
const ModelPiece& peek_piece(std::span<const std::uint32_t> message);

struct ModelSettings {
  PixelCosts costs;
  int byte_scale = 1;
};

struct ModelImage {
  int width = 0;
  int height = 0;
  std::vector<render::PixelRect> footprints;  // pairwise disjoint or equal, deduplicated
  const ModelSettings* settings = nullptr;

  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
};

// The compositor's image operations (compositor.hpp), each injecting its computation.
render::PixelRect active_rect(const ModelImage& image, render::PixelRect within);
inline render::PixelRect image_rect(const ModelImage& image) {
  return {0, 0, image.width, image.height};
}
ModelMessage outgoing_piece(const ModelImage& image, render::PixelSpan span, render::PixelRect hint,
                            const render::RowOrder& order);
int isend_piece(ModelMessage& message, int peer, int tag, MPI_Comm comm, MPI_Request* request);
// The assembly's two parts: the piece's address as the header, the rest of its scaled size as
// the body. A piece that is its whole span is taken in without the copy's cost, as the real
// one lands in the image.
int isend_piece_parts(ModelMessage& message, int peer, int tag, MPI_Comm comm,
                      MPI_Request requests[2]);
int post_piece_body(ModelImage& image, render::PixelSpan span, render::ReceiveBuffer& buffer,
                    std::size_t header_words, int peer, int tag, MPI_Comm comm,
                    MPI_Request* request, render::PartsArrival& arrival,
                    const render::RowOrder& order);
std::optional<render::PixelRect> take_piece_body(ModelImage& image, render::PixelSpan span,
                                                 const render::ReceiveBuffer& buffer,
                                                 render::PartsArrival& arrival,
                                                 std::size_t body_words,
                                                 const render::RowOrder& order);
std::optional<render::PixelRect> composite_piece(ModelImage& image,
                                                 std::span<const std::uint32_t> message,
                                                 const render::RowOrder& order);
std::uint64_t message_bytes(const ModelMessage& message);
std::size_t piece_capacity(const ModelImage& image, render::PixelSpan span);
std::uint64_t piece_bytes(const ModelImage& image, std::span<const std::uint32_t> piece);

// What of `rect` (image coordinates) a span of schedule indices (row-major, `width` per row,
// rows in `order`) holds: its pixels, the rows with at least one of them, and the rectangle of
// those rows.
struct SpanCover {
  std::uint64_t pixels = 0;
  std::uint64_t rows = 0;
  render::PixelRect rect;
};
SpanCover span_cover(render::PixelSpan span, render::PixelRect rect, int width,
                     const render::RowOrder& order = {});

}  // namespace tetray::composite_bench
