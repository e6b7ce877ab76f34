#include "minisolver/dof_space.hpp"

#include <algorithm>
#include <cmath>

namespace minisolver {

DofSpace::DofSpace(const LocalMesh& mesh, const Comm& comm, int components)
    : mesh_(mesh), comm_(comm), components_(components) {
  owned_.reserve(mesh.point_count() * static_cast<std::size_t>(components));
  for (const std::uint8_t o : mesh.owned)
    owned_.insert(owned_.end(), static_cast<std::size_t>(components), o);
}

void DofSpace::accumulate(std::span<double> partial) const {
  const auto& halo = mesh_.halo;
  if (halo.empty()) return;
  const auto c = static_cast<std::size_t>(components_);
  std::vector<int> peers;
  std::vector<std::vector<double>> send, recv;
  for (const auto& n : halo) {
    peers.push_back(n.rank);
    std::vector<double>& buffer = send.emplace_back();
    for (const std::int32_t p : n.points)
      buffer.insert(buffer.end(), partial.begin() + c * p, partial.begin() + c * (p + 1));
    recv.emplace_back(buffer.size());
  }
  comm_.exchange(peers, send, recv);

  std::vector<std::uint8_t> shared(mesh_.point_count(), 0);
  for (const auto& n : halo)
    for (const std::int32_t p : n.points) shared[p] = 1;
  const std::vector<double> own(partial.begin(), partial.end());
  for (std::size_t p = 0; p < shared.size(); ++p)
    if (shared[p]) std::fill_n(partial.begin() + c * p, c, 0.0);
  auto add_own = [&] {
    for (std::size_t p = 0; p < shared.size(); ++p)
      if (shared[p])
        for (std::size_t k = 0; k < c; ++k) partial[c * p + k] += own[c * p + k];
  };
  bool own_added = false;
  for (std::size_t i = 0; i < halo.size(); ++i) {
    if (!own_added && halo[i].rank > comm_.rank()) {
      add_own();
      own_added = true;
    }
    for (std::size_t j = 0; j < halo[i].points.size(); ++j)
      for (std::size_t k = 0; k < c; ++k) partial[c * halo[i].points[j] + k] += recv[i][c * j + k];
  }
  if (!own_added) add_own();
}

double DofSpace::dot(std::span<const double> a, std::span<const double> b) const {
  double local = 0;
  for (std::size_t i = 0; i < owned_.size(); ++i)
    if (owned_[i]) local += a[i] * b[i];
  return comm_.sum(local);
}

double DofSpace::max_abs(std::span<const double> a) const {
  double local = 0;
  for (std::size_t i = 0; i < owned_.size(); ++i)
    if (owned_[i]) local = std::max(local, std::abs(a[i]));
  return comm_.max(local);
}

}  // namespace minisolver
