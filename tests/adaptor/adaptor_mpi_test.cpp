// The adaptor across ranks (run under mpirun -np 2): an empty rank, a mesh split over the ranks
// giving the same image as one rank, one rank's bad input reaching every rank as an error
// instead of a hang, a writer rank other than 0, and per-rank debugging images; an orbit's views
// composited one by one.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "plane_scene.hpp"
#include "shared_dir.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<Adaptor> make(MPI_Comm comm, const std::string& dir,
                              const std::string& output_keys = "",
                              const std::string& top_lines = "",
                              const std::string& scene_lines = "") {
  Status status;
  auto a = Adaptor::create_from_yaml(
      comm, plane_config(dir, ", formats: [png]" + output_keys, top_lines, scene_lines), status);
  EXPECT_TRUE(status.ok()) << status.message;
  return a;
}

// This rank's slab of the plane scene's tets, by the x of their centroid, with global ids: the
// plane z = const crosses every slab, so every rank sees a part of it, side by side in the image.
class SlabPart {
 public:
  explicit SlabPart(const PlaneScene& scene) : scene_(scene) {
    const auto& tets = scene.mesh.tets;
    for (std::size_t t = 0; 4 * t < tets.size(); ++t) {
      double x = 0;
      for (int v = 0; v < 4; ++v) x += 0.25 * scene.mesh.points[3 * tets[4 * t + v]];
      const int slab = std::min(world_size() - 1, static_cast<int>((x + 1) / 2 * world_size()));
      if (slab != rank()) continue;
      tets_.insert(tets_.end(), tets.begin() + 4 * t, tets.begin() + 4 * t + 4);
      ids_.push_back(static_cast<std::int64_t>(t));
    }
  }
  MeshView view() const {
    MeshView view = scene_.view();
    view.tets = TetsView::of(std::span<const std::int64_t>(tets_));
    view.tets.global_ids = ids_.data();
    return view;
  }

 private:
  const PlaneScene& scene_;
  std::vector<std::int64_t> tets_;
  std::vector<std::int64_t> ids_;
};

// Which pixels of a PNG are covered (alpha > 0); empty when the file cannot be read.
std::vector<bool> covered_pixels(const fs::path& png) {
  const PngPixels pixels = read_png_rgba8(png.string());
  EXPECT_TRUE(pixels.error.empty()) << png << ": " << pixels.error;
  std::vector<bool> covered;
  for (std::size_t p = 3; p < pixels.rgba.size(); p += 4) covered.push_back(pixels.rgba[p] > 0);
  return covered;
}

std::size_t count(const std::vector<bool>& covered) {
  return static_cast<std::size_t>(std::count(covered.begin(), covered.end(), true));
}

TEST(AdaptorMpi, EmptyRankRendersTheOthersTets) {
  const SharedDir shared("empty");
  const std::string& dir = shared.path();
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(MPI_COMM_WORLD, dir);
  ASSERT_TRUE(a);
  MeshView view = scene.view();
  std::vector<FieldView> fields = scene.fields();
  if (rank() != 0) {
    view = {};
    fields = {FieldView::of("f", std::span<const double>()),
              FieldView::of("g", std::span<const double>())};
  }
  const Status status = a->execute(0, 0, view, fields);
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(a->finalize().ok());
  if (rank() != 0) return;
  const auto log = read_csv(dir + "/tetray_log.csv");
  ASSERT_EQ(log.size(), 2u);
  const ExpectedHits expected = expected_plane_hits();
  const auto hits = std::stoull(cell(log, 1, "hits"));
  EXPECT_GE(hits, expected.sure);
  EXPECT_LE(hits, expected.sure + expected.edge);
  EXPECT_EQ(cell(log, 1, "tets"), std::to_string(scene.mesh.tet_count()));
}

// The scene (with `scene_lines`) rendered by rank 0 alone and by every rank on its share of the
// tets, with global ids: each of `images` must be the same file both times.
void expect_split_mesh_gives_the_one_rank_images(const std::string& name,
                                                 const std::string& scene_lines,
                                                 const std::vector<std::string>& images) {
  const SharedDir shared(name);
  const std::string& dir = shared.path();
  const PlaneScene scene = make_plane_scene(6);
  if (rank() == 0) {
    auto single = make(MPI_COMM_SELF, dir + "/one", "", "", scene_lines);
    ASSERT_TRUE(single);
    ASSERT_TRUE(single->execute(0, 0, scene.view(), scene.fields()).ok());
    ASSERT_TRUE(single->finalize().ok());
  }
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::size_t tets = scene.mesh.tet_count();
  const std::size_t begin = tets * static_cast<std::size_t>(rank()) / size;
  const std::size_t end = tets * static_cast<std::size_t>(rank() + 1) / size;
  std::vector<std::int64_t> ids(end - begin);
  for (std::size_t t = begin; t < end; ++t) ids[t - begin] = static_cast<std::int64_t>(t);
  MeshView view = scene.view();
  view.tets = TetsView::of(
      std::span<const std::int64_t>(scene.mesh.tets).subspan(4 * begin, 4 * (end - begin)));
  view.tets.global_ids = ids.data();
  auto split = make(MPI_COMM_WORLD, dir + "/split", "", "", scene_lines);
  ASSERT_TRUE(split);
  const Status status = split->execute(0, 0, view, scene.fields());
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(split->finalize().ok());
  if (rank() != 0) return;
  for (const std::string& image : images) {
    const std::string one = slurp(dir + "/one/plane/" + image);
    ASSERT_FALSE(one.empty()) << image;
    EXPECT_EQ(one, slurp(dir + "/split/plane/" + image)) << image;
  }
}

