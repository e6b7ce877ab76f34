#include "render/bvh/vertex_order.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <limits>

namespace tetray::render {
namespace {

constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();

// The tets of a subtree form one contiguous range in leaf order, found from its leaves.
struct TetRange {
  std::uint32_t begin, end;
};

TetRange tets_of(const Bvh& bvh, const Bvh::Subtree& st) {
  TetRange r{std::numeric_limits<std::uint32_t>::max(), 0};
  auto cover = [&](const BvhNode& node) {
    if (!node.is_leaf()) return;
    r.begin = std::min(r.begin, node.first);
    r.end = std::max(r.end, node.first + node.count);
  };
  cover(bvh.nodes[st.root]);
  for (std::uint32_t i = st.begin; i < st.end; ++i) cover(bvh.nodes[i]);
  return r;
}

template <typename Array>
void permute(Array& items, const std::vector<std::uint32_t>& order) {
  Array out(order.size());
  tbb::parallel_for(std::size_t{0}, order.size(), [&](std::size_t k) { out[k] = items[order[k]]; });
  items.swap(out);
}

}  // namespace

void renumber_vertices(TetVolume& volume, const Bvh& bvh) {
  if (bvh.empty()) return;
  const std::size_t count = volume.vertices.size();
  std::vector<TetRange> ranges(bvh.subtrees.size());
  for (std::size_t s = 0; s < ranges.size(); ++s) ranges[s] = tets_of(bvh, bvh.subtrees[s]);
  std::sort(ranges.begin(), ranges.end(),
            [](const TetRange& a, const TetRange& b) { return a.begin < b.begin; });
  // 1. A vertex belongs to the first range (in leaf order) that uses it.
  std::vector<std::atomic<std::uint32_t>> owner(count);
  for (auto& o : owner) o.store(kUnset, std::memory_order_relaxed);
  tbb::parallel_for(std::size_t{0}, ranges.size(), [&](std::size_t s) {
    for (std::uint32_t t = ranges[s].begin; t < ranges[s].end; ++t)
      for (std::int32_t v : volume.tets[t].v) {
        std::uint32_t current = owner[v].load(std::memory_order_relaxed);
        while (s < current &&
               !owner[v].compare_exchange_weak(current, static_cast<std::uint32_t>(s)))
          ;
      }
  });
  // 2. Each range lists the vertices it owns in first-use order.
  std::vector<std::vector<std::uint32_t>> owned(ranges.size());
  std::vector<std::uint32_t> new_index(count, kUnset);
  tbb::parallel_for(std::size_t{0}, ranges.size(), [&](std::size_t s) {
    for (std::uint32_t t = ranges[s].begin; t < ranges[s].end; ++t)
      for (std::int32_t v : volume.tets[t].v) {
        if (owner[v].load(std::memory_order_relaxed) != s || new_index[v] != kUnset) continue;
        new_index[v] = static_cast<std::uint32_t>(owned[s].size());
        owned[s].push_back(static_cast<std::uint32_t>(v));
      }
  });
  // 3. Concatenate, then rewrite the tets and the points' vertices.
  std::vector<std::uint32_t> offset(ranges.size() + 1, 0), order;
  for (std::size_t s = 0; s < ranges.size(); ++s)
    offset[s + 1] = offset[s] + static_cast<std::uint32_t>(owned[s].size());
  order.reserve(offset.back());
  for (const auto& list : owned) order.insert(order.end(), list.begin(), list.end());
  auto renumbered = [&](std::size_t v) {
    const std::uint32_t o = owner[v].load(std::memory_order_relaxed);
    return o == kUnset ? kNoVertex : offset[o] + new_index[v];
  };
  tbb::parallel_for(std::size_t{0}, ranges.size(), [&](std::size_t s) {
    for (std::uint32_t t = ranges[s].begin; t < ranges[s].end; ++t)
      for (std::int32_t& v : volume.tets[t].v) v = static_cast<std::int32_t>(renumbered(v));
  });
  permute(volume.vertices, order);
  if (volume.color_field.size() == count) permute(volume.color_field, order);
  const bool first_numbering = volume.point_vertex.empty();  // vertex p is still point p
  if (first_numbering) volume.point_vertex.resize(count);
  tbb::parallel_for(std::size_t{0}, volume.point_vertex.size(), [&](std::size_t p) {
    const std::uint32_t old =
        first_numbering ? static_cast<std::uint32_t>(p) : volume.point_vertex[p];
    volume.point_vertex[p] = old == kNoVertex ? kNoVertex : renumbered(old);
  });
}

}  // namespace tetray::render
