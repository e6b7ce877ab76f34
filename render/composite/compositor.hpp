// The schedule of composite.cpp as a template over what holds the pixels, so that the one MPI
// code runs both on real framebuffers and, in the simulator's benchmark, on images that only
// know where their active pixels are (tools/composite_bench/). An `Image` provides, found by
// argument-dependent lookup (composite_codec.hpp says what each does for a Framebuffer):
//
//   PixelRect active_rect(const Image&, PixelRect within);   of the active pixels within
//   PixelRect image_rect(const Image&);                      the whole image
//   Message outgoing_piece(const Image&, PixelSpan, PixelRect, const RowOrder&);  the span's
//       active pixels
//   int isend_piece(Message&, int peer, int tag, MPI_Comm, MPI_Request*);  its MPI_Isend
//   int isend_piece_parts(Message&, int peer, int tag, MPI_Comm, MPI_Request[2]);  the same as
//       a header message and a body message (the assembly's pieces)
//   int post_piece_body(Image&, PixelSpan, ReceiveBuffer&, std::size_t header_words, int peer,
//       int tag, MPI_Comm, MPI_Request*, PartsArrival&, const RowOrder&);  the body's receive,
//       in place when the header says the piece is its whole span
//   std::optional<PixelRect> take_piece_body(Image&, PixelSpan, ReceiveBuffer&, PartsArrival&,
//       std::size_t body_words, const RowOrder&);  the assembled piece, copied unless it
//       arrived in place
//   std::optional<PixelRect> composite_piece(Image&, std::span<const std::uint32_t>,
//       const RowOrder&);
//   std::size_t Image::pixel_count() const;
//   std::uint64_t message_bytes(const Message&);   the bytes the message stands for
//   std::size_t piece_capacity(const Image&, PixelSpan);   most words a piece of the span takes
//   std::uint64_t piece_bytes(const Image&, std::span<const std::uint32_t>);   of a received one
//
// where a Message arrives as 32-bit words, and spans are of the schedule's indices in the
// RowOrder (composite_region.hpp) the ranks agreed on.
//
// Rounds (composite_plan.hpp): the fold, the radix-k rounds, then the assembly of the final
// image on the root by the same groups in reverse order. In the last radix round each group
// split one span into k consecutive parts, so its members hold neighbouring parts: the members
// of digit 1..k-1 send theirs to the member of digit 0, which then holds the group's whole span.
// Going back round by round, every message is one contiguous span and the root (virtual rank
// 0, digit 0 in every round) receives the image in as many steps as there were rounds, not
// P - 1 messages: log P latencies instead of P.
#pragma once

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "render/composite/composite.hpp"
#include "render/composite/composite_agreement.hpp"
#include "render/composite/composite_codec.hpp"
#include "render/composite/composite_plan.hpp"
#include "render/composite/composite_region.hpp"

namespace tetray::render {

// Tags of the compositor's messages: the fold, then one per round, then one per assembly step.
// The communicator should be reserved for tetray (the adaptor duplicates the solver's) so that
// no other message can match them.
inline constexpr int kFirstCompositeTag = 7700;

// Receives posted at once: a round of radix k expects k - 1 <= 7 pieces; the plain gather's
// root takes its P - 1 in batches, so that it holds at most this many buffers.
inline constexpr std::size_t kPostedReceives = 8;

template <typename Image>
class Compositor {
 public:
  using Message =
      decltype(outgoing_piece(std::declval<const Image&>(), PixelSpan{}, PixelRect{}, RowOrder{}));

  // `rank` is this rank in `comm`; the plan's virtual rank 0 is `root`. `start`: when the
  // composite began (the scan for `active` and the agreement count in round 1); `rows`: the
  // image row of each schedule row, empty in natural order.
  Compositor(Image& image, MPI_Comm comm, int rank, const CompositeOptions& options,
             CompositePlan plan, CompositeStats& stats, std::vector<ReceiveBuffer>& buffers,
             double start, PixelRect active, std::vector<std::uint32_t> rows)
      : start_(start),
        image_(image),
        comm_(comm),
        root_(options.root),
        virtual_rank_((rank - options.root + plan.rank_count) % plan.rank_count),
        plan_(std::move(plan)),
        stats_(stats),
        buffers_(buffers),
        span_{0, static_cast<std::uint32_t>(image.pixel_count())},
        rect_(active),
        rows_(std::move(rows)) {}

  Compositor(const Compositor&) = delete;
  Compositor& operator=(const Compositor&) = delete;

