#include "tools/split_study/split_timing.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <span>
#include <string>

#include "adaptor/input/cell_split.hpp"
#include "render/core/stopwatch.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::tools {
namespace {

constexpr std::uint8_t kHexahedron = 12;

struct HexMesh {
  std::vector<double> xyz;
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets{0}, connectivity;
  std::map<std::array<int, 3>, std::int64_t> index;  // lattice point (in halves) -> point

  std::int64_t point(std::array<int, 3> p, int m) {
    const auto [at, added] = index.emplace(p, static_cast<std::int64_t>(xyz.size() / 3));
    if (added) {
      for (int k = 0; k < 3; ++k) xyz.push_back(-1 + p[k] / double(m));  // p in halves of a cell
    }
    return at->second;
  }
  // The hexahedron of side `side` (in halves) at lattice corner o (in halves), VTK's order.
  void add(std::array<int, 3> o, int side, int m) {
    static constexpr int dx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dy[8] = {0, 0, 1, 1, 0, 0, 1, 1},
                         dz[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    for (int k = 0; k < 8; ++k) {
      connectivity.push_back(
          point({o[0] + side * dx[k], o[1] + side * dy[k], o[2] + side * dz[k]}, m));
    }
    types.push_back(kHexahedron);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
};

HexMesh lattice(int m, bool refine_half) {
  HexMesh mesh;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const std::array<int, 3> o = {2 * i, 2 * j, 2 * k};
        if (!refine_half || 2 * i < m) {
          mesh.add(o, 2, m);
          continue;
        }
        for (int c = 0; c < 8; ++c)
          mesh.add({o[0] + (c & 1), o[1] + (c >> 1 & 1), o[2] + (c >> 2)}, 1, m);
      }
  return mesh;
}

struct Timed {
  SplitCells split;
  double ms = 0;
};

Timed best_split(const HexMesh& mesh, std::span<const std::uint64_t> keys,
                 std::span<const double> xyz, int runs) {
  Timed out;
  out.ms = 1e300;
  for (int r = 0; r < runs; ++r) {
    const render::Stopwatch watch;
    SplitCells split = split_cells(mesh.types, mesh.offsets, mesh.connectivity, keys, xyz);
    out.ms = std::min(out.ms, watch.ms());
    out.split = std::move(split);
  }
  if (!out.split.error.empty()) throw std::runtime_error(out.split.error);
  return out;
}

}  // namespace

Json::Value split_timing(const std::vector<int>& sizes, int runs) {
  Json::Value rows(Json::arrayValue);
  std::printf("\n%-22s %6s %10s %10s %9s %9s %12s %12s\n", "mesh", "m", "cells", "tets",
              "midpoints", "centres", "split ms", "no search ms");
  for (const int m : sizes) {
    for (const bool refine : {false, true}) {
      const HexMesh mesh = lattice(m, refine);
      const std::vector<std::uint64_t> keys = position_keys(mesh.xyz);
      const Timed with = best_split(mesh, keys, mesh.xyz, runs);
      const Timed without = best_split(mesh, keys, {}, runs);
      const char* name = refine ? "hexahedra, half refined" : "hexahedra";
      const std::size_t tets = with.split.tet_cell.size();
      std::printf("%-22s %6d %10zu %10zu %9zu %9zu %12.1f %12.1f\n", name, m, mesh.types.size(),
                  tets, with.split.hanging_midpoints, with.split.hanging_centres, with.ms,
                  without.ms);
      Json::Value row;
      row["mesh"] = name;
      row["cells_per_side"] = m;
      row["cells"] = bench::count(mesh.types.size());
      row["tets"] = bench::count(tets);
      row["hanging_midpoints"] = bench::count(with.split.hanging_midpoints);
      row["hanging_centres"] = bench::count(with.split.hanging_centres);
      row["split_ms"] = bench::number(with.ms);
      row["split_without_search_ms"] = bench::number(without.ms);
      rows.append(row);
    }
  }
  return rows;
}

}  // namespace tetray::tools
