// Which tets of each leaf straddle an isovalue, found about once per frame and shared by the tiles
// (the header of render/trace/tile_trace.hpp). A leaf near the edge of a tile is reached by the
// tiles on both sides, and each tested all its tets again: 1.7 visits per leaf reached at 1M
// tets, 1.45 at 4M. The answer depends on the tets' values and the isovalues alone, so the first
// tile to reach a leaf keeps it here and the others read it (tiles reaching it at the same moment
// may each find it, and a full leaf whose every tet straddles is found on every visit: see
// kUnknown).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/bvh/bvh.hpp"

namespace tetray::render {

class LeafStraddles {
 public:
  // For a frame over a BVH of `nodes` nodes, nothing known yet.
  explicit LeafStraddles(std::size_t nodes);
  ~LeafStraddles();
  LeafStraddles(const LeafStraddles&) = delete;
  LeafStraddles& operator=(const LeafStraddles&) = delete;

  // Bit k set when tet leaf.first + k straddles: kept from an earlier call for the same leaf, or
  // find() (the leaf's tets tested) and kept. Tiles on several threads may find a leaf at once;
  // they find the same bits, and each access is atomic.
  template <typename Find>
  std::uint64_t of(std::size_t leaf_index, Find&& find) {
    const std::atomic_ref<std::uint64_t> kept((*masks_)[leaf_index]);
    std::uint64_t mask = kept.load(std::memory_order_relaxed);
    if (mask == kUnknown) {
      mask = find();
      kept.store(mask, std::memory_order_relaxed);
    }
    return mask;
  }

 private:
  // Also the mask of a full leaf whose every tet straddles: such a leaf is found again each
  // time, with the same result.
  static constexpr std::uint64_t kUnknown = ~std::uint64_t{0};
  static_assert(kMaxLeafSize <= 64, "a leaf's tets are the bits of one word");

  std::vector<std::uint64_t>* masks_;
  std::vector<std::uint64_t> own_;  // used while the thread's kept storage is taken
  bool borrowed_;                   // masks_ is the thread's kept storage
};

}  // namespace tetray::render
