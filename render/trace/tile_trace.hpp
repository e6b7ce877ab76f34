// The tiled frame (PacketSize::tiled, the default; docs/architecture.md §7, "Tiles"): the image is
// cut into tiles traced in parallel. A tile traverses the BVH once as a frustum (the one
// traversal, packet_traversal.hpp), sets up the isopolygons of the straddling tets it reaches a
// lane batch at a time and bins them by its packets (tile_polygons.hpp); the packets test their
// rays against their bins with the packet intersector from time to time, so that the traversal
// skips what their hits hide (tile_occlusion.hpp), and finally write their pixels as trace_into
// does. The per-ray box tests and the per-packet traversal of the top of the tree are gone, and
// a polygon is extracted and set up once per tile instead of once per packet.
#pragma once

#include "render/trace/frame_pixels.hpp"

namespace tetray::render {

inline constexpr int kTileSize = 128;   // pixels a side of a tile
inline constexpr int kTilePacket = 32;  // pixels a side of its packets

// Traces every pixel of `image` in tiles, in parallel in the calling oneTBB arena; `stats` (when
// `collect`) receives the frame's counters.
void trace_tiles(const Frame& f, Framebuffer& image, bool clipped, bool collect, TraceStats* stats);

}  // namespace tetray::render
