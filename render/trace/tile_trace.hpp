// The tiled frame (PacketSize::tiled, the default): the image is
// cut into tiles traced in parallel. A tile traverses the BVH once as a frustum (the one
// traversal, packet_traversal.hpp), sets up the isopolygons of the straddling tets it reaches a
// lane batch at a time and bins them by its packets (tile_polygons.hpp); the packets test their
// rays against their bins with the packet intersector from time to time, so that the traversal
// skips what their hits hide (tile_occlusion.hpp), and finally write their pixels as trace_into
// does. The per-ray box tests and the per-packet traversal of the top of the tree are gone, and
// a polygon is extracted and set up once per tile instead of once per packet.
//
// A packet's traversal repeats for each packet the walk down the top of the tree, tests each node
// against its rays one by one, and extracts and sets up each isopolygon anew for every packet that
// reaches its tet; at 1M tets that was most of the exact frame. A tile of 128 x 128 pixels instead
// walks the same traversal once as a frustum without rays (Tile, whose geometric test is its four
// planes and whose children go front to back along its center ray). Its leaf operation takes the
// leaf's straddling tets and queues them. The per-tet straddle test runs about once per leaf and
// frame (tiles reaching a leaf at the same moment may each run it, with the same result, and a leaf
// of 64 tets that all straddle is tested on every visit): the first tile to reach a leaf keeps its
// tets' straddle bits (one word per node, a leaf holds at most kMaxLeafSize = 64 tets) in the
// frame's LeafStraddles (render/trace/leaf_straddles.hpp) and the tiles that reach it later read
// them; a leaf near a tile's edge is reached by two tiles or more (1.7 tiles per leaf reached at 1M
// tets). The record is the storage of the thread that starts the frame, kept from frame to frame
// (its pages are not faulted in again each frame); a frame started inside another's tasks gets its
// own. Each full lane batch of straddling tets is gathered (its corners' vertices loaded whole,
// four to a register, and moved into lanes by unpacks, simd::gather_rows: a quarter of the loads of
// a gather per component) and set up one tet per lane (tile_polygons.cpp): the frustum test of the
// tet, the case, the polygon's corners, its plane and edge planes, its distance floor and the tile
// pixels its projection covers, each with the same operations as the one-polygon forms
// (isopolygon.hpp, isopolygon_intersect.hpp, which are templated on the batch type where they share
// code), so every value is bitwise the same and so is the image, for any tile or packet layout. The
// polygons go, set up, into one bin per 32 x 32 packet of the tile they cover (the bins are a
// worker thread's storage, thread_local and emptied for every tile, so nothing but their capacity
// outlives a tile); each packet then tests only its bin with the packet intersector's lane tests
// and writes its pixels as trace_into does. Clipping runs through the same node and hit filters,
// and level of detail through the same policy (a node it stops at gives its proxy polygons, set up
// one by one with set_up_polygon, the packets' own set-up). Transparent layers need no second
// traversal: a packet's bin holds every polygon any of its rays can hit, so each layer tests the
// bin again with the after-layer hit filter (peel_layers, render/trace/layer_peeling.hpp, is the
// one loop of layers for packets and tiles, given how to trace again).
//
// A packet's rays are stored block by block (RayPacket::index): a lane batch is a block of pixels
// (4 x 4 with 16 lanes), so the intersector tests a polygon against the blocks its covered pixels
// reach, fewer batches for a small polygon than rows of 16 pixels would take. Occlusion culling
// comes with the intersector in every path, per lane batch of rays: the packet keeps for each batch
// a bound of its rays' nearest hits (infinite while a ray has none), and a polygon whose distance
// floor lies beyond it skips the batch. The floor is the polygon's smallest corner depth less 2^-16
// of it and the frame's depth rounding; every distance the intersector computes is raised to at
// least the floor (a ray's distance to a point is at least the point's depth, so this changes
// nothing for a well-conditioned ray and keeps a grazing ray's ill-conditioned one at the polygon's
// depth), so the culling is exact: no skipped test could have won. A grazing ray's ill-conditioned
// distance is clamped between two bounds of the distances of the polygon's points from the eye, set
// up once per polygon: its farthest corner's distance plus 2^-16 of it and the depth rounding (the
// hit is a convex combination of the corners), and, for a polygon wholly in front of the eye,
// sqrt(m^2 - 3/8 D^2) less the same margin, m its nearest corner's distance and D its diameter (for
// a convex combination h, |h|^2 = sum w_k |c_k|^2 - 1/2 sum w_j w_k |c_j - c_k|^2), else the floor.
// For a polygon small beside its distance the lower bound lies within a few ulps of its nearest
// point's distance (second order in D / m), so a clamped distance never falls in front of the box
// the tiles' occlusion culling tested; clamping instead to the corners' extent along each ray took
// four dot products per ray tested (the tiled frame at 4M tets about 3% slower).
//
// A tile also culls nodes by occlusion (render/trace/tile_occlusion.hpp), as a packet's traversal
// skips a node beyond its rays' farthest hit: the tile's packets keep their rays and hits for the
// whole tile, and every 256 polygons binned they test their bins (then emptied), so their batches'
// bounds grow tight while the traversal goes on front to back. A node is then skipped when its box
// lies farther from the eye (the nearest point of the box, less 2^-12 of the distance and the
// frame's depth rounding) than the bound of every block of pixels its projection may cover
// (interval arithmetic on the tile's projection, widened by a pixel); a block with a ray still
// without a hit, or a packet not yet set up, keeps every box over it. Bounding by blocks rather
// than packets matters: half the benchmark's pixels are background, and a packet with one such
// pixel would bound nothing. The polygons extracted per frame drop by a third at 1M tets and by two
// fifths at 14M (the sheets behind the front), with the same image. Transparent layers need every
// polygon in the bins, so their frames do not cull.
#pragma once

#include "render/trace/frame_pixels.hpp"

namespace tetray::render {

inline constexpr int kTileSize = 128;   // pixels a side of a tile
inline constexpr int kTilePacket = 32;  // pixels a side of its packets

// Traces every pixel of `image` in tiles, in parallel in the calling oneTBB arena; `stats` (when
// `collect`) receives the frame's counters.
void trace_tiles(const Frame& f, Framebuffer& image, bool clipped, bool collect, TraceStats* stats);

}  // namespace tetray::render
