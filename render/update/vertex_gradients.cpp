#include "render/update/vertex_gradients.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>

namespace tetray::render {
namespace {

Vec3d position(const Vertex& v) { return {v.x, v.y, v.z}; }

// The gradient solves [a; b; c] g = [df1, df2, df3] for the edge vectors a, b, c from vertex 0:
// g = (df1 (b x c) + df2 (c x a) + df3 (a x b)) / det. Weighting by |det| cancels the division,
// so flat tets add nothing instead of dividing by zero; a tet whose terms are not finite adds
// nothing either.
TetTerms tet_terms(const TetVolume& volume, const Tet& tet) {
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
// exact integer arithmetic throughout. |term| < 2^e keeps the result below 2^kTermBits.
Int128 quantized(double term, std::int16_t e) {
  const Parts p = parts_of(term);
  const int shift = p.exponent + kTermBits - e;
  Int128 q = 0;
  if (shift >= 0) {
    q = static_cast<Int128>(p.mantissa) << shift;
  } else if (shift > -64) {
    q = static_cast<Int128>(p.mantissa >> -shift);
  }
  return p.negative ? -q : q;
}

template <typename Body>
void for_each_vertex(const GradientTerms& terms, Body&& body) {
  const std::size_t count = terms.first.size() - 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const auto& block) {
    for (std::size_t k = block.begin(); k != block.end(); ++k) {
      body(k, std::span(terms.tets).subspan(terms.first[k], terms.first[k + 1] - terms.first[k]));
    }
  });
}

}  // namespace

GradientTerms gradient_terms(const TetVolume& volume) {
  GradientTerms out;
  const std::size_t tet_count = volume.tets.size();
  out.tet.resize(tet_count);
  out.first.assign(volume.vertices.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tet_count), [&](const auto& block) {
    for (std::size_t t = block.begin(); t != block.end(); ++t) {
      out.tet[t] = tet_terms(volume, volume.tets[t]);
      for (const std::int32_t k : volume.tets[t].v) {
        std::atomic_ref<std::uint32_t>(out.first[k + 1]).fetch_add(1, std::memory_order_relaxed);
      }
    }
  });
  for (std::size_t k = 1; k < out.first.size(); ++k) out.first[k] += out.first[k - 1];
  // Each vertex's tets in whatever order the threads add them: the sums are exact, so the
  // order changes nothing.
  std::vector<std::uint32_t> cursor(out.first.begin(), out.first.end() - 1);
  out.tets.resize(out.first.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tet_count), [&](const auto& block) {
    for (std::size_t t = block.begin(); t != block.end(); ++t) {
      for (const std::int32_t k : volume.tets[t].v) {
        const std::uint32_t slot =
            std::atomic_ref<std::uint32_t>(cursor[k]).fetch_add(1, std::memory_order_relaxed);
        out.tets[slot] = static_cast<std::uint32_t>(t);
      }
    }
  });
  return out;
}

void gradient_exponents(const GradientTerms& terms, std::vector<VertexExponents>& exponents) {
  exponents.resize(terms.first.size() - 1);
  for_each_vertex(terms, [&](std::size_t k, std::span<const std::uint32_t> tets) {
    VertexExponents e{kNoTerm, kNoTerm, kNoTerm, kNoTerm};
    for (const std::uint32_t t : tets) {
      for (int c = 0; c < 4; ++c) e[c] = std::max(e[c], exponent_of(terms.tet[t][c]));
    }
    exponents[k] = e;
  });
}

void gradient_sums(const GradientTerms& terms, std::span<const VertexExponents> exponents,
                   std::vector<VertexSums>& sums) {
  sums.resize(terms.first.size() - 1);
  for_each_vertex(terms, [&](std::size_t k, std::span<const std::uint32_t> tets) {
    VertexSums s{0, 0, 0, 0};
    for (const std::uint32_t t : tets) {
      for (int c = 0; c < 4; ++c) {
        if (terms.tet[t][c] != 0) s[c] += quantized(terms.tet[t][c], exponents[k][c]);
      }
    }
    sums[k] = s;
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
  const GradientTerms terms = gradient_terms(volume);
  std::vector<VertexExponents> exponents;
  std::vector<VertexSums> sums;
  gradient_exponents(terms, exponents);
  gradient_sums(terms, exponents, sums);
  gradients_from_sums(volume, exponents, sums);
}

}  // namespace tetray::render
