// The instruction-set variants of a dispatch build (cmake/TetrayIsa.cmake) against each other:
// the kernels promise bitwise the same results for every SIMD width (render/core/simd.hpp: the
// same IEEE operations, no fused multiply-add), so the benchmark scene of docs/architecture.md §6
// must give the same bounds and the same image bytes with every variant the CPU supports.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "render/isa/isa.hpp"
#include "support/render_fixtures.hpp"

namespace tetray {
namespace {

using render::isa::Isa;

// What one variant computed: the BVH's node bounds after its build and refit, and the images.
struct VariantResult {
  render::LargeArray<render::BvhNode> nodes;
  std::vector<render::Framebuffer> images;
};

template <typename T, typename Allocator>
bool same_bytes(const std::vector<T, Allocator>& a, const std::vector<T, Allocator>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

VariantResult run_variant(const BoxMesh& mesh, const std::vector<double>& field) {
  VariantResult result;
  test::RenderScene scene = test::load_scene(mesh.points, mesh.tets, field);
  // A refit of the scalar ranges alone, as after a field-only step.
  render::refit_bvh(scene.volume, scene.bvh, false);
  result.nodes = scene.bvh.nodes;
  const std::vector<double> isovalues = {-0.3, 0.0, 0.4};
  const std::vector<render::IsoSurface> surfaces = test::make_surfaces(isovalues);
  const render::Camera camera = test::benchmark_camera(test::scaled_side(256));
  for (render::PacketSize packet : render::kPacketSizes)
    result.images.push_back(test::trace_image(scene, camera, surfaces, packet));
  return result;
}

class IsaVariants : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(render::isa::dispatched()) << "registered in dispatch builds only";
  }
  void TearDown() override {
    if (render::isa::dispatched()) render::isa::activate(initial_);
  }
  const Isa initial_ = render::isa::active();
};

TEST_F(IsaVariants, EverySupportedVariantGivesTheSameBoundsAndImageBytes) {
  const GyroidTwist scene = test::gyroid(24);
  std::vector<Isa> ran;
  std::vector<VariantResult> results;
  for (Isa isa : render::isa::kIsas) {
    if (!render::isa::cpu_supports(isa)) continue;
    ASSERT_TRUE(render::isa::activate(isa)) << render::isa::to_string(isa);
    ASSERT_EQ(render::isa::active(), isa);
    ran.push_back(isa);
    results.push_back(run_variant(scene.mesh, scene.field));
  }
  ASSERT_FALSE(ran.empty()) << "the CPU supports no variant";
  const VariantResult& first = results.front();
  ASSERT_GT(first.nodes.size(), 1u);
  for (std::size_t k = 1; k < results.size(); ++k) {
    const char* name = render::isa::to_string(ran[k]);
    EXPECT_TRUE(same_bytes(results[k].nodes, first.nodes))
        << name << " vs " << render::isa::to_string(ran[0]) << ": BVH bounds";
    for (std::size_t p = 0; p < first.images.size(); ++p) {
      const render::Framebuffer& a = results[k].images[p];
      const render::Framebuffer& b = first.images[p];
      const char* packet = render::to_string(render::kPacketSizes[p]);
      EXPECT_TRUE(same_bytes(a.rgba, b.rgba)) << name << ", packet " << packet << ": colors";
      EXPECT_TRUE(same_bytes(a.depth, b.depth)) << name << ", packet " << packet << ": depth";
      EXPECT_TRUE(same_bytes(a.hit, b.hit)) << name << ", packet " << packet << ": hit keys";
    }
  }
}

// The image must not be empty: equal blank images would prove nothing.
TEST_F(IsaVariants, TheComparedImageShowsTheSurfaces) {
  const GyroidTwist scene = test::gyroid(12);
  const VariantResult result = run_variant(scene.mesh, scene.field);
  const render::Framebuffer& image = result.images.back();
  std::size_t hits = 0;
  for (std::uint32_t key : image.hit) hits += key != render::kNoHit;
  EXPECT_GT(hits, image.hit.size() / 4);
}

TEST_F(IsaVariants, ActivateRefusesNothingTheCpuSupportsAndKeepsTheChoice) {
  for (Isa isa : render::isa::kIsas) {
    const Isa before = render::isa::active();
    const bool taken = render::isa::activate(isa);
    EXPECT_EQ(taken, render::isa::cpu_supports(isa)) << render::isa::to_string(isa);
    EXPECT_EQ(render::isa::active(), taken ? isa : before);
  }
}

TEST(IsaNames, ParseTakesExactlyTheNamesToStringGives) {
  for (Isa isa : render::isa::kIsas)
    EXPECT_EQ(render::isa::parse(render::isa::to_string(isa)), isa);
  EXPECT_FALSE(render::isa::parse("AVX2"));
  EXPECT_FALSE(render::isa::parse("avx"));
  EXPECT_FALSE(render::isa::parse(""));
  EXPECT_FALSE(render::isa::parse("sse4_2"));
}

}  // namespace
}  // namespace tetray