TEST(AdaptorMpi, SplitMeshGivesTheOneRankImage) {
  expect_split_mesh_gives_the_one_rank_images("split", "", {"plane_000000.png"});
}

// Every view of an orbit is composited on its own, in the same order on every rank.
TEST(AdaptorMpi, SplitMeshGivesTheOneRankImageOfEveryView) {
  expect_split_mesh_gives_the_one_rank_images(
      "split_views", "    orbit: {azimuth: [0, 35], elevation: [0, 25]}\n",
      {"plane_000000_view000.png", "plane_000000_view001.png", "plane_000000_view002.png",
       "plane_000000_view003.png"});
}

TEST(AdaptorMpi, OneRanksBadInputIsEveryRanksError) {
  const SharedDir shared("bad");
  const std::string& dir = shared.path();
  PlaneScene scene = make_plane_scene(4);
  auto a = make(MPI_COMM_WORLD, dir);
  ASSERT_TRUE(a);
  const std::int64_t good = scene.mesh.tets[0];
  if (rank() == 1) scene.mesh.tets[0] = -4;
  Status status = a->execute(0, 0, scene.view(), scene.fields());
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_EQ(status.message.rfind("rank 1:", 0), 0u) << status.message;
  scene.mesh.tets[0] = good;
  status = a->execute(1, 1, scene.view(), scene.fields());
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(a->finalize().ok());
}

TEST(AdaptorMpi, WriterRankOneWritesTheImageOfWriterRankZero) {
  const SharedDir shared("writer");
  // Each rank its own output directory, so the files show which rank wrote them.
  const fs::path mine = fs::path(shared.path()) / ("rank" + std::to_string(rank()));
  const PlaneScene scene = make_plane_scene(6);
  const SlabPart part(scene);
  for (int writer : {0, 1}) {
    auto a = make(MPI_COMM_WORLD, (mine / ("writer" + std::to_string(writer))).string(),
                  ", writer_rank: " + std::to_string(writer));
    ASSERT_TRUE(a);
    const Status status = a->execute(0, 0, part.view(), scene.fields());
    ASSERT_TRUE(status.ok()) << status.message;
    ASSERT_TRUE(a->finalize().ok());
  }
  for (int writer : {0, 1}) {
    const fs::path out = mine / ("writer" + std::to_string(writer));
    EXPECT_EQ(fs::exists(out / "tetray_log.csv"), writer == rank()) << out;
    EXPECT_EQ(fs::exists(out / "plane/plane_000000.png"), writer == rank()) << out;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() != 1) return;
  const std::string by_rank_zero =
      slurp(fs::path(shared.path()) / "rank0/writer0/plane/plane_000000.png");
  ASSERT_FALSE(by_rank_zero.empty());
  EXPECT_EQ(by_rank_zero, slurp(mine / "writer1/plane/plane_000000.png"));
  EXPECT_EQ(read_csv((mine / "writer1/tetray_log.csv").string()).size(), 2u);
}

TEST(AdaptorMpi, WriterRankOutsideTheCommunicatorIsAConfigError) {
  Status status;
  const auto a = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config("unused", ", writer_rank: " + std::to_string(world_size())),
      status);
  EXPECT_FALSE(a);
  EXPECT_EQ(status.code, StatusCode::config_error);
  EXPECT_NE(status.message.find("<yaml string>:1:"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("output.writer_rank"), std::string::npos) << status.message;
}

TEST(AdaptorMpi, PerRankImagesShowEachRanksPartOfTheComposite) {
  const SharedDir shared("per_rank");
  const fs::path dir = shared.path();
  const PlaneScene scene = make_plane_scene(6);
  const SlabPart part(scene);
  auto a = make(MPI_COMM_WORLD, dir.string(), ", per_rank_images: true", "trigger: {every: 2}\n");
  ASSERT_TRUE(a);
  for (int step = 0; step <= 2; ++step) {
    const Status status = a->execute(step, step, part.view(), scene.fields());
    ASSERT_TRUE(status.ok()) << status.message;
  }
  ASSERT_TRUE(a->finalize().ok());
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() != 0) return;
  std::set<std::string> written;
  for (const auto& entry : fs::directory_iterator(dir / "plane/ranks"))
    written.insert(entry.path().filename().string());
  const std::set<std::string> expected = {"plane_000000_rank0000.png", "plane_000000_rank0001.png",
                                          "plane_000002_rank0000.png", "plane_000002_rank0001.png"};
  EXPECT_EQ(written, expected);
  for (const char* step : {"000000", "000002"}) {
    const std::vector<bool> composite =
        covered_pixels(dir / "plane" / ("plane_" + std::string(step) + ".png"));
    ASSERT_GT(count(composite), 0u);
    std::vector<bool> together(composite.size(), false);
    for (const char* r : {"0000", "0001"}) {
      const fs::path path =
          dir / "plane/ranks" / ("plane_" + std::string(step) + "_rank" + r + ".png");
      const std::vector<bool> own = covered_pixels(path);
      ASSERT_EQ(own.size(), composite.size()) << path;
      // A part, not the whole: something, less than the composite, and nothing outside it.
      EXPECT_GT(count(own), 0u) << path;
      EXPECT_LT(count(own), count(composite)) << path;
      for (std::size_t p = 0; p < own.size(); ++p) {
        EXPECT_TRUE(!own[p] || composite[p]) << path << " pixel " << p;
        together[p] = together[p] || own[p];
      }
    }
    EXPECT_EQ(together, composite) << "step " << step;
  }
}

}  // namespace
}  // namespace tetray::testing
