// What a volume scene (config::VolumeSpec) needs beside its field's volume and BVH: the walk
// structure (face adjacency and boundary faces, render/walk/volume_render.hpp), kept across
// steps like the BVH, and the transfer function of a step.
#pragma once

#include <optional>

#include "adaptor/config/config.hpp"
#include "render/core/value_bounds.hpp"
#include "render/update/volume_update.hpp"
#include "render/walk/volume_render.hpp"

namespace tetray {

class WalkCache {
 public:
  // After the volume's update: a rebuild (a new topology, or a BVH rebuild that reordered the
  // tets) drops the structure, a refit of the geometry refits its boundary faces, a field-only
  // refit leaves it as it is (the adjacency depends on the topology alone).
  void after_update(const render::TetVolume& volume, render::BvhUpdateKind kind);

  // The structure, built first when there is none.
  const render::WalkStructure& get(const render::TetVolume& volume);

  std::size_t bytes() const { return walk_ ? walk_->bytes() : 0; }

 private:
  std::optional<render::WalkStructure> walk_;
};

// The render options of a volume scene; `global_range` is the field's range over all ranks
// this step (used when the spec's range is automatic).
render::VolumeRenderOptions volume_options(const config::VolumeSpec& spec,
                                           render::ValueRange global_range);

}  // namespace tetray
