#include "render/update/vertex_gradients.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <utility>

namespace tetray::render {
namespace {

Vec3d position(const Vertex& v) { return {v.x, v.y, v.z}; }

// A tet's terms (x, y, z of gradient x |det|, then |det|).
using TetTerms = std::array<double, 4>;

// The gradient solves [a; b; c] g = [df1, df2, df3] for the edge vectors a, b, c from vertex 0:
// g = (df1 (b x c) + df2 (c x a) + df3 (a x b)) / det. Weighting by |det| cancels the division,
// so flat tets add nothing instead of dividing by zero; a tet whose terms are not finite adds
// nothing either.
[[gnu::always_inline]] inline TetTerms tet_terms(const TetVolume& volume, const Tet& tet) {
  const Vertex* v[4];
  for (int k = 0; k < 4; ++k) v[k] = &volume.vertices[tet.v[k]];
  const Vec3d p0 = position(*v[0]);
  const Vec3d a = position(*v[1]) - p0, b = position(*v[2]) - p0, c = position(*v[3]) - p0;
  const double df1 = double(v[1]->f) - v[0]->f, df2 = double(v[2]->f) - v[0]->f,
               df3 = double(v[3]->f) - v[0]->f;
  const Vec3d bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
  const double det = dot(a, bc);
  const double sign = det < 0 ? -1.0 : 1.0;
  const Vec3d g = sign * (df1 * bc + df2 * ca + df3 * ab);
  const TetTerms terms{g.x, g.y, g.z, std::abs(det)};
  const bool finite =
      std::all_of(terms.begin(), terms.end(), [](double t) { return std::isfinite(t); });
  return finite ? terms : TetTerms{0, 0, 0, 0};
}

// The e with 2^(e-1) <= |term| < 2^e (std::frexp's), by bits; kNoTerm for zero.
std::int16_t exponent_of(double term) {
  if (term == 0) return kNoTerm;
  const auto bits = std::bit_cast<std::uint64_t>(term);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  // A subnormal has no implicit leading one: its fraction's width counts from 2^-1074.
  const int fraction_width =
      static_cast<int>(std::bit_width(bits & ((std::uint64_t{1} << 52) - 1)));
  return static_cast<std::int16_t>(biased != 0 ? biased - 1022 : fraction_width - 1074);
}

// A vertex's grid (render/update/vertex_gradients.hpp, VertexSums): a term t becomes
// (t scale + offset) - offset. |t scale| < 1 and offset = 1.5 2^(b-1) (b >= 3) keep the first
// sum in [2^(b-1), 2^b), where doubles are the multiples of 2^(b-53): it rounds t scale to
// nearest on that grid, and the subtraction is exact. scale is a power of two, so t scale is
// exact unless it underflows, and then below half a unit either way: whether the compiler fuses
// the multiply and add changes nothing.
struct Grid {
  std::array<double, 4> scale;
  double offset;
};

// x 2^k, by building 2^k from its bits where it is a normal double (std::ldexp is a call).
double scaled(double x, int k) {
  if (k < -1022 || k > 1023) return std::ldexp(x, k);
  return x * std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
}

Grid grid_of(const VertexExponents& e, std::int32_t tet_count) {
  Grid grid;
  for (int c = 0; c < 4; ++c) grid.scale[c] = scaled(1.0, -std::max<int>(e[c], kLeastExponent));
  const int b = std::max(
      3, static_cast<int>(std::bit_width(static_cast<std::uint32_t>(std::max(tet_count, 1) - 1))));
  grid.offset = scaled(1.5, b - 1);
  return grid;
}

constexpr std::size_t kChunkTets = 1 << 14;

std::size_t chunk_count(const TetVolume& volume) {
  return (volume.tets.size() + kChunkTets - 1) / kChunkTets;
}

std::span<const Tet> chunk_tets(const TetVolume& volume, std::size_t c) {
  return std::span(volume.tets)
      .subspan(c * kChunkTets, std::min(kChunkTets, volume.tets.size() - c * kChunkTets));
}

// The first vertex chunk c owns, for each chunk, then one past the last vertex: one past the
// largest vertex the chunks before it use, so the chunks' ranges are disjoint.
std::vector<std::int32_t> owned_vertex_starts(const TetVolume& volume) {
  const std::size_t chunks = chunk_count(volume);
  std::vector<std::int32_t> first(chunks + 1, 0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::int32_t largest = -1;
    for (const Tet& tet : chunk_tets(volume, c))
      for (const std::int32_t k : tet.v) largest = std::max(largest, k);
    first[c + 1] = largest + 1;
  });
  for (std::size_t c = 1; c <= chunks; ++c) first[c] = std::max(first[c], first[c - 1]);
  return first;
}

// Whether a tet adds to a vertex that is needed (render/update/vertex_gradients.hpp).
bool adds_to_needed(std::span<const std::uint8_t> needed, const Tet& tet) {
  return needed.empty() ||
         (needed[static_cast<std::size_t>(tet.v[0])] | needed[static_cast<std::size_t>(tet.v[1])] |
          needed[static_cast<std::size_t>(tet.v[2])] |
          needed[static_cast<std::size_t>(tet.v[3])]) != 0;
}

// Calls add(k, prepare(terms)) for each tet's vertices k, for the tets that add to a needed
// vertex: what depends on the tet alone is prepared once for its four vertices. In parallel over
// the plan's chunks of tets, each owning a range of vertices: a chunk adds to its own vertices at
// once and keeps the others' pairs, added after all chunks. The vertices are numbered in the
// tets' first-use order, so few pairs wait; and the sums are exact, so the order of the adds
// changes nothing.
template <typename Prepare, typename Add>
void for_each_tet_vertex(const TetVolume& volume, const GradientPlan& plan, Prepare&& prepare,
                         Add&& add) {
  using Prepared = decltype(prepare(TetTerms{}));
  LargeArray<std::pair<std::int32_t, Prepared>> waiting(plan.waiting_start.back());
  tbb::parallel_for(std::size_t{0}, plan.first.size() - 1, [&](std::size_t c) {
    auto* next_waiting = waiting.data() + plan.waiting_start[c];
    const std::int32_t first = plan.first[c];
    const std::span<const Tet> tets = chunk_tets(volume, c);
    const std::uint8_t* adds = plan.adds.empty() ? nullptr : plan.adds.data() + c * kChunkTets;
    for (std::size_t t = 0; t < tets.size(); ++t) {
      if (adds && !adds[t]) continue;
      const Tet& tet = tets[t];
      const Prepared prepared = prepare(tet_terms(volume, tet));
      for (const std::int32_t k : tet.v) {
        if (k >= first) {
          add(k, prepared);
        } else {
          *next_waiting++ = {k, prepared};
        }
      }
    }
  });
  for (const auto& [k, prepared] : waiting) add(k, prepared);
}

}  // namespace

