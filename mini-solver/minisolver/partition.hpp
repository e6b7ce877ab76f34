// Recursive coordinate bisection of a tet mesh over ranks: each cut splits the tets at their
// centroid along the longest extent, in proportion to the weights of the parts on either side.
// A part of weight zero gets no tets (an empty rank).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "minisolver/mesh.hpp"

namespace minisolver {

// The part of every tet; weights has one entry per part (equal weights when it has not, e.g.
// when empty). A negative or NaN weight counts as no share of its cut.
std::vector<std::int32_t> partition_rcb(const Mesh& mesh, int parts,
                                        std::span<const double> weights = {});

}  // namespace minisolver
