// The adaptor across ranks (run under mpirun -np 2): an empty rank, a mesh split over the ranks
// giving the same image as one rank, and one rank's bad input reaching every rank as an error
// instead of a hang.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <fstream>

#include "plane_scene.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// A directory made by rank 0, known to every rank, removed by rank 0 once all are done.
class SharedDir {
 public:
  explicit SharedDir(const std::string& name) {
    char path[256] = {};
    if (rank() == 0) {
      const fs::path dir =
          fs::temp_directory_path() / ("tetray_mpi_" + std::to_string(::getpid()) + name);
      fs::remove_all(dir);
      fs::create_directories(dir);
      std::snprintf(path, sizeof path, "%s", dir.c_str());
    }
    MPI_Bcast(path, sizeof path, MPI_CHAR, 0, MPI_COMM_WORLD);
    path_ = path;
  }
  ~SharedDir() {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank() == 0) fs::remove_all(path_);
  }
  SharedDir(const SharedDir&) = delete;
  SharedDir& operator=(const SharedDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::unique_ptr<Adaptor> make(MPI_Comm comm, const std::string& dir) {
  Status status;
  auto a = Adaptor::create_from_yaml(comm, plane_config(dir, ", formats: [png]"), status);
  EXPECT_TRUE(status.ok()) << status.message;
  return a;
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

TEST(AdaptorMpi, SplitMeshGivesTheOneRankImage) {
  const SharedDir shared("split");
  const std::string& dir = shared.path();
  const PlaneScene scene = make_plane_scene(6);
  if (rank() == 0) {
    auto single = make(MPI_COMM_SELF, dir + "/one");
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
  auto split = make(MPI_COMM_WORLD, dir + "/split");
  ASSERT_TRUE(split);
  const Status status = split->execute(0, 0, view, scene.fields());
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(split->finalize().ok());
  if (rank() != 0) return;
  const std::string one = slurp(dir + "/one/plane/plane_000000.png");
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(one, slurp(dir + "/split/plane/plane_000000.png"));
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

}  // namespace
}  // namespace tetray::testing
