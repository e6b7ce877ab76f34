#include "render/update/volume_update.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/bvh/node_planes.hpp"
#include "render/core/stopwatch.hpp"
#include "render/core/value_bounds.hpp"
#include "render/update/vertex_gradients.hpp"
#include "render/volume/point_read.hpp"

namespace tetray::render {
namespace {

Vec3d center_of_points(const PointSource& points) {
  const BoundingBox box = with_points(points, [&](const auto* xyz, const auto* disp) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, points.count), BoundingBox{},
        [&](const auto& block, BoundingBox b) {
          for (std::size_t i = block.begin(); i != block.end(); ++i) {
            double p[3];
            point_position(xyz, disp, i, p);
            b.include(Vec3d{p[0], p[1], p[2]});
          }
          return b;
        },
        [](BoundingBox a, const BoundingBox& b) {
          a.merge(b);
          return a;
        });
  });
  if (box.empty()) return {};
  return 0.5 * (box.lo() + box.hi());
}

// Calls visit(p, k) for each of the caller's points p and the vertex k it became, in the
// caller's order and in parallel: the caller's arrays are read front to back once and the
// store written scattered (within its leaf-local order), which is cheaper than gathering.
template <typename Visit>
void for_each_point_vertex(const TetVolume& volume, std::size_t point_count, Visit&& visit) {
  const bool renumbered = !volume.point_vertex.empty();
  // Never past the caller's arrays, even when a step brings fewer points than the map knows:
  // the vertices of points cut off keep their values (the adaptor, which checks the tets
  // against the point count, never lets a used point be cut off).
  const std::size_t count =
      std::min(point_count, renumbered ? volume.point_vertex.size() : volume.vertices.size());
  // Whether the points were renumbered is asked once per block, not per point (the update at
  // 4M tets about 7% faster).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const auto& block) {
    if (!renumbered) {
      for (std::size_t p = block.begin(); p != block.end(); ++p) visit(p, p);
      return;
    }
    const std::uint32_t* vertex_of = volume.point_vertex.data();
    for (std::size_t p = block.begin(); p != block.end(); ++p)
      if (vertex_of[p] != kNoVertex) visit(p, std::size_t{vertex_of[p]});
  });
}

// A point's value, 0 without a field.
template <typename F>
float value_of(const F* f, std::size_t p) {
  return f ? static_cast<float>(f[p]) : 0.0f;
}

// Converts the changed arrays into the vertex store in one pass. What changed is a template
// argument and the arrays are local pointers, so the loop reloads nothing per point: with the
// flags and the store read through the closure for each point (the compiler cannot tell they
// are not the vertex just written), the ingest at 14M tets took 1.3x as long.
template <bool kGeometry, bool kValues, typename P, typename D, typename F>
void convert(TetVolume& volume, std::size_t point_count, const P* xyz, const D* disp, const F* f) {
  Vertex* const vertices = volume.vertices.data();
  const Vec3d o = volume.origin;
  for_each_point_vertex(volume, point_count, [=](std::size_t p, std::size_t k) {
    Vertex& v = vertices[k];
    if constexpr (kGeometry) {
      double xyz_p[3];
      point_position(xyz, disp, p, xyz_p);
      // The whole vertex in one 16-byte store: a scalar store per component into the vertex
      // store made the ingest a tenth slower.
      v = {static_cast<float>(xyz_p[0] - o.x), static_cast<float>(xyz_p[1] - o.y),
           static_cast<float>(xyz_p[2] - o.z), kValues ? value_of(f, p) : v.f};
    } else {
      v.f = value_of(f, p);
    }
  });
}

void ingest(TetVolume& volume, const PointSource& points, const FieldSource& field, bool geometry,
            bool values) {
  if (volume.point_vertex.empty()) volume.vertices.resize(points.count);
  with_points(points, [&](const auto* xyz, const auto* disp) {
    with_scalar(field.kind, [&](auto tag) {
      const auto* f = static_cast<const decltype(tag)*>(field.values);
      if (geometry && values) return convert<true, true>(volume, points.count, xyz, disp, f);
      if (geometry) return convert<true, false>(volume, points.count, xyz, disp, f);
      if (values) convert<false, true>(volume, points.count, xyz, disp, f);
    });
  });
}