  int run() {
    int tag = kFirstCompositeTag;
    if (plan_.folded_count() > 0) {
      if (int error = timed(fold(tag++)); error != MPI_SUCCESS) return error;
      if (virtual_rank_ >= plan_.swap_count) return MPI_SUCCESS;
    }
    for (std::size_t round = 0; round < plan_.radices.size(); ++round) {
      if (int error = timed(swap(static_cast<int>(round), tag++)); error != MPI_SUCCESS) {
        return error;
      }
    }
    if (plan_.radices.empty()) return timed(gather(tag));
    for (auto round = static_cast<int>(plan_.radices.size()) - 1; round >= 0; --round) {
      bool handed_on = false;
      if (int error = timed(assemble(round, tag++, handed_on)); error != MPI_SUCCESS) return error;
      if (handed_on) return MPI_SUCCESS;
    }
    return MPI_SUCCESS;
  }

 private:
  // Records when the round that returned `error` ended (CompositeStats::round_seconds).
  int timed(int error) {
    stats_.round_seconds.push_back(MPI_Wtime() - start_);
    return error;
  }

  int actual_rank(int virtual_rank) const { return (virtual_rank + root_) % plan_.rank_count; }

  // Ranks past swap_count hand their whole image to a partner among the first ones.
  int fold(int tag) {
    std::vector<Outgoing> sends;
    std::vector<Incoming> receives;
    if (virtual_rank_ >= plan_.swap_count) {
      sends.push_back({actual_rank(virtual_rank_ - plan_.swap_count), encode(span_)});
    } else if (virtual_rank_ < plan_.folded_count()) {
      receives.push_back({actual_rank(virtual_rank_ + plan_.swap_count), span_});
    }
    return exchange(tag, std::move(sends), receives);
  }

  // Radix-k round: the group splits the current span into k parts; this rank keeps part
  // `digit`, sends every other part to the member that keeps it and receives its own part from
  // every other member.
  int swap(int round, int tag) {
    const int radix = plan_.radices[static_cast<std::size_t>(round)];
    const RoundPosition position = round_position(plan_, round, virtual_rank_);
    const PixelSpan kept = split_span(span_, radix, position.digit);
    std::vector<Outgoing> sends;
    std::vector<Incoming> receives;
    for (int part = 0; part < radix; ++part) {
      if (part == position.digit) continue;
      const int peer = actual_rank(virtual_rank_ + (part - position.digit) * position.stride);
      sends.push_back({peer, encode(split_span(span_, radix, part))});
      receives.push_back({peer, kept});
    }
    spans_before_round_.push_back(span_);
    span_ = kept;
    return exchange(tag, std::move(sends), receives);
  }

  // Assembly step of `round`, the rounds taken back in reverse: digit 0 receives its group's
  // other parts and holds the span the group split; the others hand theirs on and are done.
  // This rank's own pixels outside its span need no clearing before they are overwritten: the
  // composited pixel that arrives for each was chosen over it, or is it, and a pixel whose
  // composite is the background was the background here too. So the pieces are copied, not
  // composited (take_piece_body): no comparison, the same image; a piece that is its whole span
  // lands in the image itself.
  int assemble(int round, int tag, bool& handed_on) {
    const int radix = plan_.radices[static_cast<std::size_t>(round)];
    const RoundPosition position = round_position(plan_, round, virtual_rank_);
    const PixelSpan whole = spans_before_round_[static_cast<std::size_t>(round)];
    handed_on = position.digit != 0;
    if (handed_on) {
      const int keeper = virtual_rank_ - position.digit * position.stride;
      return exchange(tag, one_send(actual_rank(keeper), encode(span_)), {}, Arrival::copy);
    }
    std::vector<Incoming> receives;
    for (int part = 1; part < radix; ++part) {
      receives.push_back(
          {actual_rank(virtual_rank_ + part * position.stride), split_span(whole, radix, part)});
    }
    span_ = whole;
    return exchange(tag, {}, receives, Arrival::copy);
  }

  // The plan without rounds: every rank's image goes straight to the root.
  int gather(int tag) {
    if (virtual_rank_ != 0) return exchange(tag, one_send(root_, encode(span_)), {});
    std::vector<Incoming> receives;
    for (int v = 1; v < plan_.swap_count; ++v) receives.push_back({actual_rank(v), span_});
    return exchange(tag, {}, receives);
  }

  struct Outgoing {
    int peer;
    Message message;
  };

  // A piece this rank expects: from whom, and the span it covers (which bounds its size).
  struct Incoming {
    int peer;
    PixelSpan span;
  };

  // (A braced list would copy the message; messages only move.)
  static std::vector<Outgoing> one_send(int peer, Message message) {
    std::vector<Outgoing> sends;
    sends.push_back({peer, std::move(message)});
    return sends;
  }

  RowOrder order() const { return {rows_}; }

  Message encode(PixelSpan span) const { return outgoing_piece(image_, span, rect_, order()); }

