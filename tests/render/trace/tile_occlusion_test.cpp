// Occlusion culling of the tiles (render/trace/tile_occlusion.hpp): a box is hidden exactly when
// every block of pixels it may cover has all its hits nearer than the box, and a tiled frame of
// sheets one behind the other extracts the front sheet's polygons and few of the others', with
// the image bitwise that of packets, which cull by their rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "render/trace/tile_occlusion.hpp"
#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr int S = 32;  // packet side
using Packet = render::RayPacket<S>;
constexpr float kInf = std::numeric_limits<float>::infinity();

// A camera at the origin looking down -z, 64 x 64 pixels: one tile of 2 x 2 packets.
struct OneTile {
  render::Camera camera = look_at({0, 0, 0}, {0, 0, -1}, 60.0, 2 * S, 2 * S);
  render::CameraFrame frame = render::make_frame(camera);
  render::RowProjection projection = render::row_projection(camera, frame, 0, 0, 100.0f);
  std::vector<float> block_far = std::vector<float>(4 * Packet::kBatches, kInf);
  render::TileOcclusion occlusion;

  OneTile() {
    occlusion.reset<S>(projection.depth_slack, 2);
    for (int k = 0; k < 4; ++k) occlusion.watch(k, block_far.data() + k * Packet::kBatches);
  }
  // Every block has all its hits, the farthest at `far`.
  void bound_all(float far) {
    std::fill(block_far.begin(), block_far.end(), far);
    for (int k = 0; k < 4; ++k) occlusion.note(k, Packet::kBatches);
  }
  // A box of half side h around the point at distance d along the view axis.
  bool hides(float d, float h = 0.05f, float x = 0, float y = 0) const {
    return occlusion.hides({x - h, y - h, -d - h}, {x + h, y + h, -d + h}, projection, 2 * S - 1,
                           2 * S - 1);
  }
};

TEST(TileOcclusion, HidesNothingBeforeEveryRayOfABlockHasAHit) {
  OneTile tile;
  EXPECT_FALSE(tile.hides(10));
  for (int k = 0; k < 4; ++k) tile.occlusion.note(k, Packet::kBatches);  // all still unknown
  EXPECT_FALSE(tile.hides(10));
}

TEST(TileOcclusion, HidesABoxBehindTheBoundOfEveryBlockItCovers) {
  OneTile tile;
  tile.bound_all(5.0f);
  EXPECT_TRUE(tile.hides(10));
  EXPECT_TRUE(tile.hides(5.2f));
  EXPECT_FALSE(tile.hides(4.0f));   // in front of the hits
  EXPECT_FALSE(tile.hides(5.04f));  // its near face at 4.99
}

TEST(TileOcclusion, ABlockWithoutAHitKeepsTheBoxesOverItVisible) {
  OneTile tile;
  tile.bound_all(5.0f);
  // The pixel at the tile's centre and the blocks around it: packet 3 (bottom right), block 0.
  tile.block_far[3 * Packet::kBatches] = kInf;
  tile.occlusion.note(3, Packet::kBatches);
  EXPECT_FALSE(tile.hides(10));            // covers the centre
  EXPECT_TRUE(tile.hides(10, 0.05f, -2));  // off to the left, over other blocks only
  // A block of packet 0 far nearer than the rest does not hide what lies in front of the others.
  tile.block_far[0] = 1.0f;
  tile.occlusion.note(0, Packet::kBatches);
  EXPECT_FALSE(tile.hides(4.0f, 0.05f, -2));
}

TEST(TileOcclusion, ABoxReachingTheEyesPlaneIsNeverHidden) {
  OneTile tile;
  tile.bound_all(0.5f);
  EXPECT_FALSE(
      tile.occlusion.hides({-3, -3, -3}, {3, 3, 0.5f}, tile.projection, 2 * S - 1, 2 * S - 1));
}

// Sheets of f = z at several depths seen head on: the front one covers the whole image.
struct Sheets {
  RenderScene scene;
  render::Camera camera = look_at({0, 0, 6}, {0, 0, 0}, 20.0, 128, 128);

  Sheets() {
    BoxMeshSpec spec;
    spec.cells = {12, 12, 24};
    const BoxMesh mesh = make_box_mesh(spec);
    scene =
        load_scene(mesh.points, mesh.tets, sample_field(mesh.points, [](Vec3d p) { return p.z; }));
  }
  render::TraceStats stats(const std::vector<double>& isovalues, render::Framebuffer& image) const {
    render::TraceOptions options;
    options.packet = render::PacketSize::tiled;
    options.collect_stats = true;
    render::TraceStats s;
    image = render::trace(scene.volume, scene.bvh, camera, make_surfaces(isovalues), options, &s);
    return s;
  }
};

TEST(TileOcclusion, TheTilesSkipTheSheetsBehindTheFront) {
  const Sheets sheets;
  render::Framebuffer front_only, all;
  const std::uint64_t front = sheets.stats({0.8}, front_only).isopolygon_extractions;
  const std::uint64_t four = sheets.stats({0.8, 0.3, -0.2, -0.7}, all).isopolygon_extractions;
  ASSERT_GT(front, 0u);
  // Without the culling every sheet's polygons would be extracted: four times the front's. With
  // it, only those of the nodes reached before the front's blocks all had hits.
  EXPECT_LT(four, 2 * front) << "front sheet " << front << ", four sheets " << four;
  const std::vector<double> isovalues{0.8, 0.3, -0.2, -0.7};
  EXPECT_EQ(image_difference(all, trace_image(sheets.scene, sheets.camera, make_surfaces(isovalues),
                                              render::PacketSize::p16x16)),
            "");
  EXPECT_LT(std::count(all.hit.begin(), all.hit.end(), render::kNoHit), 1);
}

}  // namespace
}  // namespace tetray::test
