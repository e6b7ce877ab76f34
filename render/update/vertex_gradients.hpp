// Per-vertex gradients of the isosurface field for smooth shading: the gradient of a linear tet
// is constant, so a normal from it alone is flat per isopolygon and shows the mesh as facets.
// Averaging the tets' gradients at each vertex (weighted by tet volume) and interpolating them
// barycentrically at the hit gives a normal that varies continuously across shared faces.
//
// The sums are exact, so a vertex's gradient does not depend on the order of its tets nor on how
// they are split among ranks (smooth shading across ranks, docs/architecture.md §2). Per vertex
// and term (gradient x |det| per component, and |det|):
// - pass 1 finds the largest term's binary exponent e (a maximum: any order and partition agree)
//   and counts the vertex's tets n (a sum, likewise);
// - pass 2 scales each term by 2^-e and rounds it to a multiple of 2^(b - 53),
//   b = max(3, ceil(log2 n)), by adding and subtracting 1.5 2^(b-1). A term is then at most
//   2^(53 - b) units and n of them at most 2^53: every partial sum is a double, so plain double
//   additions never round and any order gives the same bits.
// The price is precision: a term's rounding error is 2^(b - 54) of 2^e (2^-49 for up to 32 tets,
// 2^-42 below 4096, well below the float gradients' 2^-24); a vertex of many more tets only gets a
// coarser grid. Since no order matters, each pass runs in parallel over chunks of tets, each chunk
// owning a range of vertices (numbered in the tets' first-use order, render/volume/tet_volume.hpp)
// and handing the few terms of other chunks' vertices on to a serial tail; the per-vertex arrays
// are on huge pages and the waiting pairs are counted first into one array (fresh 4 KiB pages per
// update were most of the time at 14M tets).
//
// On one rank update_volume runs both passes. On several ranks, when any rank's smooth volume
// changed (one allreduce of flags, which also says whether some rank's update failed, so that
// none waits in the exchange), the multi-rank stage runs pass 1, takes the maximum of the
// exponents and the sum of the tet counts of the shared vertices over the ranks, runs pass 2 and
// adds the shared sums over the ranks. The shared vertices are found once per topology (or keep
// mask) change on any rank: each rank's candidates are the vertices of its domain's boundary faces
// (render/walk/face_adjacency.hpp), keyed by their exact reference coordinates (point numbers are
// per rank), and sent to a home rank chosen by a hash of the key; the home keeps the keys that
// several ranks hold and tells each rank which of its candidates those are. Each exchange then
// sends every rank's shared vertices' values to their homes, which combine them and send the
// result back: two all-to-all calls per exchange (three exchanges), O(shared vertices) bytes per
// rank. The gradients are then bit for bit those of one rank holding every tet
// (tests/adaptor/smooth_mpi_test.cpp, 1 to 4 ranks).
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

// Only the gradients a frame reads are needed: those of the corners of the tets a surface
// passes through (interpolate_normals reads the hit tet's four). `needed` has a flag per vertex;
// the passes skip every tet none of whose corners is flagged, so each flagged vertex still gets
// the terms of all its tets, and its gradient is the same to the bit as when every tet is
// summed. The other vertices' gradients are zero. An empty `needed` flags every vertex.
// On the bench's gyroid of 1M tets with one surface, 26% of the tets have a flagged corner (18% of
// the vertices are flagged).

// Flags the corners of the tets that straddle one of `isovalues` (ascending), by the tracer's
// test: some isovalue in (the tet's least value, its largest]; no flags (every vertex) for no
// isovalues. On several ranks the caller also flags the vertices other ranks share (their sums
// must hold every rank's tets).
std::vector<std::uint8_t> vertices_of_surfaces(const TetVolume& volume,
                                               std::span<const float> isovalues);

// How both passes split the work: contiguous chunks of tets, the range of vertices each chunk
// owns (it adds to those at once), where its pairs for other chunks' vertices start in one array
// (added after all chunks), and which tets add to a needed vertex. Made once per update.
struct GradientPlan {
  std::vector<std::int32_t> first;         // per chunk its first owned vertex, then one past all
  std::vector<std::size_t> waiting_start;  // per chunk where its pairs start, then their total
  std::vector<std::uint8_t> adds;          // per tet, 1 when it adds to a needed one; empty: all
};
GradientPlan plan_gradients(const TetVolume& volume, std::span<const std::uint8_t> needed = {});

// Pass 1: `exponents` and `tet_counts` get one entry per vertex, from this rank's tets.
void gradient_exponents(const TetVolume& volume, const GradientPlan& plan,
                        LargeArray<VertexExponents>& exponents,
                        LargeArray<std::int32_t>& tet_counts);

// Pass 2: `sums` gets one entry per vertex, this rank's tets' terms on the grids that
// `exponents` and `tet_counts` (over all ranks) set.
void gradient_sums(const TetVolume& volume, const GradientPlan& plan,
                   std::span<const VertexExponents> exponents,
                   std::span<const std::int32_t> tet_counts, LargeArray<VertexSums>& sums);

// Fills volume.gradients from the sums: the gradient sum over the |det| sum (zero for a vertex
// of flat tets only, or one `needed` does not flag).
void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums,
                         std::span<const std::uint8_t> needed = {});

// The three passes in a row, for a volume that shares no vertex with another rank: at the
// corners of the tets that straddle `isovalues` (ascending), or at every vertex when it is empty.
void compute_vertex_gradients(TetVolume& volume, std::span<const float> isovalues = {});

}  // namespace tetray::render
