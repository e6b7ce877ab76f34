// Tiled tracing (the header of render/trace/tile_trace.hpp): a tile of the image is one frustum
// that traverses the BVH once; the isopolygons of the straddling tets it reaches are set up a lane
// batch at a time, one tet per lane (Wald et al. 2007, §4.1-4.3: extraction, edge planes, the
// rows and columns the polygon projects to), and binned by the packets of the tile they cover.
// Each lane runs the very operations of the one-polygon forms (isopolygon.hpp,
// isopolygon_intersect.hpp), so every value, and the image, is bitwise the same as the packet
// traversal's.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/simd.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/packet_frustum.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/tile_occlusion.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// A tile of the image as the traversal and the set-up see it: a frustum without rays.
struct Tile {
  static constexpr int kRays = 0;  // the traversal tests its frustum only (packet_traversal.hpp)

  Vec3f eye;                 // local
  PacketFrustum frustum;     // of the tile's pixels in the image
  RowProjection projection;  // onto the tile's pixels: its top-left pixel is row 0, column 0
  int x0 = 0, y0 = 0;        // its top-left pixel in the image
  int last_row = 0, last_column = 0;  // of the tile's part in the image
  Vec3f center_direction;             // through the tile's center: front-to-back order
  TileOcclusion occlusion;            // what its packets' hits so far hide

  // No ray of the tile can meet the box, or none can find a nearer hit in it.
  bool misses(const Bounds4& b) const {
    const Vec3f lo{b.lo[0] - eye.x, b.lo[1] - eye.y, b.lo[2] - eye.z};
    const Vec3f hi{b.hi[0] - eye.x, b.hi[1] - eye.y, b.hi[2] - eye.z};
    return frustum.misses_box(lo, hi) || occlusion.hides(lo, hi, projection, last_row, last_column);
  }
};

// The tile whose top-left pixel is (x0, y0), `size` pixels a side; `magnitude` as for
// make_packet_frustum.
Tile make_tile(const Camera& camera, const CameraFrame& frame, Vec3d origin, float magnitude,
               int x0, int y0, int size);

// A polygon set up for the tile's eye, with the pixels of the tile it covers.
struct TilePolygon {
  PolygonSetup setup;
  PolygonHit id;
  std::int16_t first_row, last_row, first_column, last_column;
};

// The set-up polygons of a tile, binned by the packets (packet_size pixels a side) whose pixels
// they cover, in the order they were set up; the bins' storage is kept from tile to tile.
class TilePolygons {
 public:
  // Fields of a lane batch of polygons. Floats: corner k's component c relative to the eye at
  // kRel + 4 c + k, edge k's plane normal likewise at kEdge, the polygon's normal, plane,
  // distance floor, and the bounds of an ill-conditioned distance.
  static constexpr int kRel = 0, kEdge = 12, kNormal = 24, kPlane = 27, kNearFloor = 28,
                       kClosest = 29, kFarCeiling = 30, kFloats = 31;
  // Integers: the tile rows and columns covered, tie key, tet, isovalue index.
  static constexpr int kFirstRow = 0, kLastRow = 1, kFirstColumn = 2, kLastColumn = 3, kKey = 4,
                       kTet = 5, kIso = 6, kInts = 7;

  // Empties the bins, for a tile of packets_across x packets_down packets of packet_size (a power
  // of two: the bins are found by shifts, not by divisions, which cost more than the binning).
  void reset(int packets_across, int packets_down, int packet_size);
  // Adds the polygons of the lanes of `valid` to the bins of the packets they cover.
  void add(const simd::Floats (&floats)[kFloats], const simd::Ints (&ints)[kInts],
           simd::Mask valid);
  // Adds one polygon so (a level-of-detail proxy's, set up on its own).
  void add(const TilePolygon& polygon);
  // Empties the bins, their polygons tested, keeping the count of polygons added to the tile.
  void empty_bins();

  const std::vector<TilePolygon>& bin(int packet_x, int packet_y) const {
    return bins_[static_cast<std::size_t>(packet_y * across_ + packet_x)];
  }
  std::uint64_t polygons_added() const { return added_; }

 private:
  std::size_t bin_of(int row, int column) const {
    return static_cast<std::size_t>((row >> packet_shift_) * across_ + (column >> packet_shift_));
  }
  // Whether pixels from first to last row and column lie in more than one bin.
  bool spans_bins(int first_row, int last_row, int first_column, int last_column) const {
    return ((first_row ^ last_row) | (first_column ^ last_column)) >> packet_shift_ != 0;
  }
  // Adds p, which lies in the bin of its first row and column, to the other bins it covers.
  void copy_to_other_bins(const TilePolygon& p);

  std::vector<std::vector<TilePolygon>> bins_;
  int across_ = 0, packet_shift_ = 0;  // log2 of the packet size
  std::uint64_t added_ = 0;
};

// The corners of a lane batch of tets: component c (x, y, z, f) of corner k in corner[c][k],
// tet `index` lane by lane; lanes past the count repeat the first tet and are not `valid`.
struct TetBatch {
  simd::Floats corner[4][4];
  simd::Ints index;
  simd::Mask valid;
};

// The tets tets[0, count), 1 <= count <= simd::kWidth.
TetBatch gather_tets(const TetVolume& volume, const std::uint32_t* tets, int count);

// The lanes whose tet's hull lies outside a plane of the tile's frustum (misses_hull, lanewise).
simd::Mask outside_tile(const TetBatch& batch, const Tile& tile);

// Sets up the polygons of isovalue `iso` (index iso_index of the frame's sorted isovalues) of
// the `live` lanes' tets and adds to `out` those that set_up_polygon would keep for the tile:
// hull within its frustum, a pixel center of it covered, an area. Returns how many of the
// lanes' tets hold a polygon.
int set_up_polygons(const TetVolume& volume, const TetBatch& batch, simd::Mask live, float iso,
                    int iso_index, const Tile& tile, TilePolygons& out);

}  // namespace tetray::render
