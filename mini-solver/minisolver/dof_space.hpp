// Distributed vectors with `components` values per local point. Every rank holds all its local
// points; a vector is "consistent" when shared points hold the same, complete value on every rank
// that has them. Element loops produce partial sums; accumulate() completes them.
#pragma once

#include <span>
#include <vector>

#include "minisolver/comm.hpp"
#include "minisolver/local_mesh.hpp"

namespace minisolver {

class DofSpace {
 public:
  DofSpace(const LocalMesh& mesh, const Comm& comm, int components);

  std::size_t size() const { return owned_.size(); }
  int components() const { return components_; }
  const Comm& comm() const { return comm_; }
  const LocalMesh& mesh() const { return mesh_; }

  // Adds the partial values of every rank sharing a point, in ascending rank order, so all of
  // them end with the bitwise same sum.
  void accumulate(std::span<double> partial) const;
  // Global dot product; each shared dof is counted once, by its owner.
  double dot(std::span<const double> a, std::span<const double> b) const;
  double max_abs(std::span<const double> a) const;

 private:
  const LocalMesh& mesh_;
  const Comm& comm_;
  int components_;
  std::vector<std::uint8_t> owned_;  // per dof
};

}  // namespace minisolver
