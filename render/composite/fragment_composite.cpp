#include "render/composite/fragment_composite.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

namespace tetray::render {
namespace {

// One rank's per-pixel fragment counts over the pixels from its first to its last with any
// fragment (outside them it has none): what travels to the root instead of a count per pixel.
struct CountRun {
  std::uint32_t first = 0, last = 0;  // [first, last)
  std::span<const std::uint32_t> counts;

  std::uint32_t at(std::size_t p) const { return p >= first && p < last ? counts[p - first] : 0; }
};

template <typename F>
std::vector<std::uint32_t> run_counts(const BasicFragmentImage<F>& image, std::uint32_t& first,
                                      std::uint32_t& last) {
  const std::size_t pixels = image.pixel_count();
  std::size_t a = 0, b = pixels;
  while (a < pixels && image.begin[a + 1] == image.begin[a]) ++a;
  while (b > a && image.begin[b] == image.begin[b - 1]) --b;
  first = static_cast<std::uint32_t>(a);
  last = static_cast<std::uint32_t>(b);
  std::vector<std::uint32_t> counts(b - a);
  for (std::size_t p = a; p < b; ++p) counts[p - a] = image.begin[p + 1] - image.begin[p];
  return counts;
}

// Whether a pixel's fragments from one rank are already what the merge keeps of them: front to
// back in the merge's order, none opaque before the last, at most max_layers (what trace_layers
// gives). A pixel only one rank covers then needs no sort.
template <typename F>
bool already_kept(std::span<const F> layers, std::size_t max_layers) {
  if (layers.size() > max_layers) return false;
  for (std::size_t k = 1; k < layers.size(); ++k) {
    if (!in_front_of(layers[k - 1], layers[k]) || layers[k - 1].rgba[3] >= 1) return false;
  }
  return true;
}

// The root's merge: pixel by pixel, every rank's fragments of that pixel together, of which
// the pixel keeps its nearest (kept_layers). Only pixels that several ranks cover are sorted.
template <typename F>
void merge_ranks(const BasicFragmentImage<F>& shape, const std::vector<CountRun>& runs,
                 const std::vector<int>& offsets, const std::vector<F>& all, std::size_t max_layers,
                 BasicFragmentImage<F>& out) {
  const std::size_t pixels = shape.pixel_count(), ranks = runs.size();
  out.width = shape.width;
  out.height = shape.height;
  out.begin.assign(pixels + 1, 0);  // out's storage is reused: no new pages for a new frame
  out.fragments.clear();
  out.fragments.reserve(all.size());
  std::vector<std::size_t> cursor(ranks);
  std::size_t from = pixels, to = 0;  // the pixels any rank covers
  for (std::size_t r = 0; r < ranks; ++r) {
    cursor[r] = static_cast<std::size_t>(offsets[r]) / sizeof(F);
    if (runs[r].first < runs[r].last) {
      from = std::min<std::size_t>(from, runs[r].first);
      to = std::max<std::size_t>(to, runs[r].last);
    }
  }
  std::vector<F> layers;
  for (std::size_t p = from; p < to; ++p) {
    out.begin[p] = static_cast<std::uint32_t>(out.fragments.size());
    std::size_t contributors = 0, only = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      if (runs[r].at(p) == 0) continue;
      ++contributors;
      only = r;
    }
    if (contributors == 0) continue;
    if (contributors == 1) {
      const std::span<const F> mine(all.data() + cursor[only], runs[only].at(p));
      cursor[only] += mine.size();
      if (already_kept(mine, max_layers)) {
        out.fragments.insert(out.fragments.end(), mine.begin(), mine.end());
        continue;
      }
      layers.assign(mine.begin(), mine.end());
    } else {
      layers.clear();
      for (std::size_t r = 0; r < ranks; ++r) {
        const std::uint32_t n = runs[r].at(p);
        layers.insert(layers.end(), all.begin() + static_cast<std::ptrdiff_t>(cursor[r]),
                      all.begin() + static_cast<std::ptrdiff_t>(cursor[r] + n));
        cursor[r] += n;
      }
    }
    const std::size_t kept = kept_layers(layers, max_layers);
    out.fragments.insert(out.fragments.end(), layers.begin(),
                         layers.begin() + static_cast<std::ptrdiff_t>(kept));
  }
  const auto total = static_cast<std::uint32_t>(out.fragments.size());
  for (std::size_t p = std::max(from, to); p <= pixels; ++p) out.begin[p] = total;
}

// The total of `sizes` as int offsets, or false when it does not fit one int count.
bool int_offsets(const std::vector<unsigned long long>& sizes, std::vector<int>& counts,
                 std::vector<int>& offsets) {
  counts.resize(sizes.size());
  offsets.resize(sizes.size());
  unsigned long long total = 0;
  for (std::size_t r = 0; r < sizes.size(); ++r) {
    offsets[r] = static_cast<int>(total);
    counts[r] = static_cast<int>(sizes[r]);
    total += sizes[r];
    if (total > static_cast<unsigned long long>(std::numeric_limits<int>::max())) return false;
  }
  return true;
}

}  // namespace

