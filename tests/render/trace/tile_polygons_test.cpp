// The lanewise isopolygon set-up of tiles (render/trace/tile_polygons.hpp) against the one-polygon
// forms it mirrors (extract_isopolygon, set_up_polygon): for every tet
// and isovalue of random and grid-valued fields, seen by cameras outside and inside the mesh,
// the tile keeps exactly the polygons that cover one of its pixels, with bitwise the same
// set-up, and bins each in the packets whose pixels it covers.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "render/trace/tile_polygons.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

using render::Tile;
using render::TilePolygon;
using render::TilePolygons;

constexpr int kTile = 32, kPacket = 8;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_setup(const render::PolygonSetup& a, const render::PolygonSetup& b) {
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 4; ++k)
      if (!same_bits(a.edge[c][k], b.edge[c][k])) return false;
  for (int c = 0; c < 3; ++c)
    if (!same_bits(a.normal[c], b.normal[c])) return false;
  return same_bits(a.plane, b.plane) && same_bits(a.near_floor, b.near_floor) &&
         same_bits(a.closest, b.closest) && same_bits(a.far_ceiling, b.far_ceiling);
}

// What the one-polygon forms give for tet t and isovalue k, or nothing where the tile keeps no
// polygon.
std::optional<TilePolygon> expected_polygon(const render::TetVolume& volume, std::uint32_t t,
                                            float iso, int k, const Tile& tile) {
  const render::TetCorners corners = render::load_corners(volume, volume.tets[t]);
  const render::simd::Float4 q[3] = {corners.column[0] - tile.eye.x, corners.column[1] - tile.eye.y,
                                     corners.column[2] - tile.eye.z};
  const int case_index = render::iso_case(corners, iso);
  if (case_index == 0 || case_index == 15 || tile.frustum.misses_hull(q)) return std::nullopt;
  const render::Isopolygon poly = render::extract_isopolygon(corners, case_index, iso);
  TilePolygon expected{};
  render::CoveredPixels covered;
  if (!render::set_up_polygon(poly, tile.eye, &tile.frustum, tile.projection, tile.last_row,
                              tile.last_column, true, expected.setup, covered))
    return std::nullopt;
  expected.id = {volume.tet_ids[t], static_cast<std::int32_t>(t), k};
  expected.first_row = static_cast<std::int16_t>(covered.first_row);
  expected.last_row = static_cast<std::int16_t>(covered.last_row);
  expected.first_column = static_cast<std::int16_t>(covered.first_column);
  expected.last_column = static_cast<std::int16_t>(covered.last_column);
  return expected;
}

// Every tet of the volume through the lanewise set-up, in batches of every size up to the lane
// width, into one tile's bins.
TilePolygons set_up_all(const render::TetVolume& volume, std::span<const float> isovalues,
                        const Tile& tile) {
  TilePolygons polygons;
  polygons.reset(kTile / kPacket, kTile / kPacket, kPacket);
  std::vector<std::uint32_t> tets(volume.tets.size());
  std::iota(tets.begin(), tets.end(), 0u);
  int count = 1;
  for (std::size_t first = 0; first < tets.size(); first += static_cast<std::size_t>(count)) {
    count = std::min<int>(count % render::simd::kWidth + 1, static_cast<int>(tets.size() - first));
    const render::TetBatch batch = render::gather_tets(volume, tets.data() + first, count);
    const render::simd::Mask live = batch.valid & !render::outside_tile(batch, tile);
    for (std::size_t k = 0; k < isovalues.size(); ++k)
      render::set_up_polygons(volume, batch, live, isovalues[k], static_cast<int>(k), tile,
                              polygons);
  }
  return polygons;
}

