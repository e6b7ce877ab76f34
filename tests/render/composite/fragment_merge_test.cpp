// One pixel's fragments merged (render/core/fragments.hpp) and the fragment compositor on one rank
// (render/composite/fragment_composite.hpp) against answers worked out here, never by the code
// under test: the order is the tie rule of docs/architecture.md §3 (nearer depth first, at equal
// depth the smaller key), written out by hand for surfaces of known colors and opacities, and the
// color is the closed form of front-to-back "over",
//   C = sum_i c_i a_i prod_{j<i} (1 - a_j),   A = 1 - prod_i (1 - a_i),
// with straight colors c_i and opacities a_i. Surfaces at one depth have different colors, so an
// order flipped at a tie changes the color, and a broken over operator fails here on one rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <span>
#include <vector>

#include "render/composite/fragment_composite.hpp"
#include "support/over_reference.hpp"

namespace tetray::render {
namespace {

constexpr double kColorTolerance = 1e-6;  // float colors, premultiplied in float

// A surface as a pixel sees it: its depth, tie key, straight color and opacity.
struct Surface {
  float depth;
  std::uint32_t key;
  std::array<float, 3> color;
  float alpha;
};

// In the order of the tie rule, by hand: three surfaces at depth 2 with keys 3 < 7 < 40, and the
// smallest key of all behind them (depth comes first).
const std::vector<Surface> kTiesBehind = {
    {1.0f, 12, {0.9f, 0.1f, 0.1f}, 0.5f}, {2.0f, 3, {0.1f, 0.8f, 0.2f}, 0.6f},
    {2.0f, 7, {0.2f, 0.2f, 0.9f}, 0.3f},  {2.0f, 40, {0.9f, 0.9f, 0.1f}, 0.7f},
    {2.5f, 1, {0.5f, 0.3f, 0.7f}, 0.4f},
};
// The two nearest tie: the pixel's depth is theirs and its key the smaller one, 5.
const std::vector<Surface> kTieInFront = {
    {1.0f, 5, {0.2f, 0.6f, 0.9f}, 0.45f},
    {1.0f, 8, {0.95f, 0.4f, 0.1f}, 0.8f},
    {3.0f, 2, {0.3f, 0.9f, 0.3f}, 0.5f},
};

template <typename F>
F fragment_of(const Surface& s) {
  F f;
  f.depth_in = f.depth_out = s.depth;
  f.key = s.key;
  for (int c = 0; c < 3; ++c) f.rgba[c] = s.color[c] * s.alpha;  // premultiplied
  f.rgba[3] = s.alpha;
  return f;
}

// The closed form of "over" for surfaces listed front to back.
std::array<double, 4> over(std::span<const Surface> front_to_back) {
  return ::tetray::testing::over_front_to_back(front_to_back);
}

// The same surfaces with every run of equal depths in the opposite key order.
std::vector<Surface> ties_reversed(std::vector<Surface> surfaces) {
  for (auto run = surfaces.begin(); run != surfaces.end();) {
    const auto end =
        std::find_if(run, surfaces.end(), [&](const Surface& s) { return s.depth != run->depth; });
    std::reverse(run, end);
    run = end;
  }
  return surfaces;
}

double largest_difference(const std::array<double, 4>& a, const float b[4]) {
  double d = 0;
  for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(a[c] - double{b[c]}));
  return d;
}

// Every arrival order of `surfaces` (listed in the rule's order) merges to the closed form, with
// the nearest surface's depth and key.
template <typename F>
void expect_every_order_merges_to_the_closed_form(const std::vector<Surface>& surfaces) {
  const std::array<double, 4> expected = over(surfaces);
  std::vector<std::size_t> arrival(surfaces.size());
  std::iota(arrival.begin(), arrival.end(), 0);
  int orders = 0;
  do {
    std::vector<F> layers;
    for (std::size_t k : arrival) layers.push_back(fragment_of<F>(surfaces[k]));
    float rgba[4], depth = 0;
    std::uint32_t key = 0;
    merge_pixel(layers, rgba, depth, key);
    ASSERT_LE(largest_difference(expected, rgba), kColorTolerance) << "arrival order " << orders;
    ASSERT_EQ(depth, surfaces.front().depth) << "arrival order " << orders;
    ASSERT_EQ(key, surfaces.front().key) << "arrival order " << orders;
    ++orders;
  } while (std::next_permutation(arrival.begin(), arrival.end()));
  EXPECT_GE(orders, 6);
}

TEST(FragmentMerge, EqualDepthsGoToTheSmallerKeyInEveryArrivalOrder) {
  for (const std::vector<Surface>* surfaces : {&kTiesBehind, &kTieInFront}) {
    // The data can tell the orders apart: the ties the other way round blend to another color.
    const std::array<double, 4> flipped = over(ties_reversed(*surfaces));
    const std::array<double, 4> expected = over(*surfaces);
    float as_float[4];
    for (int c = 0; c < 4; ++c) as_float[c] = static_cast<float>(flipped[c]);
    ASSERT_GT(largest_difference(expected, as_float), 0.01);
    expect_every_order_merges_to_the_closed_form<Fragment>(*surfaces);
    expect_every_order_merges_to_the_closed_form<VolumeFragment>(*surfaces);
  }
}

// Front to back: red 1/4, green 1/2, blue 3/4, opaque white, and a surface the white one hides.
// By hand: R = 1/4 + (3/4)(1/2)(1/4) = 0.34375, G = (3/4)(1/2) + 3/32 = 0.46875,
// B = (3/4)(1/2)(3/4) + 3/32 = 0.375, A = 1; the first two alone: (1/4, 3/8, 0, 5/8).
const std::vector<Surface> kKnownLayers = {
    {0.5f, 4, {1, 0, 0}, 0.25f}, {1.5f, 2, {0, 1, 0}, 0.5f},          {2.5f, 9, {0, 0, 1}, 0.75f},
    {3.5f, 1, {1, 1, 1}, 1.0f},  {4.5f, 3, {0.5f, 0.5f, 0.5f}, 0.5f},
};

template <typename F>
void expect_known_layers_blend_as_by_hand() {
  std::vector<F> layers;
  for (auto s = kKnownLayers.rbegin(); s != kKnownLayers.rend(); ++s)
    layers.push_back(fragment_of<F>(*s));  // farthest first
  float rgba[4], depth = 0;
  std::uint32_t key = 0;
  std::vector<F> all = layers;
  merge_pixel(all, rgba, depth, key);
  const std::array<double, 4> by_hand = {0.34375, 0.46875, 0.375, 1.0};
  EXPECT_LE(largest_difference(by_hand, rgba), kColorTolerance);
  EXPECT_LE(largest_difference(over(kKnownLayers), rgba), kColorTolerance);
  EXPECT_EQ(depth, 0.5f);
  EXPECT_EQ(key, 4u);
  std::vector<F> two = layers;
  merge_pixel(two, rgba, depth, key, 2);
  EXPECT_LE(largest_difference({0.25, 0.375, 0.0, 0.625}, rgba), kColorTolerance);
}

TEST(FragmentMerge, OverOfKnownSurfacesIsTheClosedForm) {
  expect_known_layers_blend_as_by_hand<Fragment>();
  expect_known_layers_blend_as_by_hand<VolumeFragment>();
}

// A one-row fragment image, pixel p holding pixels[p]'s surfaces in a scrambled arrival order.
FragmentImage scrambled_image(std::span<const std::vector<Surface>> pixels) {
  FragmentImage image;
  image.width = static_cast<int>(pixels.size());
  image.height = 1;
  image.begin.push_back(0);
  for (const std::vector<Surface>& surfaces : pixels) {
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      const std::size_t scrambled = (2 * k + 1) % surfaces.size();  // 2 is prime to 3 and 5
      image.fragments.push_back(fragment_of<Fragment>(surfaces[scrambled]));
    }
    image.begin.push_back(static_cast<std::uint32_t>(image.fragments.size()));
  }
  return image;
}

