#include "render/update/step_store.hpp"

#include <cstdint>
#include <vector>

namespace tetray::render {
namespace {

// A stored step is only traced again, never refit: the refit's lists (the leaf vertex lists,
// the subtrees, the caller's point -> vertex map) stay out of the copy.
StepStore::Entry traceable_copy(const TetVolume& volume, const Bvh& bvh) {
  StepStore::Entry entry{volume, {}};
  LargeArray<std::uint32_t>().swap(entry.volume.point_vertex);
  entry.bvh.nodes = bvh.nodes;
  entry.bvh.sah_cost_at_build = bvh.sah_cost_at_build;
  entry.bvh.sah_cost_now = bvh.sah_cost_now;
  return entry;
}

std::size_t bytes_of(const StepStore::Entry& entry) {
  return entry.volume.bytes() + entry.bvh.bytes();
}

}  // namespace

bool StepStore::store(std::int64_t step, const TetVolume& volume, const Bvh& bvh) {
  Entry copy = traceable_copy(volume, bvh);
  const std::size_t size = bytes_of(copy);
  const auto existing = entries_.find(step);
  const std::size_t replaced = existing == entries_.end() ? 0 : bytes_of(existing->second);
  if (bytes_ - replaced + size > budget_) return false;
  entries_[step] = std::move(copy);
  bytes_ = bytes_ - replaced + size;
  return true;
}

const StepStore::Entry* StepStore::find(std::int64_t step) const {
  const auto it = entries_.find(step);
  return it == entries_.end() ? nullptr : &it->second;
}

}  // namespace tetray::render
