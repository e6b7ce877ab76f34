#include "tools/composite_bench/bench_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace tetray::composite_bench {

const char* coverage_name(Coverage coverage) {
  return coverage == Coverage::dense ? "dense" : "sparse";
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

render::PixelRect footprint(Coverage coverage, int size, int rank, int ranks) {
  if (coverage == Coverage::dense) return {0, 0, size, size};
  const auto [a, b, c] = cube_factors(ranks);
  (void)c;
  const int i = rank % a, j = (rank / a) % b;
  return {size * i / a, size * j / b, size * (i + 1) / a, size * (j + 1) / b};
}

render::Framebuffer bench_image(Coverage coverage, int size, int rank, int ranks) {
  render::Framebuffer image(size, size);
  const render::PixelRect rect = footprint(coverage, size, rank, ranks);
  const auto [a, b, c] = cube_factors(ranks);
  (void)c;
  const float layer = coverage == Coverage::dense ? 0.0f : static_cast<float>(rank / (a * b));
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
