#include "support/reference_intersector.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

namespace tetray::test {
namespace {

Vec3d local_point(const render::Vertex& v) { return {v.x, v.y, v.z}; }

// Diagonal of the bounding box of the points the tets use.
double tets_diagonal(const render::TetVolume& volume) {
  if (volume.tets.empty()) return 0;
  Vec3d lo = local_point(volume.vertices[volume.tets[0].v[0]]), hi = lo;
  for (const render::Tet& tet : volume.tets) {
    for (const std::int32_t v : tet.v) {
      lo = min(lo, local_point(volume.vertices[v]));
      hi = max(hi, local_point(volume.vertices[v]));
    }
  }
  return length(hi - lo);
}

struct NearestTwo {
  double t = ReferenceHit::kNone, second_t = ReferenceHit::kNone;
  const ReferenceTet* tet = nullptr;
  int surface = -1;

  void offer(double candidate, const ReferenceTet* candidate_tet, int candidate_surface) {
    if (candidate < t) {
      second_t = t;
      t = candidate;
      tet = candidate_tet;
      surface = candidate_surface;
    } else {
      second_t = std::min(second_t, candidate);
    }
  }
};

}  // namespace

std::vector<ReferenceTet> reference_tets(const render::TetVolume& volume) {
  std::vector<ReferenceTet> tets;
  tets.reserve(volume.tets.size());
  for (std::size_t k = 0; k < volume.tets.size(); ++k) {
    std::array<Vec3d, 4> points{};
    std::array<double, 4> values{};
    for (int c = 0; c < 4; ++c) {
      const render::Vertex& v = volume.vertices[volume.tets[k].v[c]];
      points[c] = local_point(v);
      values[c] = v.f;
    }
    tets.emplace_back(points, values, volume.tet_ids[k]);
  }
  return tets;
}

ReferenceIntersector::ReferenceIntersector(const render::TetVolume& volume,
                                           std::vector<double> isovalues,
                                           const render::ClipRegion& clip)
    : origin_(volume.origin),
      extent_(tets_diagonal(volume)),
      tets_(reference_tets(volume)),
      isovalues_(std::move(isovalues)),
      clip_(clip, volume.origin),
      clipped_(!clip.empty()) {}

ReferenceHit ReferenceIntersector::trace_ray(const ReferenceCamera& camera, Vec3d direction) const {
  const Ray ray{camera.eye() - origin_, direction};
  ReferenceHit result;
  result.length_scale = std::max(length(ray.origin), extent_);
  const double pad = 2 * kGrazingDistance * result.length_scale;

  // Pass 1: the nearest two hits, and the tets close enough to matter for pass 2.
  std::vector<std::pair<double, const ReferenceTet*>> near_tets;  // with their reach
  NearestTwo nearest;
  std::vector<std::pair<double, double>> clip_candidates;  // every hit: t, distance to the clip
  for (const ReferenceTet& tet : tets_) {
    const std::optional<double> reach = tet.reach(ray, pad);
    if (!reach) continue;
    near_tets.emplace_back(*reach, &tet);
    for (std::size_t s = 0; s < isovalues_.size(); ++s) {
      const auto t = tet.intersect(ray, isovalues_[s]);
      if (!t) continue;
      if (clipped_) {
        const Vec3d point = ray.origin + *t * ray.direction;
        clip_candidates.emplace_back(*t, clip_.boundary_distance(point));
        if (!clip_.keeps(point)) continue;
      }
      nearest.offer(*t, &tet, static_cast<int>(s));
    }
  }
  for (const auto& [t, distance] : clip_candidates) {
    if (t > nearest.t * (1 + 1e-5) + pad) continue;
    result.clip_boundary_distance =
        std::min(result.clip_boundary_distance, distance / result.length_scale);
  }
  const auto depth_at = [&](double t) {
    return t == ReferenceHit::kNone ? t : camera.depth(camera.eye() + t * direction);
  };
  result.hit = nearest.tet != nullptr;
  if (result.hit) {
    result.t = nearest.t;
    result.depth = depth_at(nearest.t);
    result.second_depth = depth_at(nearest.second_t);
    result.tet_id = nearest.tet->id();
    result.surface = nearest.surface;
    result.abs_cos = nearest.tet->abs_cos(ray);
  }

  // Pass 2: grazing distances along the part of the ray that decides the pixel.
  const double t_max =
      result.hit ? result.t * (1 + 1e-5) + pad : length(ray.origin) + 2 * extent_ + pad;
  double iso_edge = ReferenceHit::kNone, tet_edge = ReferenceHit::kNone;
  for (const auto& [reach, tet] : near_tets) {
    if (reach > t_max) continue;
    tet_edge = std::min(tet_edge, tet->tet_edge_distance(ray, t_max));
    for (const double iso : isovalues_) {
      iso_edge = std::min(iso_edge, tet->isopolygon_edge_distance(ray, t_max, iso));
    }
  }
  result.isopolygon_edge_distance = iso_edge / result.length_scale;
  result.tet_edge_distance = tet_edge / result.length_scale;
  return result;
}

ReferenceLayers ReferenceIntersector::trace_layers(const ReferenceCamera& camera,
                                                   Vec3d direction) const {
  const Ray ray{camera.eye() - origin_, direction};
  ReferenceLayers result;
  result.length_scale = std::max(length(ray.origin), extent_);
  const double scale = result.length_scale;
  const double pad = 2 * kGrazingDistance * scale;
  const double t_max = length(ray.origin) + 2 * extent_ + pad;
  for (const ReferenceTet& tet : tets_) {
    if (!tet.reach(ray, pad)) continue;
    for (std::size_t s = 0; s < isovalues_.size(); ++s) {
      result.isopolygon_edge_distance =
          std::min(result.isopolygon_edge_distance,
                   tet.isopolygon_edge_distance(ray, t_max, isovalues_[s]) / scale);
      const auto t = tet.intersect(ray, isovalues_[s]);
      if (!t) continue;
      if (clipped_) {
        const Vec3d point = ray.origin + *t * ray.direction;
        result.clip_boundary_distance =
            std::min(result.clip_boundary_distance, clip_.boundary_distance(point) / scale);
        if (!clip_.keeps(point)) continue;
      }
      result.layers.push_back({*t, static_cast<int>(s)});
    }
  }
  std::sort(result.layers.begin(), result.layers.end(),
            [](const auto& a, const auto& b) { return a.t < b.t; });
  for (std::size_t k = 1; k < result.layers.size(); ++k) {
    result.closest_layers =
        std::min(result.closest_layers, (result.layers[k].t - result.layers[k - 1].t) / scale);
  }
  return result;
}

std::vector<ReferenceHit> ReferenceIntersector::trace_image(const render::Camera& camera) const {
  const ReferenceCamera rays(camera);
  std::vector<ReferenceHit> hits(static_cast<std::size_t>(camera.width) * camera.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height), [&](const auto& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < camera.width; ++i) {
        hits[static_cast<std::size_t>(j) * camera.width + i] =
            trace_ray(rays, rays.pixel_direction(i, j));
      }
    }
  });
  return hits;
}

