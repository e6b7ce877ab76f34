#include "render/update/vertex_gradients.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::render {
namespace {

Vec3d position(const Vertex& v) { return {v.x, v.y, v.z}; }

// A tet's four terms: gradient x |det| per component, then |det| (six times its volume).
using Terms = std::array<double, 4>;

// The gradient solves [a; b; c] g = [df1, df2, df3] for the edge vectors a, b, c from vertex 0:
// g = (df1 (b x c) + df2 (c x a) + df3 (a x b)) / det. Weighting by |det| cancels the division,
// so flat tets add nothing instead of dividing by zero. False for a tet whose terms are not
// finite (it adds nothing either).
bool tet_terms(const TetVolume& volume, const Tet& tet, Terms& terms) {
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
  terms = {g.x, g.y, g.z, std::abs(det)};
  return std::all_of(terms.begin(), terms.end(), [](double t) { return std::isfinite(t); });
}

std::int16_t exponent_of(double term) {
  if (term == 0) return kNoTerm;
  int e = 0;
  std::frexp(term, &e);  // |term| < 2^e
  return static_cast<std::int16_t>(e);
}

// The term in units of 2^(e - kTermBits): scaling by a power of two is exact, the conversion
// truncates what lies below one unit.
Int128 quantized(double term, std::int16_t e) {
  return static_cast<Int128>(std::ldexp(term, kTermBits - e));
}

}  // namespace

void gradient_exponents(const TetVolume& volume, std::vector<VertexExponents>& exponents) {
  exponents.assign(volume.vertices.size(), {kNoTerm, kNoTerm, kNoTerm, kNoTerm});
  Terms terms;
  for (const Tet& tet : volume.tets) {
    if (!tet_terms(volume, tet, terms)) continue;
    for (const std::int32_t k : tet.v) {
      for (int c = 0; c < 4; ++c)
        exponents[k][c] = std::max(exponents[k][c], exponent_of(terms[c]));
    }
  }
}

void gradient_sums(const TetVolume& volume, std::span<const VertexExponents> exponents,
                   std::vector<VertexSums>& sums) {
  sums.assign(volume.vertices.size(), {0, 0, 0, 0});
  Terms terms;
  for (const Tet& tet : volume.tets) {
    if (!tet_terms(volume, tet, terms)) continue;
    for (const std::int32_t k : tet.v) {
      for (int c = 0; c < 4; ++c) {
        if (terms[c] != 0) sums[k][c] += quantized(terms[c], exponents[k][c]);
      }
    }
  }
}

void gradients_from_sums(TetVolume& volume, std::span<const VertexExponents> exponents,
                         std::span<const VertexSums> sums) {
  volume.gradients.resize(volume.vertices.size());
  for (std::size_t k = 0; k < sums.size(); ++k) {
    double value[4];
    for (int c = 0; c < 4; ++c) {
      const std::int16_t e = exponents[k][c];
      value[c] = e == kNoTerm ? 0.0 : std::ldexp(static_cast<double>(sums[k][c]), e - kTermBits);
    }
    const Vec3d sum{value[0], value[1], value[2]};
    volume.gradients[k] = value[3] > 0 ? static_cast<Vec3f>((1 / value[3]) * sum) : Vec3f{0, 0, 0};
  }
}

void compute_vertex_gradients(TetVolume& volume) {
  std::vector<VertexExponents> exponents;
  std::vector<VertexSums> sums;
  gradient_exponents(volume, exponents);
  gradient_sums(volume, exponents, sums);
  gradients_from_sums(volume, exponents, sums);
}

}  // namespace tetray::render
