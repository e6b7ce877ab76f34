// Bringing a new time step into the renderer (Wald et al. 2007, §6.2, Schema II): one BVH per rank
// kept across steps. New coordinates, displacements and field values are converted into the vertex
// store in one pass over the solver's arrays (fused ingest), then the BVH is refit from the store;
// field-only changes touch only the scalar ranges; a topology change or a quality loss past the
// threshold rebuilds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/volume/point_source.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

enum class BvhUpdateKind { none, field_only, refit, rebuild };
const char* to_string(BvhUpdateKind kind);

struct UpdatePolicy {
  double rebuild_ratio = 1.5;  // rebuild when SAH cost / cost at build exceeds this
  BvhBuildOptions build{};
  bool vertex_gradients = false;  // keep TetVolume::gradients current (smooth shading)
  // Where: at the corners of the tets that straddle these (ascending), or everywhere when empty.
  std::vector<float> gradient_isovalues;
  bool node_planes = false;  // keep Bvh::lod_planes current (level of detail)
};

struct UpdateResult {
  BvhUpdateKind kind = BvhUpdateKind::none;
  double quality_ratio = 1.0;  // SAH cost now / at the last build
  double ingest_refit_ms = 0;
  double rebuild_ms = 0;
};

// What changed on the same topology (a topology change goes through load_volume).
struct StepChanges {
  bool geometry = false;
  bool field = false;
};

// Sets the volume's topology from `tets` (4 indices per tet, already validated to lie in
// [0, point_count)), keeping only tets whose `keep` flag is set when `keep` is non-empty, with
// ids `ids` (or their position when empty). Points and field are then ingested and the BVH
// built. The local origin is `origin` when given (ranks that share one get bitwise equal
// vertices on shared points), else the center of the points' bounding box.
UpdateResult load_volume(TetVolume& volume, Bvh& bvh, std::span<const std::int64_t> tets,
                         std::span<const std::uint8_t> keep, std::span<const std::uint32_t> ids,
                         const PointSource& points, const FieldSource& field,
                         const UpdatePolicy& policy, const Vec3d* origin = nullptr);

// A new step on the same topology: converts what changed and refits (field only, or geometry
// and field), rebuilding when the quality ratio passes the policy's threshold.
UpdateResult update_volume(TetVolume& volume, Bvh& bvh, const PointSource& points,
                           const FieldSource& field, StepChanges changes,
                           const UpdatePolicy& policy);

// Fills volume.color_field (the field a scene colors by) from the caller's per-point values,
// in the vertex store's order.
void load_color_field(TetVolume& volume, const FieldSource& field);

// The same for any per-vertex field kept beside the volume (a clip cap's): `per_vertex` gets
// one value per vertex of the store.
void load_vertex_field(const TetVolume& volume, const FieldSource& field,
                       std::vector<float>& per_vertex);

}  // namespace tetray::render
