// Occlusion culling for a tile's traversal (the header of render/trace/tile_trace.hpp). A tile
// traverses front to back, and its packets test the polygons binned so far from time to time
// (tile_trace.cpp). Once every ray of a block of pixels (a packet's lane batch) has a hit, the
// block's farthest hit (RayPacket::batch_far) bounds what any later polygon can win there. A node
// whose box lies farther from the eye than that bound in every block its projection covers
// cannot change a pixel of the tile, so the traversal skips it. This is the packets' own
// occlusion culling (Wald et al. 2007, §5.2: a node beyond the packet's tmax is skipped) for a
// traversal without rays, at the grain of blocks so that a hole or an edge of the surface costs
// only its own blocks; it makes the frame's cost follow the surface in front rather than every
// sheet of it along the rays.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "render/core/vec.hpp"
#include "render/trace/ray_packet.hpp"

namespace tetray::render {

class TileOcclusion {
 public:
  static constexpr int kMaxPackets = 16;

  // A tile of packets of S x S rays, packets_across a row (up to kMaxPackets of them), none set
  // up yet: nothing hidden. `slack` bounds the rounding of a distance from eye-relative floats
  // (the frame's depth_rounding).
  template <int S>
  void reset(float slack, int packets_across) {
    using Packet = RayPacket<S>;
    static_assert(std::has_single_bit(unsigned{S}) &&
                      std::has_single_bit(unsigned{Packet::kBlockRows}) &&
                      std::has_single_bit(unsigned{Packet::kBlockColumns}),
                  "packets and blocks are found by shifts");
    packet_size_ = S;
    packet_shift_ = std::countr_zero(unsigned{S});
    packets_across_ = packets_across;
    row_shift_ = std::countr_zero(unsigned{Packet::kBlockRows});
    column_shift_ = std::countr_zero(unsigned{Packet::kBlockColumns});
    blocks_across_ = S / Packet::kBlockColumns;
    slack_ = slack;
    std::fill(std::begin(block_far_), std::end(block_far_), nullptr);
    nearest_far_ = kUnknown;
  }

  // Packet k (row-major among the tile's packets) has its rays set up; its blocks' bounds are
  // read from `block_far` from now on.
  void watch(int k, const float* block_far) {
    block_far_[k] = block_far;
    packet_far_[k] = kUnknown;
  }

  // Packet k's blocks' bounds (`blocks` of them) have changed (a packet's bounds only fall, as
  // its rays find nearer hits): the nearest of all blocks, for a quick answer about boxes in
  // front of every bound, and the packet's farthest, for one about boxes behind all of it.
  void note(int k, int blocks) {
    float farthest = -kUnknown;
    for (int b = 0; b < blocks; ++b) {
      if (block_far_[k][b] > -kUnknown) nearest_far_ = std::min(nearest_far_, block_far_[k][b]);
      farthest = std::max(farthest, block_far_[k][b]);
    }
    packet_far_[k] = farthest;
  }

  // Whether no ray of the tile can find a nearer hit in the box (relative to the eye): it lies
  // farther than the bound of every block its projection onto the tile (rows and columns as
  // `projection` gives them, up to last_row, last_column) covers.
  bool hides(Vec3f lo, Vec3f hi, const RowProjection& projection, int last_row,
             int last_column) const {
    if (nearest_far_ == kUnknown) return false;
    const float reach = (std::sqrt(distance2(lo, hi)) - slack_) / kGrowth;
    if (!(nearest_far_ < reach)) return false;
    PixelRect r;
    if (!project(lo, hi, projection, last_row, last_column, r)) return false;
    for (int pr = r.first_row >> packet_shift_; pr <= r.last_row >> packet_shift_; ++pr)
      for (int pc = r.first_column >> packet_shift_; pc <= r.last_column >> packet_shift_; ++pc)
        if (!hidden_in_packet(pr, pc, r, reach)) return false;
    return true;
  }

 private:
  static constexpr float kUnknown = std::numeric_limits<float>::infinity();
  // Far above a distance's rounding and the spread of a hit computed at a grazing angle, which
  // isopolygon_intersect.hpp clamps between bounds of the polygon's points' distances.
  static constexpr float kGrowth = 1.0f + 0x1p-12f;
  // Past this many blocks a box is not worth the look: only the top of the tree covers so many.
  static constexpr int kMaxBlocks = 1024;

