// The images tetray-composite-bench composites: where each rank's hits lie on the screen and
// the real framebuffers with those hits.
//
// dense:  every rank covers the whole screen (the worst case of the compositor).
// sparse: the mesh is a cube split into P = a b c blocks (a <= b <= c as near each other as P
//         allows, x fastest in rank order, as a domain decomposition numbers them) seen along its
//         z axis: rank r covers screen cell (r mod a, (r / a) mod b) of an a x b grid, about
//         P^(-2/3) of the screen, at depth layer r / (a b). The ranks of one cell are a b apart
//         in rank order.
// sparse_x: the same cube seen along its x axis: rank r covers cell ((r / a) mod b, r / (a b))
//         of a b x c grid at depth layer r mod a. The ranks of one cell are consecutive.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "render/composite/composite_region.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::composite_bench {

enum class Coverage { dense, sparse, sparse_x };

const char* coverage_name(Coverage coverage);

// Three factors of `ranks` as near its cube root as its divisors allow, largest last.
std::array<int, 3> cube_factors(int ranks);

// The screen rectangle rank `rank` of `ranks` covers in a square image of `size` pixels.
render::PixelRect footprint(Coverage coverage, int size, int rank, int ranks);

// Rank `rank`'s framebuffer: random colors and depths inside its footprint (depths of a sparse
// rank inside its layer), unique hit keys; background elsewhere.
render::Framebuffer bench_image(Coverage coverage, int size, int rank, int ranks);

// FNV-1a over every pixel's color, depth and key: equal images give equal hashes, so that the
// root of a simulated run and of a real one can be compared by one number.
std::uint64_t image_hash(const render::Framebuffer& image);

}  // namespace tetray::composite_bench
