// Images for the codec and scan tests: active and background pixels in runs of random length,
// so that blocks of 16 pixels come all active, all background and mixed, and runs cross rows.
#pragma once

#include <cstdint>

#include "render/core/framebuffer.hpp"

namespace tetray::render::testing {

// Runs of 1 to `longest` pixels, active and background alternately (the first of either kind).
// Active pixels get depths from a few levels (ties), now and then +infinity with a key (which
// still wins over the background), keys below 1000 and random colors.
Framebuffer run_image(int width, int height, std::uint32_t seed, int longest);

// Whether pixel p is active, spelled apart from the library: anything but the background
// (depth +infinity with the key kNoHit). The test images hold no NaN.
bool differs_from_background(const Framebuffer& image, std::size_t p);

}  // namespace tetray::render::testing
