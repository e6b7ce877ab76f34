// Per-vertex gradients of the isosurface field for smooth shading: the gradient of a linear tet
// is constant, so a normal from it alone is flat per isopolygon and shows the mesh as facets.
// Averaging the tets' gradients at each vertex (weighted by tet volume) and interpolating them
// barycentrically at the hit gives a normal that varies continuously across shared faces.
//
// The sums are exact, so a vertex's gradient does not depend on the order of its tets nor on how
// they are split among ranks (docs/architecture.md, "Smooth shading across ranks"): each tet's
// terms (gradient x |det| per component, and |det|) are quantized on a grid set by the largest
// term of the vertex in that component (a maximum, which any order and any partition find
// alike) and summed as 128-bit integers. A rank that shares vertices with others combines their
// exponents (a maximum) and then their sums (an integer addition) between the passes.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "render/core/int128.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Per vertex and term (x, y, z of gradient x |det|, then |det|), the binary exponent e of the
// largest |term| of its tets (|term| < 2^e), or kNoTerm when every such term is zero.
using VertexExponents = std::array<std::int16_t, 4>;
inline constexpr std::int16_t kNoTerm = std::numeric_limits<std::int16_t>::min();

// Per vertex and term, the sum of its tets' terms in units of 2^(e - kTermBits): each term is
// below 2^kTermBits in these units, so fewer than 2^31 tets per vertex cannot overflow.
using VertexSums = std::array<Int128, 4>;
inline constexpr int kTermBits = 96;

// Pass 1: `exponents` gets one entry per vertex, from this rank's tets.
void gradient_exponents(const TetVolume& volume, std::vector<VertexExponents>& exponents);

// Pass 2: `sums` gets one entry per vertex, this rank's tets' terms on the grids `exponents` set
// (truncated toward zero: the grid is 2^-96 of the largest term, far below float precision).
void gradient_sums(const TetVolume& volume, std::span<const VertexExponents> exponents,
                   std::vector<VertexSums>& sums);

// Fills volume.gradients from the sums: the gradient sum over the |det| sum (zero for a vertex
// of flat tets only).
void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums);

// The three passes in a row, for a volume that shares no vertex with another rank.
void compute_vertex_gradients(TetVolume& volume);

}  // namespace tetray::render
