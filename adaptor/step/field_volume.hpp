// One renderer volume and BVH per distinct isosurface field, kept across steps (Wald et al. 2007,
// §6.2, Schema II). It knows which changes it has already absorbed, so a step that changed nothing
// it reads costs nothing, and it reloads (rebuilds) only when the topology or the set of
// rendered tets changed.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/update/volume_update.hpp"
#include "render/volume/mesh_check.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray {

// Counters bumped by every execute call that reports a change (also off-trigger calls), so a
// volume updated only every N calls still sees every change since its last update.
struct ChangeEpochs {
  std::uint64_t geometry = 0;
  std::uint64_t topology = 0;
  std::uint64_t fields = 0;
};

struct VolumeInputs {
  std::span<const std::int64_t> tets;
  std::span<const std::uint32_t> tie_keys;  // one per tet (adaptor/input/tie_keys.hpp)
  render::PointSource points;
  render::FieldSource field;
};

class FieldVolume {
 public:
  explicit FieldVolume(std::string field) : field_(std::move(field)) {}

  const std::string& field() const { return field_; }
  const render::TetVolume& volume() const { return volume_; }
  render::TetVolume& volume() { return volume_; }
  const render::Bvh& bvh() const { return bvh_; }
  // The keep mask being assembled for this step (check_mesh output, ghosts, ...).
  std::vector<std::uint8_t>& keep() { return keep_; }

  // Whether anything this volume reads changed since its last update.
  bool stale(const ChangeEpochs& now) const;
  bool topology_stale(const ChangeEpochs& now) const {
    return !loaded_ || now.topology != seen_.topology;
  }

  // Whether update will load (rebuild from scratch): first use, new topology or keep mask.
  bool needs_load(const ChangeEpochs& now) const {
    return topology_stale(now) || keep_ != keep_at_load_;
  }

  // Brings the volume to this step: load (build) on a topology or keep-mask change, with the
  // local origin `origin` shared by all ranks, else a refit of what changed, else nothing.
  render::UpdateResult update(const VolumeInputs& in, const ChangeEpochs& now,
                              const render::UpdatePolicy& policy, const render::Vec3d& origin);

 private:
  std::string field_;
  render::TetVolume volume_;
  render::Bvh bvh_;
  bool loaded_ = false;
  ChangeEpochs seen_{};
  std::vector<std::uint8_t> keep_;
  std::vector<std::uint8_t> keep_at_load_;
};

}  // namespace tetray