std::vector<std::uint8_t> vertices_of_surfaces(const TetVolume& volume,
                                               std::span<const float> isovalues) {
  if (isovalues.empty()) return {};  // every vertex
  std::vector<std::uint8_t> needed(volume.vertices.size(), 0);
  // Corners of neighbouring tets are written by different threads: each flag is set, never
  // cleared, and to the same value, through an atomic reference (no tear, no race).
  tbb::parallel_for(std::size_t{0}, chunk_count(volume), [&](std::size_t c) {
    for (const Tet& tet : chunk_tets(volume, c)) {
      float lo = volume.vertices[tet.v[0]].f, hi = lo;
      for (int k = 1; k < 4; ++k) {
        const float f = volume.vertices[tet.v[k]].f;
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
      // The first isovalue above lo: the tet straddles it when it is at most hi.
      const auto above = std::upper_bound(isovalues.begin(), isovalues.end(), lo);
      if (above == isovalues.end() || !(*above <= hi)) continue;
      for (const std::int32_t k : tet.v)
        std::atomic_ref<std::uint8_t>(needed[static_cast<std::size_t>(k)])
            .store(1, std::memory_order_relaxed);
    }
  });
  return needed;
}

GradientPlan plan_gradients(const TetVolume& volume, std::span<const std::uint8_t> needed) {
  GradientPlan plan;
  plan.first = owned_vertex_starts(volume);
  const std::size_t chunks = plan.first.size() - 1;
  if (!needed.empty()) plan.adds.resize(volume.tets.size());
  // Where the pairs (vertex, tet's terms) of the vertices chunk c does not own start in one
  // array that holds every chunk's in chunk order, then their count. Counted first, so that the
  // array is allocated once, on huge pages: grown per chunk on 4 KiB pages, faulted in one by
  // one, it was most of the time of the gradients at 14M tets.
  plan.waiting_start.assign(chunks + 1, 0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::size_t waiting = 0;
    const std::span<const Tet> tets = chunk_tets(volume, c);
    for (std::size_t t = 0; t < tets.size(); ++t) {
      const bool adds = adds_to_needed(needed, tets[t]);
      if (!plan.adds.empty()) plan.adds[c * kChunkTets + t] = adds;
      if (!adds) continue;
      for (const std::int32_t k : tets[t].v) waiting += k < plan.first[c];
    }
    plan.waiting_start[c + 1] = waiting;
  });
  for (std::size_t c = 1; c <= chunks; ++c) plan.waiting_start[c] += plan.waiting_start[c - 1];
  return plan;
}

