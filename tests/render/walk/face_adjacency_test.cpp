// The compact adjacency against an independent match of faces through an ordered map: every
// tet's neighbour across every face, decoded from Tet20 and from Tet16, and the boundary faces.
#include "render/walk/face_adjacency.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "walk_meshes.hpp"

namespace tetray::test {
namespace {

using render::kBoundaryFace;

using FaceKey = std::array<std::int32_t, 3>;

FaceKey face_key(const render::Tet& tet, int opposite) {
  FaceKey key{};
  int n = 0;
  for (int c = 0; c < 4; ++c) {
    if (c != opposite) key[n++] = tet.v[c];
  }
  std::sort(key.begin(), key.end());
  return key;
}

// neighbour[4 t + k]: the tet across tet t's face opposite its vertex k.
std::vector<std::uint32_t> neighbours_by_map(const render::TetVolume& volume) {
  std::map<FaceKey, std::vector<std::uint32_t>> owners;
  for (std::uint32_t t = 0; t < volume.tets.size(); ++t) {
    for (int k = 0; k < 4; ++k) owners[face_key(volume.tets[t], k)].push_back(t);
  }
  std::vector<std::uint32_t> neighbour(4 * volume.tets.size(), kBoundaryFace);
  for (std::uint32_t t = 0; t < volume.tets.size(); ++t) {
    for (int k = 0; k < 4; ++k) {
      const std::vector<std::uint32_t>& o = owners[face_key(volume.tets[t], k)];
      if (o.size() == 2) neighbour[4 * t + k] = o[0] == t ? o[1] : o[0];
    }
  }
  return neighbour;
}

int order_of_vertex(const render::Tet& tet, int k) {
  const auto u = [&](int c) { return static_cast<std::uint32_t>(tet.v[c]); };
  return render::vertex_order(u(k), u((k + 1) % 4), u((k + 2) % 4), u((k + 3) % 4));
}

void expect_adjacency_of(const render::TetVolume& volume) {
  const std::vector<std::uint32_t> expected = neighbours_by_map(volume);
  const auto tet20 = render::build_face_adjacency<render::Tet20>(volume);
  const auto tet16 = render::build_face_adjacency<render::Tet16>(volume);
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected_boundary;
  for (std::uint32_t t = 0; t < volume.tets.size(); ++t) {
    const render::Tet& tet = volume.tets[t];
    ASSERT_EQ(tet20.tets[t].vertex_xor, std::uint32_t(tet.v[0] ^ tet.v[1] ^ tet.v[2] ^ tet.v[3]));
    ASSERT_EQ(tet16.tets[t].vertex_xor, tet20.tets[t].vertex_xor);
    for (int a = 0; a < 4; ++a) {
      const std::uint32_t n_a = expected[4 * t + a];
      if (n_a == kBoundaryFace) expected_boundary.insert({t, a});
      ASSERT_EQ(tet20.tets[t].neighbor[order_of_vertex(tet, a)], n_a) << "tet " << t;
      // Tet16 recovers every neighbour from any other one.
      for (int b = 0; b < 4; ++b) {
        ASSERT_EQ(tet16.tets[t].next(n_a, order_of_vertex(tet, a), order_of_vertex(tet, b)),
                  expected[4 * t + b])
            << "tet " << t << " from face " << a << " to face " << b;
      }
    }
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> boundary;
  for (const render::BoundaryFaceRef& f : tet20.boundary) boundary.insert({f.tet, f.opposite});
  EXPECT_EQ(boundary, expected_boundary);
  EXPECT_EQ(tet20.boundary.size(), expected_boundary.size());
  EXPECT_EQ(tet20.nonmanifold_faces, 0u);
  EXPECT_EQ(tet20.bytes() - tet20.boundary.capacity() * sizeof(render::BoundaryFaceRef),
            20 * volume.tets.size());
}

TEST(FaceAdjacency, MatchesAMapOfFacesOnABox) {
  const RenderScene scene = load_walk_scene(make_walk_mesh({}));
  expect_adjacency_of(scene.volume);
  // A closed box of 5^3 cells: 2 boundary triangles per cell face on each of 6 sides.
  EXPECT_EQ(render::build_face_adjacency<render::Tet20>(scene.volume).boundary.size(), 6u * 2 * 25);
}

TEST(FaceAdjacency, MatchesAMapOfFacesWithHoles) {
  MeshShape shape;
  shape.removed_fraction = 0.3;
  expect_adjacency_of(load_walk_scene(make_walk_mesh(shape)).volume);
}

TEST(FaceAdjacency, FacesOfThreeTetsAndRepeatedVerticesAreBoundary) {
  render::TetVolume volume;
  for (int i = 0; i < 6; ++i) volume.vertices.push_back({float(i), float(i * i), float(i % 2), 0});
  // Three tets on face {0, 1, 2}, and one with vertex 3 twice.
  volume.tets = {{{0, 1, 2, 3}}, {{0, 1, 2, 4}}, {{2, 1, 0, 5}}, {{3, 3, 4, 5}}};
  const auto adjacency = render::build_face_adjacency<render::Tet20>(volume);
  EXPECT_EQ(adjacency.nonmanifold_faces, 1u);
  EXPECT_EQ(adjacency.degenerate_tets, 1u);
  EXPECT_EQ(adjacency.boundary.size(), 12u);  // every face of the three good tets
  for (const render::Tet20& t : adjacency.tets) {
    for (std::uint32_t n : t.neighbor) EXPECT_EQ(n, kBoundaryFace);
  }
}

}  // namespace
}  // namespace tetray::test
