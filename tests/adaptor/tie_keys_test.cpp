// Tie keys: the solver's global ids when given, else keys from the corners' positions that every
// partition of the mesh gives the same tet, whatever the order of its corners.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <span>
#include <vector>

#include "adaptor/input/tie_keys.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray {
namespace {

std::vector<std::uint32_t> keys_of(std::span<const std::int64_t> tets,
                                   std::span<const double> points,
                                   const std::int64_t* global_ids = nullptr) {
  TetsView view = TetsView::of(tets);
  view.global_ids = global_ids;
  std::vector<std::uint32_t> keys;
  EXPECT_EQ(tie_keys(view, tets, PointsView::of(points), keys), "");
  return keys;
}

TEST(TieKeys, AreTheGlobalIdsWhenGiven) {
  const BoxMesh mesh = make_box_mesh({{2, 2, 2}});
  std::vector<std::int64_t> ids(mesh.tet_count());
  for (std::size_t t = 0; t < ids.size(); ++t) ids[t] = static_cast<std::int64_t>(7 * t + 3);
  const std::vector<std::uint32_t> keys = keys_of(mesh.tets, mesh.points, ids.data());
  ASSERT_EQ(keys.size(), ids.size());
  for (std::size_t t = 0; t < ids.size(); ++t) EXPECT_EQ(keys[t], ids[t]);
}

TEST(TieKeys, AGlobalIdBeyond32BitsIsAnError) {
  const BoxMesh mesh = make_box_mesh({{1, 1, 1}});
  std::vector<std::int64_t> ids(mesh.tet_count(), 0);
  ids[4] = std::int64_t{1} << 33;
  std::vector<std::uint32_t> keys;
  TetsView view = TetsView::of(std::span<const std::int64_t>(mesh.tets));
  view.global_ids = ids.data();
  const std::string error =
      tie_keys(view, mesh.tets, PointsView::of(std::span<const double>(mesh.points)), keys);
  EXPECT_NE(error.find("global_ids[4]"), std::string::npos) << error;
}

// Each slab of tets, numbered from 0 on its own "rank", gets the keys the whole mesh gives them.
TEST(TieKeys, DoNotDependOnThePartition) {
  const BoxMesh mesh = make_box_mesh({{6, 5, 4}, {-1, -1, -1}, {1, 1, 1}, 0.15});
  const std::vector<std::uint32_t> whole = keys_of(mesh.tets, mesh.points);
  const std::size_t count = mesh.tet_count();
  for (const std::size_t parts : {2u, 3u}) {
    for (std::size_t part = 0; part < parts; ++part) {
      const std::size_t begin = count * part / parts, end = count * (part + 1) / parts;
      const std::span<const std::int64_t> slab =
          std::span<const std::int64_t>(mesh.tets).subspan(4 * begin, 4 * (end - begin));
      const std::vector<std::uint32_t> keys = keys_of(slab, mesh.points);
      EXPECT_TRUE(std::equal(keys.begin(), keys.end(), whole.begin() + begin))
          << "part " << part << " of " << parts;
    }
  }
}

TEST(TieKeys, DoNotDependOnTheOrderOfCornersOrTheSignOfZero) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<double> negative_zeros = {-0.0, 0, -0.0, 1, -0.0, 0, 0, 1, 0, 0, -0.0, 1};
  const std::vector<std::int64_t> tet = {0, 1, 2, 3}, permuted = {2, 0, 3, 1};
  const std::uint32_t key = keys_of(tet, points)[0];
  EXPECT_EQ(keys_of(permuted, points)[0], key);
  EXPECT_EQ(keys_of(tet, negative_zeros)[0], key);
}

TEST(TieKeys, DifferForTheTetsOfAMesh) {
  const BoxMesh mesh = make_box_mesh({{10, 10, 10}, {-1, -1, -1}, {1, 1, 1}, 0.15});
  const std::vector<std::uint32_t> keys = keys_of(mesh.tets, mesh.points);
  EXPECT_EQ(std::set<std::uint32_t>(keys.begin(), keys.end()).size(), mesh.tet_count());
}

// An index outside the points is hashed as a number; the points array is not read there
// (AddressSanitizer would report it).
TEST(TieKeys, NeverReadAPointThroughABadIndex) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<std::int64_t> bad = {0, 1, 2, 1'000'000'000}, also_bad = {0, 1, 2, -5};
  EXPECT_NE(keys_of(bad, points)[0], keys_of(also_bad, points)[0]);
}

}  // namespace
}  // namespace tetray
