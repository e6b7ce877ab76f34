#include "render/composite/fragment_composite.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

#include "render/composite/fragment_runs.hpp"

namespace tetray::render {
namespace {

// The root's merge: pixel by pixel, every rank's fragments of that pixel together, of which
// the pixel keeps its nearest (kept_of_runs).
template <typename F>
void merge_ranks(const BasicFragmentImage<F>& shape, std::span<const FragmentRun<F>> runs,
                 std::size_t fragment_count, std::size_t max_layers, BasicFragmentImage<F>& out) {
  const std::size_t pixels = shape.pixel_count();
  out.width = shape.width;
  out.height = shape.height;
  out.begin.assign(pixels + 1, 0);  // out's storage is reused: no new pages for a new frame
  out.fragments.clear();
  out.fragments.reserve(fragment_count);
  std::size_t from = pixels, to = 0;  // the pixels any rank covers
  for (const FragmentRun<F>& run : runs) {
    from = std::min<std::size_t>(from, run.first);
    to = std::max<std::size_t>(to, run.last);
  }
  std::vector<F> scratch;
  for (std::size_t p = from; p < to; ++p) {
    out.begin[p] = static_cast<std::uint32_t>(out.fragments.size());
    const std::span<const F> kept = kept_of_runs(runs, p, max_layers, scratch);
    out.fragments.insert(out.fragments.end(), kept.begin(), kept.end());
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
  // Each rank's run of pixels with fragments, its offsets there (one more than its pixels) and
  // its fragment bytes (the bytes' total must fit one int count); images are at most 16384^2
  // pixels.
  const auto [first, last] = covered_pixels(local, 0, local.pixel_count());
  const std::size_t offset_count = first < last ? last - first + 1 : 0;
  const unsigned long long header[3] = {first, last, local.fragments.size() * sizeof(F)};
  std::vector<unsigned long long> headers(3 * count);
  int rc = MPI_Allgather(header, 3, MPI_UNSIGNED_LONG_LONG, headers.data(), 3,
                         MPI_UNSIGNED_LONG_LONG, comm);
  if (rc != MPI_SUCCESS) return rc;
  std::vector<unsigned long long> run_lengths(count), bytes(count);
  for (std::size_t r = 0; r < count; ++r) {
    const unsigned long long a = headers[3 * r], b = headers[3 * r + 1];
    run_lengths[r] = a < b ? b - a + 1 : 0;
    bytes[r] = headers[3 * r + 2];
  }
  std::vector<int> run_sizes, run_offsets, sizes, offsets;
  if (!int_offsets(run_lengths, run_sizes, run_offsets) || !int_offsets(bytes, sizes, offsets))
    return MPI_ERR_COUNT;
  std::vector<std::uint32_t> begins(
      is_root ? static_cast<std::size_t>(run_offsets.back()) + run_lengths.back() : 0);
  rc = MPI_Gatherv(local.begin.data() + first, static_cast<int>(offset_count), MPI_UINT32_T,
                   begins.data(), run_sizes.data(), run_offsets.data(), MPI_UINT32_T, root, comm);
  if (rc != MPI_SUCCESS) return rc;
  const std::size_t total = static_cast<std::size_t>(offsets.back()) + bytes.back();
  std::vector<F> all(is_root ? total / sizeof(F) : 0);
  rc = MPI_Gatherv(local.fragments.data(), static_cast<int>(bytes[static_cast<std::size_t>(rank)]),
                   MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, root, comm);
  if (rc != MPI_SUCCESS || !is_root) return rc;
  std::vector<FragmentRun<F>> runs;
  for (std::size_t r = 0; r < count; ++r) {
    if (run_lengths[r] == 0) continue;
    runs.push_back({static_cast<std::uint32_t>(headers[3 * r]),
                    static_cast<std::uint32_t>(headers[3 * r + 1]), begins.data() + run_offsets[r],
                    all.data() + static_cast<std::size_t>(offsets[r]) / sizeof(F)});
  }
  merge_ranks<F>(local, runs, all.size(), max_layers, merged);
  if (stats != nullptr) *stats = {all.size(), 0, total};
  return MPI_SUCCESS;
}

#define TETRAY_GATHER_FRAGMENTS(F)                                                           \
  template int gather_fragments<F>(const BasicFragmentImage<F>&, MPI_Comm, int, std::size_t, \
                                   BasicFragmentImage<F>&, FragmentCompositeStats*);
TETRAY_GATHER_FRAGMENTS(Fragment)
TETRAY_GATHER_FRAGMENTS(VolumeFragment)

}  // namespace tetray::render
