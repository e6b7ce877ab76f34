#include "render/update/vertex_gradients.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
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

// A finite double as sign, 53-bit integer mantissa and exponent: |x| = mantissa 2^exponent.
struct Parts {
  bool negative;
  std::uint64_t mantissa;
  int exponent;
};

Parts parts_of(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  // Subnormals have no implicit leading one and the exponent of the smallest normals.
  if (biased == 0) return {x < 0, fraction, -1074};
  return {x < 0, fraction | (std::uint64_t{1} << 52), biased - 1075};
}

// The e with 2^(e-1) <= |term| < 2^e (std::frexp's), by bits; kNoTerm for zero.
std::int16_t exponent_of(double term) {
  if (term == 0) return kNoTerm;
  const Parts p = parts_of(term);
  return static_cast<std::int16_t>(p.exponent + std::bit_width(p.mantissa));
}

// The term in units of 2^(e - kTermBits), truncated toward zero: its mantissa shifted, so
// exact integer arithmetic throughout. |term| < 2^e keeps the result below 2^kTermBits; a zero
// term (mantissa 0) gives 0 whatever the shift, even for a vertex whose e is kNoTerm.
Int128 quantized(const Parts& p, std::int16_t e) {
  const int shift = p.exponent + kTermBits - e;
  const Int128 q = shift >= 0 ? static_cast<Int128>(p.mantissa) << std::min(shift, 127)
                              : static_cast<Int128>(p.mantissa >> std::min(-shift, 63));
  // The sign without a branch: terms of both signs interleave unpredictably.
  const Int128 negative = -static_cast<Int128>(p.negative);
  return (q ^ negative) - negative;
}

// Calls add(k, prepare(terms)) for each tet's vertices k: what depends on the tet alone is
// prepared once for its four vertices. In parallel over contiguous chunks of tets: chunk c owns
// the vertices [first[c], first[c + 1]), first[c] being one past the largest vertex the chunks
// before it use, so the ranges are disjoint; a chunk adds to its own vertices at once and keeps
// the others' pairs, added after all chunks. The vertices are numbered in the tets' first-use
// order, so few pairs wait; and the sums are exact, so the order of the adds changes nothing.
template <typename Prepare, typename Add>
void for_each_tet_vertex(const TetVolume& volume, Prepare&& prepare, Add&& add) {
  using Prepared = decltype(prepare(TetTerms{}));
  constexpr std::size_t kChunkTets = 1 << 14;
  const std::size_t chunks = (volume.tets.size() + kChunkTets - 1) / kChunkTets;
  const auto tets_of = [&](std::size_t c) {
    return std::span(volume.tets)
        .subspan(c * kChunkTets, std::min(kChunkTets, volume.tets.size() - c * kChunkTets));
  };
  std::vector<std::int32_t> first(chunks + 1, 0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::int32_t largest = -1;
    for (const Tet& tet : tets_of(c))
      for (const std::int32_t k : tet.v) largest = std::max(largest, k);
    first[c + 1] = largest + 1;
  });
  for (std::size_t c = 1; c <= chunks; ++c) first[c] = std::max(first[c], first[c - 1]);
  std::vector<std::vector<std::pair<std::int32_t, Prepared>>> waiting(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    for (const Tet& tet : tets_of(c)) {
      const Prepared prepared = prepare(tet_terms(volume, tet));
      for (const std::int32_t k : tet.v) {
        if (k >= first[c]) {
          add(k, prepared);
        } else {
          waiting[c].emplace_back(k, prepared);
        }
      }
    }
  });
  for (const auto& pairs : waiting)
    for (const auto& [k, prepared] : pairs) add(k, prepared);
}

}  // namespace

void gradient_exponents(const TetVolume& volume, std::vector<VertexExponents>& exponents) {
  exponents.assign(volume.vertices.size(), {kNoTerm, kNoTerm, kNoTerm, kNoTerm});
  for_each_tet_vertex(
      volume,
      [](const TetTerms& terms) {
        VertexExponents e;
        for (int c = 0; c < 4; ++c) e[c] = exponent_of(terms[c]);
        return e;
      },
      [&](std::int32_t k, const VertexExponents& e) {
        for (int c = 0; c < 4; ++c) exponents[k][c] = std::max(exponents[k][c], e[c]);
      });
}

void gradient_sums(const TetVolume& volume, std::span<const VertexExponents> exponents,
                   std::vector<VertexSums>& sums) {
  sums.assign(volume.vertices.size(), {0, 0, 0, 0});
  for_each_tet_vertex(
      volume,
      [](const TetTerms& terms) {
        std::array<Parts, 4> p;
        for (int c = 0; c < 4; ++c) p[c] = parts_of(terms[c]);
        return p;
      },
      [&](std::int32_t k, const std::array<Parts, 4>& p) {
        for (int c = 0; c < 4; ++c) sums[k][c] += quantized(p[c], exponents[k][c]);
      });
}

void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums) {
  volume.gradients.resize(volume.vertices.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sums.size()), [&](const auto& block) {
    for (std::size_t k = block.begin(); k != block.end(); ++k) {
      double value[4];
      for (int c = 0; c < 4; ++c) {
        const std::int16_t e = exponents[k][c];
        value[c] = e == kNoTerm ? 0.0 : std::ldexp(static_cast<double>(sums[k][c]), e - kTermBits);
      }
      const Vec3d sum{value[0], value[1], value[2]};
      volume.gradients[k] =
          value[3] > 0 ? static_cast<Vec3f>((1 / value[3]) * sum) : Vec3f{0, 0, 0};
    }
  });
}

void compute_vertex_gradients(TetVolume& volume) {
  std::vector<VertexExponents> exponents;
  std::vector<VertexSums> sums;
  gradient_exponents(volume, exponents);
  gradient_sums(volume, exponents, sums);
  gradients_from_sums(volume, exponents, sums);
}

}  // namespace tetray::render
