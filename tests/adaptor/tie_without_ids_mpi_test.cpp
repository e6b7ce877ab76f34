// The same image on 1, 2 and 3 ranks when the solver gives no global tet ids. The scene ties at
// every pixel: two layers of tets share no point but meet on the plane z = 0, where the lower
// layer's field (f = z) has its isosurface 0 and the upper layer's (f = 0.5 - z) its isosurface
// 0.5; seen from below, each pixel of the plane is hit at equal depth by a tet of each layer, in
// the two isosurfaces' colors. One rank holds both layers, or rank 0 the lower one and rank 1
// the upper one (a third rank none): rank-local tet numbers would give the ties to different
// layers on one rank and on two, keys from the tets' positions do not.
#include <gtest/gtest.h>
#include <mpi.h>

#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "shared_dir.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

struct Layers {
  std::vector<double> points, f;
  std::vector<std::int64_t> lower, upper;  // tets of each layer
};

// The layer [0, 1]^2 x [z0, z0 + 1] appended to `layers`, with f = offset + slope z.
void add_layer(Layers& layers, double z0, double offset, double slope,
               std::vector<std::int64_t>& tets) {
  const BoxMesh box = make_box_mesh({{4, 4, 1}, {0, 0, z0}, {1, 1, z0 + 1}});
  const auto first = static_cast<std::int64_t>(layers.f.size());
  layers.points.insert(layers.points.end(), box.points.begin(), box.points.end());
  for (std::size_t p = 0; p < box.point_count(); ++p) {
    layers.f.push_back(offset + slope * box.points[3 * p + 2]);
  }
  for (std::int64_t v : box.tets) tets.push_back(first + v);
}

Layers two_layers() {
  Layers layers;
  add_layer(layers, -1, 0, 1, layers.lower);
  add_layer(layers, 0, 0.5, -1, layers.upper);
  return layers;
}

std::string config(const std::string& directory) {
  return "output: {directory: " + directory +
         ", formats: [png], quiet: true}\n"
         "scenes:\n"
         "  - name: ties\n"
         "    field: f\n"
         "    isovalues: [0, 0.5]\n"
         "    colors: [[1, 0, 0], [0, 0, 1]]\n"
         "    camera: {eye: [0.5, 0.5, -3], look_at: [0.5, 0.5, 0], up: [0, 1, 0], fov_deg: 30}\n"
         "    image: {width: 48, height: 48}\n";
}

void render(MPI_Comm comm, const std::string& directory, const Layers& layers,
            const std::vector<std::int64_t>& tets) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, config(directory), status);
  ASSERT_TRUE(adaptor) << status.message;
  MeshView mesh{PointsView::of(std::span<const double>(layers.points)),
                TetsView::of(std::span<const std::int64_t>(tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(layers.f))};
  status = adaptor->execute(0, 0, mesh, fields);
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(adaptor->finalize().ok());
}

TEST(TiesWithoutGlobalIds, GiveTheSameImageOnAnyRankCount) {
  const SharedDir shared("ties_without_ids");
  const Layers layers = two_layers();
  // The upper layer first: on one rank its tets have the smaller positions in the input.
  std::vector<std::int64_t> both = layers.upper;
  both.insert(both.end(), layers.lower.begin(), layers.lower.end());
  if (rank() == 0) render(MPI_COMM_SELF, shared.path() + "/one", layers, both);
  const std::vector<std::int64_t> none;
  render(MPI_COMM_WORLD, shared.path() + "/split", layers,
         rank() == 0   ? layers.lower
         : rank() == 1 ? layers.upper
                       : none);
  if (rank() != 0) return;
  const std::string one = slurp(shared.path() + "/one/ties/ties_000000.png");
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(one, slurp(shared.path() + "/split/ties/ties_000000.png"));
}

}  // namespace
}  // namespace tetray::testing
