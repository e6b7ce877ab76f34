// tetray-split-study: the image error of splitting finite-element cells into linear tets,
// against render time (README "Cells other than tets"). A solver's hexahedra carry a trilinear
// (Q1) or triquadratic (Q2) field; tetray renders the isosurface of its linear interpolant on the
// tets the cells split into (through the nodes of quadratic cells). Against a reference that
// samples the same field on a fine lattice, the table gives the depth error and the pixels that
// differ in hit or miss, for several mesh sizes, and for "levels" that sample each cell on an
// r^3 lattice first: more tets, less error, more time. A second table times the split itself at a
// topology change, with and without the search for hanging nodes.
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/stopwatch.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "tetray/vtk_bridge.hpp"
#include "tools/bench_common/json_file.hpp"
#include "tools/split_study/split_fields.hpp"
#include "tools/split_study/split_timing.hpp"

namespace tetray::tools {
namespace {

constexpr float kIso = 0.62f;
const Point3 kCenter = {0.06, -0.04, 0.09};

double distance_to_center(const Point3& x) {
  return std::hypot(x[0] - kCenter[0], x[1] - kCenter[1], x[2] - kCenter[2]);
}

// m^3 hexahedra on [-1, 1]^3 carrying `field` at their corners, split into tets by the adaptor's
// conversion of VTK cells (the same split as the API's).
vtkio::TetGrid lattice_tets(int m, const HexField& field) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  values->SetName("f");
  const auto index = [m](int i, int j, int k) {
    return (vtkIdType(k) * (m + 1) + j) * (m + 1) + i;
  };
  for (int k = 0; k <= m; ++k)
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i) {
        const Point3 x = {-1 + 2.0 * i / m, -1 + 2.0 * j / m, -1 + 2.0 * k / m};
        points->InsertNextPoint(x.data());
        values->InsertNextValue(field(x));
      }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(values);
  grid->Allocate(vtkIdType(m) * m * m);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const vtkIdType hexahedron[8] = {index(i, j, k),
                                         index(i + 1, j, k),
                                         index(i + 1, j + 1, k),
                                         index(i, j + 1, k),
                                         index(i, j, k + 1),
                                         index(i + 1, j, k + 1),
                                         index(i + 1, j + 1, k + 1),
                                         index(i, j + 1, k + 1)};
        grid->InsertNextCell(VTK_HEXAHEDRON, 8, hexahedron);
      }
  vtkio::TetGrid out;
  std::string error;
  if (!vtkio::from_vtk(grid, out, error)) throw std::runtime_error(error);
  return out;
}

struct Rendered {
  render::Framebuffer image;
  std::size_t tets = 0;
  double build_ms = 0, trace_ms = 0;
};

Rendered render_grid(const vtkio::TetGrid& grid, const render::Camera& camera) {
  const std::vector<double>& f = grid.point_fields.at("f");
  const render::PointSource points{grid.points.data(), render::ScalarKind::f64, nullptr,
                                   render::ScalarKind::f64, grid.points.size() / 3};
  const render::FieldSource values{f.data(), render::ScalarKind::f64, f.size()};
  const std::vector<std::uint8_t> keep(grid.tets.size() / 4, 1);
  Rendered out;
  out.tets = keep.size();
  render::TetVolume volume;
  render::Bvh bvh;
  const render::Stopwatch build;
  render::load_volume(volume, bvh, grid.tets, keep, {}, points, values, render::UpdatePolicy{});
  out.build_ms = build.ms();
  const render::IsoSurface surfaces[] = {{kIso, {0.8f, 0.5f, 0.2f}}};
  const render::Stopwatch trace;
  out.image = render::trace(volume, bvh, camera, surfaces, {});
  out.trace_ms = trace.ms();
  return out;
}

struct ImageError {
  double mean_depth = 0;    // over pixels both images hit, relative to the domain's side (2)
  double max_depth = 0;     // likewise
  double hit_mismatch = 0;  // fraction of the pixels either image hits
};

