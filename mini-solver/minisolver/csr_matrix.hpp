// A rank-local sparse matrix in compressed rows over the local dofs (`components` per point);
// rows of shared points hold only this rank's tets' contributions (see DofSpace::accumulate).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace minisolver {

struct SparsePattern {
  std::vector<std::int64_t> row_start;  // rows + 1
  std::vector<std::int32_t> columns;    // ascending within a row
  int components = 1;

  std::size_t rows() const { return row_start.size() - 1; }
};

// The pattern of P1 couplings: every dof with every dof of every point of a common tet.
std::shared_ptr<const SparsePattern> make_pattern(std::span<const std::int32_t> tets,
                                                  std::size_t points, int components);

struct CsrMatrix {
  std::shared_ptr<const SparsePattern> pattern;
  std::vector<double> values;

  explicit CsrMatrix(std::shared_ptr<const SparsePattern> p)
      : pattern(std::move(p)), values(pattern->columns.size(), 0.0) {}

  // Adds `block` (row-major, 4*components square) of the tet with local points `v`.
  void add_element(const std::int32_t* v, std::span<const double> block);
  void multiply(std::span<const double> x, std::span<double> y) const;
  std::vector<double> diagonal() const;
  // this + factor * other, same pattern.
  CsrMatrix plus(double factor, const CsrMatrix& other) const;
};

}  // namespace minisolver
