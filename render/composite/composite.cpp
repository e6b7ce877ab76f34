#include "render/composite/composite.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "render/composite/composite_codec.hpp"
#include "render/composite/composite_plan.hpp"

namespace tetray::render {
namespace {

// Tags of the compositor's messages: the fold, then one per round, then the final gather. The
// communicator should be reserved for tetray (the adaptor duplicates the solver's) so that no
// other message can match them.
constexpr int kFirstTag = 7700;

struct Outgoing {
  int peer;
  PieceMessage message;
};

// One rank's part of the schedule: its virtual rank (the root is 0), the span it owns and a
// rectangle known to hold every active pixel of its image.
class Compositor {
 public:
  Compositor(Framebuffer& image, MPI_Comm comm, int rank, int root, CompositePlan plan,
             CompositeStats& stats)
      : image_(image),
        comm_(comm),
        root_(root),
        virtual_rank_((rank - root + plan.rank_count) % plan.rank_count),
        plan_(std::move(plan)),
        stats_(stats),
        span_{0, static_cast<std::uint32_t>(image.pixel_count())},
        rect_(active_rect(image)) {}

  int run() {
    int tag = kFirstTag;
    if (plan_.folded_count() > 0) {
      if (int error = fold(tag++); error != MPI_SUCCESS) return error;
      if (virtual_rank_ >= plan_.swap_count) return MPI_SUCCESS;
    }
    for (std::size_t round = 0; round < plan_.radices.size(); ++round) {
      if (int error = swap(static_cast<int>(round), tag++); error != MPI_SUCCESS) return error;
    }
    return gather(tag);
  }

 private:
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
    span_ = split_span(span_, radix, position.digit);
    return exchange(tag, std::move(sends), radix - 1);
  }

  // Every span goes to the root. The root's own pixels outside its span need no clearing:
  // the composited pixel that arrives for each was chosen over it, or is it.
  int gather(int tag) {
    if (virtual_rank_ != 0) return exchange(tag, {{root_, encode(span_)}}, 0);
    return exchange(tag, {}, plan_.swap_count - 1);
  }

  PieceMessage encode(PixelSpan span) const { return encode_piece(image_, span, rect_); }

  // Sends every message, composites the incoming ones in their order of arrival (the result
  // does not depend on it: wins_over is a total order), then waits for the sends.
  int exchange(int tag, std::vector<Outgoing> sends, int receive_count) {
    std::vector<MPI_Request> requests(sends.size(), MPI_REQUEST_NULL);
    int error = MPI_SUCCESS;
    for (std::size_t k = 0; k < sends.size() && error == MPI_SUCCESS; ++k) {
      const PieceMessage& message = sends[k].message;
      error = MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_UINT32_T,
                        sends[k].peer, tag, comm_, &requests[k]);
      stats_.bytes_sent += message.size() * sizeof(std::uint32_t);
    }
    for (int k = 0; k < receive_count && error == MPI_SUCCESS; ++k) error = receive(tag);
    const int wait_error =
        MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return error != MPI_SUCCESS ? error : wait_error;
  }

  int receive(int tag) {
    MPI_Message handle;
    MPI_Status status;
    if (int error = MPI_Mprobe(MPI_ANY_SOURCE, tag, comm_, &handle, &status);
        error != MPI_SUCCESS) {
      return error;
    }
    int count = 0;
    MPI_Get_count(&status, MPI_UINT32_T, &count);
    buffer_.resize(static_cast<std::size_t>(count));
    if (int error = MPI_Mrecv(buffer_.data(), count, MPI_UINT32_T, &handle, MPI_STATUS_IGNORE);
        error != MPI_SUCCESS) {
      return error;
    }
    stats_.bytes_received += buffer_.size() * sizeof(std::uint32_t);
    const std::optional<PixelRect> piece_rect = composite_piece(image_, buffer_);
    if (!piece_rect) return MPI_ERR_OTHER;
    rect_ = united(rect_, *piece_rect);
    return MPI_SUCCESS;
  }

  Framebuffer& image_;
  MPI_Comm comm_;
  int root_;
  int virtual_rank_;
  CompositePlan plan_;
  CompositeStats& stats_;
  PixelSpan span_;
  PixelRect rect_;
  PieceMessage buffer_;
};

bool well_formed(const Framebuffer& image) {
  const auto pixels = static_cast<std::int64_t>(image.width) * image.height;
  return image.width >= 0 && image.height >= 0 && pixels < (std::int64_t{1} << 31) &&
         image.depth.size() == static_cast<std::size_t>(pixels) &&
         image.hit.size() == image.depth.size() && image.rgba.size() == 4 * image.depth.size();
}

// Every rank must pass a well-formed image of the same size and the same options; checked in
// one small allreduce so that a mismatch returns an error everywhere instead of hanging.
int agree_on_inputs(const Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
                    int rank_count) {
  const bool image_ok = well_formed(image);
  const bool root_ok = options.root >= 0 && options.root < rank_count;
  const int width = image_ok ? image.width : 0;
  const int height = image_ok ? image.height : 0;
  const int root = root_ok ? options.root : 0;
  const int algorithm = static_cast<int>(options.algorithm);
  int maxima[] = {width, -width,    height,     -height,          root,
                  -root, algorithm, -algorithm, image_ok ? 0 : 1, root_ok ? 0 : 1};
  if (int error = MPI_Allreduce(MPI_IN_PLACE, maxima, static_cast<int>(std::size(maxima)), MPI_INT,
                                MPI_MAX, comm);
      error != MPI_SUCCESS) {
    return error;
  }
  if (maxima[9] != 0 || maxima[4] != -maxima[5]) return MPI_ERR_ROOT;
  const bool same = maxima[0] == -maxima[1] && maxima[2] == -maxima[3] && maxima[6] == -maxima[7];
  return same && maxima[8] == 0 ? MPI_SUCCESS : MPI_ERR_ARG;
}

}  // namespace

int composite(Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
              CompositeStats* stats) {
  CompositeStats local_stats;
  CompositeStats& out = stats ? *stats : local_stats;
  out = {};
  int rank = 0, rank_count = 1;
  if (int error = MPI_Comm_size(comm, &rank_count); error != MPI_SUCCESS) return error;
  if (rank_count == 1) return options.root == 0 ? MPI_SUCCESS : MPI_ERR_ROOT;
  const double start = MPI_Wtime();
  MPI_Comm_rank(comm, &rank);
  int error = agree_on_inputs(image, comm, options, rank_count);
  if (error == MPI_SUCCESS && image.pixel_count() > 0) {
    CompositePlan plan = make_plan(rank_count, options.algorithm);
    out.rounds = plan.round_count();
    error = Compositor(image, comm, rank, options.root, std::move(plan), out).run();
  }
  out.seconds = MPI_Wtime() - start;
  return error;
}

}  // namespace tetray::render
