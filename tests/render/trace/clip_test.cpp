// Clipping (Wald et al. 2007, §7) against the double-precision reference with the same region:
// hits outside the kept region are discarded and the ray goes on to the surfaces behind the cut;
// every packet size gives the same image; subtrees outside are skipped (fewer isopolygons).
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

const int kWidth = scaled_side(80);
const int kHeight = scaled_side(60);

render::ClipRegion half_box() {
  render::ClipRegion clip;
  clip.has_box = true;
  clip.box_lo = {-1.2, -1.2, -1.2};
  clip.box_hi = {0.05, 1.2, 1.2};  // keeps x <= 0.05: about half the mesh
  return clip;
}

render::ClipRegion box_and_planes() {
  render::ClipRegion clip;
  clip.has_box = true;
  clip.box_lo = {-0.8, -0.9, -0.7};
  clip.box_hi = {0.9, 0.6, 0.8};
  clip.planes[0] = {{0.1, 0.0, 0.2}, {1, 1, 1}};      // cuts away the corner towards the eye
  clip.planes[1] = {{0.0, -0.3, 0.0}, {0, -1, 0.3}};  // and the bottom
  clip.plane_count = 2;
  return clip;
}

render::Framebuffer trace_clipped(const RenderScene& scene, const render::Camera& camera,
                                  std::span<const render::IsoSurface> surfaces,
                                  const render::ClipRegion& clip, render::PacketSize packet,
                                  render::TraceStats* stats = nullptr) {
  render::TraceOptions options;
  options.packet = packet;
  options.clip = clip;
  options.collect_stats = stats != nullptr;
  return render::trace(scene.volume, scene.bvh, camera, surfaces, options, stats);
}

void expect_clipped_agreement(const render::ClipRegion& clip, const std::string& label) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const double isovalues[] = {0.0, 0.5};
  const auto surfaces = make_surfaces(isovalues);
  const ReferenceIntersector reference(scene.volume, isovalues_of(surfaces), clip);
  int index = 0;
  for (const render::Camera& camera : standard_cameras(kWidth, kHeight)) {
    const std::string name = label + " camera " + std::to_string(index++);
    const auto image = trace_clipped(scene, camera, surfaces, clip, render::PacketSize::p16x16);
    const auto counts =
        compare_with_reference(image, reference.trace_image(camera), surfaces, name);
    std::cout << "[ agreement ] " << name << ": " << counts.summary() << "\n";
    EXPECT_EQ(counts.failures(), 0u) << name << ": " << counts.summary();
    EXPECT_GT(counts.reference_hits, 0u) << name;
    for (const render::PacketSize packet : render::kPacketSizes) {
      EXPECT_EQ(image_difference(image, trace_clipped(scene, camera, surfaces, clip, packet)), "")
          << name << " packet " << render::to_string(packet);
    }
  }
}

TEST(Clip, BoxAgreesWithTheReference) { expect_clipped_agreement(half_box(), "half box"); }

TEST(Clip, BoxAndPlanesAgreeWithTheReference) {
  expect_clipped_agreement(box_and_planes(), "box and planes");
}

// The cut must show what lies behind it: pixels whose nearest unclipped hit is cut away but
// that still hit something.
TEST(Clip, RaysGoOnBehindTheCut) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  const render::Camera camera = benchmark_camera(64);
  const auto whole = trace_clipped(scene, camera, surfaces, {}, render::PacketSize::p16x16);
  const auto cut = trace_clipped(scene, camera, surfaces, half_box(), render::PacketSize::p16x16);
  std::size_t seen_behind = 0;
  for (std::size_t p = 0; p < whole.pixel_count(); ++p) {
    seen_behind += whole.hit[p] != render::kNoHit && cut.hit[p] != render::kNoHit &&
                   cut.depth[p] > whole.depth[p];
  }
  EXPECT_GT(seen_behind, whole.pixel_count() / 20);
}

TEST(Clip, SubtreesOutsideAreSkipped) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  const render::Camera camera = benchmark_camera(64);
  render::TraceStats whole, cut;
  trace_clipped(scene, camera, surfaces, {}, render::PacketSize::p16x16, &whole);
  trace_clipped(scene, camera, surfaces, box_and_planes(), render::PacketSize::p16x16, &cut);
  // Rays behind the cut visit more of the mesh; the skipped subtrees must more than pay for it.
  EXPECT_LT(cut.isopolygon_extractions, whole.isopolygon_extractions);
}

}  // namespace
}  // namespace tetray::test
