#include "render/composite/fragment_composite.hpp"

#include <limits>
#include <vector>

namespace tetray::render {
namespace {

// Per-pixel fragment counts of a fragment image.
template <typename F>
std::vector<std::uint32_t> pixel_counts(const BasicFragmentImage<F>& image) {
  std::vector<std::uint32_t> counts(image.pixel_count());
  for (std::size_t p = 0; p < counts.size(); ++p) counts[p] = image.begin[p + 1] - image.begin[p];
  return counts;
}

// The root's merge: pixel by pixel, every rank's fragments of that pixel together, of which
// the pixel keeps its nearest (kept_layers).
template <typename F>
BasicFragmentImage<F> merge_ranks(const BasicFragmentImage<F>& shape,
                                  const std::vector<std::uint32_t>& counts,
                                  const std::vector<int>& offsets, const std::vector<F>& all,
                                  int ranks, std::size_t max_layers) {
  const std::size_t pixels = shape.pixel_count();
  BasicFragmentImage<F> out;
  out.width = shape.width;
  out.height = shape.height;
  out.begin.reserve(pixels + 1);
  out.begin.push_back(0);
  out.fragments.reserve(all.size());
  std::vector<std::size_t> cursor(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r) {
    cursor[static_cast<std::size_t>(r)] =
        static_cast<std::size_t>(offsets[static_cast<std::size_t>(r)]) / sizeof(F);
  }
  std::vector<F> layers;
  for (std::size_t p = 0; p < pixels; ++p) {
    // Most pixels of an image hold no fragment on any rank: nothing to gather or sort.
    std::uint32_t any = 0;
    for (std::size_t r = 0; r < cursor.size(); ++r) any |= counts[r * pixels + p];
    if (any == 0) {
      out.begin.push_back(static_cast<std::uint32_t>(out.fragments.size()));
      continue;
    }
    layers.clear();
    for (std::size_t r = 0; r < cursor.size(); ++r) {
      const std::uint32_t n = counts[r * pixels + p];
      layers.insert(layers.end(), all.begin() + static_cast<std::ptrdiff_t>(cursor[r]),
                    all.begin() + static_cast<std::ptrdiff_t>(cursor[r] + n));
      cursor[r] += n;
    }
    const std::size_t kept = kept_layers(layers, max_layers);
    out.fragments.insert(out.fragments.end(), layers.begin(),
                         layers.begin() + static_cast<std::ptrdiff_t>(kept));
    out.begin.push_back(static_cast<std::uint32_t>(out.fragments.size()));
  }
  return out;
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
  const std::size_t pixels = local.pixel_count();
  // Counts per pixel from every rank (pixel counts fit an int: images are at most 16384^2).
  const std::vector<std::uint32_t> mine = pixel_counts(local);
  std::vector<std::uint32_t> counts(is_root ? pixels * static_cast<std::size_t>(ranks) : 0);
  int rc = MPI_Gather(mine.data(), static_cast<int>(pixels), MPI_UINT32_T, counts.data(),
                      static_cast<int>(pixels), MPI_UINT32_T, root, comm);
  if (rc != MPI_SUCCESS) return rc;
  // Fragment bytes per rank; the total must fit one int count.
  const unsigned long long my_bytes = local.fragments.size() * sizeof(F);
  std::vector<unsigned long long> bytes(static_cast<std::size_t>(ranks));
  rc = MPI_Allgather(&my_bytes, 1, MPI_UNSIGNED_LONG_LONG, bytes.data(), 1, MPI_UNSIGNED_LONG_LONG,
                     comm);
  if (rc != MPI_SUCCESS) return rc;
  std::vector<int> sizes(static_cast<std::size_t>(ranks)), offsets(sizes.size());
  unsigned long long total = 0;
  for (std::size_t r = 0; r < sizes.size(); ++r) {
    offsets[r] = static_cast<int>(total);
    sizes[r] = static_cast<int>(bytes[r]);
    total += bytes[r];
    if (total > static_cast<unsigned long long>(std::numeric_limits<int>::max())) {
      return MPI_ERR_COUNT;
    }
  }
  std::vector<F> all(is_root ? total / sizeof(F) : 0);
  rc = MPI_Gatherv(local.fragments.data(), static_cast<int>(my_bytes), MPI_BYTE, all.data(),
                   sizes.data(), offsets.data(), MPI_BYTE, root, comm);
  if (rc != MPI_SUCCESS || !is_root) return rc;
  merged = merge_ranks(local, counts, offsets, all, ranks, max_layers);
  if (stats != nullptr) *stats = {all.size(), total};
  return MPI_SUCCESS;
}

template <typename F>
int composite_fragments(const BasicFragmentImage<F>& local, MPI_Comm comm, int root,
                        Framebuffer& out, FragmentCompositeStats* stats) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  BasicFragmentImage<F> merged;
  const int rc = gather_fragments(local, comm, root, kAllLayers, merged, stats);
  if (rc == MPI_SUCCESS && rank == root) out = resolve(merged);
  return rc;
}

TETRAY_FRAGMENT_COMPOSITE(, Fragment)
TETRAY_FRAGMENT_COMPOSITE(, VolumeFragment)

}  // namespace tetray::render
