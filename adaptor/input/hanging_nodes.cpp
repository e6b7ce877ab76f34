#include "adaptor/input/hanging_nodes.hpp"

#include <algorithm>
#include <cmath>

#include "adaptor/input/cell_faces.hpp"

namespace tetray {
namespace {

// How far (relative to the edge, or the face's diagonal) a hanging node may lie from the straight
// middle: solvers place new vertices on curved boundaries and manifolds (deal.II does), off the
// chord by several percent of the edge, and float coordinates far from the origin round by more
// than 1e-4 of a small cell. What makes a node hanging is the mesh's structure (below); the
// place only rules out a third point that is not between the ends.
constexpr double kPlaceTolerance = 0.25;

// Calls visit(cell, nodes, faces) for every linear cell whose node count fits its type and whose
// nodes name points of the mesh (the split reports the others).
template <typename Visit>
void for_each_linear_cell(std::span<const std::uint8_t> types,
                          std::span<const std::int64_t> offsets,
                          std::span<const std::int64_t> connectivity, std::size_t points,
                          Visit visit) {
  if (offsets.size() != types.size() + 1) return;
  for (std::size_t c = 0; c < types.size(); ++c) {
    if (offsets[c] < 0 || offsets[c + 1] < offsets[c] ||
        static_cast<std::size_t>(offsets[c + 1]) > connectivity.size()) {
      continue;
    }
    const auto nodes = connectivity.subspan(static_cast<std::size_t>(offsets[c]),
                                            static_cast<std::size_t>(offsets[c + 1] - offsets[c]));
    const std::span<const CellFace> faces =
        linear_cell_faces(static_cast<CellType>(types[c]), nodes.size());
    if (faces.empty()) continue;
    const bool named = std::all_of(nodes.begin(), nodes.end(), [&](std::int64_t p) {
      return p >= 0 && static_cast<std::size_t>(p) < points;
    });
    if (named) visit(c, nodes, faces);
  }
}

// Every point's neighbours along the cells' edges, each once, in no order (compressed rows).
struct EdgeGraph {
  std::vector<std::int64_t> start, neighbours;

  std::span<const std::int64_t> of(std::int64_t p) const {
    const auto at = static_cast<std::size_t>(p);
    return std::span(neighbours)
        .subspan(static_cast<std::size_t>(start[at]),
                 static_cast<std::size_t>(start[at + 1] - start[at]));
  }
  bool joined(std::int64_t p, std::int64_t q) const {
    const auto n = of(p);
    return std::find(n.begin(), n.end(), q) != n.end();
  }
};

template <typename CellVisitor>
EdgeGraph edge_graph(std::size_t points, CellVisitor for_each_cell) {
  const auto for_each_edge = [&](auto use) {
    for_each_cell(
        [&](std::size_t, std::span<const std::int64_t> nodes, std::span<const CellFace> faces) {
          for (const CellEdge& edge : edges_of(faces)) use(nodes[edge[0]], nodes[edge[1]]);
        });
  };
  std::vector<std::int64_t> fill(points + 1, 0);
  for_each_edge([&](std::int64_t a, std::int64_t b) {
    ++fill[static_cast<std::size_t>(a) + 1];
    ++fill[static_cast<std::size_t>(b) + 1];
  });
  for (std::size_t p = 0; p < points; ++p) fill[p + 1] += fill[p];
  std::vector<std::int64_t> all(static_cast<std::size_t>(fill[points]));
  std::vector<std::int64_t> next(fill.begin(), fill.end() - 1);
  for_each_edge([&](std::int64_t a, std::int64_t b) {
    all[static_cast<std::size_t>(next[static_cast<std::size_t>(a)]++)] = b;
    all[static_cast<std::size_t>(next[static_cast<std::size_t>(b)]++)] = a;
  });
  // Each edge is listed by every cell around it: keep it once, in place (a stamp per point says
  // which row last kept it; no sort).
  EdgeGraph graph;
  graph.start.assign(points + 1, 0);
  std::vector<std::int64_t> kept_in(points, -1);
  std::size_t out = 0;
  for (std::size_t p = 0; p < points; ++p) {
    for (auto k = static_cast<std::size_t>(fill[p]); k < static_cast<std::size_t>(fill[p + 1]);
         ++k) {
      const std::int64_t q = all[k];
      if (kept_in[static_cast<std::size_t>(q)] == static_cast<std::int64_t>(p)) continue;
      kept_in[static_cast<std::size_t>(q)] = static_cast<std::int64_t>(p);
      all[out++] = q;
    }
    graph.start[p + 1] = static_cast<std::int64_t>(out);
  }
  all.resize(out);
  graph.neighbours = std::move(all);
  return graph;
}

struct Positions {
  std::span<const double> xyz;

