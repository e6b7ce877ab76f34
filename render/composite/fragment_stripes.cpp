// composite_fragments (fragment_composite.hpp): the image split into one stripe of consecutive
// pixels per rank (direct send), each stripe's fragments of all ranks sent to its rank, merged
// and blended there, and the blended stripes gathered on the root. Every rank merges 1/P of the
// pixels and receives about 1/P of the fragments, where a gather to one root makes the root
// receive and merge them all.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <exception>
#include <new>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "render/composite/composite_agreement.hpp"
#include "render/composite/composite_region.hpp"
#include "render/composite/fragment_composite.hpp"
#include "render/composite/fragment_merge.hpp"
#include "render/composite/fragment_runs.hpp"

namespace tetray::render {
namespace {

// Tags of the stripes' messages (the depth compositor's start at 7700 and take one per round).
constexpr int kOffsetsTag = 7900, kFragmentsTag = 7901;

// What a rank sends another: its pixels [first, last) of the receiver's stripe from its first
// to its last with a fragment (none outside them), and how many fragments they hold. The
// message is then those pixels' last - first + 1 offsets into the sender's fragments (its
// begin array, sent where it lies) and the fragments themselves.
struct StripeHeader {
  std::uint64_t first = 0, last = 0, count = 0;
};

PixelSpan stripe_of(std::size_t pixels, int ranks, int rank) {
  return split_span({0, static_cast<std::uint32_t>(pixels)}, ranks, rank);
}

template <typename F>
StripeHeader header_of(const BasicFragmentImage<F>& image, PixelSpan stripe) {
  const auto [first, last] = covered_pixels(image, stripe.begin, stripe.end);
  return {first, last, image.begin[last] - image.begin[first]};
}

// A rank's image is well formed and small enough for the stripes' int counts.
template <typename F>
bool well_formed(const BasicFragmentImage<F>& image) {
  const std::size_t pixels = image.pixel_count();
  if (image.width < 0 || image.height < 0 || 4 * pixels > std::size_t{INT_MAX}) return false;
  if (image.begin.size() != pixels + 1 || image.begin.front() != 0) return false;
  if (image.begin.back() != image.fragments.size()) return false;
  return std::is_sorted(image.begin.begin(), image.begin.end());
}

// Room for every other rank's fragments of this rank's stripe (`in`), in the workspace.
template <typename F>
void reserve_receives(const std::vector<StripeHeader>& in, int rank, FragmentWorkspace<F>& work) {
  work.offsets.resize(in.size());
  work.fragments.resize(in.size());
  for (std::size_t r = 0; r < in.size(); ++r) {
    if (in[r].count == 0 || r == static_cast<std::size_t>(rank)) continue;
    const std::size_t offset_count = in[r].last - in[r].first + 1;
    if (work.offsets[r].size() < offset_count) work.offsets[r].resize(offset_count);
    if (work.fragments[r].size() < in[r].count) work.fragments[r].resize(in[r].count);
  }
}

template <typename F>
class StripeExchange {
 public:
  StripeExchange(const BasicFragmentImage<F>& local, MPI_Comm comm, int rank, int ranks,
                 FragmentWorkspace<F>& workspace, FragmentCompositeStats& stats)
      : local_(local),
        comm_(comm),
        rank_(rank),
        ranks_(static_cast<std::size_t>(ranks)),
        workspace_(workspace),
        stats_(stats) {
    MPI_Type_contiguous(static_cast<int>(sizeof(F)), MPI_BYTE, &type_);
    MPI_Type_commit(&type_);
  }
  ~StripeExchange() { MPI_Type_free(&type_); }
  StripeExchange(const StripeExchange&) = delete;
  StripeExchange& operator=(const StripeExchange&) = delete;

