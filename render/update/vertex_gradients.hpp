// Per-vertex gradients of the isosurface field for smooth shading: the gradient of a linear tet
// is constant, so a normal from it alone is flat per isopolygon and shows the mesh as facets.
// Averaging the tets' gradients at each vertex (weighted by tet volume) and interpolating them
// barycentrically at the hit gives a normal that varies continuously across shared faces.
//
// The sums are exact, so a vertex's gradient does not depend on the order of its tets nor on how
// they are split among ranks (docs/architecture.md, "Smooth shading across ranks"): each tet's
// terms (gradient x |det| per component, and |det|) are rounded to a grid set by the largest
// term of the vertex in that component (a maximum, which any order and any partition find
// alike) and by its tet count (a sum, likewise), coarse enough that every partial sum is a
// multiple of the grid below 2^53 of its units: double additions of them never round. A rank
// that shares vertices with others combines their exponents (a maximum) and tet counts (a sum)
// and then their sums (exact additions) between the passes.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Per vertex and term (x, y, z of gradient x |det|, then |det|), the binary exponent e of the
// largest |term| of its tets (|term| < 2^e), or kNoTerm when every such term is zero.
using VertexExponents = std::array<std::int16_t, 4>;
inline constexpr std::int16_t kNoTerm = std::numeric_limits<std::int16_t>::min();

// Per vertex and term, the sum of its tets' terms scaled by 2^-e (e at least kLeastExponent,
// so that 2^-e is a double), each rounded to a multiple of 2^(b - 53), b = max(3, ceil(log2
// n)) for the vertex's n tets: |term| < 1 rounds to at most 2^(53 - b) units, so n of them sum
// to at most 2^53 units, which doubles hold exactly. A term's rounding error is at most
// 2^(b - 54) of 2^e: below 2^-48 for n <= 32, 2^-42 for n < 4096 (float precision is 2^-24).
using VertexSums = std::array<double, 4>;
inline constexpr int kLeastExponent = -1021;

// The per-vertex arrays of the passes are large arrays (huge pages): at 14M tets they hold about
// 100 MB per update, and on 4 KiB pages their faults cost more than the passes' arithmetic.

// Pass 1: `exponents` and `tet_counts` get one entry per vertex, from this rank's tets.
void gradient_exponents(const TetVolume& volume, LargeArray<VertexExponents>& exponents,
                        LargeArray<std::int32_t>& tet_counts);

// Pass 2: `sums` gets one entry per vertex, this rank's tets' terms on the grids that
// `exponents` and `tet_counts` (over all ranks) set.
void gradient_sums(const TetVolume& volume, std::span<const VertexExponents> exponents,
                   std::span<const std::int32_t> tet_counts, LargeArray<VertexSums>& sums);

// Fills volume.gradients from the sums: the gradient sum over the |det| sum (zero for a vertex
// of flat tets only).
void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums);

// The three passes in a row, for a volume that shares no vertex with another rank.
void compute_vertex_gradients(TetVolume& volume);

}  // namespace tetray::render
