#include "tools/composite_bench/bench_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace tetray::composite_bench {

const char* coverage_name(Coverage coverage) {
  switch (coverage) {
    case Coverage::dense:
      return "dense";
    case Coverage::sparse:
      return "sparse";
    case Coverage::sparse_x:
      break;
  }
  return "sparse_x";
}

namespace {

// The divisor of n nearest to target (from below first).
int divisor_near(int n, double target) {
  int best = 1;
  for (int d = 1; d <= n; ++d) {
    if (n % d == 0 && std::abs(d - target) < std::abs(best - target)) best = d;
  }
  return best;
}

}  // namespace

std::array<int, 3> cube_factors(int ranks) {
  const int a = divisor_near(ranks, std::cbrt(static_cast<double>(ranks)));
  const int rest = ranks / a;
  const int b = divisor_near(rest, std::sqrt(static_cast<double>(rest)));
  std::array<int, 3> factors{a, b, rest / b};
  std::sort(factors.begin(), factors.end());
  return factors;
}

namespace {

// Where a sparse rank's block lies on the screen: its cell of a columns x rows grid, and its
// depth layer.
struct Placement {
  int i, j, columns, rows, layer;
};

Placement sparse_placement(Coverage coverage, int rank, int ranks) {
  const auto [a, b, c] = cube_factors(ranks);
  if (coverage == Coverage::sparse_x) return {(rank / a) % b, rank / (a * b), b, c, rank % a};
  return {rank % a, (rank / a) % b, a, b, rank / (a * b)};
}

}  // namespace

render::PixelRect footprint(Coverage coverage, int size, int rank, int ranks) {
  if (coverage == Coverage::dense) return {0, 0, size, size};
  const Placement p = sparse_placement(coverage, rank, ranks);
  return {size * p.i / p.columns, size * p.j / p.rows, size * (p.i + 1) / p.columns,
          size * (p.j + 1) / p.rows};
}

render::Framebuffer bench_image(Coverage coverage, int size, int rank, int ranks) {
  render::Framebuffer image(size, size);
  const render::PixelRect rect = footprint(coverage, size, rank, ranks);
  const float layer = coverage == Coverage::dense
                          ? 0.0f
                          : static_cast<float>(sparse_placement(coverage, rank, ranks).layer);
  std::mt19937 rng(static_cast<std::uint32_t>(rank) + 1u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int j = rect.y0; j < rect.y1; ++j) {
    for (int i = rect.x0; i < rect.x1; ++i) {
      const std::size_t p = image.index(i, j);
      image.depth[p] = 1.0f + layer + unit(rng);
      image.hit[p] = static_cast<std::uint32_t>(p) * static_cast<std::uint32_t>(ranks) +
                     static_cast<std::uint32_t>(rank);
      for (int k = 0; k < 4; ++k) image.rgba[4 * p + k] = unit(rng);
    }
  }
  return image;
}

std::uint64_t image_hash(const render::Framebuffer& image) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  const auto mix = [&](const void* data, std::size_t bytes) {
    const auto* byte = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) hash = (hash ^ byte[k]) * 0x100000001b3ull;
  };
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    mix(&image.rgba[4 * p], 4 * sizeof(float));
    mix(&image.depth[p], sizeof(float));
    mix(&image.hit[p], sizeof(std::uint32_t));
  }
  return hash;
}

}  // namespace tetray::composite_bench
