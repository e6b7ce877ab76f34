// A mesh on which a vertex's smooth-shading gradient depends on its tet count over all ranks
// (render/update/vertex_gradients.hpp: a term is rounded to a grid whose step grows with the
// count), for the tests that the count is exchanged across ranks (render/parallel/
// shared_gradients.hpp). Vertex 0, at the origin, has nine tets:
// - `up` and `down`, with x terms 2^49 and -2^49 (field 2^49 at (1, 0, 0) and (-1, 0, 0)), which
//   cancel and set the scale: the x terms are scaled by 2^-50;
// - `view`, with x term 1 and y term -1 (field 1 at (2, 0, 0), 1/2 at (0, -1, 0)): scaled, its x
//   term is 2^-50, half a step of the grid of nine tets (b = 4, steps of 2^-49), where it rounds
//   to even, to 0, but a whole step of the grid of three tets (b = 3), where it stays;
// - six thin tets of zero field, which only count.
// So vertex 0's gradient is (0, -1, 0) / S (S = 4 + 27/256, its tets' |det| summed) on the grid
// of its nine tets, and (1, -1, 0) / S on the grid of three: what a rank holding up, down and
// view gets if the counts are not exchanged. Two unused points at -8 and 8 make the points'
// bounds symmetric, so the adaptor's local origin (their centre) is 0 and every term above is
// exact.
#pragma once

#include <cstdint>
#include <vector>

namespace tetray::testing {

struct CountStar {
  std::vector<double> points;      // xyz interleaved
  std::vector<double> field;       // one value per point
  std::vector<std::int64_t> tets;  // up, down, view, then the six thin tets

  static constexpr std::size_t kTetsAroundTheView = 3;  // up, down, view

  // Rank `rank`'s tets of `ranks`: up, down and view on rank 0, the thin ones spread over the
  // others (every tet on rank 0 when it is alone).
  std::vector<std::int64_t> tets_of(int rank, int ranks) const {
    std::vector<std::int64_t> mine;
    for (std::size_t t = 0; t < tets.size() / 4; ++t) {
      const int owner = ranks == 1 || t < kTetsAroundTheView
                            ? 0
                            : 1 + static_cast<int>(t % static_cast<std::size_t>(ranks - 1));
      if (owner == rank) mine.insert(mine.end(), tets.begin() + 4 * t, tets.begin() + 4 * t + 4);
    }
    return mine;
  }
};

inline CountStar count_star() {
  constexpr double kBig = 0x1p49;
  CountStar star;
  const auto point = [&](double x, double y, double z, double f) {
    star.points.insert(star.points.end(), {x, y, z});
    star.field.push_back(f);
    return static_cast<std::int64_t>(star.field.size() - 1);
  };
  const std::int64_t origin = point(0, 0, 0, 0);
  const std::int64_t right = point(1, 0, 0, kBig), y1 = point(0, 1, 0, 0), z1 = point(0, 0, 1, 0);
  const std::int64_t left = point(-1, 0, 0, kBig);
  const std::int64_t x2 = point(2, 0, 0, 1), below = point(0, -1, 0, 0.5),
                     back = point(0, 0, -1, 0);
  star.tets = {origin, right, y1, z1, origin, left, z1, y1, origin, x2, below, back};
  for (int s = 2; s <= 7; ++s) {  // |det| = s / 256, positively oriented
    const std::int64_t p = point(-s, 0, 0, 0), q = point(-s, 1.0 / 16, 0, 0),
                       r = point(-s, 0, 1.0 / 16, 0);
    star.tets.insert(star.tets.end(), {origin, p, r, q});
  }
  point(-8, -8, -8, 0);
  point(8, 8, 8, 0);
  return star;
}

}  // namespace tetray::testing
