// Per-pixel fragment lists ("deep" images): what a rank sees along each pixel's ray as layers
// with an entry and an exit depth and a premultiplied color, several per pixel where its
// sub-domain is non-convex or a surface is transparent. Volume runs and surface hits (zero
// length) are the same kind of fragment, so one merge serves both: fragments of a pixel are put
// in order by entry depth, ties to the smaller key (the tie rule of docs/architecture.md §3),
// and laid front to back with the over operator. Here so that both the walk stage (which makes
// them) and the compositor (which exchanges them across ranks) see it without MPI.
//
// A volume run's entry depth is where the ray first meets opacity, which does not depend on where
// a rank's sub-domain begins. Fragment (float, 28 bytes) serves the tracer's surface hits,
// VolumeFragment (double, 48 bytes) volume runs, whose colors are sums. What is guaranteed across
// rank counts: the same tets are visited with the same per-tet integrals (up to the last bits of a
// face crossing computed from another starting vertex of the face), but the sums are associated
// differently, since the fragment boundaries depend on the partition and the over operator is not
// associative in floating point. In float that difference (about 1e-7 relative) reached the
// written files (a 320 x 320 EXR differed on 2 ranks); in double it is about 1e-16 relative and
// reaches the float framebuffer, then the 8-bit PNG and half-float EXR, only for a value within
// that distance of a rounding boundary. The tests (fragment_composite_mpi, adaptor_volume_ranks:
// bytes on 1-4 ranks) see identical outputs; a proof would need an exact accumulation. Early
// termination breaks even this: each rank stops on the opacity it sees, so with termination < 1
// images agree only to within 1 - termination.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <ranges>
#include <span>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

// `Real` is the precision of the color: float for surface hits (trace_layers), double for
// volume runs, whose colors are sums that a rank count splits differently (the over operator
// is not associative in floating point): kept in double up to the final image, the merged
// colors of any split differ by about 1e-16 relative, far below the float framebuffer's and
// the written files' rounding (the comment at the top of this file says what that guarantees).
template <typename Real>
struct BasicFragment {
  float depth_in = 0, depth_out = 0;  // view-axis depths
  std::uint32_t key = kNoHit;         // tie key of the first primitive of the fragment
  Real rgba[4] = {0, 0, 0, 0};        // linear, premultiplied
};
using Fragment = BasicFragment<float>;
using VolumeFragment = BasicFragment<double>;

template <typename Real>
bool in_front_of(const BasicFragment<Real>& a, const BasicFragment<Real>& b) {
  return wins_over(a.depth_in, a.key, b.depth_in, b.key);
}

// Pixel p's fragments are fragments[begin[p], begin[p + 1]).
template <typename F>
struct BasicFragmentImage {
  using value_type = F;
  int width = 0, height = 0;
  std::vector<std::uint32_t> begin;  // pixel_count + 1 offsets
  std::vector<F> fragments;

  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * height; }
  std::span<const F> pixel(std::size_t p) const {
    return {fragments.data() + begin[p], fragments.data() + begin[p + 1]};
  }
};
using FragmentImage = BasicFragmentImage<Fragment>;
using VolumeFragmentImage = BasicFragmentImage<VolumeFragment>;

// No cap on the layers a pixel keeps (volume runs).
inline constexpr std::size_t kAllLayers = ~std::size_t{0};

// Puts a pixel's fragments in order (in_front_of) and returns how many of them it keeps: its
// nearest, up to and with the first opaque one (nothing behind it shows) and at most
// max_layers (transparent surfaces, Wald et al. 2007, §8.5: the nearest layers of all ranks
// together are those one rank tracing the whole mesh keeps).
// `Layers` is a contiguous range of fragments of one precision (a span or a vector).
template <std::ranges::contiguous_range Layers>
std::size_t kept_layers(Layers&& layers, std::size_t max_layers) {
  std::sort(std::ranges::begin(layers), std::ranges::end(layers),
            [](const auto& a, const auto& b) { return in_front_of(a, b); });
  const std::size_t count = std::min(layers.size(), max_layers);
  for (std::size_t k = 0; k < count; ++k) {
    if (layers[k].rgba[3] >= 1) return k + 1;
  }
  return count;
}

// The over operator front to back: `f` seen through what `out` (premultiplied, in double) has
// gathered in front of it.
template <typename F>
void add_behind(double out[4], const F& f) {
  const double through = 1.0 - out[3];
  for (int c = 0; c < 4; ++c) out[c] += through * f.rgba[c];
}

// Front-to-back over of fragments already in order and kept (kept_layers), with the nearest
// one's depth and key.
template <typename F>
void blend_layers(std::span<const F> layers, float rgba[4], float& depth, std::uint32_t& key) {
  double out[4] = {0, 0, 0, 0};
  for (const auto& f : layers) add_behind(out, f);
  for (int c = 0; c < 4; ++c) rgba[c] = static_cast<float>(out[c]);
  depth = layers.empty() ? std::numeric_limits<float>::infinity() : layers.front().depth_in;
  key = layers.empty() ? kNoHit : layers.front().key;
}

// Front-to-back over of one pixel's kept fragments (kept_layers), with the nearest one's depth
// and key.
template <std::ranges::contiguous_range Layers>
void merge_pixel(Layers&& all, float rgba[4], float& depth, std::uint32_t& key,
                 std::size_t max_layers = kAllLayers) {
  using F = std::ranges::range_value_t<Layers>;
  const std::span<const F> layers = std::span<const F>(all).first(kept_layers(all, max_layers));
  blend_layers(layers, rgba, depth, key);
}

// The flat image of a fragment image: merged color, the nearest fragment's depth and key.
template <typename F>
Framebuffer resolve(BasicFragmentImage<F>& image) {
  Framebuffer out(image.width, image.height);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    std::span<F> layers(image.fragments.data() + image.begin[p],
                        image.fragments.data() + image.begin[p + 1]);
    merge_pixel(layers, &out.rgba[4 * p], out.depth[p], out.hit[p]);
  }
  return out;
}

}  // namespace tetray::render