template <typename F>
int gather_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                     std::size_t max_layers, BasicFragmentImage<F>& merged,
                     FragmentCompositeStats* stats) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const bool is_root = rank == root;
  const auto count = static_cast<std::size_t>(ranks);
  // Each rank's run of pixels with fragments, its counts there and its fragment bytes (the
  // bytes' total must fit one int count); images are at most 16384^2 pixels.
  std::uint32_t first = 0, last = 0;
  const std::vector<std::uint32_t> mine = run_counts(local, first, last);
  const unsigned long long header[3] = {first, last, local.fragments.size() * sizeof(F)};
  std::vector<unsigned long long> headers(3 * count);
  int rc = MPI_Allgather(header, 3, MPI_UNSIGNED_LONG_LONG, headers.data(), 3,
                         MPI_UNSIGNED_LONG_LONG, comm);
  if (rc != MPI_SUCCESS) return rc;
  std::vector<unsigned long long> run_lengths(count), bytes(count);
  for (std::size_t r = 0; r < count; ++r) {
    run_lengths[r] = headers[3 * r + 1] - headers[3 * r];
    bytes[r] = headers[3 * r + 2];
  }
  std::vector<int> run_sizes, run_offsets, sizes, offsets;
  if (!int_offsets(run_lengths, run_sizes, run_offsets) || !int_offsets(bytes, sizes, offsets))
    return MPI_ERR_COUNT;
  std::vector<std::uint32_t> counts(
      is_root ? static_cast<std::size_t>(run_offsets.back()) + run_lengths.back() : 0);
  rc = MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_UINT32_T, counts.data(),
                   run_sizes.data(), run_offsets.data(), MPI_UINT32_T, root, comm);
  if (rc != MPI_SUCCESS) return rc;
  const std::size_t total = static_cast<std::size_t>(offsets.back()) + bytes.back();
  std::vector<F> all(is_root ? total / sizeof(F) : 0);
  rc = MPI_Gatherv(local.fragments.data(), static_cast<int>(bytes[static_cast<std::size_t>(rank)]),
                   MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, root, comm);
  if (rc != MPI_SUCCESS || !is_root) return rc;
  std::vector<CountRun> runs(count);
  for (std::size_t r = 0; r < count; ++r) {
    runs[r] = {static_cast<std::uint32_t>(headers[3 * r]),
               static_cast<std::uint32_t>(headers[3 * r + 1]),
               std::span<const std::uint32_t>(counts).subspan(
                   static_cast<std::size_t>(run_offsets[r]), run_lengths[r])};
  }
  merge_ranks(local, runs, offsets, all, max_layers, merged);
  if (stats != nullptr) *stats = {all.size(), total};
  return MPI_SUCCESS;
}

template <typename F>
int composite_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                        Framebuffer& out, FragmentCompositeStats* stats,
                        BasicFragmentImage<F>* merged) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  BasicFragmentImage<F> fresh;
  BasicFragmentImage<F>& kept = merged != nullptr ? *merged : fresh;
  const int rc = gather_fragments(local, comm, root, kAllLayers, kept, stats);
  if (rc == MPI_SUCCESS && rank == root) out = resolve(kept);
  return rc;
}

TETRAY_FRAGMENT_COMPOSITE(, Fragment)
TETRAY_FRAGMENT_COMPOSITE(, VolumeFragment)

}  // namespace tetray::render
