// Transparent surfaces through the adaptor on a split mesh (Wald et al. 2007, §8.5): the
// gyroid-twist scene with three transparent isosurfaces peeled to three layers, a clip box and
// plane, and a shadowing point and directional light, rendered by rank 0 alone and by all ranks
// with the tets split into slabs, gives the same image pixel for pixel: each rank keeps its
// nearest layers, the fragment compositor the nearest of all, and each layer is shadowed at its
// own hit point. The transparency and the shadows show (the image differs from the opaque and
// the unshadowed one), and a scene whose opacities are all 1 writes the very bytes of one
// without the keys. Smooth shading across ranks: smooth_mpi_test.cpp.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "shared_dir.hpp"
#include "slab_partition.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  return gyroid;
}

struct Variant {
  std::string layers;  // the scene's transparency keys
  bool shadows = true;
};

const Variant kTransparent{"    opacity: [0.4, 0.5, 0.6]\n    max_layers: 3\n"};
const Variant kUnshadowed{kTransparent.layers, false};
const Variant kOpaque{""};
const Variant kOpaqueByKeys{"    opacity: [1, 1, 1]\n    max_layers: 4\n"};

std::string config(const std::string& directory, const Variant& variant) {
  const std::string on = variant.shadows ? "true" : "false";
  return "output: {directory: " + directory +
         ", formats: [png, exr], quiet: true}\n"
         "scenes:\n"
         "  - name: glass\n"
         "    field: f\n"
         "    isovalues: [-0.5, 0, 0.5]\n"
         "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 96, height: 96}\n" +
         variant.layers +
         "    clip:\n"
         "      box: {min: [-2, -2, -2], max: [0.3, 2, 2]}\n"
         "      planes: [{point: [0, 0.5, 0], normal: [0.2, 1, 0.1]}]\n"
         "    lights: [{type: headlight},\n"
         "             {type: point, position: [2, 3, 1.5], shadows: " +
         on +
         "},\n"
         "             {type: directional, direction: [-1, -0.4, -2], shadows: " +
         on + "}]\n";
}

void render(MPI_Comm comm, const std::string& directory, const Variant& variant,
            const std::vector<std::int64_t>& tets) {
  const MeshView mesh{PointsView::of(std::span<const double>(scene().mesh.points)),
                      TetsView::of(std::span<const std::int64_t>(tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(scene().field))};
  render_step_zero(comm, config(directory, variant), mesh, fields);
}

PngPixels png(const std::string& run) { return read_png_rgba8(run + "/glass/glass_000000.png"); }

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(LayersAcrossRanks, TransparencyClipAndShadowsGiveTheImageOfOneRank) {
  const SharedDir shared("layers_across_ranks");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  if (rank() == 0) {
    render(MPI_COMM_SELF, one, kTransparent, scene().mesh.tets);
    render(MPI_COMM_SELF, shared.path() + "/unshadowed", kUnshadowed, scene().mesh.tets);
    render(MPI_COMM_SELF, shared.path() + "/opaque", kOpaque, scene().mesh.tets);
  }
  render(MPI_COMM_WORLD, split, kTransparent, x_slab(scene().mesh, rank(), world_size()).tets);
  if (rank() != 0) return;
  const PngPixels whole = png(one), parts = png(split);
  const PngPixels unshadowed = png(shared.path() + "/unshadowed");
  const PngPixels opaque = png(shared.path() + "/opaque");
  ASSERT_TRUE(whole.error.empty() && parts.error.empty() && unshadowed.error.empty() &&
              opaque.error.empty())
      << whole.error << parts.error << unshadowed.error << opaque.error;
  ASSERT_EQ(whole.rgba.size(), parts.rgba.size());
  const std::size_t pixels = whole.rgba.size() / 4;
  EXPECT_EQ(differing_pixels(whole, parts), 0u) << "on " << world_size() << " ranks";
  EXPECT_TRUE(bytes(one + "/glass/glass_000000.exr") == bytes(split + "/glass/glass_000000.exr"))
      << "the EXR's color and first-layer depth on " << world_size() << " ranks";
  EXPECT_GT(differing_pixels(whole, unshadowed), pixels / 20) << "the layers must be shadowed";
  EXPECT_GT(differing_pixels(whole, opaque), pixels / 5) << "the surfaces must be transparent";
}

TEST(LayersAcrossRanks, AllOpaqueWritesTheBytesOfAnOpaqueScene) {
  const SharedDir shared("layers_all_opaque");
  const std::string plain = shared.path() + "/plain", keys = shared.path() + "/keys";
  render(MPI_COMM_WORLD, plain, kOpaque, x_slab(scene().mesh, rank(), world_size()).tets);
  render(MPI_COMM_WORLD, keys, kOpaqueByKeys, x_slab(scene().mesh, rank(), world_size()).tets);
  if (rank() != 0) return;
  for (const char* format : {"png", "exr"}) {
    const std::string file = std::string("/glass/glass_000000.") + format;
    const std::string a = bytes(plain + file);
    EXPECT_FALSE(a.empty()) << format;
    EXPECT_TRUE(a == bytes(keys + file)) << format;
  }
}

}  // namespace
}  // namespace tetray::testing
