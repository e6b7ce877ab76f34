// The schedule of composite.cpp as a template over what holds the pixels, so that the one MPI
// code runs both on real framebuffers and, in the simulator's benchmark, on images that only
// know where their active pixels are (tools/composite_bench/). An `Image` provides, found by
// argument-dependent lookup (composite_codec.hpp says what each does for a Framebuffer):
//
//   PixelRect active_rect(const Image&);                    every active pixel lies inside
//   Message encode_piece(const Image&, PixelSpan, PixelRect);  the span's active pixels
//   std::optional<PixelRect> composite_piece(Image&, std::span<const std::uint32_t>);
//   std::optional<PixelRect> copy_piece(Image&, std::span<const std::uint32_t>);  (assembly)
//   std::size_t Image::pixel_count() const;
//   std::uint64_t message_bytes(const Message&);   the bytes the message stands for
//
// where Message has data(), size() (in 32-bit words, what goes on the wire) and resize(n), and
// serves as the receive buffer too.
//
// Rounds (composite_plan.hpp): the fold, the radix-k rounds, then the assembly of the final
// image on the root by the same groups in reverse order. In the last radix round each group
// split one span into k consecutive parts, so its members hold neighbouring parts: the members
// of digit 1..k-1 send theirs to the member of digit 0, which then holds the group's whole span.
// Going back round by round, every message is one contiguous span and the root (virtual rank
// 0, digit 0 in every round) receives the image in as many steps as there were rounds, not
// P - 1 messages: log P latencies instead of P (Moreland et al., SC 2011, §4, the same tree).
#pragma once

#include <mpi.h>

#include <algorithm>
#include <cstdint>
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

template <typename Image>
class Compositor {
 public:
  using Message = decltype(encode_piece(std::declval<const Image&>(), PixelSpan{}, PixelRect{}));

