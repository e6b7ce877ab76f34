#include "render/trace/tile_trace.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <memory>
#include <type_traits>

#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/layer_peeling.hpp"
#include "render/trace/leaf_straddles.hpp"
#include "render/trace/level_of_detail.hpp"
#include "render/trace/nearest_layers.hpp"
#include "render/trace/packet_traversal.hpp"
#include "render/trace/proxy_intersect.hpp"
#include "render/trace/tet_straddle.hpp"
#include "render/trace/tile_polygons.hpp"

namespace tetray::render {
namespace {

constexpr int kPackets = kTileSize / kTilePacket;  // packets a side of a tile
constexpr int W = simd::kWidth;

constexpr int kTilePackets = kPackets * kPackets;
static_assert(kTilePackets <= TileOcclusion::kMaxPackets);

// Polygons binned since the packets last tested their bins, past which they test them again
// (occlusion culling, tile_occlusion.hpp). Lower finds the front surface's bound sooner but
// tests more often a packet that still has rays without hits.
constexpr std::uint64_t kPolygonsPerTest = 256;

// What a thread keeps from tile to tile: the bins, grown to the largest tile's, and the tile's
// packets, which keep their hits from one test of their bins to the next.
struct TileScratch {
  TilePolygons polygons;
  std::uint32_t pending[W];  // straddling tets not yet set up
  int pending_count = 0;
  std::uint64_t polygons_tested = 0;  // of polygons_added(), those the packets have tested
  std::unique_ptr<RayPacket<kTilePacket>[]> packets =
      std::make_unique<RayPacket<kTilePacket>[]>(kTilePackets);
  bool set_up[kTilePackets] = {};  // packet k's rays are set up (its bin has had a polygon)
};

// Sets up the polygons of `count` tets of every isovalue.
template <bool kStats>
void set_up_tets(const Frame& f, const Tile& tile, const std::uint32_t* tets, int count,
                 TilePolygons& polygons, TraceStats& stats) {
  const TetBatch batch = gather_tets(f.volume, tets, count);
  const simd::Mask live = batch.valid & !outside_tile(batch, tile);
  if (!xsimd::any(live)) return;
  for (int k = 0; k < f.isos.count; ++k) {
    const int extracted =
        set_up_polygons(f.volume, batch, live, f.isos.values[k], k, tile, polygons);
    if constexpr (kStats) stats.isopolygon_extractions += static_cast<std::uint64_t>(extracted);
  }
}

// Sets up the proxy isopolygons of a node the level of detail stopped at (for_each_proxy, the
// packets' own, each set up on its own).
template <bool kStats>
void set_up_proxy(const Frame& f, const Tile& tile, const BvhNode& node, TilePolygons& polygons,
                  TraceStats& stats) {
  for_each_proxy(f.volume, f.bvh, f.lod, f.isos, node,
                 [&](const Isopolygon& proxy, const PolygonHit& id) {
                   if constexpr (kStats) ++stats.isopolygon_extractions;
                   TilePolygon p;
                   CoveredPixels covered;
                   if (!set_up_polygon(proxy, tile.eye, &tile.frustum, tile.projection,
                                       tile.last_row, tile.last_column, true, p.setup, covered))
                     return;
                   p.id = id;
                   p.first_row = static_cast<std::int16_t>(covered.first_row);
                   p.last_row = static_cast<std::int16_t>(covered.last_row);
                   p.first_column = static_cast<std::int16_t>(covered.first_column);
                   p.last_column = static_cast<std::int16_t>(covered.last_column);
                   polygons.add(p);
                 });
}

// The leaf's tets that straddle an isovalue (Wald et al. 2007, §5.2 V), tested unless another
// tile of the frame has (leaf_straddles.hpp).
template <bool kStats>
std::uint64_t straddling_tets_of(const Frame& f, const BvhNode& leaf, LeafStraddles& straddles,
                                 TraceStats& stats) {
  return straddles.of(static_cast<std::size_t>(&leaf - f.bvh.nodes.data()), [&] {
    if constexpr (kStats) stats.isorange_tests += leaf.count;
    return leaf_straddling_tets(f.volume, leaf.first, leaf.count, f.isos);
  });
}

// Asks for the cache lines of a leaf's tets, which its set-up reads first and waited on: the leaf
// is set up once the traversal hands over the next one (collect_polygons), the lines arriving
// meanwhile.
void prefetch_leaf(const Frame& f, const BvhNode& leaf) {
  if (!leaf.is_leaf()) return;
  constexpr std::size_t kLine = 64;
  const auto* tets = reinterpret_cast<const char*>(f.volume.tets.data() + leaf.first);
  for (std::size_t byte = 0; byte < leaf.count * sizeof(Tet); byte += kLine)
    __builtin_prefetch(tets + byte);
}

// Queues the leaf's straddling tets and sets up each full lane batch of them.
template <bool kStats>
void set_up_leaf(const Frame& f, const Tile& tile, const BvhNode& leaf, LeafStraddles& straddles,
                 TileScratch& scratch, TraceStats& stats) {
  for (std::uint64_t straddling = straddling_tets_of<kStats>(f, leaf, straddles, stats); straddling;
       straddling &= straddling - 1) {
    scratch.pending[scratch.pending_count++] =
        leaf.first + static_cast<std::uint32_t>(std::countr_zero(straddling));
    if (scratch.pending_count < W) continue;
    set_up_tets<kStats>(f, tile, scratch.pending, W, scratch.polygons, stats);
    scratch.pending_count = 0;
  }
}

// Calls visit(k, row, column) for each packet of the tile in the image: k its index, (row,
// column) its top-left pixel in the tile.
template <typename Visit>
void for_each_packet(const Tile& tile, Visit&& visit) {
  for (int row = 0; row <= tile.last_row; row += kTilePacket)
    for (int column = 0; column <= tile.last_column; column += kTilePacket)
      visit(row / kTilePacket * kPackets + column / kTilePacket, row, column);
}

// Packet k's rays, set up the first time its bin has polygons; from then on the tile's occlusion
// culling reads their bounds.
RayPacket<kTilePacket>& packet_rays(const Frame& f, Tile& tile, TileScratch& scratch, int k,
                                    int row, int column) {
  constexpr int S = kTilePacket;
  RayPacket<S>& packet = scratch.packets[static_cast<std::size_t>(k)];
  if (!scratch.set_up[k]) {
    const int x = tile.x0 + column, y = tile.y0 + row;
    setup_packet<S, false>(packet, f.camera, f.view, f.directions, f.volume.origin,
                           tile_frustum<S>(f.camera, f.view, f.extent.magnitude, x, y),
                           f.extent.magnitude, x, y);
    scratch.set_up[k] = true;
    tile.occlusion.watch(k, packet.batch_far);
  }
  return packet;
}

// The pixels of polygon p that the packet at (row, column) of the tile holds, in the packet's rows
// and columns.
CoveredPixels packet_cover(const TilePolygon& p, int row, int column) {
  constexpr int S = kTilePacket;
  return {std::max<int>(p.first_row - row, 0), std::min<int>(p.last_row - row, S - 1),
          std::max<int>(p.first_column - column, 0), std::min<int>(p.last_column - column, S - 1)};
}

// Tests the packet's rays against its bin (the polygons of the packet at row, column of its
// tile), with a hit filter: the clip region's, or a layer's.
template <bool kStats, typename HitFilter>
void test_bin(const std::vector<TilePolygon>& bin, RayPacket<kTilePacket>& packet, int row,
              int column, HitFilter hit_filter, TraceStats& stats) {
  constexpr int S = kTilePacket;
  IsopolygonIntersector<S, kStats, HitFilter> intersector(packet, stats, hit_filter);
  for (const TilePolygon& p : bin)
    intersector.intersect_rays(p.setup, p.id, 0, packet_cover(p, row, column));
}

// The packets test the polygons binned since their last test, and those whose every ray now
// has a hit bound what the rest of the traversal can add (tile_occlusion.hpp).
template <bool kStats, bool kClip>
void test_bins(const Frame& f, Tile& tile, TileScratch& scratch, TraceStats& stats) {
  for_each_packet(tile, [&](int k, int row, int column) {
    const std::vector<TilePolygon>& bin =
        scratch.polygons.bin(column / kTilePacket, row / kTilePacket);
    if (bin.empty()) return;
    RayPacket<kTilePacket>& packet = packet_rays(f, tile, scratch, k, row, column);
    test_bin<kStats>(bin, packet, row, column, ClipHits<kClip>(f.clip), stats);
    tile.occlusion.note(k, RayPacket<kTilePacket>::kBatches);
  });
  scratch.polygons.empty_bins();
  scratch.polygons_tested = scratch.polygons.polygons_added();
}

// The tile's traversal, with the scene's clip region and level of detail: a leaf gives its tets'
// polygons, a node the level of detail stopped at (or a leaf narrow enough) its proxies. Every
// kPolygonsPerTest polygons the packets test their bins, and what their hits hide is skipped
// from then on; a frame of transparent layers keeps every polygon in its bins for the layers.
// A node is set up once the traversal has handed over the next one, its lines asked for when it
// came (prefetch_leaf): the tiled frame at 4M tets 5% faster in alternating runs. (Asking also
// for the vertices, one leaf further ahead, gained nothing more, and for the leaf's straddle
// record lost 5%.) The occlusion culling then knows one node's polygons less, which changes no
// pixel.
template <bool kStats, bool kClip, bool kLod>
void collect_polygons(const Frame& f, Tile& tile, LeafStraddles& straddles, TileScratch& scratch,
                      TraceStats& stats) {
  const auto lod = lod_policy<kLod>(f);
  PacketTraversal<Tile, kStats, ClipNodes<kClip>, decltype(lod)> traversal(
      f.bvh, f.isos, tile, stats, ClipNodes<kClip>(f.clip), lod);
  scratch.pending_count = 0;
  auto set_up = [&](const BvhNode& node) {
    if (gives_proxy(f, lod, node, tile.eye)) {
      set_up_proxy<kStats>(f, tile, node, scratch.polygons, stats);
    } else {
      set_up_leaf<kStats>(f, tile, node, straddles, scratch, stats);
    }
    if (!f.layers &&
        scratch.polygons.polygons_added() - scratch.polygons_tested >= kPolygonsPerTest)
      test_bins<kStats, kClip>(f, tile, scratch, stats);
  };
  const BvhNode* waiting = nullptr;
  traversal.run([&](const BvhNode& node, int) {
    prefetch_leaf(f, node);
    if (waiting) set_up(*waiting);
    waiting = &node;
  });
  if (waiting) set_up(*waiting);
  if (scratch.pending_count > 0)
    set_up_tets<kStats>(f, tile, scratch.pending, scratch.pending_count, scratch.polygons, stats);
}

// A frame of transparent layers: the packet tests its bin once, keeping each ray's nearest
// layers (nearest_layers.hpp), and writes them.
template <bool kStats, bool kClip>
void write_bin_layers(const Frame& f, const std::vector<TilePolygon>& bin,
                      RayPacket<kTilePacket>& packet, int row, int column, int x, int y,
                      TraceStats& stats) {
  constexpr int S = kTilePacket;
  // Per thread, about 460 KB at 16 layers: made once, on the first frame of layers.
  thread_local std::unique_ptr<NearestLayers<S>> nearest = std::make_unique<NearestLayers<S>>();
  nearest->reset(f.layers->max_layers);
  IsopolygonIntersector<S, kStats, ClipHits<kClip>> intersector(packet, stats,
                                                                ClipHits<kClip>(f.clip));
  for (const TilePolygon& p : bin) {
    intersector.for_each_hit_batch(p.setup, p.id, packet_cover(p, row, column),
                                   [&](int base, auto ahead, auto t) {
                                     nearest->insert(base, ahead, t, p.id, p.setup.normal);
                                   });
  }
  write_nearest_layers<S, kStats>(f, packet, *nearest, x, y, stats);
}

// Each packet tests what is left in its bin and writes its pixels, or, in a frame of transparent
// layers, its nearest layers; a packet that never had a polygon writes the background.
template <bool kStats, bool kClip>
void finish_packets(const Frame& f, Tile& tile, TileScratch& scratch, Framebuffer& image,
                    TraceStats& stats) {
  constexpr int S = kTilePacket;
  for_each_packet(tile, [&](int k, int row, int column) {
    const std::vector<TilePolygon>& bin = scratch.polygons.bin(column / S, row / S);
    const int x = tile.x0 + column, y = tile.y0 + row;
    if (!scratch.set_up[k] && bin.empty()) {
      if (!f.layers) write_background<S, kStats>(f, x, y, image, stats);
      return;  // with layers, the slots' counts are zero
    }
    RayPacket<S>& packet = packet_rays(f, tile, scratch, k, row, column);
    if (f.layers) return write_bin_layers<kStats, kClip>(f, bin, packet, row, column, x, y, stats);
    test_bin<kStats>(bin, packet, row, column, ClipHits<kClip>(f.clip), stats);
    write_pixels<S, kStats>(f, packet, x, y, image, stats);
  });
}

template <bool kStats, bool kClip, bool kLod>
void trace_tile(const Frame& f, int x0, int y0, Framebuffer& image, LeafStraddles& straddles,
                TileScratch& scratch, TraceStats& stats) {
  Tile tile = make_tile(f.camera, f.view, f.volume.origin, f.extent.magnitude, x0, y0, kTileSize);
  scratch.polygons.reset(kPackets, kPackets, kTilePacket);
  scratch.polygons_tested = 0;
  std::fill(std::begin(scratch.set_up), std::end(scratch.set_up), false);
  const std::uint64_t extracted_before = stats.isopolygon_extractions;
  if (!f.bvh.empty() && !f.extent.empty() && !tile.frustum.misses_box(f.extent.lo, f.extent.hi)) {
    tile.occlusion.reset<kTilePacket>(tile.projection.depth_slack, kPackets);
    collect_polygons<kStats, kClip, kLod>(f, tile, straddles, scratch, stats);
  }
  if constexpr (kStats)  // polygons beside the tile's pixels
    stats.frustum_culled_isopolygons +=
        stats.isopolygon_extractions - extracted_before - scratch.polygons.polygons_added();
  finish_packets<kStats, kClip>(f, tile, scratch, image, stats);
}

template <bool kStats, bool kClip, bool kLod>
void trace_tiles_with(const Frame& f, Framebuffer& image, TraceStats* total) {
  const int across = (f.camera.width + kTileSize - 1) / kTileSize;
  const int tiles = across * ((f.camera.height + kTileSize - 1) / kTileSize);
  tbb::enumerable_thread_specific<TraceStats> stats;
  LeafStraddles straddles(f.bvh.nodes.size());
  tbb::parallel_for(
      0, tiles,
      [&](int t) {
        // Storage only, per worker thread: every tile starts from emptied bins, so nothing of
        // one tile or frame reaches the next, but a time loop's frames find the bins grown (a
        // scratch made per frame re-grew them and gave their pages back: slower in alternating
        // runs at 1M tets). It holds the largest tile's polygons a thread has seen.
        thread_local TileScratch scratch;
        trace_tile<kStats, kClip, kLod>(f, t % across * kTileSize, t / across * kTileSize, image,
                                        straddles, scratch, stats.local());
      },
      tbb::simple_partitioner());
  if (total) {
    for (const TraceStats& s : stats) *total += s;
  }
}

}  // namespace

void trace_tiles(const Frame& f, Framebuffer& image, bool clipped, bool collect,
                 TraceStats* stats) {
  const auto with = [&](auto clip, auto lod) {
    constexpr bool kClip = decltype(clip)::value, kLod = decltype(lod)::value;
    collect ? trace_tiles_with<true, kClip, kLod>(f, image, stats)
            : trace_tiles_with<false, kClip, kLod>(f, image, nullptr);
  };
  using Yes = std::true_type;
  using No = std::false_type;
  if (clipped) {
    f.lod.enabled() ? with(Yes{}, Yes{}) : with(Yes{}, No{});
  } else {
    f.lod.enabled() ? with(No{}, Yes{}) : with(No{}, No{});
  }
}

}  // namespace tetray::render
