// Probes end to end (run under mpirun with 1 and 3 ranks): on the plane scene's box with a
// random value per point, probes at mesh vertices read exactly the vertex's value, probes inside
// read the linear fields f = z and g = x to rounding and a random field as the barycentric
// interpolant of an independent point location, a point outside is reported as outside, and
// the box cut into slabs over the ranks writes the same CSV, byte for byte, as one rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <fstream>
#include <random>
#include <sstream>

#include "plane_scene.hpp"
#include "shared_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

struct ProbeScene {
  PlaneScene plane = make_plane_scene(4);
  std::vector<double> h;  // independent uniform values, one per point
  std::vector<std::array<double, 3>> vertex_points, inside_points;

  ProbeScene() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(-1, 1);
    for (std::size_t p = 0; p < plane.mesh.point_count(); ++p) h.push_back(value(rng));
    for (std::size_t p = 0; p < plane.mesh.point_count(); p += 7) {
      vertex_points.push_back(
          {plane.mesh.points[3 * p], plane.mesh.points[3 * p + 1], plane.mesh.points[3 * p + 2]});
    }
    std::uniform_real_distribution<double> inside(-0.97, 0.97);
    for (int i = 0; i < 40; ++i) inside_points.push_back({inside(rng), inside(rng), inside(rng)});
  }

  std::vector<FieldView> fields() const {
    std::vector<FieldView> views = plane.fields();
    views.push_back(FieldView::of("h", std::span<const double>(h)));
    return views;
  }
};

std::string point_list(const std::vector<std::array<double, 3>>& points) {
  std::ostringstream out;
  out.precision(17);
  out << '[';
  for (std::size_t i = 0; i < points.size(); ++i) {
    out << (i ? ", " : "") << '[' << points[i][0] << ", " << points[i][1] << ", " << points[i][2]
        << ']';
  }
  return out.str() + ']';
}

std::string probe_config(const ProbeScene& scene, const std::string& dir) {
  return plane_config(dir, ", formats: [png]", "", "") +
         "probes:\n"
         "  - name: vertices\n"
         "    fields: [h]\n"
         "    points: " +
         point_list(scene.vertex_points) +
         "\n"
         "  - name: inside\n"
         "    fields: [f, g, h]\n"
         "    points: " +
         point_list(scene.inside_points) +
         "\n"
         "    lines: [{from: [-0.5, 0.3, -2], to: [-0.5, 0.3, 2], samples: 9}]\n";
}

// This rank's slab of the tets by centroid x, with global ids.
struct Slab {
  std::vector<std::int64_t> tets, ids;
  explicit Slab(const BoxMesh& mesh) {
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
      double x = 0;
      for (int v = 0; v < 4; ++v) x += 0.25 * mesh.points[3 * mesh.tets[4 * t + v]];
      const int slab = std::min(world_size() - 1, static_cast<int>((x + 1) / 2 * world_size()));
      if (slab != rank()) continue;
      tets.insert(tets.end(), mesh.tets.begin() + 4 * t, mesh.tets.begin() + 4 * t + 4);
      ids.push_back(static_cast<std::int64_t>(t));
    }
  }
};

void run(MPI_Comm comm, const std::string& dir, const ProbeScene& scene, const MeshView& view) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, probe_config(scene, dir), status);
  ASSERT_TRUE(status.ok()) << status.message;
  for (int step = 0; step < 2; ++step) {
    status = adaptor->execute(step, 0.5 * step, view, scene.fields());
    ASSERT_TRUE(status.ok()) << status.message;
  }
  ASSERT_TRUE(adaptor->finalize().ok());
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Independent of the renderer: the Kuhn tet of the unjittered 4^3 box containing p and its
// barycentric coordinates, from the cell's sorted local coordinates (Freudenthal's rule).
double kuhn_interpolant(const BoxMesh& mesh, const std::vector<double>& values,
                        const std::array<double, 3>& p) {
  std::array<int, 3> cell{};
  std::array<double, 3> local{};
  for (int a = 0; a < 3; ++a) {
    const double s = (p[a] + 1) / 2 * mesh.cells[a];
    cell[a] = std::min(mesh.cells[a] - 1, static_cast<int>(s));
    local[a] = s - cell[a];
  }
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return local[a] > local[b]; });
  // Walk from corner (0,0,0) to (1,1,1) along the axes in decreasing local coordinate.
  std::array<int, 3> corner = cell;
  double sum = values[mesh.point_index(corner[0], corner[1], corner[2])] * (1 - local[order[0]]);
  for (int k = 0; k < 3; ++k) {
    ++corner[order[k]];
    const double w = local[order[k]] - (k < 2 ? local[order[k + 1]] : 0.0);
    sum += w * values[mesh.point_index(corner[0], corner[1], corner[2])];
  }
  return sum;
}

TEST(Probes, ValuesAndRankCountIndependence) {
  const SharedDir shared("probes");
  const std::string& dir = shared.path();
  const ProbeScene scene;
  if (rank() == 0) run(MPI_COMM_SELF, dir + "/one", scene, scene.plane.view());
  const Slab slab(scene.plane.mesh);
  MeshView view = scene.plane.view();
  view.tets = TetsView::of(std::span<const std::int64_t>(slab.tets));
  view.tets.global_ids = slab.ids.data();
  run(MPI_COMM_WORLD, dir + "/split", scene, view);
  if (rank() != 0) return;

  const auto vertices = read_csv(dir + "/one/probe_vertices.csv");
  ASSERT_EQ(vertices.size(), 1 + 2 * scene.vertex_points.size());
  for (std::size_t i = 0; i < scene.vertex_points.size(); ++i) {
    const std::size_t p = 7 * i;
    EXPECT_EQ(std::stod(cell(vertices, 1 + i, "h")), scene.h[p]) << "vertex " << p;
  }
  const auto inside = read_csv(dir + "/one/probe_inside.csv");
  const std::size_t rows = scene.inside_points.size() + 9;
  ASSERT_EQ(inside.size(), 1 + 2 * rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const std::array<double, 3> p = {std::stod(cell(inside, 1 + i, "x")),
                                     std::stod(cell(inside, 1 + i, "y")),
                                     std::stod(cell(inside, 1 + i, "z"))};
    if (std::abs(p[2]) > 1) {
      EXPECT_EQ(cell(inside, 1 + i, "f"), "outside");
      EXPECT_EQ(cell(inside, 1 + i, "h"), "outside");
      continue;
    }
    EXPECT_NEAR(std::stod(cell(inside, 1 + i, "f")), p[2], 1e-12);
    EXPECT_NEAR(std::stod(cell(inside, 1 + i, "g")), p[0], 1e-12);
    EXPECT_NEAR(std::stod(cell(inside, 1 + i, "h")), kuhn_interpolant(scene.plane.mesh, scene.h, p),
                1e-12);
  }
  EXPECT_EQ(cell(inside, rows + 1, "step"), "1");
  for (const char* set : {"vertices", "inside"}) {
    const std::string file = std::string("/probe_") + set + ".csv";
    EXPECT_EQ(slurp(dir + "/one" + file), slurp(dir + "/split" + file)) << set;
  }
}

}  // namespace
}  // namespace tetray::testing