  struct PixelRect {
    int first_row, last_row, first_column, last_column;
  };

  // Squared distance from the eye (the origin) to the nearest point of the box.
  static float distance2(Vec3f lo, Vec3f hi) {
    float d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const float d = std::max({lo[a], -hi[a], 0.0f});
      d2 += d * d;
    }
    return d2;
  }

  // The interval of dot(n, p) over the box.
  static void dot_range(Vec3f n, Vec3f lo, Vec3f hi, float& low, float& high) {
    low = high = 0;
    for (int a = 0; a < 3; ++a) {
      low += std::min(n[a] * lo[a], n[a] * hi[a]);
      high += std::max(n[a] * lo[a], n[a] * hi[a]);
    }
  }

  // The tile's pixels whose centers may see the box, by interval arithmetic on the projection,
  // widened by a pixel against rounding; false when the box reaches the eye's plane or covers
  // more than kMaxBlocks.
  bool project(Vec3f lo, Vec3f hi, const RowProjection& p, int last_row, int last_column,
               PixelRect& r) const {
    float d_lo, d_hi, u_lo, u_hi, s_lo, s_hi;
    dot_range(p.forward, lo, hi, d_lo, d_hi);
    if (!(d_lo > p.depth_slack)) return false;
    dot_range(p.up, lo, hi, u_lo, u_hi);
    dot_range(p.right, lo, hi, s_lo, s_hi);
    const float up_lo = u_lo >= 0 ? u_lo / d_hi : u_lo / d_lo;
    const float up_hi = u_hi >= 0 ? u_hi / d_lo : u_hi / d_hi;
    const float right_lo = s_lo >= 0 ? s_lo / d_hi : s_lo / d_lo;
    const float right_hi = s_hi >= 0 ? s_hi / d_lo : s_hi / d_hi;
    r.first_row = std::max(0, static_cast<int>(std::floor(p.row_center - p.row_scale * up_hi)) - 1);
    r.last_row =
        std::min(last_row, static_cast<int>(std::ceil(p.row_center - p.row_scale * up_lo)) + 1);
    r.first_column =
        std::max(0, static_cast<int>(std::floor(p.column_center + p.column_scale * right_lo)) - 1);
    r.last_column = std::min(
        last_column, static_cast<int>(std::ceil(p.column_center + p.column_scale * right_hi)) + 1);
    if (r.first_row > r.last_row || r.first_column > r.last_column) return false;
    const int blocks = ((r.last_row >> row_shift_) - (r.first_row >> row_shift_) + 1) *
                       ((r.last_column >> column_shift_) - (r.first_column >> column_shift_) + 1);
    return blocks <= kMaxBlocks;
  }

  // Whether every block of packet (pr, pc) within r has a bound nearer than `reach`.
  bool hidden_in_packet(int pr, int pc, const PixelRect& r, float reach) const {
    const int k = pr * packets_across_ + pc;
    const float* far = block_far_[k];
    if (!far) return false;                   // not set up: its rays have no hits yet
    if (packet_far_[k] < reach) return true;  // behind every block of the packet
    const int row0 = pr * packet_size_, column0 = pc * packet_size_;
    const int first_row = std::max(r.first_row - row0, 0) >> row_shift_;
    const int last_row = std::min(r.last_row - row0, packet_size_ - 1) >> row_shift_;
    const int first_column = std::max(r.first_column - column0, 0) >> column_shift_;
    const int last_column = std::min(r.last_column - column0, packet_size_ - 1) >> column_shift_;
    for (int br = first_row; br <= last_row; ++br)
      for (int bc = first_column; bc <= last_column; ++bc)
        if (!(far[br * blocks_across_ + bc] < reach)) return false;
    return true;
  }

  const float* block_far_[kMaxPackets] = {};  // per packet, null until set up
  float packet_far_[kMaxPackets] = {};        // per packet, its blocks' farthest bound at note()
  // Rows and columns are never negative here: shifts, not divisions (a fifth of the node test).
  int packet_size_ = 1, packet_shift_ = 0, packets_across_ = 1;
  int row_shift_ = 0, column_shift_ = 0, blocks_across_ = 1;
  float slack_ = 0;
  float nearest_far_ = kUnknown;  // the nearest finite bound of any block
};

}  // namespace tetray::render
