#include "render/step_store.hpp"

namespace tetray::render {

bool StepStore::store(std::int64_t step, const TetVolume& volume, const Bvh& bvh) {
  const std::size_t size = bytes_of(volume, bvh);
  const auto existing = entries_.find(step);
  const std::size_t replaced =
      existing == entries_.end() ? 0 : bytes_of(existing->second.volume, existing->second.bvh);
  if (bytes_ - replaced + size > budget_) return false;
  entries_[step] = Entry{volume, bvh};
  bytes_ = bytes_ - replaced + size;
  return true;
}

const StepStore::Entry* StepStore::find(std::int64_t step) const {
  const auto it = entries_.find(step);
  return it == entries_.end() ? nullptr : &it->second;
}

}  // namespace tetray::render