  // The runs of this rank's stripe, every rank's (this one's where they lie) in rank order.
  // The workspace holds room for every receive (reserve_receives).
  int exchange(const std::vector<StripeHeader>& out, const std::vector<StripeHeader>& in,
               std::vector<FragmentRun<F>>& runs) {
    std::vector<MPI_Request> requests;
    int rc = MPI_SUCCESS;
    for (std::size_t r = 0; r < ranks_ && rc == MPI_SUCCESS; ++r) {
      if (in[r].count == 0 || r == std::size_t(rank_)) continue;
      rc = receive(r, in[r], requests);
    }
    for (std::size_t q = 0; q < ranks_ && rc == MPI_SUCCESS; ++q) {
      if (out[q].count == 0 || q == std::size_t(rank_)) continue;
      rc = send(q, out[q], requests);
    }
    const int waited =
        MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    if (rc != MPI_SUCCESS || waited != MPI_SUCCESS) return rc != MPI_SUCCESS ? rc : waited;
    for (std::size_t r = 0; r < ranks_; ++r) {
      if (in[r].count == 0) continue;
      const bool mine = r == std::size_t(rank_);
      const auto first = static_cast<std::uint32_t>(in[r].first);
      runs.push_back(
          {first, static_cast<std::uint32_t>(in[r].last),
           mine ? local_.begin.data() + first : workspace_.offsets[r].data(),
           mine ? local_.fragments.data() + local_.begin[first] : workspace_.fragments[r].data()});
      stats_.fragments += in[r].count;
    }
    return MPI_SUCCESS;
  }

 private:
  int receive(std::size_t r, const StripeHeader& h, std::vector<MPI_Request>& requests) {
    LargeArray<std::uint32_t>& offsets = workspace_.offsets[r];
    LargeArray<F>& fragments = workspace_.fragments[r];
    const std::size_t offset_count = h.last - h.first + 1;
    requests.resize(requests.size() + 2, MPI_REQUEST_NULL);
    stats_.bytes_received += offset_count * sizeof(std::uint32_t) + h.count * sizeof(F);
    const int peer = static_cast<int>(r);
    if (int rc = MPI_Irecv(offsets.data(), static_cast<int>(offset_count), MPI_UINT32_T, peer,
                           kOffsetsTag, comm_, &requests[requests.size() - 2]);
        rc != MPI_SUCCESS)
      return rc;
    return MPI_Irecv(fragments.data(), static_cast<int>(h.count), type_, peer, kFragmentsTag, comm_,
                     &requests.back());
  }

  int send(std::size_t q, const StripeHeader& h, std::vector<MPI_Request>& requests) {
    const std::size_t offset_count = h.last - h.first + 1;
    requests.resize(requests.size() + 2, MPI_REQUEST_NULL);
    stats_.bytes_sent += offset_count * sizeof(std::uint32_t) + h.count * sizeof(F);
    const int peer = static_cast<int>(q);
    if (int rc = MPI_Isend(local_.begin.data() + h.first, static_cast<int>(offset_count),
                           MPI_UINT32_T, peer, kOffsetsTag, comm_, &requests[requests.size() - 2]);
        rc != MPI_SUCCESS)
      return rc;
    return MPI_Isend(local_.fragments.data() + local_.begin[h.first], static_cast<int>(h.count),
                     type_, peer, kFragmentsTag, comm_, &requests.back());
  }