  double distance(std::int64_t p, const std::array<double, 3>& x) const {
    const double* q = &xyz[3 * static_cast<std::size_t>(p)];
    return std::hypot(q[0] - x[0], q[1] - x[1], q[2] - x[2]);
  }
  // The mean of the points' positions.
  template <std::size_t N>
  std::array<double, 3> mean(const std::array<std::int64_t, N>& ps) const {
    std::array<double, 3> m{};
    for (std::int64_t p : ps) {
      for (int k = 0; k < 3; ++k) m[k] += xyz[3 * static_cast<std::size_t>(p) + k] / N;
    }
    return m;
  }
  double between(std::int64_t a, std::int64_t b) const {
    const double* q = &xyz[3 * static_cast<std::size_t>(b)];
    return distance(a, {q[0], q[1], q[2]});
  }
};

bool has_triangular_faces(std::span<const std::uint8_t> types) {
  return std::any_of(types.begin(), types.end(), [](std::uint8_t t) {
    const auto type = static_cast<CellType>(t);
    return type == CellType::tetra || type == CellType::wedge || type == CellType::pyramid ||
           type == CellType::lagrange_tetrahedron;
  });
}

// Drops the candidates (a, b, m) that one cell holds all three of: a triangular face of a tet, a
// wedge or a pyramid, however flat, is no finer neighbour's corner.
template <typename Candidate, typename CellVisitor>
void drop_triangles_of_one_cell(std::span<const std::int64_t> offsets,
                                std::span<const std::int64_t> connectivity, std::size_t points,
                                CellVisitor for_each_cell, std::vector<Candidate>& candidates) {
  std::vector<std::uint8_t> wanted(points, 0);
  for (const Candidate& c : candidates) wanted[static_cast<std::size_t>(c.a)] = 1;
  // The cells around each end a (compressed rows).
  std::vector<std::int64_t> start(points + 1, 0);
  for_each_cell([&](std::size_t, std::span<const std::int64_t> nodes, std::span<const CellFace>) {
    for (std::int64_t p : nodes) start[static_cast<std::size_t>(p) + 1] += wanted[p];
  });
  for (std::size_t p = 0; p < points; ++p) start[p + 1] += start[p];
  std::vector<std::size_t> cells(static_cast<std::size_t>(start[points]));
  std::vector<std::int64_t> next(start.begin(), start.end() - 1);
  for_each_cell([&](std::size_t c, std::span<const std::int64_t> nodes, std::span<const CellFace>) {
    for (std::int64_t p : nodes) {
      if (wanted[p]) cells[static_cast<std::size_t>(next[static_cast<std::size_t>(p)]++)] = c;
    }
  });
  const auto holds = [&](std::size_t c, std::int64_t p) {
    const auto first = connectivity.begin() + offsets[c],
               last = connectivity.begin() + offsets[c + 1];
    return std::find(first, last, p) != last;
  };
  std::erase_if(candidates, [&](const Candidate& c) {
    const auto a = static_cast<std::size_t>(c.a);
    for (auto k = static_cast<std::size_t>(start[a]); k < static_cast<std::size_t>(start[a + 1]);
         ++k) {
      if (holds(cells[k], c.b) && holds(cells[k], c.mid)) return true;
    }
    return false;
  });
}

}  // namespace

HangingNodes HangingNodes::find(std::span<const std::uint8_t> types,
                                std::span<const std::int64_t> offsets,
                                std::span<const std::int64_t> connectivity,
                                std::span<const double> xyz) {
  HangingNodes out;
  const std::size_t points = xyz.size() / 3;
  const auto for_each_cell = [&](auto visit) {
    for_each_linear_cell(types, offsets, connectivity, points, visit);
  };
  const EdgeGraph graph = edge_graph(points, for_each_cell);
  const Positions at{xyz};

  // Midpoints: a third point m joined to both ends of an edge (a, b), near its middle, where no
  // cell holds all three (a triangular face has three such edges). Each edge is met once, from
  // its end of larger degree, whose neighbours are stamped; the other end's are looked up in the
  // stamps, so a point of many edges costs its degree, not its degree squared.
  const auto degree = [&](std::int64_t p) { return graph.of(p).size(); };
  const auto before = [&](std::int64_t p, std::int64_t q) {
    return degree(p) < degree(q) || (degree(p) == degree(q) && p < q);
  };
  std::vector<std::int64_t> stamp(points, -1);
  for (std::size_t p = 0; p < points; ++p) {
    const auto a = static_cast<std::int64_t>(p);
    for (std::int64_t q : graph.of(a)) stamp[static_cast<std::size_t>(q)] = a;
    for (std::int64_t b : graph.of(a)) {
      if (!before(b, a)) continue;
      const double length = at.between(a, b);
      if (length == 0) continue;  // a collapsed edge has no middle
      for (std::int64_t m : graph.of(b)) {
        if (stamp[static_cast<std::size_t>(m)] != a) continue;
        // A triangle of edges: rare in a mesh without triangular faces.
        const std::array<double, 3> middle = at.mean(std::array{a, b});
        if (at.distance(m, middle) <= kPlaceTolerance * length) {
          out.midpoints_.push_back({std::min(a, b), std::max(a, b), m});
        }
      }
    }
  }
  if (!out.midpoints_.empty() && has_triangular_faces(types)) {
    drop_triangles_of_one_cell(offsets, connectivity, points, for_each_cell, out.midpoints_);
  }
  std::sort(out.midpoints_.begin(), out.midpoints_.end(), [](const Midpoint& x, const Midpoint& y) {
    return std::pair{x.a, x.b} < std::pair{y.a, y.b};
  });
  if (out.midpoints_.empty()) return out;
  out.edge_end_flags_.assign(points, 0);
  for (const Midpoint& m : out.midpoints_) {
    out.edge_end_flags_[static_cast<std::size_t>(m.a)] = 1;
    out.edge_end_flags_[static_cast<std::size_t>(m.b)] = 1;
  }

  // Centres: a point joined to the midpoints of a quadrilateral's four edges, at its mean.
  for_each_cell(
      [&](std::size_t, std::span<const std::int64_t> nodes, std::span<const CellFace> faces) {
        for (const CellFace& face : faces) {
          if (face.count != 4) continue;
          std::array<std::int64_t, 4> corners{}, mids{};
          for (int k = 0; k < 4; ++k) corners[k] = nodes[face.at[k]];
          if (!std::all_of(corners.begin(), corners.end(),
                           [&](std::int64_t p) { return out.ends_hanging_edge(p); })) {
            continue;
          }
          for (int k = 0; k < 4; ++k) mids[k] = out.midpoint(corners[k], corners[(k + 1) % 4]);
          if (std::any_of(mids.begin(), mids.end(), [](std::int64_t m) { return m < 0; })) continue;
          const std::array<double, 3> mean = at.mean(corners);
          const double tolerance = kPlaceTolerance * at.between(corners[0], corners[2]);
          for (std::int64_t c : graph.of(mids[0])) {
            const bool joined = std::all_of(mids.begin() + 1, mids.end(),
                                            [&](std::int64_t m) { return graph.joined(m, c); });
            if (!joined || at.distance(c, mean) > tolerance) continue;
            std::sort(corners.begin(), corners.end());
            out.centres_.push_back({corners, c});
            break;
          }
        }
      });
  const auto by_corners = [](const Centre& x, const Centre& y) { return x.corners < y.corners; };
  std::sort(out.centres_.begin(), out.centres_.end(), by_corners);
  out.centres_.erase(
      std::unique(out.centres_.begin(), out.centres_.end(),
                  [](const Centre& x, const Centre& y) { return x.corners == y.corners; }),
      out.centres_.end());
  if (!out.centres_.empty()) {
    out.centre_flags_.assign(points, 0);
    for (const Centre& c : out.centres_) out.centre_flags_[static_cast<std::size_t>(c.centre)] = 1;
  }
  return out;
}

std::int64_t HangingNodes::midpoint(std::int64_t a, std::int64_t b) const {
  if (a > b) std::swap(a, b);
  const auto found =
      std::lower_bound(midpoints_.begin(), midpoints_.end(), std::pair{a, b},
                       [](const Midpoint& m, const std::pair<std::int64_t, std::int64_t>& key) {
                         return std::pair{m.a, m.b} < key;
                       });
  return found != midpoints_.end() && found->a == a && found->b == b ? found->mid : -1;
}

std::int64_t HangingNodes::centre(std::int64_t a, std::int64_t b, std::int64_t c,
                                  std::int64_t d) const {
  if (centres_.empty()) return -1;
  std::array<std::int64_t, 4> key{a, b, c, d};
  std::sort(key.begin(), key.end());
  const auto found = std::lower_bound(
      centres_.begin(), centres_.end(), key,
      [](const Centre& x, const std::array<std::int64_t, 4>& k) { return x.corners < k; });
  return found != centres_.end() && found->corners == key ? found->centre : -1;
}

}  // namespace tetray
