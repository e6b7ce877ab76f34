#include "minisolver/csr_matrix.hpp"

#include <algorithm>

namespace minisolver {

std::shared_ptr<const SparsePattern> make_pattern(std::span<const std::int32_t> tets,
                                                  std::size_t points, int components) {
  // Point graph first (rows of point neighbors), then each point couples to whole blocks.
  std::vector<std::vector<std::int32_t>> neighbors(points);
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) neighbors[tets[4 * t + a]].push_back(tets[4 * t + b]);
  auto pattern = std::make_shared<SparsePattern>();
  pattern->components = components;
  const auto c = static_cast<std::size_t>(components);
  pattern->row_start.push_back(0);
  for (auto& row : neighbors) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    for (std::size_t k = 0; k < c; ++k) {
      for (const std::int32_t q : row)
        for (std::size_t j = 0; j < c; ++j)
          pattern->columns.push_back(static_cast<std::int32_t>(c * q + j));
      pattern->row_start.push_back(static_cast<std::int64_t>(pattern->columns.size()));
    }
    std::vector<std::int32_t>().swap(row);
  }
  return pattern;
}

void CsrMatrix::add_element(const std::int32_t* v, std::span<const double> block) {
  const auto c = static_cast<std::size_t>(pattern->components);
  const std::size_t width = 4 * c;
  const auto& cols = pattern->columns;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t i = 0; i < c; ++i) {
      const std::size_t row = c * v[a] + i;
      const auto first = cols.begin() + pattern->row_start[row];
      const auto last = cols.begin() + pattern->row_start[row + 1];
      for (std::size_t b = 0; b < 4; ++b) {
        // The block of point v[b] is c consecutive columns.
        const auto at = std::lower_bound(first, last, static_cast<std::int32_t>(c * v[b]));
        const auto position = static_cast<std::size_t>(at - cols.begin());
        for (std::size_t j = 0; j < c; ++j)
          values[position + j] += block[(c * a + i) * width + c * b + j];
      }
    }
}

void CsrMatrix::multiply(std::span<const double> x, std::span<double> y) const {
  const auto& p = *pattern;
  for (std::size_t r = 0; r < p.rows(); ++r) {
    double sum = 0;
    for (auto k = p.row_start[r]; k < p.row_start[r + 1]; ++k) sum += values[k] * x[p.columns[k]];
    y[r] = sum;
  }
}

std::vector<double> CsrMatrix::diagonal() const {
  const auto& p = *pattern;
  std::vector<double> d(p.rows(), 0.0);
  for (std::size_t r = 0; r < p.rows(); ++r)
    for (auto k = p.row_start[r]; k < p.row_start[r + 1]; ++k)
      if (static_cast<std::size_t>(p.columns[k]) == r) d[r] = values[k];
  return d;
}

CsrMatrix CsrMatrix::plus(double factor, const CsrMatrix& other) const {
  CsrMatrix sum(pattern);
  for (std::size_t k = 0; k < values.size(); ++k)
    sum.values[k] = values[k] + factor * other.values[k];
  return sum;
}

}  // namespace minisolver
