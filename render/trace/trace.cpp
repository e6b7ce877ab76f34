// Frame driver: splits the image into 32 x 32 blocks traced in parallel, each as packets of
// the chosen size; the leaf operation intersects on-the-fly isopolygons (Wald et al. 2007, §4.4: no
// cache) of every tet whose own range straddles an isovalue (§5.2 V).
#include "render/trace/trace.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/packet_traversal.hpp"
#include "render/trace/shade.hpp"
#include "render/trace/tet_straddle.hpp"

namespace tetray::render {
namespace {

constexpr int kBlock = 32;  // pixels a side of a parallel task, a multiple of every packet size

// What the frustum tests need of the volume: the root's box relative to the eye (a packet whose
// frustum misses it sees only background) and the largest absolute coordinate of the eye and of
// the tets' vertices (make_packet_frustum).
struct VolumeExtent {
  Vec3f lo, hi;
  float magnitude = 0;
};

VolumeExtent volume_extent(const Bvh& bvh, Vec3f eye) {
  VolumeExtent extent;
  extent.magnitude = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
  if (bvh.empty()) return extent;
  const Bounds4& root = bvh.nodes[0].bounds;
  for (int a = 0; a < 3; ++a) {
    extent.lo[a] = root.lo[a] - eye[a];
    extent.hi[a] = root.hi[a] - eye[a];
    extent.magnitude = std::max({extent.magnitude, std::abs(root.lo[a]), std::abs(root.hi[a])});
  }
  return extent;
}

struct Frame {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  CameraFrame view;
  PixelDirections directions;
  IsoSet isos;
  VolumeExtent extent;
  int surface_of_sorted[kMaxIsovalues];
  ShadeContext shade;
};

// One packet row's pixels, composed in the cache and then written to the frame in one go.
template <int S>
struct PixelRow {
  alignas(64) float rgba[4 * S];
  alignas(64) float depth[S];
  alignas(64) std::uint32_t hit[S];
};

// Copies `count` elements to the frame, with streaming stores where the destination lines up
// with them: they skip reading each cache line before overwriting it, which made up much of
// writing the frame (a fifth of the trace when written pixel by pixel).
template <typename T>
void write_row(T* to, const T* from, int count) {
  const std::size_t bytes = sizeof(T) * static_cast<std::size_t>(count);
  if (reinterpret_cast<std::uintptr_t>(to) % simd::kStreamBytes == 0 &&
      bytes % simd::kStreamBytes == 0) {
    simd::stream_copy(to, from, bytes);
  } else {
    std::copy_n(from, count, to);
  }
}

// Writes the packet's rows that lie in the image, each composed in the cache first by
// compose(row, columns, out).
template <int S, typename Compose>
void write_rows(const Frame& f, int x0, int y0, Framebuffer& image, Compose&& compose) {
  const int columns = std::min(S, f.camera.width - x0);
  PixelRow<S> out;
  for (int row = 0; row < S && y0 + row < f.camera.height; ++row) {
    compose(row, columns, out);
    const std::size_t p0 = image.index(x0, y0 + row);
    write_row(&image.rgba[4 * p0], out.rgba, 4 * columns);
    write_row(&image.depth[p0], out.depth, columns);
    write_row(&image.hit[p0], out.hit, columns);
  }
  simd::stream_fence();
}

// Writes the packet's pixels: the background, or the shaded hit.
template <int S, bool kStats>
void write_pixels(const Frame& f, const RayPacket<S>& packet, int x0, int y0, Framebuffer& image,
                  TraceStats& stats) {
  constexpr int n = RayPacket<S>::kRays;
  alignas(64) float light[n], depth[n];
  light_and_depth(
      f.shade, {packet.dx, packet.dy, packet.dz, packet.nx, packet.ny, packet.nz, packet.tmax, n},
      light, depth);
  write_rows<S>(f, x0, y0, image, [&](int row, int columns, PixelRow<S>& out) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const int r0 = row * S;
    const std::int32_t* tet = packet.tet + r0;
    for (int c = 0; c < columns; ++c) {
      out.depth[c] = tet[c] >= 0 ? depth[r0 + c] : kInf;
      out.hit[c] = tet[c] >= 0 ? packet.key[r0 + c] : kNoHit;
    }
    for (int c = 0; c < columns; ++c) {
      const int r = r0 + c;
      float* rgba = &out.rgba[4 * c];
      if (tet[c] < 0) {
        std::fill_n(rgba, 4, 0.0f);
        continue;
      }
      if constexpr (kStats) ++stats.hits;
      shade_color(f.shade, {packet.dx[r], packet.dy[r], packet.dz[r]}, packet.tmax[r], tet[c],
                  packet.iso[r], light[r], rgba);
    }
    if constexpr (kStats) stats.rays += static_cast<std::uint64_t>(columns);
  });
}

// A packet whose frustum misses the whole volume: background, without setting up its rays.
template <int S, bool kStats>
void write_background(const Frame& f, int x0, int y0, Framebuffer& image, TraceStats& stats) {
  write_rows<S>(f, x0, y0, image, [&](int, int columns, PixelRow<S>& out) {
    std::fill_n(out.rgba, 4 * columns, 0.0f);
    std::fill_n(out.depth, columns, std::numeric_limits<float>::infinity());
    std::fill_n(out.hit, columns, kNoHit);
    if constexpr (kStats) stats.rays += static_cast<std::uint64_t>(columns);
  });
}

// The tet's hull lies outside the packet's frustum, behind the eye or beyond every ray's hit so
// far.
template <int S>
bool frustum_misses_tet(const RayPacket<S>& packet, const TetCorners& corners) {
  const simd::Float4 q[3] = {corners.column[0] - packet.eye.x, corners.column[1] - packet.eye.y,
                             corners.column[2] - packet.eye.z};
  return packet.frustum.misses_hull(q) || packet.frustum.outside_depths(q, packet.tmax_bound);
}

// Intersects the isopolygons of the leaf's tets that straddle an isovalue (§5.2 V) and, for
// packets, meet the packet's frustum; returns whether any ray got a new nearest hit.
template <int S, bool kStats>
bool intersect_leaf(const Frame& f, const BvhNode& leaf, int first_active,
                    IsopolygonIntersector<S, kStats>& intersector, const RayPacket<S>& packet,
                    TraceStats& stats) {
  bool hit = false;
  const std::uint32_t end = leaf.first + leaf.count;
  for (std::uint32_t batch = leaf.first; batch < end; batch += simd::kWidth) {
    const int count = static_cast<int>(std::min<std::uint32_t>(simd::kWidth, end - batch));
    if constexpr (kStats) stats.isorange_tests += static_cast<std::uint64_t>(count);
    for (std::uint64_t straddling = straddling_tets(f.volume, batch, count, f.isos); straddling;
         straddling &= straddling - 1) {
      const std::uint32_t t = batch + static_cast<std::uint32_t>(std::countr_zero(straddling));
      const TetCorners corners = load_corners(f.volume, f.volume.tets[t]);
      if constexpr (S > 1) {
        if (frustum_misses_tet(packet, corners)) continue;
      }
      for (int k = 0; k < f.isos.count; ++k) {
        const int case_index = iso_case(corners, f.isos.values[k]);
        if (case_index == 0 || case_index == 15) continue;
        if constexpr (kStats) ++stats.isopolygon_extractions;
        const Isopolygon poly = extract_isopolygon(corners, case_index, f.isos.values[k]);
        const PolygonHit id{f.volume.tet_ids[t], static_cast<std::int32_t>(t), k};
        hit |= intersector.intersect(poly, id, first_active);
      }
    }
  }
  return hit;
}

template <int S, bool kStats>
void trace_packet(const Frame& f, int x0, int y0, Framebuffer& image, TraceStats& stats) {
  PacketFrustum frustum{};  // single rays use none
  if constexpr (S > 1) {
    frustum = tile_frustum<S>(f.camera, f.view, f.extent.magnitude, x0, y0);
    if (f.bvh.empty() || frustum.misses_box(f.extent.lo, f.extent.hi))
      return write_background<S, kStats>(f, x0, y0, image, stats);
  }
  RayPacket<S> packet;
  setup_packet(packet, f.camera, f.view, f.directions, f.volume.origin, frustum, x0, y0);
  PacketTraversal<S, kStats> traversal(f.bvh, f.isos, packet, stats);
  IsopolygonIntersector<S, kStats> intersector(packet, stats);
  traversal.run([&](const BvhNode& leaf, int first_active) {
    if (intersect_leaf(f, leaf, first_active, intersector, packet, stats))
      update_tmax_bound(packet);
  });
  write_pixels<S, kStats>(f, packet, x0, y0, image, stats);
}

template <int S, bool kStats>
void trace_blocks(const Frame& f, Framebuffer& image, TraceStats* total) {
  const int blocks_x = (f.camera.width + kBlock - 1) / kBlock;
  const int blocks = blocks_x * ((f.camera.height + kBlock - 1) / kBlock);
  tbb::enumerable_thread_specific<TraceStats> stats;
  tbb::parallel_for(0, blocks, [&](int b) {
    TraceStats& local = stats.local();
    const int bx = b % blocks_x * kBlock, by = b / blocks_x * kBlock;
    for (int y = by; y < by + kBlock && y < f.camera.height; y += S)
      for (int x = bx; x < bx + kBlock && x < f.camera.width; x += S)
        trace_packet<S, kStats>(f, x, y, image, local);
  });
  if (total) {
    for (const TraceStats& s : stats) *total += s;
  }
}

template <int S>
void trace_with(const Frame& f, Framebuffer& image, bool collect, TraceStats* stats) {
  if (collect) {
    trace_blocks<S, true>(f, image, stats);
  } else {
    trace_blocks<S, false>(f, image, nullptr);
  }
}

}  // namespace

