// Sort-last depth compositing of RGBA+Z framebuffers across MPI ranks. Binary swap for
// power-of-two rank counts, radix-k otherwise, then the image assembled on the root by a tree
// (compositor.hpp); ranks exchange only their active region, run-length encoded. Ties in depth
// are broken by the hit key (framebuffer.hpp, wins_over), so the result does not depend on the
// rank count.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "render/composite/composite_region.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::render {

enum class CompositeAlgorithm { automatic, binary_swap, radix_k, gather };

// The order in which the schedule takes the image's rows (RowOrder, composite_region.hpp).
// Natural order splits the image into bands of rows: where a rank's hits cover a short band of
// the screen, all of a group's pixels can fall in one member's part. Interlaced order spreads
// every band over all parts, at the price of a run per row (no piece sent from the image without
// a copy, unless it is within one row). automatic: interlaced when every rank's active rows
// span at most a quarter of the image's height (the domain decompositions of many ranks),
// natural otherwise (kInterlaceBelow, composite_plan.hpp).
enum class CompositeRows { automatic, natural, interlaced };

struct CompositeOptions {
  CompositeAlgorithm algorithm = CompositeAlgorithm::automatic;
  int root = 0;  // the rank that receives the final image
  // A rectangle this rank knows holds all its active pixels (the screen bound of its part of
  // the mesh): only it is scanned for them, instead of the whole image, whose scan is the
  // largest cost of a rank that covers little of a large image. Per rank; unset: the image.
  std::optional<PixelRect> active_hint;
  CompositeRows rows = CompositeRows::automatic;
};

struct CompositeStats {
  double seconds = 0;
  std::uint64_t bytes_sent = 0;      // by this rank
  std::uint64_t bytes_received = 0;  // by this rank
  int rounds = 0;
  bool interlaced = false;  // the schedule took the rows interlaced (CompositeRows)
  // The most bytes of messages this rank held at once (its sends of a round and the message
  // being received), beside the image itself: the compositor's memory.
  std::uint64_t peak_message_bytes = 0;
  // Seconds from the start of the schedule to the end of each of this rank's rounds (fold,
  // radix rounds, assembly steps), as far as it took part.
  std::vector<double> round_seconds;
};

// Room for one incoming piece: grown, never shrunk, and left uninitialised (a receive writes
// what it uses).
struct ReceiveBuffer {
  std::unique_ptr<std::uint32_t[]> words;
  std::size_t capacity = 0;

  void reserve(std::size_t count) {
    if (count > capacity) {
      words.reset(new std::uint32_t[count]);
      capacity = count;
    }
  }
};

// What a caller that composites every step keeps between calls: the receive buffers, whose
// pages a fresh allocation would fault in again each time (about 20 ms a step for a dense 2048²
// image on 2 ranks here). At most 7/8 of the image's 24 bytes per pixel. One per thread that
// composites.
struct CompositeWorkspace {
  std::vector<ReceiveBuffer> receive_buffers;
};

// Composites `image` (this rank's part, same size on every rank) over `comm`. On return the
// root's `image` holds the composited image; other ranks' images are unspecified. With one rank
// it returns at once. Collective: every rank of `comm` must call it. Returns MPI_SUCCESS or the
// first MPI error code.
int composite(Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
              CompositeStats* stats = nullptr, CompositeWorkspace* workspace = nullptr);

}  // namespace tetray::render
