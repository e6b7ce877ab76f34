// Volume scenes through the adaptor on a split mesh (docs/architecture.md §8): the gyroid-twist
// mesh with a linear temperature volume-rendered, alone and with isosurfaces of the gyroid field
// along the walk (one transparent, one opaque), rendered by rank 0 alone and by all ranks with
// the tets split into slabs, writes the very bytes of the one-rank PNG and EXR files: a rank's
// runs keep their colors in double, so the over operator's different association on a split
// changes them far below the files' rounding. The surfaces show: the image differs from the
// volume's alone. A camera inside the mesh starts every ray in the eye's tet on the rank
// holding it (the others' rays enter their slabs through boundary faces): every pixel sees
// the volume, and the bytes are again those of one rank. An orbit renders each of its views
// from the step's one walk structure: its first view (azimuth and elevation 0) is the plain
// scene's image, the others differ, and every view's bytes are again those of one rank.
#include <gtest/gtest.h>
#include <mpi.h>

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

const GyroidWithTemperature& scene() {
  static const GyroidWithTemperature s = gyroid_with_temperature({0.5, 0.3, -0.15, 0.1});
  return s;
}

const char* const kScenes[] = {"fog", "skin", "inside"};
const char* const kOrbitViews[] = {"view000", "view001", "view002", "view003"};

std::string config(const std::string& directory) {
  const std::string volume =
      "    field: temperature\n"
      "    volume: {colormap: coolwarm, range: [0, 1], opacity: [[0, 0.1], [1, 1.2]],\n"
      "             unit_distance: 0.5, termination: 1}\n"
      "    image: {width: 320, height: 320}\n";
  const std::string outside =
      "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n";
  const std::string surfaces =
      "    surfaces: {field: f, isovalues: [0.5, 0], opacity: [0.4, 1],\n"
      "               colors: [[0.9, 0.9, 0.9], [0.2, 0.8, 0.3]]}\n";
  const std::string inside =
      "    camera: {eye: [-0.1, 0.15, 0.2], look_at: [1, 0.5, -0.6], up: [0, 1, 0], fov_deg: 70}\n";
  const std::string orbit = "    orbit: {azimuth: [0, 120], elevation: [0, 25]}\n";
  return "output: {directory: " + directory + ", formats: [png, exr], quiet: true}\n" +
         "scenes:\n  - name: fog\n" + volume + outside + "  - name: skin\n" + volume + outside +
         surfaces + "  - name: inside\n" + volume + inside + surfaces + "  - name: orbit\n" +
         volume + outside + orbit;
}

void render(MPI_Comm comm, const std::string& directory, const Slab& part) {
  render_gyroid_with_temperature(comm, config(directory), scene(), part);
}

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string file(const std::string& run, const std::string& name, const char* format,
                 const std::string& view = "") {
  return run + "/" + name + "/" + name + "_000000" + (view.empty() ? "" : "_" + view) + "." +
         format;
}

// The orbit scene's views of the runs `one` and `split` (on rank 0).
void expect_orbit_views(const std::string& one, const std::string& split) {
  for (const char* view : kOrbitViews) {
    for (const char* format : {"png", "exr"}) {
      const std::string a = bytes(file(one, "orbit", format, view));
      EXPECT_FALSE(a.empty()) << view << " " << format;
      EXPECT_TRUE(a == bytes(file(split, "orbit", format, view)))
          << view << " " << format << " on " << world_size() << " ranks";
    }
  }
  const PngPixels fog = read_png_rgba8(file(one, "fog", "png"));
  ASSERT_TRUE(fog.error.empty()) << fog.error;
  for (const char* view : kOrbitViews) {
    const PngPixels image = read_png_rgba8(file(one, "orbit", "png", view));
    ASSERT_TRUE(image.error.empty()) << image.error;
    if (view == kOrbitViews[0]) {
      EXPECT_EQ(differing_pixels(fog, image), 0u) << "the first view is the scene's own camera";
    } else {
      EXPECT_GT(differing_pixels(fog, image), fog.rgba.size() / 4 / 10) << view;
    }
  }
}

TEST(VolumeAcrossRanks, WritesTheBytesOfOneRank) {
  const SharedDir shared("volume_across_ranks");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  if (rank() == 0) render(MPI_COMM_SELF, one, x_slab(scene().gyroid.mesh, 0, 1));
  render(MPI_COMM_WORLD, split, x_slab(scene().gyroid.mesh, rank(), world_size()));
  if (rank() != 0) return;
  for (const char* name : kScenes) {
    for (const char* format : {"png", "exr"}) {
      const std::string a = bytes(file(one, name, format));
      EXPECT_FALSE(a.empty()) << name << " " << format;
      EXPECT_TRUE(a == bytes(file(split, name, format)))
          << name << " " << format << " on " << world_size() << " ranks";
    }
  }
  const PngPixels fog = read_png_rgba8(file(one, "fog", "png"));
  const PngPixels skin = read_png_rgba8(file(one, "skin", "png"));
  ASSERT_TRUE(fog.error.empty() && skin.error.empty()) << fog.error << skin.error;
  EXPECT_GT(differing_pixels(fog, skin), fog.rgba.size() / 4 / 5) << "the surfaces must show";
  const PngPixels inside = read_png_rgba8(file(one, "inside", "png"));
  ASSERT_TRUE(inside.error.empty()) << inside.error;
  std::size_t clear = 0;
  for (std::size_t p = 3; p < inside.rgba.size(); p += 4) clear += inside.rgba[p] == 0;
  EXPECT_EQ(clear, 0u) << "every ray from inside the mesh must see the volume";
  expect_orbit_views(one, split);
}

}  // namespace
}  // namespace tetray::testing