TEST(FragmentCompositeOneRank, MergesTiesAndOverAsTheClosedForm) {
  const std::vector<Surface> pixels[] = {kTiesBehind, kTieInFront, kKnownLayers};
  const FragmentImage image = scrambled_image(pixels);
  Framebuffer out;
  ASSERT_EQ(composite_fragments(image, MPI_COMM_SELF, 0, out), MPI_SUCCESS);
  ASSERT_EQ(out.pixel_count(), std::size(pixels));
  for (std::size_t p = 0; p < std::size(pixels); ++p) {
    EXPECT_LE(largest_difference(over(pixels[p]), &out.rgba[4 * p]), kColorTolerance) << p;
    EXPECT_EQ(out.depth[p], pixels[p].front().depth) << p;
    EXPECT_EQ(out.hit[p], pixels[p].front().key) << p;
  }
  // Three layers kept: the first three of each list, in its order.
  FragmentImage kept;
  ASSERT_EQ(gather_fragments(image, MPI_COMM_SELF, 0, 3, kept), MPI_SUCCESS);
  for (std::size_t p = 0; p < std::size(pixels); ++p) {
    const auto layers = kept.pixel(p);
    ASSERT_EQ(layers.size(), 3u) << p;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(layers[k].key, pixels[p][k].key) << p;
  }
}

}  // namespace
}  // namespace tetray::render