  // What a received piece does to the image: composited by wins_over, or copied over it (the
  // assembly's pieces, already final).
  enum class Arrival { composite, copy };

  // Posts the receives (at most kPostedReceives at a time, each into a buffer as large as its
  // span allows), sends every message, takes in the incoming pieces in their order of arrival
  // (the result does not depend on it: wins_over is a total order, and copied pieces do not
  // overlap), then waits for the sends. Receives are posted from known peers rather than
  // probed: a probe polls in SimGrid's SMPI, whose simulated time it would distort. The
  // assembly's pieces (Arrival::copy) travel as a header and a body, so that a piece that is
  // its whole span lands in the image itself (receive_parts_batch).
  int exchange(int tag, std::vector<Outgoing> sends, const std::vector<Incoming>& receives,
               Arrival arrival = Arrival::composite) {
    std::vector<MPI_Request> send_requests(2 * sends.size(), MPI_REQUEST_NULL);
    int error = MPI_SUCCESS;
    std::uint64_t held = 0;
    for (std::size_t k = 0; k < sends.size() && error == MPI_SUCCESS; ++k) {
      Message& message = sends[k].message;
      MPI_Request* requests = &send_requests[2 * k];
      error = arrival == Arrival::copy
                  ? isend_piece_parts(message, sends[k].peer, tag, comm_, requests)
                  : isend_piece(message, sends[k].peer, tag, comm_, requests);
      stats_.bytes_sent += message_bytes(message);
      held += message_bytes(message);
    }
    stats_.peak_message_bytes = std::max(stats_.peak_message_bytes, held);
    for (std::size_t first = 0; first < receives.size() && error == MPI_SUCCESS;
         first += kPostedReceives) {
      const std::size_t count = std::min(kPostedReceives, receives.size() - first);
      const auto batch = std::span(receives).subspan(first, count);
      error = arrival == Arrival::copy ? receive_parts_batch(tag, batch, held)
                                       : receive_batch(tag, batch, held);
    }
    const int wait_error = MPI_Waitall(static_cast<int>(send_requests.size()), send_requests.data(),
                                       MPI_STATUSES_IGNORE);
    return error != MPI_SUCCESS ? error : wait_error;
  }

  // `held`: bytes of this round's outgoing messages, for the peak of what the rank holds.
  int receive_batch(int tag, std::span<const Incoming> receives, std::uint64_t held) {
    if (buffers_.size() < receives.size()) buffers_.resize(receives.size());
    std::vector<MPI_Request> requests(receives.size(), MPI_REQUEST_NULL);
    for (std::size_t k = 0; k < receives.size(); ++k) {
      ReceiveBuffer& buffer = buffers_[k];
      buffer.reserve(piece_capacity(image_, receives[k].span));
      if (int error = MPI_Irecv(buffer.words.get(), static_cast<int>(buffer.capacity), MPI_UINT32_T,
                                receives[k].peer, tag, comm_, &requests[k]);
          error != MPI_SUCCESS) {
        cancel(requests);
        return error;
      }
    }
    for (std::size_t done = 0; done < receives.size(); ++done) {
      std::size_t index = 0, count = 0;
      if (int error = wait_any(requests, index, count); error != MPI_SUCCESS) return error;
      const std::span<const std::uint32_t> piece(buffers_[index].words.get(), count);
      const std::uint64_t bytes = piece_bytes(image_, piece);
      held += bytes;
      stats_.bytes_received += bytes;
      const auto piece_rect = composite_piece(image_, piece, order());
      if (!piece_rect) {
        cancel(requests);
        return MPI_ERR_OTHER;
      }
      rect_ = united(rect_, *piece_rect);
    }
    stats_.peak_message_bytes = std::max(stats_.peak_message_bytes, held);
    return MPI_SUCCESS;
  }

