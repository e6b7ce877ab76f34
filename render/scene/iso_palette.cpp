#include "render/scene/iso_palette.hpp"

#include "render/core/srgb.hpp"

namespace tetray::render {
namespace {

// Tableau 10 followed by six of its light Tableau 20 companions (sRGB hex), chosen so that
// consecutive isovalues get clearly different hues.
constexpr unsigned kPaletteSrgb[kMaxIsovalues] = {
    0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f, 0xedc948, 0xb07aa1, 0xff9da7,
    0x9c755f, 0xbab0ac, 0xa0cbe8, 0xffbe7d, 0x8cd17d, 0xff9d9a, 0xd4a6c8, 0x86bcb6,
};

float channel(unsigned rgb, int shift) {
  return static_cast<float>(srgb_decode(((rgb >> shift) & 0xffu) / 255.0));
}

}  // namespace

Rgb default_iso_color(std::size_t k) {
  const unsigned rgb = kPaletteSrgb[k % kMaxIsovalues];
  return {channel(rgb, 16), channel(rgb, 8), channel(rgb, 0)};
}

}  // namespace tetray::render
