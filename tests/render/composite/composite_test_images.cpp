#include "composite_test_images.hpp"

#include <random>
#include <utility>
#include <vector>

namespace tetray::render::testing {

Coverage random_coverage(std::uint32_t seed, int rank) {
  std::mt19937 rng(seed * 7919u + static_cast<std::uint32_t>(rank));
  const int draw = std::uniform_int_distribution<int>(0, 9)(rng);
  return draw < 2 ? Coverage::empty : (draw < 4 ? Coverage::full : Coverage::random_rect);
}

Framebuffer random_image(int width, int height, std::uint32_t seed, int rank, int rank_count,
                         Coverage coverage) {
  Framebuffer image(width, height);
  if (coverage == Coverage::empty) return image;
  std::mt19937 rng(seed * 104729u + static_cast<std::uint32_t>(rank) * 31u + 1u);
  const auto uniform = [&](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(rng);
  };
  int x0 = 0, x1 = width, y0 = 0, y1 = height;
  if (coverage == Coverage::random_rect) {
    x0 = uniform(0, width - 1);
    x1 = uniform(x0 + 1, width);
    y0 = uniform(0, height - 1);
    y1 = uniform(y0 + 1, height);
  }
  const bool holes = coverage == Coverage::random_rect;
  std::uniform_real_distribution<float> color(0.0f, 1.0f);
  for (int j = y0; j < y1; ++j) {
    for (int i = x0; i < x1; ++i) {
      if (holes && uniform(0, 3) == 0) continue;
      const std::size_t p = image.index(i, j);
      image.depth[p] = 1.0f + 0.25f * static_cast<float>(uniform(0, 7));
      image.hit[p] = static_cast<std::uint32_t>(uniform(0, 999) * rank_count + rank);
      for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = color(rng);
    }
  }
  return image;
}

Framebuffer brute_force_composite(const Framebuffer& image, MPI_Comm comm, int root) {
  int rank = 0, rank_count = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &rank_count);
  const std::size_t pixels = image.pixel_count();
  const bool on_root = rank == root;
  std::vector<float> rgba(on_root ? 4 * pixels * rank_count : 0);
  std::vector<float> depth(on_root ? pixels * rank_count : 0);
  std::vector<std::uint32_t> hit(on_root ? pixels * rank_count : 0);
  const int n = static_cast<int>(pixels);
  MPI_Gather(image.rgba.data(), 4 * n, MPI_FLOAT, rgba.data(), 4 * n, MPI_FLOAT, root, comm);
  MPI_Gather(image.depth.data(), n, MPI_FLOAT, depth.data(), n, MPI_FLOAT, root, comm);
  MPI_Gather(image.hit.data(), n, MPI_UINT32_T, hit.data(), n, MPI_UINT32_T, root, comm);
  Framebuffer result(image.width, image.height);
  if (!on_root) return result;
  // The rule of docs/architecture.md §3 spelled as the lexicographic order of (depth, key), not
  // through the library's wins_over, so a changed rule in the library shows here. The background
  // (+inf, kNoHit) is the start, and loses to every pixel that carries a key.
  for (std::size_t p = 0; p < pixels; ++p) {
    std::pair<float, std::uint32_t> nearest{result.depth[p], result.hit[p]};
    int nearest_rank = -1;
    for (int r = 0; r < rank_count; ++r) {
      const std::size_t q = r * pixels + p;
      if (std::pair{depth[q], hit[q]} < nearest) {
        nearest = {depth[q], hit[q]};
        nearest_rank = r;
      }
    }
    if (nearest_rank < 0) continue;
    const std::size_t q = nearest_rank * pixels + p;
    result.depth[p] = depth[q];
    result.hit[p] = hit[q];
    for (int c = 0; c < 4; ++c) result.rgba[4 * p + c] = rgba[4 * q + c];
  }
  return result;
}

}  // namespace tetray::render::testing