UpdateResult rebuild(TetVolume& volume, Bvh& bvh, const UpdatePolicy& policy) {
  const Stopwatch watch;
  bvh = build_bvh(volume, policy.build);
  UpdateResult result;
  result.kind = BvhUpdateKind::rebuild;
  result.rebuild_ms = watch.ms();
  return result;
}

// What the scenes derive from a new step beyond the BVH, only when one asks for it.
void derive_per_step(TetVolume& volume, Bvh& bvh, const UpdatePolicy& policy) {
  if (policy.vertex_gradients) compute_vertex_gradients(volume, policy.gradient_isovalues);
  if (policy.node_planes) fit_node_planes(volume, bvh, bvh.lod_planes);
}

}  // namespace

const char* to_string(BvhUpdateKind kind) {
  switch (kind) {
    case BvhUpdateKind::none:
      return "none";
    case BvhUpdateKind::field_only:
      return "field_refit";
    case BvhUpdateKind::refit:
      return "refit";
    case BvhUpdateKind::rebuild:
      return "rebuild";
  }
  return "unknown";
}

UpdateResult load_volume(TetVolume& volume, Bvh& bvh, std::span<const std::int64_t> tets,
                         std::span<const std::uint8_t> keep, std::span<const std::uint32_t> ids,
                         const PointSource& points, const FieldSource& field,
                         const UpdatePolicy& policy, const Vec3d* origin) {
  const Stopwatch watch;
  const std::size_t count = tets.size() / 4;
  volume.tets.clear();
  volume.tet_ids.clear();
  volume.tets.reserve(count);
  volume.tet_ids.reserve(count);
  for (std::size_t t = 0; t < count; ++t) {
    if (!keep.empty() && !keep[t]) continue;
    volume.tets.push_back(
        {{static_cast<std::int32_t>(tets[4 * t]), static_cast<std::int32_t>(tets[4 * t + 1]),
          static_cast<std::int32_t>(tets[4 * t + 2]), static_cast<std::int32_t>(tets[4 * t + 3])}});
    volume.tet_ids.push_back(ids.empty() ? static_cast<std::uint32_t>(t) : ids[t]);
  }
  volume.origin = origin ? *origin : center_of_points(points);
  volume.point_vertex.clear();
  volume.color_field.clear();
  volume.gradients.clear();
  ingest(volume, points, field, true, true);
  const double ingest_ms = watch.ms();
  UpdateResult result = rebuild(volume, bvh, policy);
  result.ingest_refit_ms = ingest_ms;
  derive_per_step(volume, bvh, policy);
  return result;
}

UpdateResult update_volume(TetVolume& volume, Bvh& bvh, const PointSource& points,
                           const FieldSource& field, StepChanges changes,
                           const UpdatePolicy& policy) {
  UpdateResult result;
  if (!changes.geometry && !changes.field) return result;
  const Stopwatch watch;
  ingest(volume, points, field, changes.geometry, changes.field);
  refit_bvh(volume, bvh, changes.geometry);
  result.ingest_refit_ms = watch.ms();
  result.kind = changes.geometry ? BvhUpdateKind::refit : BvhUpdateKind::field_only;
  if (bvh.sah_cost_at_build > 0) result.quality_ratio = bvh.sah_cost_now / bvh.sah_cost_at_build;
  if (result.quality_ratio > policy.rebuild_ratio) {
    const double refit_ms = result.ingest_refit_ms;
    const double ratio = result.quality_ratio;
    result = rebuild(volume, bvh, policy);
    result.ingest_refit_ms = refit_ms;
    result.quality_ratio = ratio;
  }
  // After a rebuild too: it renumbers the vertices and reorders the tets.
  derive_per_step(volume, bvh, policy);
  return result;
}

void load_color_field(TetVolume& volume, const FieldSource& field) {
  load_vertex_field(volume, field, volume.color_field);
}

void load_vertex_field(const TetVolume& volume, const FieldSource& field,
                       std::vector<float>& per_vertex) {
  per_vertex.resize(volume.vertices.size());
  with_scalar(field.kind, [&](auto tag) {
    const auto* values = static_cast<const decltype(tag)*>(field.values);
    for_each_point_vertex(volume, field.count, [&](std::size_t p, std::size_t k) {
      per_vertex[k] = static_cast<float>(values[p]);
    });
  });
}

}  // namespace tetray::render