  const BasicFragmentImage<F>& local_;
  MPI_Comm comm_;
  int rank_;
  std::size_t ranks_;
  FragmentWorkspace<F>& workspace_;
  FragmentCompositeStats& stats_;
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

// Where a stripe's blended pixels go: the root's image itself, another rank's workspace.
struct StripePixels {
  float* rgba;
  float* depth;
  std::uint32_t* hit;
};

// Every pixel of the stripe, on the rank's threads (each pixel is its own), a block of pixels
// at a time: first each pixel's merged order (or, for the few the merge leaves to the sort,
// the pixel itself), then the block's blends (fragment_merge.hpp says why).
template <typename F>
void blend_stripe(std::span<const FragmentRun<F>> runs, PixelSpan stripe, std::size_t max_layers,
                  StripePixels pixels) {
  constexpr std::size_t kBlock = 32;
  tbb::enumerable_thread_specific<std::vector<F>> scratch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(stripe.begin, stripe.end, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<F>& layers = scratch.local();
                      std::array<std::array<const F*, kMergedFragments>, kBlock> orders;
                      std::array<std::size_t, kBlock> counts;
                      for (std::size_t first = range.begin(); first < range.end();
                           first += kBlock) {
                        const std::size_t n = std::min(kBlock, range.end() - first);
                        for (std::size_t b = 0; b < n; ++b) {
                          const std::size_t p = first + b, k = p - stripe.begin;
                          counts[b] = merged_order(runs, p, orders[b].data());
                          if (counts[b] == kNotMerged)
                            blend_layers(kept_of_runs(runs, p, max_layers, layers),
                                         pixels.rgba + 4 * k, pixels.depth[k], pixels.hit[k]);
                        }
                        for (std::size_t b = 0; b < n; ++b) {
                          const std::size_t k = first + b - stripe.begin;
                          if (counts[b] != kNotMerged)
                            blend_order(orders[b].data(), counts[b], max_layers,
                                        pixels.rgba + 4 * k, pixels.depth[k], pixels.hit[k]);
                        }
                      }
                    });
}

// The blended stripes to the root, into its image in place.
int gather_stripes(const StripePixels& mine, Framebuffer& out, std::size_t pixels, int root,
                   int rank, int ranks, MPI_Comm comm) {
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(counts.size());
  std::vector<int> counts4(counts.size()), starts4(counts.size());
  for (int r = 0; r < ranks; ++r) {
    const PixelSpan s = stripe_of(pixels, ranks, r);
    const auto k = static_cast<std::size_t>(r);
    counts[k] = static_cast<int>(s.size());
    starts[k] = static_cast<int>(s.begin);
    counts4[k] = 4 * counts[k];
    starts4[k] = 4 * starts[k];
  }
  const bool is_root = rank == root;
  const int n = counts[static_cast<std::size_t>(rank)];
  int rc = MPI_Gatherv(is_root ? MPI_IN_PLACE : mine.rgba, 4 * n, MPI_FLOAT, out.rgba.data(),
                       counts4.data(), starts4.data(), MPI_FLOAT, root, comm);
  if (rc == MPI_SUCCESS)
    rc = MPI_Gatherv(is_root ? MPI_IN_PLACE : mine.depth, n, MPI_FLOAT, out.depth.data(),
                     counts.data(), starts.data(), MPI_FLOAT, root, comm);
  if (rc == MPI_SUCCESS)
    rc = MPI_Gatherv(is_root ? MPI_IN_PLACE : mine.hit, n, MPI_UINT32_T, out.hit.data(),
                     counts.data(), starts.data(), MPI_UINT32_T, root, comm);
  return rc;
}

// Where this rank blends its stripe: in place in the root's image when it has the right size,
// in a new image (`fresh`, which becomes the root's image once every rank has agreed, so that
// an error leaves the image alone) otherwise; in the workspace on the other ranks.
template <typename F>
StripePixels stripe_pixels(bool is_root, int width, int height, PixelSpan stripe, Framebuffer& out,
                           std::optional<Framebuffer>& fresh, FragmentWorkspace<F>& workspace) {
  if (is_root) {
    const bool fits = has_shape(out, width, height);
    if (!fits) fresh.emplace(width, height);
    Framebuffer& image = fits ? out : *fresh;
    return {image.rgba.data() + 4 * std::size_t{stripe.begin}, image.depth.data() + stripe.begin,
            image.hit.data() + stripe.begin};
  }
  const std::size_t n = stripe.size();
  if (workspace.depth.size() < n) {
    workspace.rgba.resize(4 * n);
    workspace.depth.resize(n);
    workspace.hit.resize(n);
  }
  return {workspace.rgba.data(), workspace.depth.data(), workspace.hit.data()};
}

// The ranks' agreement before any fragment moves (composite_agreement.hpp), as
// composite_fragments names its errors: MPI_SUCCESS, MPI_ERR_ROOT, MPI_ERR_SIZE, MPI_ERR_NO_MEM,
// MPI_ERR_COUNT or the allreduce's error, the same on every rank.
template <typename F>
int agree(bool ok, bool allocated, const BasicFragmentImage<F>& local, int root,
          std::uint64_t largest, int ranks, MPI_Comm comm) {
  CompositeInputs mine;
  mine.width = local.width;
  mine.height = local.height;
  mine.image_ok = ok;
  mine.root = root;
  mine.allocated = allocated;
  mine.largest_message = largest;
  CompositeAgreement agreed;
  if (const int rc = agree_on(mine, ranks, comm, agreed); rc != MPI_SUCCESS) return rc;
  return !agreed.root_ok      ? MPI_ERR_ROOT
         : !agreed.images_ok  ? MPI_ERR_SIZE
         : !agreed.allocated  ? MPI_ERR_NO_MEM
         : !agreed.counts_fit ? MPI_ERR_COUNT
                              : MPI_SUCCESS;
}

// Blends this rank's stripe and hands its depths to the hook; then every rank learns whether
// any stripe failed (memory running out in the blend, a hook that throws) before the gather, so
// that a rank that failed does not leave the others waiting there: MPI_SUCCESS, MPI_ERR_NO_MEM,
// MPI_ERR_OTHER or the allreduce's error, the same on every rank.
template <typename F>
int blend_on_every_rank(std::span<const FragmentRun<F>> runs, PixelSpan stripe,
                        const FragmentCompositeOptions& options, const StripePixels& mine,
                        MPI_Comm comm) {
  int blended = MPI_SUCCESS;
  try {
    blend_stripe<F>(runs, stripe, options.max_layers, mine);
    if (options.stripe_depths) options.stripe_depths(stripe.begin, {mine.depth, stripe.size()});
  } catch (const std::bad_alloc&) {
    blended = MPI_ERR_NO_MEM;
  } catch (...) {
    blended = MPI_ERR_OTHER;
  }
  if (const int rc = MPI_Allreduce(MPI_IN_PLACE, &blended, 1, MPI_INT, MPI_MAX, comm);
      rc != MPI_SUCCESS)
    return rc;
  return blended;
}

}  // namespace

template <typename F>
int composite_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                        Framebuffer& out, const FragmentCompositeOptions& options,
                        FragmentCompositeStats* stats, FragmentWorkspace<F>* workspace) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  FragmentCompositeStats counted;
  FragmentWorkspace<F> fresh;
  FragmentWorkspace<F>& kept = workspace != nullptr ? *workspace : fresh;
  const bool ok = well_formed(local);
  const std::size_t pixels = local.pixel_count();
  std::vector<StripeHeader> out_headers(static_cast<std::size_t>(ranks));
  std::uint64_t largest = 0;
  for (int q = 0; q < ranks && ok; ++q) {
    out_headers[static_cast<std::size_t>(q)] = header_of(local, stripe_of(pixels, ranks, q));
    largest = std::max(largest, out_headers[static_cast<std::size_t>(q)].count);
  }
  // The headers go both ways before the agreement (a malformed rank sends none), so that every
  // buffer is allocated first: memory that runs out on one rank is agreed on too, instead of
  // leaving the others waiting in the exchange.
  std::vector<StripeHeader> in_headers(out_headers.size());
  if (int rc = MPI_Alltoall(out_headers.data(), 3, MPI_UINT64_T, in_headers.data(), 3, MPI_UINT64_T,
                            comm);
      rc != MPI_SUCCESS)
    return rc;
  const PixelSpan stripe = stripe_of(pixels, ranks, rank);
  StripePixels mine{};
  std::optional<Framebuffer> new_image;
  bool allocated = true;
  try {
    if (ok) {
      reserve_receives(in_headers, rank, kept);
      mine = stripe_pixels(rank == root, local.width, local.height, stripe, out, new_image, kept);
    }
  } catch (const std::exception&) {
    allocated = false;
  }
  if (const int verdict = agree(ok, allocated, local, root, largest, ranks, comm);
      verdict != MPI_SUCCESS)
    return verdict;
  if (new_image) out = std::move(*new_image);  // its arrays, which `mine` points into, move along
  std::vector<FragmentRun<F>> runs;
  {
    StripeExchange<F> exchange(local, comm, rank, ranks, kept, counted);
    if (int rc = exchange.exchange(out_headers, in_headers, runs); rc != MPI_SUCCESS) return rc;
  }
  if (const int blended = blend_on_every_rank<F>(runs, stripe, options, mine, comm);
      blended != MPI_SUCCESS)
    return blended;
  if (stats != nullptr) *stats = counted;
  return ranks == 1 ? MPI_SUCCESS : gather_stripes(mine, out, pixels, root, rank, ranks, comm);
}

#define TETRAY_COMPOSITE_FRAGMENTS(F)                                                            \
  template int composite_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int, Framebuffer&, \
                                      const FragmentCompositeOptions&, FragmentCompositeStats*,  \
                                      FragmentWorkspace<F>*);
TETRAY_COMPOSITE_FRAGMENTS(Fragment)
TETRAY_COMPOSITE_FRAGMENTS(VolumeFragment)

}  // namespace tetray::render
