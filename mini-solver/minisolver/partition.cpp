#include "minisolver/partition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace minisolver {
namespace {

struct Bisection {
  const std::vector<double>& centroids;  // 3 per tet
  std::span<const double> weights;
  std::vector<std::int32_t>& part;

  int longest_axis(std::span<const std::int64_t> tets) const {
    Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const std::int64_t t : tets)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], centroids[3 * t + a]);
        hi[a] = std::max(hi[a], centroids[3 * t + a]);
      }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    return axis;
  }

  double weight(int first, int last) const {
    return std::accumulate(weights.begin() + first, weights.begin() + last, 0.0);
  }

  // Ties in the coordinate are broken by tet index so the cut is the same on every rank.
  void split(std::span<std::int64_t> tets, int first_part, int last_part) const {
    if (last_part - first_part == 1) {
      for (const std::int64_t t : tets) part[t] = first_part;
      return;
    }
    const int middle = (first_part + last_part) / 2;
    const double total = weight(first_part, last_part);
    // Clamped: weights the config did not check (negative, NaN) must not cut outside the tets.
    const double share = total > 0 ? weight(first_part, middle) / total : 0.5;
    const double fraction = std::isfinite(share) ? std::clamp(share, 0.0, 1.0) : 0.5;
    const auto left =
        static_cast<std::ptrdiff_t>(std::llround(fraction * static_cast<double>(tets.size())));
    const int axis = longest_axis(tets);
    std::nth_element(tets.begin(), tets.begin() + left, tets.end(),
                     [&](std::int64_t a, std::int64_t b) {
                       const double ca = centroids[3 * a + axis], cb = centroids[3 * b + axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    split(tets.first(static_cast<std::size_t>(left)), first_part, middle);
    split(tets.subspan(static_cast<std::size_t>(left)), middle, last_part);
  }
};

std::vector<double> tet_centroids(const Mesh& mesh) {
  std::vector<double> centroids(3 * mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    for (int c = 0; c < 4; ++c)
      for (int a = 0; a < 3; ++a)
        centroids[3 * t + a] += 0.25 * mesh.points[3 * mesh.tets[4 * t + c] + a];
  return centroids;
}

}  // namespace

std::vector<std::int32_t> partition_rcb(const Mesh& mesh, int parts,
                                        std::span<const double> weights) {
  std::vector<double> equal(static_cast<std::size_t>(parts), 1.0);
  const std::vector<double> centroids = tet_centroids(mesh);
  std::vector<std::int32_t> part(mesh.tet_count(), 0);
  std::vector<std::int64_t> order(mesh.tet_count());
  std::iota(order.begin(), order.end(), 0);
  const bool one_per_part = weights.size() == equal.size();
  const Bisection bisection{centroids, one_per_part ? weights : std::span<const double>(equal),
                            part};
  bisection.split(order, 0, parts);
  return part;
}

}  // namespace minisolver
