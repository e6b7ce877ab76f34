// A short soak (tools/soak runs the long one): 200 rendered steps with moving points, images and
// rows written each step, and the open file descriptors do not grow. A leak of one descriptor
// per step, or per file written, would show as hundreds.
#include <gtest/gtest.h>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"
#include "tools/soak/process_usage.hpp"

namespace tetray::testing {
namespace {

constexpr int kSteps = 200;

std::size_t open_fds() { return tools::process_usage().open_fds; }

// Renders kSteps steps, the points shifted a little each step; the descriptors open after each.
std::vector<std::size_t> fds_per_step(Adaptor& adaptor) {
  PlaneScene scene = make_plane_scene(2);
  const auto fields = scene.fields();
  std::vector<std::size_t> fds;
  for (int step = 0; step < kSteps; ++step) {
    for (std::size_t p = 0; p < scene.mesh.point_count(); ++p) scene.mesh.points[3 * p] += 1e-4;
    const Status status =
        adaptor.execute(step, 0.1 * step, scene.view(), fields, {true, step % 50 == 0, false});
    EXPECT_TRUE(status.ok()) << status.message;
    fds.push_back(open_fds());
  }
  return fds;
}

// Writing inside execute: nothing is in flight between calls, so the count is exact.
TEST(DescriptorLeak, InlineWriterKeepsTheCountFlat) {
  const ScratchDir dir;
  Status status;
  auto adaptor = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(dir.path().string(), ", writer_queue_depth: 0"), status);
  ASSERT_TRUE(adaptor) << status.message;
  const std::vector<std::size_t> fds = fds_per_step(*adaptor);
  EXPECT_EQ(fds.back(), fds.front());
  EXPECT_EQ(*std::max_element(fds.begin(), fds.end()), fds.front());
}

// Through the writer thread: one file may be open mid-write at any call; after finalize and
// the adaptor's end, the process holds what it held before it.
TEST(DescriptorLeak, WriterThreadReturnsEveryDescriptor) {
  const ScratchDir dir;
  const std::size_t before = open_fds();
  {
    Status status;
    auto adaptor =
        Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config(dir.path().string()), status);
    ASSERT_TRUE(adaptor) << status.message;
    const std::vector<std::size_t> fds = fds_per_step(*adaptor);
    EXPECT_LE(*std::max_element(fds.begin(), fds.end()), fds.front() + 1);
    EXPECT_TRUE(adaptor->finalize().ok());
  }
  EXPECT_EQ(open_fds(), before);
}

}  // namespace
}  // namespace tetray::testing