  // `rank` is this rank in `comm`; the plan's virtual rank 0 is `root`.
  Compositor(Image& image, MPI_Comm comm, int rank, int root, CompositePlan plan,
             CompositeStats& stats)
      : start_(MPI_Wtime()),
        image_(image),
        comm_(comm),
        root_(root),
        virtual_rank_((rank - root + plan.rank_count) % plan.rank_count),
        plan_(std::move(plan)),
        stats_(stats),
        span_{0, static_cast<std::uint32_t>(image.pixel_count())},
        rect_(active_rect(image)) {}

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
    if (virtual_rank_ >= plan_.swap_count) {
      sends.push_back({actual_rank(virtual_rank_ - plan_.swap_count), encode(span_)});
    }
    return exchange(tag, std::move(sends), virtual_rank_ < plan_.folded_count() ? 1 : 0);
  }

  // Radix-k round: the group splits the current span into k parts; this rank keeps part
  // `digit` and sends every other part to the member that keeps it.
  int swap(int round, int tag) {
    const int radix = plan_.radices[static_cast<std::size_t>(round)];
    const RoundPosition position = round_position(plan_, round, virtual_rank_);
    std::vector<Outgoing> sends;
    for (int part = 0; part < radix; ++part) {
      if (part == position.digit) continue;
      const int peer = virtual_rank_ + (part - position.digit) * position.stride;
      sends.push_back({actual_rank(peer), encode(split_span(span_, radix, part))});
    }
    spans_before_round_.push_back(span_);
    span_ = split_span(span_, radix, position.digit);
    return exchange(tag, std::move(sends), radix - 1);
  }

  // Assembly step of `round`, the rounds taken back in reverse: digit 0 receives its group's
  // other parts and holds the span the group split; the others hand theirs on and are done.
  // This rank's own pixels outside its span need no clearing before they are overwritten: the
  // composited pixel that arrives for each was chosen over it, or is it, and a pixel whose
  // composite is the background was the background here too. So the pieces are copied, not
  // composited (copy_piece): no comparison, the same image.
  int assemble(int round, int tag, bool& handed_on) {
    const RoundPosition position = round_position(plan_, round, virtual_rank_);
    const PixelSpan whole = spans_before_round_[static_cast<std::size_t>(round)];
    handed_on = position.digit != 0;
    if (handed_on) {
      const int keeper = virtual_rank_ - position.digit * position.stride;
      return exchange(tag, one_send(actual_rank(keeper), encode(span_)), 0);
    }
    span_ = whole;
    return exchange(tag, {}, plan_.radices[static_cast<std::size_t>(round)] - 1, Arrival::copy);
  }

  // The plan without rounds: every rank's image goes straight to the root.
  int gather(int tag) {
    if (virtual_rank_ != 0) return exchange(tag, one_send(root_, encode(span_)), 0);
    return exchange(tag, {}, plan_.swap_count - 1);
  }

  struct Outgoing {
    int peer;
    Message message;
  };

  // (A braced list would copy the message; messages only move.)
  static std::vector<Outgoing> one_send(int peer, Message message) {
    std::vector<Outgoing> sends;
    sends.push_back({peer, std::move(message)});
    return sends;
  }

  Message encode(PixelSpan span) const { return encode_piece(image_, span, rect_); }

  // What a received piece does to the image: composited by wins_over, or copied over it (the
  // assembly's pieces, already final).
  enum class Arrival { composite, copy };

  // Sends every message, takes in the incoming ones in their order of arrival (the result does
  // not depend on it: wins_over is a total order, and copied pieces do not overlap), then waits
  // for the sends.
  int exchange(int tag, std::vector<Outgoing> sends, int receive_count,
               Arrival arrival = Arrival::composite) {
    std::vector<MPI_Request> requests(sends.size(), MPI_REQUEST_NULL);
    int error = MPI_SUCCESS;
    std::uint64_t held = 0;
    for (std::size_t k = 0; k < sends.size() && error == MPI_SUCCESS; ++k) {
      const Message& message = sends[k].message;
      error = MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_UINT32_T,
                        sends[k].peer, tag, comm_, &requests[k]);
      stats_.bytes_sent += message_bytes(message);
      held += message_bytes(message);
    }
    stats_.peak_message_bytes = std::max(stats_.peak_message_bytes, held);
    for (int k = 0; k < receive_count && error == MPI_SUCCESS; ++k) {
      error = receive(tag, held, arrival);
    }
    const int wait_error =
        MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return error != MPI_SUCCESS ? error : wait_error;
  }

  // `held`: bytes of this round's outgoing messages, for the peak of what the rank holds.
  int receive(int tag, std::uint64_t held, Arrival arrival) {
    // Probe, then receive from the probed source: messages of one source and tag do not
    // overtake each other, and only this call receives on the compositor's tags. (Not the
    // matched MPI_Mprobe: SimGrid's SMPI, which runs this code at scale, lacks it.)
    MPI_Status status;
    if (int error = MPI_Probe(MPI_ANY_SOURCE, tag, comm_, &status); error != MPI_SUCCESS) {
      return error;
    }
    int count = 0;
    MPI_Get_count(&status, MPI_UINT32_T, &count);
    buffer_.resize(static_cast<std::size_t>(count));
    if (int error = MPI_Recv(buffer_.data(), count, MPI_UINT32_T, status.MPI_SOURCE, tag, comm_,
                             MPI_STATUS_IGNORE);
        error != MPI_SUCCESS) {
      return error;
    }
    const std::uint64_t bytes = message_bytes(buffer_);
    stats_.peak_message_bytes = std::max(stats_.peak_message_bytes, held + bytes);
    stats_.bytes_received += bytes;
    const std::span<const std::uint32_t> piece(buffer_.data(), buffer_.size());
    const auto piece_rect =
        arrival == Arrival::copy ? copy_piece(image_, piece) : composite_piece(image_, piece);
    if (!piece_rect) return MPI_ERR_OTHER;
    rect_ = united(rect_, *piece_rect);
    return MPI_SUCCESS;
  }

  double start_;  // first, so that the scan of the constructor counts in round 1
  Image& image_;
  MPI_Comm comm_;
  int root_;
  int virtual_rank_;
  CompositePlan plan_;
  CompositeStats& stats_;
  PixelSpan span_;
  PixelRect rect_;
  std::vector<PixelSpan> spans_before_round_;  // the span each radix round split
  Message buffer_;
};

// render::composite for any Image (with width and height): agree, plan, run. `image_ok` says
// whether this rank's image is well formed.
template <typename Image>
int composite_image(Image& image, bool image_ok, MPI_Comm comm, const CompositeOptions& options,
                    CompositeStats& stats) {
  stats = {};
  int rank = 0, rank_count = 1;
  if (int error = MPI_Comm_size(comm, &rank_count); error != MPI_SUCCESS) return error;
  if (rank_count == 1) return options.root == 0 ? MPI_SUCCESS : MPI_ERR_ROOT;
  const double start = MPI_Wtime();
  MPI_Comm_rank(comm, &rank);
  int error = agree_on_inputs(image.width, image.height, image_ok, comm, options, rank_count);
  if (error == MPI_SUCCESS && image.pixel_count() > 0) {
    CompositePlan plan = make_plan(rank_count, options.algorithm);
    stats.rounds = plan.round_count();
    error = Compositor<Image>(image, comm, rank, options.root, std::move(plan), stats).run();
  }
  stats.seconds = MPI_Wtime() - start;
  return error;
}

}  // namespace tetray::render