ReferenceShadow ReferenceIntersector::shadow_ray(Vec3d from, Vec3d direction, double t_min,
                                                 double t_max) const {
  const Ray ray{from, direction};
  const double scale = std::max(length(from), extent_);
  const double pad = 2 * kGrazingDistance * scale;
  ReferenceShadow result;
  for (const ReferenceTet& tet : tets_) {
    const std::optional<double> reach = tet.reach(ray, pad);
    if (!reach || *reach > t_max + pad) continue;
    for (const double iso : isovalues_) {
      result.isopolygon_edge_distance = std::min(
          result.isopolygon_edge_distance, tet.isopolygon_edge_distance(ray, t_max, iso) / scale);
      const auto t = tet.intersect(ray, iso);
      if (!t || *t <= t_min || *t >= t_max) continue;
      const Vec3d point = ray.origin + *t * ray.direction;
      if (clipped_) {
        result.clip_boundary_distance =
            std::min(result.clip_boundary_distance, clip_.boundary_distance(point) / scale);
        if (!clip_.keeps(point)) continue;
      }
      result.blocked = true;
      result.nearest_t = std::min(result.nearest_t, *t);
    }
  }
  return result;
}

BelowLevelProbe::BelowLevelProbe(const render::TetVolume& volume, double level)
    : origin_(volume.origin), level_(level) {
  for (ReferenceTet& tet : reference_tets(volume)) {
    if (tet.min_value() < level && !tet.is_flat()) tets_.push_back(std::move(tet));
  }
}

bool BelowLevelProbe::passes_below(Vec3d eye, Vec3d direction) const {
  const Ray ray{eye - origin_, direction};
  return std::any_of(tets_.begin(), tets_.end(), [&](const ReferenceTet& tet) {
    if (!tet.reach(ray, 0)) return false;
    const auto segment = tet.field_on_ray(ray);
    return segment && std::min(segment->f_in, segment->f_out) < level_;
  });
}

}  // namespace tetray::test
