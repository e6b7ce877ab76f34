// Frame driver: splits the image into 32 x 32 blocks traced in parallel, each as packets of
// the chosen size; the leaf operation intersects on-the-fly isopolygons (seed 000 §4.4: no
// cache) of every tet whose own range straddles an isovalue (§5.2 V).
#include "render/trace.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include "render/bounds.hpp"
#include "render/isopolygon_intersect.hpp"
#include "render/packet_traversal.hpp"
#include "render/shade.hpp"

namespace tetray::render {
namespace {

constexpr int kBlock = 32;  // pixels a side of a parallel task, a multiple of every packet size

struct Frame {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  CameraFrame view;
  PixelDirections directions;
  IsoSet isos;
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

// Writes the packet's pixels that lie in the image, row by row: the background, or the shaded
// hit.
template <int S, bool kStats>
void write_pixels(const Frame& f, const RayPacket<S>& packet, int x0, int y0, Framebuffer& image,
                  TraceStats& stats) {
  constexpr int n = RayPacket<S>::kRays;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  alignas(64) float light[n], depth[n];
  light_and_depth(
      f.shade, {packet.dx, packet.dy, packet.dz, packet.nx, packet.ny, packet.nz, packet.tmax, n},
      light, depth);
  const int columns = std::min(S, f.camera.width - x0);
  PixelRow<S> out;
  for (int row = 0; row < S && y0 + row < f.camera.height; ++row) {
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
    const std::size_t p0 = image.index(x0, y0 + row);
    write_row(&image.rgba[4 * p0], out.rgba, 4 * columns);
    write_row(&image.depth[p0], out.depth, columns);
    write_row(&image.hit[p0], out.hit, columns);
  }
  simd::stream_fence();
}

template <int S, bool kStats>
void trace_packet(const Frame& f, int x0, int y0, Framebuffer& image, TraceStats& stats) {
  RayPacket<S> packet;
  setup_packet(packet, f.camera, f.view, f.directions, f.volume.origin, x0, y0);
  PacketTraversal<S, kStats> traversal(f.bvh, f.isos, packet, stats);
  IsopolygonIntersector<S, kStats> intersector(packet, stats);
  traversal.run([&](const BvhNode& leaf, int first_active) {
    bool hit = false;
    for (std::uint32_t t = leaf.first; t < leaf.first + leaf.count; ++t) {
      const Tet& tet = f.volume.tets[t];
      const Vertex* v[4] = {&f.volume.vertices[tet.v[0]], &f.volume.vertices[tet.v[1]],
                            &f.volume.vertices[tet.v[2]], &f.volume.vertices[tet.v[3]]};
      // The value range first: most tets of a leaf hold no isosurface, and need no box.
      const float fmin = std::min(std::min(v[0]->f, v[1]->f), std::min(v[2]->f, v[3]->f));
      const float fmax = std::max(std::max(v[0]->f, v[1]->f), std::max(v[2]->f, v[3]->f));
      if constexpr (kStats) ++stats.isorange_tests;
      if (!f.isos.straddled_by(fmin, fmax)) continue;
      if constexpr (S > 1) {
        Bounds4Builder box;  // from the corners already loaded, not the tet again
        for (const Vertex* corner : v) box.grow(*corner);
        if (traversal.frustum_misses(box.bounds())) continue;
      }
      for (int k = 0; k < f.isos.count && f.isos.values[k] <= fmax; ++k) {
        if (!range_straddles(fmin, fmax, f.isos.values[k])) continue;
        if constexpr (kStats) ++stats.isopolygon_extractions;
        const Isopolygon poly = extract_isopolygon(v, f.isos.values[k]);
        const PolygonHit id{f.volume.tet_ids[t], static_cast<std::int32_t>(t), k};
        hit |= intersector.intersect(poly, id, first_active);
      }
    }
    if (hit) update_tmax_bound(packet);
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
