#include "render/trace/leaf_straddles.hpp"

namespace tetray::render {
namespace {

// The masks' storage, kept from frame to frame by the thread that starts the frames: allocated
// anew per frame, its pages were faulted in again each time (0.2 ms of a 9 ms frame at 1M tets).
// A frame started while it is taken (from a task run inside another frame's wait) gets its own.
struct KeptMasks {
  std::vector<std::uint64_t> masks;
  bool taken = false;
};

thread_local KeptMasks kept_masks;

}  // namespace

LeafStraddles::LeafStraddles(std::size_t nodes) : borrowed_(!kept_masks.taken) {
  masks_ = borrowed_ ? &kept_masks.masks : &own_;
  masks_->assign(nodes, kUnknown);  // first: should it throw, the storage is not left taken
  kept_masks.taken = true;
}

LeafStraddles::~LeafStraddles() {
  if (borrowed_) kept_masks.taken = false;
}

}  // namespace tetray::render
