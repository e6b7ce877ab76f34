// Test images for the compositor and the brute-force reference it is checked against.
#pragma once

#include <mpi.h>

#include <cstdint>

#include "render/core/framebuffer.hpp"
#include "support/mpi_world.hpp"

namespace tetray::render::testing {

enum class Coverage { empty, full, random_rect };

// An image whose active pixels lie in a region given by `coverage` (a random rectangle with
// random holes for random_rect), with depths from a few levels so that many pixels tie in
// depth, and hit keys that never repeat across ranks at one pixel (key % rank_count == rank).
Framebuffer random_image(int width, int height, std::uint32_t seed, int rank, int rank_count,
                         Coverage coverage);

// Coverage drawn from the seed and rank: empty, full or a random rectangle.
Coverage random_coverage(std::uint32_t seed, int rank);

// Gathers every rank's image on `root` and keeps the nearest per pixel, equal depths going to
// the smaller key: the definition of the composited image, independent of the compositor's code
// and of its wins_over. Collective;
// meaningful on the root only.
Framebuffer brute_force_composite(const Framebuffer& image, MPI_Comm comm, int root);

}  // namespace tetray::render::testing