  // The assembly's pieces: each header's receive posted at once, each body's when its header
  // has come (into the image where the piece is its whole span), each piece taken in when its
  // body has come. Requests [0, n) are the headers', [n, 2n) the bodies'.
  int receive_parts_batch(int tag, std::span<const Incoming> receives, std::uint64_t held) {
    const std::size_t n = receives.size();
    if (buffers_.size() < n) buffers_.resize(n);
    std::vector<MPI_Request> requests(2 * n, MPI_REQUEST_NULL);
    std::vector<PartsArrival> arrivals(n);
    for (std::size_t k = 0; k < n; ++k) {
      ReceiveBuffer& buffer = buffers_[k];
      buffer.reserve(piece_capacity(image_, receives[k].span));
      if (int error = MPI_Irecv(buffer.words.get(), static_cast<int>(kFirstPartWords), MPI_UINT32_T,
                                receives[k].peer, tag, comm_, &requests[k]);
          error != MPI_SUCCESS) {
        cancel(requests);
        return error;
      }
    }
    for (std::size_t pending = n; pending > 0;) {
      std::size_t index = 0, count = 0;
      if (int error = wait_any(requests, index, count); error != MPI_SUCCESS) return error;
      const std::size_t k = index % n;
      const Incoming& incoming = receives[k];
      const bool header = index < n;
      if (header) {
        if (int error = post_piece_body(image_, incoming.span, buffers_[k], count, incoming.peer,
                                        tag, comm_, &requests[n + k], arrivals[k], order());
            error != MPI_SUCCESS) {
          cancel(requests);
          return error;
        }
        if (arrivals[k].body_words > 0) continue;  // its body is on the way
      }
      const std::size_t body = header ? 0 : count;
      const std::uint64_t bytes = piece_bytes(
          image_, {buffers_[k].words.get(), arrivals[k].header_words + arrivals[k].body_words});
      held += bytes;
      stats_.bytes_received += bytes;
      const auto piece_rect =
          take_piece_body(image_, incoming.span, buffers_[k], arrivals[k], body, order());
      if (!piece_rect) {
        cancel(requests);
        return MPI_ERR_OTHER;
      }
      rect_ = united(rect_, *piece_rect);
      --pending;
    }
    stats_.peak_message_bytes = std::max(stats_.peak_message_bytes, held);
    return MPI_SUCCESS;
  }

  // Waits for any of `requests`: its index and the 32-bit words it received, or the error, the
  // receives still pending cancelled.
  static int wait_any(std::vector<MPI_Request>& requests, std::size_t& index, std::size_t& words) {
    int which = MPI_UNDEFINED;
    MPI_Status status;
    const int error =
        MPI_Waitany(static_cast<int>(requests.size()), requests.data(), &which, &status);
    if (error != MPI_SUCCESS || which == MPI_UNDEFINED) {
      cancel(requests);
      return error != MPI_SUCCESS ? error : MPI_ERR_REQUEST;
    }
    int count = 0;
    MPI_Get_count(&status, MPI_UINT32_T, &count);
    index = static_cast<std::size_t>(which);
    words = static_cast<std::size_t>(count);
    return MPI_SUCCESS;
  }

  // Cancels and completes the receives still pending after an error, so that no buffer is
  // written after it is gone.
  static void cancel(std::vector<MPI_Request>& requests) {
    for (MPI_Request& request : requests) {
      if (request != MPI_REQUEST_NULL) MPI_Cancel(&request);
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  }

  double start_;
  Image& image_;
  MPI_Comm comm_;
  int root_;
  int virtual_rank_;
  CompositePlan plan_;
  CompositeStats& stats_;
  std::vector<ReceiveBuffer>& buffers_;  // the caller's, kept between calls
  PixelSpan span_;
  PixelRect rect_;
  std::vector<std::uint32_t> rows_;            // RowOrder::rows
  std::vector<PixelSpan> spans_before_round_;  // the span each radix round split
};

// render::composite for any Image (with width and height): agree, plan, run. `image_ok` says
// whether this rank's image is well formed.
template <typename Image>
int composite_image(Image& image, bool image_ok, MPI_Comm comm, const CompositeOptions& options,
                    CompositeStats& stats, CompositeWorkspace& workspace) {
  stats = {};
  int rank = 0, rank_count = 1;
  if (int error = MPI_Comm_size(comm, &rank_count); error != MPI_SUCCESS) return error;
  if (rank_count == 1) return options.root == 0 ? MPI_SUCCESS : MPI_ERR_ROOT;
  const double start = MPI_Wtime();
  MPI_Comm_rank(comm, &rank);
  const PixelRect active =
      image_ok ? active_rect(image, options.active_hint.value_or(image_rect(image))) : PixelRect{};
  int tallest_active_rows = 0;
  int error = agree_on_inputs(image.width, image.height, image_ok, comm, options, rank_count,
                              active.empty() ? 0 : active.y1 - active.y0, tallest_active_rows);
  if (error == MPI_SUCCESS && image.pixel_count() > 0) {
    CompositePlan plan = make_plan(rank_count, options.algorithm);
    stats.rounds = plan.round_count();
    stats.interlaced = interlace_rows(options.rows, tallest_active_rows, image.height);
    error =
        Compositor<Image>(
            image, comm, rank, options, std::move(plan), stats, workspace.receive_buffers, start,
            active, stats.interlaced ? interlaced_rows(image.height) : std::vector<std::uint32_t>{})
            .run();
  }
  stats.seconds = MPI_Wtime() - start;
  return error;
}

}  // namespace tetray::render
