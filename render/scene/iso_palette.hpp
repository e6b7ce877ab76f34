// Default colors of isosurfaces that have none of their own, the one palette of tetray-render and
// of config scenes without `colors:`: kMaxIsovalues colors that stay distinguishable next to each
// other.
#pragma once

#include <cstddef>

#include "render/scene/iso_set.hpp"
#include "render/scene/iso_surface.hpp"

namespace tetray::render {

// Linear RGB of the k-th isosurface; k wraps around after kMaxIsovalues.
Rgb default_iso_color(std::size_t k);

}  // namespace tetray::render