ImageError image_error(const render::Framebuffer& image, const render::Framebuffer& reference) {
  ImageError e;
  std::size_t both = 0, either = 0, mismatched = 0;
  for (std::size_t p = 0; p < image.hit.size(); ++p) {
    const bool a = image.hit[p] != render::kNoHit, b = reference.hit[p] != render::kNoHit;
    either += a || b;
    mismatched += a != b;
    if (!a || !b) continue;
    const double d = std::abs(double(image.depth[p]) - double(reference.depth[p])) / 2;
    e.mean_depth += d;
    e.max_depth = std::max(e.max_depth, d);
    ++both;
  }
  e.mean_depth = both ? e.mean_depth / double(both) : 0;
  e.hit_mismatch = either ? double(mismatched) / double(either) : 0;
  return e;
}

struct Options {
  std::vector<int> sizes = {4, 8, 16};
  std::vector<int> levels = {1, 2};
  int reference = 96;
  int side = 512;
  std::vector<int> split_sizes = {32, 64};
  int split_runs = 3;
  std::string json;
};

Json::Value study(const Options& options) {
  const render::Camera camera{{2.2, 1.6, 3.0}, {0, 0, 0},   {0, 1, 0}, 40,
                              options.side,    options.side};
  Json::Value rows(Json::arrayValue);
  std::printf("%-13s %6s %5s %10s %9s %9s %12s %12s %10s\n", "field", "cells", "level", "tets",
              "build ms", "trace ms", "mean depth", "max depth", "hit/miss");
  for (const int order : {1, 2}) {
    for (const int cells : options.sizes) {
      const HexField field{order == 1 ? "Q1 hexahedra" : "Q2 hexahedra", order, cells,
                           distance_to_center};
      const Rendered reference = render_grid(lattice_tets(options.reference, field), camera);
      for (const int level : options.levels) {
        const Rendered split = render_grid(lattice_tets(cells * order * level, field), camera);
        const ImageError e = image_error(split.image, reference.image);
        std::printf("%-13s %6d %5d %10zu %9.1f %9.1f %12.2e %12.2e %9.3f%%\n", field.name.c_str(),
                    cells, level, split.tets, split.build_ms, split.trace_ms, e.mean_depth,
                    e.max_depth, 100 * e.hit_mismatch);
        Json::Value row;
        row["field"] = field.name;
        row["cells_per_side"] = cells;
        row["level"] = level;
        row["tets"] = bench::count(split.tets);
        row["build_ms"] = bench::number(split.build_ms);
        row["trace_ms"] = bench::number(split.trace_ms);
        row["mean_depth_error"] = bench::number(e.mean_depth);
        row["max_depth_error"] = bench::number(e.max_depth);
        row["hit_mismatch_fraction"] = bench::number(e.hit_mismatch);
        rows.append(row);
      }
    }
  }
  return rows;
}

}  // namespace
}  // namespace tetray::tools

int main(int argc, char** argv) {
  tetray::tools::Options options;
  CLI::App app{"tetray-split-study: image error of the cell split against render time"};
  app.add_option("--sizes", options.sizes, "cells per side of the solver's mesh")
      ->capture_default_str();
  app.add_option("--levels", options.levels, "samplings of each cell (1: the cells as given)")
      ->capture_default_str();
  app.add_option("--reference", options.reference, "cells per side of the reference lattice")
      ->capture_default_str()
      ->check(CLI::Range(8, 512));
  app.add_option("--size", options.side, "image side in pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  app.add_option("--split-sizes", options.split_sizes,
                 "cells per side of the lattices whose split is timed")
      ->capture_default_str();
  app.add_option("--split-runs", options.split_runs, "runs of each split (the best is shown)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--json", options.json, "also write the rows as JSON to this file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    Json::Value rows(Json::objectValue);
    rows["images"] = tetray::tools::study(options);
    rows["split"] = tetray::tools::split_timing(options.split_sizes, options.split_runs);
    if (!options.json.empty() && !tetray::bench::write_json_file(rows, options.json)) {
      std::fprintf(stderr, "tetray-split-study: cannot write %s\n", options.json.c_str());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tetray-split-study: %s\n", e.what());
    return 1;
  }
  return 0;
}