void gradient_exponents(const TetVolume& volume, const GradientPlan& plan,
                        LargeArray<VertexExponents>& exponents,
                        LargeArray<std::int32_t>& tet_counts) {
  exponents.assign(volume.vertices.size(), {kNoTerm, kNoTerm, kNoTerm, kNoTerm});
  tet_counts.assign(volume.vertices.size(), 0);
  for_each_tet_vertex(
      volume, plan,
      [](const TetTerms& terms) {
        VertexExponents e;
        for (int c = 0; c < 4; ++c) e[c] = exponent_of(terms[c]);
        return e;
      },
      [&](std::int32_t k, const VertexExponents& e) {
        for (int c = 0; c < 4; ++c) exponents[k][c] = std::max(exponents[k][c], e[c]);
        ++tet_counts[k];
      });
}

void gradient_sums(const TetVolume& volume, const GradientPlan& plan,
                   std::span<const VertexExponents> exponents,
                   std::span<const std::int32_t> tet_counts, LargeArray<VertexSums>& sums) {
  LargeArray<Grid> grids(volume.vertices.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grids.size()), [&](const auto& block) {
    for (std::size_t k = block.begin(); k != block.end(); ++k) {
      grids[k] = grid_of(exponents[k], tet_counts[k]);
    }
  });
  sums.assign(volume.vertices.size(), {0, 0, 0, 0});
  for_each_tet_vertex(
      volume, plan, [](const TetTerms& terms) { return terms; },
      [&](std::int32_t k, const TetTerms& terms) {
        const Grid& grid = grids[k];
        for (int c = 0; c < 4; ++c) {
          sums[k][c] += (terms[c] * grid.scale[c] + grid.offset) - grid.offset;
        }
      });
}

void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums, std::span<const std::uint8_t> needed) {
  volume.gradients.resize(volume.vertices.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sums.size()), [&](const auto& block) {
    for (std::size_t k = block.begin(); k != block.end(); ++k) {
      const VertexSums& s = sums[k];
      // A vertex that is not needed holds the terms of some of its tets only.
      if (!(s[3] > 0) || (!needed.empty() && needed[k] == 0)) {
        volume.gradients[k] = {0, 0, 0};
        continue;
      }
      // The sums are scaled by 2^-e: the quotient of two is scaled by the exponents' difference.
      const auto unscaled = [&](int c) {
        const int shift = std::max<int>(exponents[k][c], kLeastExponent) -
                          std::max<int>(exponents[k][3], kLeastExponent);
        return scaled(s[c] / s[3], shift);
      };
      volume.gradients[k] = static_cast<Vec3f>(Vec3d{unscaled(0), unscaled(1), unscaled(2)});
    }
  });
}

void compute_vertex_gradients(TetVolume& volume, std::span<const float> isovalues) {
  const std::vector<std::uint8_t> needed = vertices_of_surfaces(volume, isovalues);
  LargeArray<VertexExponents> exponents;
  LargeArray<std::int32_t> tet_counts;
  LargeArray<VertexSums> sums;
  const GradientPlan plan = plan_gradients(volume, needed);
  gradient_exponents(volume, plan, exponents, tet_counts);
  gradient_sums(volume, plan, exponents, tet_counts, sums);
  gradients_from_sums(volume, exponents, sums, needed);
}

}  // namespace tetray::render