const char* to_string(PacketSize packet) {
  switch (packet) {
    case PacketSize::single:
      return "1";
    case PacketSize::p8x8:
      return "8x8";
    case PacketSize::p16x16:
      return "16x16";
    case PacketSize::p32x32:
      return "32x32";
  }
  return "?";
}

TraceStats& TraceStats::operator+=(const TraceStats& o) {
  rays += o.rays;
  hits += o.hits;
  packet_box_tests += o.packet_box_tests;
  ray_box_tests += o.ray_box_tests;
  isorange_tests += o.isorange_tests;
  isopolygon_extractions += o.isopolygon_extractions;
  ray_isopolygon_tests += o.ray_isopolygon_tests;
  frustum_culled_isopolygons += o.frustum_culled_isopolygons;
  return *this;
}

Framebuffer trace(const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats) {
  Framebuffer image;
  trace_into(image, volume, bvh, camera, surfaces, options, stats);
  return image;
}

void trace_into(Framebuffer& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                std::span<const IsoSurface> surfaces, const TraceOptions& options,
                TraceStats* stats) {
  if (image.width != camera.width || image.height != camera.height)
    image = Framebuffer(camera.width, camera.height);
  const CameraFrame view = make_frame(camera);
  Frame f{volume,
          bvh,
          camera,
          view,
          PixelDirections(view, camera),
          {},
          volume_extent(bvh, static_cast<Vec3f>(view.eye - volume.origin)),
          {},
          {volume, view, surfaces, nullptr, options}};
  f.shade.surface_of_sorted = f.surface_of_sorted;
  f.isos.count = static_cast<int>(std::min<std::size_t>(surfaces.size(), kMaxIsovalues));
  std::iota(f.surface_of_sorted, f.surface_of_sorted + f.isos.count, 0);
  std::sort(f.surface_of_sorted, f.surface_of_sorted + f.isos.count,
            [&](int a, int b) { return surfaces[a].value < surfaces[b].value; });
  for (int k = 0; k < f.isos.count; ++k) f.isos.values[k] = surfaces[f.surface_of_sorted[k]].value;
  if (stats) *stats = {};
  const bool collect = options.collect_stats && stats;
  switch (options.packet) {
    case PacketSize::single:
      trace_with<1>(f, image, collect, stats);
      break;
    case PacketSize::p8x8:
      trace_with<8>(f, image, collect, stats);
      break;
    case PacketSize::p16x16:
      trace_with<16>(f, image, collect, stats);
      break;
    case PacketSize::p32x32:
      trace_with<32>(f, image, collect, stats);
      break;
  }
}

}  // namespace tetray::render
