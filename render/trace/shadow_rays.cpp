#include "render/trace/shadow_rays.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

#include "render/scene/shade.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/leaf_intersect.hpp"
#include "render/trace/packet_traversal.hpp"

namespace tetray::render {
namespace {

constexpr int kTile = 16;  // pixels a side of a point light's shadow packet
constexpr float kInf = std::numeric_limits<float>::infinity();

struct ShadowFrame {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  CameraFrame view;
  IsoSet isos;
  LocalClip clip;
  std::span<const float> depth;
  float eye_magnitude = 0;  // largest coordinate of the eye, local
  // Bounds every coordinate of the vertices, the eye and the point lights (local): the
  // frustums' and the clip margin's rounding scale.
  float magnitude = 0;
};

// The hit point of pixel p (local coordinates) from its depth, in double as every rank does it.
Vec3f hit_point(const ShadowFrame& f, int i, int j, float depth) {
  const Vec3d d = pixel_direction(f.view, f.camera, i, j);
  const double t = depth / dot(d, f.view.forward);
  return static_cast<Vec3f>(f.view.eye + t * d - f.volume.origin);
}

float max_abs(Vec3f v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// How far short of its hit point a shadow ray stops (or, towards a directional light, how far
// from it it starts): far above the float rounding of the point (computed from the eye) and of
// the ray, so the surface never shadows itself where it is lit.
float surface_gap(const ShadowFrame& f, Vec3f point, float distance) {
  return 1e-4f * std::max({distance, max_abs(point), f.eye_magnitude, 1e-30f});
}

// A frustum that culls nothing: shadow rays have no corner rays (the interval test of the
// traversal bounds them), and with a zero view axis the row restriction of the intersector
// keeps every ray.
PacketFrustum open_frustum() {
  PacketFrustum frustum{};
  for (int k = 0; k < 4; ++k) frustum.slack[k] = kInf;
  frustum.forward = {0, 0, 0};
  frustum.forward_slack = kInf;
  return frustum;
}

// Any-hit: traces the packet's rays and returns which got a hit; a ray stops at its first
// one, the traversal when every ray has.
template <int S, bool kClip>
void trace_any_hit(const ShadowFrame& f, RayPacket<S>& packet, std::uint8_t* occluded) {
  using NodeFilter = std::conditional_t<kClip, ClipNodeFilter, NoNodeFilter>;
  using HitFilter = std::conditional_t<kClip, ClipHitFilter, NoHitFilter>;
  constexpr int n = RayPacket<S>::kRays;
  int waiting = 0;
  for (int r = 0; r < n; ++r) waiting += packet.tmax[r] > 0;
  if (waiting == 0) return;
  TraceStats stats;
  PacketTraversal<RayPacket<S>, false, NodeFilter> traversal(f.bvh, f.isos, packet, stats,
                                                             NodeFilter(f.clip));
  IsopolygonIntersector<S, false, HitFilter> intersector(packet, stats, HitFilter(f.clip));
  traversal.run([&](const BvhNode& leaf, int first_active) {
    if (!intersect_leaf<S, false>(f.volume, f.isos, leaf, first_active, intersector, packet, stats))
      return false;
    for (int r = first_active; r < n; ++r) {
      if (packet.tet[r] < 0 || packet.tmax[r] == -kInf) continue;
      occluded[r] = 1;
      packet.tmax[r] = -kInf;  // done: no later test accepts it
      --waiting;
    }
    return waiting == 0;
  });
}

// Finishes a packet whose eye, directions and tmax are set, with `frustum`.
template <int S>
void finish_shadow_packet(RayPacket<S>& packet, const PacketFrustum& frustum) {
  packet.frustum = frustum;
  prepare_rays(packet);
  packet.tmax_bound = *std::max_element(packet.tmax, packet.tmax + RayPacket<S>::kRays);
  packet.rays_without_hit = 0;
  packet.projection = {};
}

// The tile's rays from a point light at `light` (local) to its hit points; bit `bit` of
// `result` set for each occluded pixel.
template <bool kClip>
void point_light_tile(const ShadowFrame& f, Vec3f light, int x0, int y0, std::uint8_t bit,
                      std::uint8_t* result) {
  RayPacket<kTile> packet;
  constexpr int n = RayPacket<kTile>::kRays;
  int first_valid = -1;
  for (int r = 0; r < n; ++r) {
    const int i = x0 + r % kTile, j = y0 + r / kTile;
    const bool inside = i < f.camera.width && j < f.camera.height;
    const float depth = inside ? f.depth[static_cast<std::size_t>(j) * f.camera.width + i] : kInf;
    packet.tmax[r] = -kInf;
    packet.dx[r] = packet.dy[r] = packet.dz[r] = 1;
    if (!(depth < kInf)) continue;
    const Vec3f point = hit_point(f, i, j, depth);
    const Vec3f v = point - light;
    const float distance = length(v);
    if (!(distance > 0)) continue;
    const Vec3f d = (1 / distance) * v;
    packet.dx[r] = d.x;
    packet.dy[r] = d.y;
    packet.dz[r] = d.z;
    packet.tmax[r] = distance - surface_gap(f, point, distance);
    if (first_valid < 0) first_valid = r;
  }
  if (first_valid < 0) return;
  // Rays without a hit point take a valid ray's direction, so the packet's interval stays tight.
  for (int r = 0; r < n; ++r) {
    if (packet.tmax[r] != -kInf) continue;
    packet.dx[r] = packet.dx[first_valid];
    packet.dy[r] = packet.dy[first_valid];
    packet.dz[r] = packet.dz[first_valid];
  }
  packet.eye = light;
  finish_shadow_packet(packet,
                       make_direction_frustum(packet.dx, packet.dy, packet.dz, n, f.magnitude)
                           .value_or(open_frustum()));
  std::uint8_t occluded[n] = {};
  trace_any_hit<kTile, kClip>(f, packet, occluded);
  for (int r = 0; r < n; ++r) {
    const int i = x0 + r % kTile, j = y0 + r / kTile;
    if (occluded[r]) result[static_cast<std::size_t>(j) * f.camera.width + i] |= bit;
  }
}

// One ray per hit point of the tile towards a directional light (unit vector `to_light`).
template <bool kClip>
void directional_light_tile(const ShadowFrame& f, Vec3f to_light, int x0, int y0, std::uint8_t bit,
                            std::uint8_t* result) {
  for (int j = y0; j < std::min(y0 + kTile, f.camera.height); ++j)
    for (int i = x0; i < std::min(x0 + kTile, f.camera.width); ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * f.camera.width + i;
      if (!(f.depth[p] < kInf)) continue;
      const Vec3f point = hit_point(f, i, j, f.depth[p]);
      RayPacket<1> ray;
      ray.eye = point + surface_gap(f, point, 0) * to_light;
      ray.dx[0] = to_light.x;
      ray.dy[0] = to_light.y;
      ray.dz[0] = to_light.z;
      ray.tmax[0] = kInf;
      finish_shadow_packet(ray, open_frustum());
      std::uint8_t occluded = 0;
      trace_any_hit<1, kClip>(f, ray, &occluded);
      if (occluded) result[p] |= bit;
    }
}

template <bool kClip>
void trace_tiles(const ShadowFrame& f, const LocalLights& lights, std::uint8_t* result) {
  const int tiles_x = (f.camera.width + kTile - 1) / kTile;
  const int tiles = tiles_x * ((f.camera.height + kTile - 1) / kTile);
  tbb::parallel_for(0, tiles, [&](int tile) {
    const int x0 = tile % tiles_x * kTile, y0 = tile / tiles_x * kTile;
    int shadowing = 0;
    for (int k = 0; k < lights.count; ++k) {
      if (!lights.shadows[k]) continue;
      const auto bit = static_cast<std::uint8_t>(1u << shadowing++);
      if (lights.kind[k] == LightKind::point) {
        point_light_tile<kClip>(f, lights.vector[k], x0, y0, bit, result);
      } else {
        directional_light_tile<kClip>(f, lights.vector[k], x0, y0, bit, result);
      }
    }
  });
}

}  // namespace

std::vector<std::uint8_t> trace_shadow_rays(const TetVolume& volume, const Bvh& bvh,
                                            const Camera& camera,
                                            std::span<const IsoSurface> surfaces,
                                            const TraceOptions& options,
                                            std::span<const float> depth) {
  std::vector<std::uint8_t> result(depth.size(), 0);
  if (bvh.empty() || options.lights.shadow_count() == 0) return result;
  ShadowFrame f{volume, bvh, camera, make_frame(camera), {}, {}, depth, 0, 0};
  f.eye_magnitude = max_abs(static_cast<Vec3f>(f.view.eye - volume.origin));
  f.isos.count = static_cast<int>(std::min<std::size_t>(surfaces.size(), kMaxIsovalues));
  for (int k = 0; k < f.isos.count; ++k) f.isos.values[k] = surfaces[k].value;
  std::sort(f.isos.values, f.isos.values + f.isos.count);
  const LocalLights lights = local_lights(options.lights, volume.origin);
  const Bounds4& root = bvh.nodes[0].bounds;
  f.magnitude = f.eye_magnitude;
  for (int a = 0; a < 3; ++a)
    f.magnitude = std::max({f.magnitude, std::abs(root.lo[a]), std::abs(root.hi[a])});
  for (int k = 0; k < lights.count; ++k) {
    if (lights.kind[k] == LightKind::point)
      f.magnitude = std::max(f.magnitude, max_abs(lights.vector[k]));
  }
  if (options.clip.empty()) {
    trace_tiles<false>(f, lights, result.data());
  } else {
    f.clip = LocalClip(options.clip, volume.origin, f.magnitude);
    trace_tiles<true>(f, lights, result.data());
  }
  return result;
}

void apply_shadows(Framebuffer& image, std::span<const Framebuffer> shadow_terms,
                   std::span<const std::uint8_t> occluded) {
  for (std::size_t j = 0; j < shadow_terms.size(); ++j) {
    const auto bit = static_cast<std::uint8_t>(1u << j);
    const Framebuffer& term = shadow_terms[j];
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      if (!(occluded[p] & bit)) continue;
      for (int c = 0; c < 3; ++c) image.rgba[4 * p + c] -= term.rgba[4 * p + c];
    }
  }
}

}  // namespace tetray::render
