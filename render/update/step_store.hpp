// Schema I of Wald et al. 2007, §6.1: a BVH and vertex store kept per time step, so that a short
// series can be replayed (re-rendered with another camera or isovalue) without refitting. It costs
// a full copy per step, so it holds at most `budget_bytes` and reports what it uses; the default in
// situ path is Schema II (one BVH, refit per step).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

class StepStore {
 public:
  explicit StepStore(std::size_t budget_bytes) : budget_(budget_bytes) {}

  // Copies what tracing the step needs (vertices, tets, ids, nodes); returns false (storing
  // nothing) when the copy would exceed the budget.
  bool store(std::int64_t step, const TetVolume& volume, const Bvh& bvh);

  struct Entry {
    TetVolume volume;
    Bvh bvh;
  };
  // The stored step, or null.
  const Entry* find(std::int64_t step) const;

  std::size_t bytes() const { return bytes_; }
  std::size_t steps() const { return entries_.size(); }

 private:
  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::map<std::int64_t, Entry> entries_;
};

}  // namespace tetray::render
