#include "render/walk/face_adjacency.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <tuple>

namespace tetray::render {
namespace {

// A tet's face opposite local vertex `opposite`, keyed by its two larger vertex indices (the
// smallest is the bucket it sits in).
struct FaceRecord {
  std::uint32_t middle, largest;
  std::uint32_t tet_face;  // 4 * tet + opposite
};

bool has_repeated_vertex(const Tet& tet) {
  const auto& v = tet.v;
  return v[0] == v[1] || v[0] == v[2] || v[0] == v[3] || v[1] == v[2] || v[1] == v[3] ||
         v[2] == v[3];
}

// The three vertices of a face sorted ascending.
std::array<std::uint32_t, 3> sorted_face(const Tet& tet, int opposite) {
  std::array<std::uint32_t, 3> f{};
  int n = 0;
  for (int c = 0; c < 4; ++c) {
    if (c != opposite) f[n++] = static_cast<std::uint32_t>(tet.v[c]);
  }
  std::sort(f.begin(), f.end());
  return f;
}

// Faces bucketed by their smallest vertex: bucket v is records[begin[v], begin[v + 1]).
struct FaceBuckets {
  std::vector<std::uint32_t> begin;
  std::vector<FaceRecord> records;
};

FaceBuckets bucket_faces(const TetVolume& volume, const std::vector<std::uint8_t>& degenerate) {
  const std::size_t tet_count = volume.tets.size();
  FaceBuckets buckets;
  std::vector<std::uint32_t> cursor(volume.vertices.size() + 1, 0);
  const auto each_face = [&](auto&& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tet_count),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t t = r.begin(); t != r.end(); ++t) {
                          if (degenerate[t]) continue;
                          for (int k = 0; k < 4; ++k) f(t, k, sorted_face(volume.tets[t], k));
                        }
                      });
  };
  each_face([&](std::size_t, int, const std::array<std::uint32_t, 3>& face) {
    std::atomic_ref<std::uint32_t>(cursor[face[0] + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  for (std::size_t v = 1; v < cursor.size(); ++v) cursor[v] += cursor[v - 1];
  buckets.begin = cursor;
  buckets.records.resize(cursor.back());
  each_face([&](std::size_t t, int k, const std::array<std::uint32_t, 3>& face) {
    const std::uint32_t at =
        std::atomic_ref<std::uint32_t>(cursor[face[0]]).fetch_add(1, std::memory_order_relaxed);
    buckets.records[at] = {face[1], face[2], static_cast<std::uint32_t>(4 * t + k)};
  });
  return buckets;
}

// Matches the faces inside each bucket: the neighbour across every tet face (kBoundaryFace for
// none), indexed 4 * tet + opposite. Sorting a bucket fully makes the result independent of the
// order the scatter filled it in.
std::vector<std::uint32_t> match_faces(FaceBuckets& buckets, std::size_t tet_count,
                                       std::atomic<std::uint64_t>& nonmanifold) {
  std::vector<std::uint32_t> across(4 * tet_count, kBoundaryFace);
  const std::size_t bucket_count = buckets.begin.size() - 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bucket_count), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      FaceRecord* first = buckets.records.data() + buckets.begin[v];
      FaceRecord* last = buckets.records.data() + buckets.begin[v + 1];
      std::sort(first, last, [](const FaceRecord& a, const FaceRecord& b) {
        return std::tie(a.middle, a.largest, a.tet_face) <
               std::tie(b.middle, b.largest, b.tet_face);
      });
      for (FaceRecord* group = first; group != last;) {
        FaceRecord* end = group + 1;
        while (end != last && end->middle == group->middle && end->largest == group->largest) {
          ++end;
        }
        if (end - group == 2) {
          across[group[0].tet_face] = group[1].tet_face / 4;
          across[group[1].tet_face] = group[0].tet_face / 4;
        } else if (end - group > 2) {
          nonmanifold.fetch_add(1, std::memory_order_relaxed);
        }
        group = end;
      }
    }
  });
  return across;
}

void set_neighbors(Tet20& out, const std::uint32_t (&n)[4]) {
  for (int k = 0; k < 4; ++k) out.neighbor[k] = n[k];
}
void set_neighbors(Tet16& out, const std::uint32_t (&n)[4]) {
  for (int k = 0; k < 3; ++k) out.neighbor_xor[k] = n[k] ^ n[3];
}

}  // namespace

template <typename Layout>
FaceAdjacency<Layout> build_face_adjacency(const TetVolume& volume) {
  const std::size_t tet_count = volume.tets.size();
  if (tet_count >= (std::size_t{1} << 30)) {
    throw std::length_error("face adjacency: more than 2^30 tets on one rank");
  }
  FaceAdjacency<Layout> adjacency;
  std::vector<std::uint8_t> degenerate(tet_count);
  tbb::parallel_for(std::size_t{0}, tet_count,
                    [&](std::size_t t) { degenerate[t] = has_repeated_vertex(volume.tets[t]); });
  FaceBuckets buckets = bucket_faces(volume, degenerate);
  std::atomic<std::uint64_t> nonmanifold{0};
  const std::vector<std::uint32_t> across = match_faces(buckets, tet_count, nonmanifold);
  adjacency.nonmanifold_faces = nonmanifold.load();

  adjacency.tets.resize(tet_count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tet_count), [&](const auto& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const auto& v = volume.tets[t].v;
      const auto u = [&](int c) { return static_cast<std::uint32_t>(v[c]); };
      std::uint32_t by_order[4] = {kBoundaryFace, kBoundaryFace, kBoundaryFace, kBoundaryFace};
      if (!degenerate[t]) {
        for (int k = 0; k < 4; ++k) {
          const int order = vertex_order(u(k), u((k + 1) % 4), u((k + 2) % 4), u((k + 3) % 4));
          by_order[order] = across[4 * t + k];
        }
      }
      adjacency.tets[t].vertex_xor = u(0) ^ u(1) ^ u(2) ^ u(3);
      set_neighbors(adjacency.tets[t], by_order);
    }
  });
  for (std::size_t t = 0; t < tet_count; ++t) {
    if (degenerate[t]) {
      ++adjacency.degenerate_tets;
      continue;
    }
    for (std::uint32_t k = 0; k < 4; ++k) {
      if (across[4 * t + k] == kBoundaryFace) {
        adjacency.boundary.push_back({static_cast<std::uint32_t>(t), k});
      }
    }
  }
  return adjacency;
}

template FaceAdjacency<Tet20> build_face_adjacency<Tet20>(const TetVolume&);
template FaceAdjacency<Tet16> build_face_adjacency<Tet16>(const TetVolume&);

}  // namespace tetray::render
