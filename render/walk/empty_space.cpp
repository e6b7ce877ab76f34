#include "render/walk/empty_space.hpp"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/bvh/bounds.hpp"
#include "render/walk/slab_ray.hpp"

namespace tetray::render {
namespace {

// A value interpolated at a face (cross_face) may round an ulp or so beyond its tet's range:
// the ranges are widened by far more than that.
double slack(double lo, double hi) { return 1e-9 * (1.0 + std::max(std::abs(lo), std::abs(hi))); }

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();

  void grow(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

bool tet_busy(const TetVolume& volume, const Tet& tet, const TransferFunction& transfer,
              std::span<const IsoSurface> surfaces, std::span<const float> surface_field) {
  Range f, g;
  for (const std::int32_t v : tet.v) {
    const double value = volume.vertices[static_cast<std::size_t>(v)].f;
    const double second =
        surface_field.empty() ? value : double{surface_field[static_cast<std::size_t>(v)]};
    // A value that is not a number: the walk would carry it, so the tet is never skipped.
    if (std::isnan(value) || std::isnan(second)) return true;
    f.grow(value);
    g.grow(second);
  }
  const double f_slack = slack(f.lo, f.hi), g_slack = slack(g.lo, g.hi);
  if (!transfer.clear_over(f.lo - f_slack, f.hi + f_slack)) return true;
  for (const IsoSurface& s : surfaces) {
    if (s.value >= g.lo - g_slack && s.value <= g.hi + g_slack) return true;
  }
  return false;
}

struct Candidate {
  double t;  // where the ray enters the tet's box
  std::uint32_t tet;
};

void fill_region(const Bvh& bvh, BusyTets& busy, std::uint32_t i) {
  const BvhNode& node = bvh.nodes[i];
  if (node.is_leaf()) {
    std::fill_n(busy.tet.begin() + node.first, node.count, BusyTets::kEmptyRegion);
    return;
  }
  fill_region(bvh, busy, node.first);
  fill_region(bvh, busy, node.first + 1);
}

// Children before parents: whether any tet below node i is busy.
bool mark_nodes(const Bvh& bvh, BusyTets& busy, std::uint32_t i) {
  const BvhNode& node = bvh.nodes[i];
  bool any = false;
  if (node.is_leaf()) {
    for (std::uint32_t t = node.first; t < node.first + node.count && !any; ++t) any = busy.busy(t);
  } else {
    const bool first = mark_nodes(bvh, busy, node.first);
    const bool second = mark_nodes(bvh, busy, node.first + 1);
    any = first || second;
  }
  busy.node[i] = any ? 1 : 0;
  return any;
}

// Every tet below an empty inner node i lies in an empty region of at least two leaves.
void mark_regions(const Bvh& bvh, BusyTets& busy, std::uint32_t i) {
  const BvhNode& node = bvh.nodes[i];
  if (node.is_leaf()) return;
  if (busy.node[i] != 0) {
    mark_regions(bvh, busy, node.first);
    mark_regions(bvh, busy, node.first + 1);
    return;
  }
  fill_region(bvh, busy, i);
}

}  // namespace

BusyTets find_busy_tets(const TetVolume& volume, const Bvh& bvh, const TransferFunction& transfer,
                        std::span<const IsoSurface> surfaces,
                        std::span<const float> surface_field) {
  BusyTets busy;
  busy.tet.resize(volume.tets.size());
  busy.node.assign(bvh.nodes.size(), 0);
  tbb::parallel_for(std::size_t{0}, volume.tets.size(), [&](std::size_t t) {
    busy.tet[t] = tet_busy(volume, volume.tets[t], transfer, surfaces, surface_field)
                      ? BusyTets::kBusy
                      : BusyTets::kEmpty;
  });
  busy.busy_count =
      static_cast<std::size_t>(std::count(busy.tet.begin(), busy.tet.end(), BusyTets::kBusy));
  if (!bvh.empty()) {
    mark_nodes(bvh, busy, 0);
    mark_regions(bvh, busy, 0);
  }
  return busy;
}

std::optional<FaceEntry> next_busy_entry(const TetVolume& volume, const Bvh& bvh,
                                         const BusyTets& busy, const RayFrame& frame, double t_from,
                                         std::span<const float> second) {
  std::optional<FaceEntry> best;
  if (bvh.empty() || busy.node[0] == 0) return best;
  double t_best = std::numeric_limits<double>::infinity();
  const SlabRay ray(frame);
  // The leaf's busy tets whose boxes the ray enters in time, nearest box first: the exact entry
  // test runs only until a box starts beyond the best entry found.
  const auto leaf = [&](std::uint32_t i) {
    const BvhNode& node = bvh.nodes[i];
    Candidate candidates[kMaxLeafSize];
    int n = 0;
    for (std::uint32_t t = node.first; t < node.first + node.count; ++t) {
      if (!busy.busy(t)) continue;
      const Bounds4 box = tet_bounds(volume, volume.tets[t]);
      const double t_box = grown_slab_entry(ray, box.lo, box.hi, t_from, t_best);
      if (t_box <= t_best) candidates[n++] = {t_box, t};
    }
    std::sort(candidates, candidates + n,
              [](const Candidate& a, const Candidate& b) { return a.t < b.t; });
    for (const Candidate* c = candidates; c != candidates + n && c->t <= t_best; ++c) {
      const std::optional<FaceEntry> entry = entry_behind(volume, frame, c->tet, second);
      if (!entry || entry->crossing.t < t_from) continue;
      if (best &&
          (entry->crossing.t > t_best ||
           (entry->crossing.t == t_best && volume.tet_ids[c->tet] > volume.tet_ids[best->tet])))
        continue;
      best = entry;
      t_best = entry->crossing.t;
    }
  };
  // One pending node per level, plus the pair just pushed (the builders bound the depth well
  // below this, as point location assumes).
  visit_nearest_first<130>(
      t_best,
      [&](std::uint32_t i) {
        const Bounds4& b = bvh.nodes[i].bounds;
        return busy.node[i] != 0 ? grown_slab_entry(ray, b.lo, b.hi, t_from, t_best)
                                 : std::numeric_limits<double>::quiet_NaN();
      },
      [&](std::uint32_t i) { return bvh.nodes[i].is_leaf(); },
      [&](std::uint32_t i) { return bvh.nodes[i].first; }, leaf);
  return best;
}

}  // namespace tetray::render