void expect_lanewise_set_up(const RenderScene& scene, std::span<const float> isovalues,
                            const std::string& label) {
  const render::TetVolume& volume = scene.volume;
  const float magnitude = 4.0f;       // the coordinates of the meshes and eyes below stay within it
  const int width = 70, height = 45;  // partial tiles at the right and bottom
  std::size_t polygons_seen = 0;
  for (const render::Camera& camera : standard_cameras(width, height)) {
    const render::CameraFrame frame = render::make_frame(camera);
    for (int y0 = 0; y0 < height; y0 += kTile)
      for (int x0 = 0; x0 < width; x0 += kTile) {
        const std::string where = label + " tile (" + std::to_string(x0) + ", " +
                                  std::to_string(y0) + ") eye " + std::to_string(camera.eye.x) +
                                  "," + std::to_string(camera.eye.z);
        const Tile tile = render::make_tile(camera, frame, volume.origin, magnitude, x0, y0, kTile);
        const TilePolygons polygons = set_up_all(volume, isovalues, tile);
        // Each polygon once, from the bins it lies in.
        std::map<std::pair<std::int32_t, std::int32_t>, TilePolygon> kept;
        std::map<std::pair<std::int32_t, std::int32_t>, int> bins_holding;
        for (int py = 0; py < kTile / kPacket; ++py)
          for (int px = 0; px < kTile / kPacket; ++px)
            for (const TilePolygon& p : polygons.bin(px, py)) {
              kept.emplace(std::make_pair(p.id.tet, p.id.iso), p);
              ++bins_holding[{p.id.tet, p.id.iso}];
              EXPECT_TRUE(p.first_row / kPacket <= py && py <= p.last_row / kPacket &&
                          p.first_column / kPacket <= px && px <= p.last_column / kPacket)
                  << where << ": tet " << p.id.tet << " binned outside its pixels";
            }
        EXPECT_EQ(polygons.polygons_added(), kept.size()) << where;
        std::size_t expected_count = 0;
        for (std::uint32_t t = 0; t < volume.tets.size(); ++t)
          for (std::size_t k = 0; k < isovalues.size(); ++k) {
            const auto expected =
                expected_polygon(volume, t, isovalues[k], static_cast<int>(k), tile);
            const auto found = kept.find({static_cast<std::int32_t>(t), static_cast<int>(k)});
            if (!expected) {
              EXPECT_EQ(found, kept.end()) << where << ": tet " << t << " kept without a polygon";
              continue;
            }
            ++expected_count;
            ASSERT_NE(found, kept.end()) << where << ": tet " << t << " iso " << k << " lost";
            const TilePolygon& p = found->second;
            EXPECT_TRUE(same_setup(p.setup, expected->setup)) << where << ": tet " << t;
            EXPECT_EQ(p.id.key, expected->id.key) << where;
            EXPECT_EQ(std::make_tuple(p.first_row, p.last_row, p.first_column, p.last_column),
                      std::make_tuple(expected->first_row, expected->last_row,
                                      expected->first_column, expected->last_column))
                << where << ": tet " << t;
            const int packets = (p.last_row / kPacket - p.first_row / kPacket + 1) *
                                (p.last_column / kPacket - p.first_column / kPacket + 1);
            EXPECT_EQ(bins_holding[found->first], packets) << where << ": tet " << t;
          }
        EXPECT_EQ(kept.size(), expected_count) << where;
        polygons_seen += kept.size();
      }
  }
  EXPECT_GT(polygons_seen, 100u) << label;
}

TEST(TilePolygons, LanewiseSetUpMatchesOnePolygonOnARandomField) {
  const BoxMesh mesh = jittered_box(4);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, random_field(mesh.point_count(), 5));
  const float isovalues[] = {-0.4f, 0.0f, 0.3f};
  expect_lanewise_set_up(scene, isovalues, "random");
}

// Values on a grid of quarters put the isovalues on vertices: polygons of zero area, corners on
// mesh vertices and cases the sign rule decides.
TEST(TilePolygons, LanewiseSetUpMatchesOnePolygonWithIsovaluesOnVertices) {
  const BoxMesh mesh = jittered_box(4, 0.0);
  const RenderScene scene = load_scene(
      mesh.points, mesh.tets,
      sample_field(mesh.points, [](Vec3d p) { return std::round(4 * (p.x + p.y - p.z)) / 4; }));
  const float isovalues[] = {0.0f, 0.5f};
  expect_lanewise_set_up(scene, isovalues, "grid");
}

// A lane batch's corners are the vertex store's (simd::gather_rows moves whole rows into lanes):
// tets picked out of order, every batch size, lanes past the count repeating the first tet.
TEST(TilePolygons, GatheredCornersAreTheVertexStores) {
  const BoxMesh mesh = jittered_box(3);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, random_field(mesh.point_count(), 9));
  const render::TetVolume& volume = scene.volume;
  constexpr int W = render::simd::kWidth;
  std::vector<std::uint32_t> tets(volume.tets.size());
  std::iota(tets.begin(), tets.end(), 0u);
  std::reverse(tets.begin(), tets.end());
  for (int count = 1; count <= W; ++count)
    for (std::size_t first = 0; first + static_cast<std::size_t>(count) <= tets.size();
         first += 7) {
      const render::TetBatch batch = render::gather_tets(volume, tets.data() + first, count);
      float lanes[W];
      for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k) {
          batch.corner[c][k].store_unaligned(lanes);
          for (int j = 0; j < W; ++j) {
            const std::uint32_t tet = tets[first + static_cast<std::size_t>(j < count ? j : 0)];
            const render::Vertex& v =
                volume.vertices[static_cast<std::size_t>(volume.tets[tet].v[k])];
            const float expected[4] = {v.x, v.y, v.z, v.f};
            ASSERT_EQ(std::bit_cast<std::uint32_t>(lanes[j]),
                      std::bit_cast<std::uint32_t>(expected[c]))
                << "tet " << tet << " corner " << k << " component " << c << " lane " << j;
          }
        }
    }
}

// The bins are found by shifts: a packet size that is not a power of two is refused by name.
TEST(TilePolygons, RefuseAPacketSizeThatIsNotAPowerOfTwo) {
  render::TilePolygons polygons;
  EXPECT_THROW(polygons.reset(4, 4, 24), std::invalid_argument);
  EXPECT_NO_THROW(polygons.reset(4, 4, 32));
}

}  // namespace
}  // namespace tetray::test
