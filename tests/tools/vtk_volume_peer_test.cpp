// tetray-bench's VTK volume-rendering peer on a tiny scene: without a display it is skipped with a
// message saying why; under Xvfb (Mesa's llvmpipe) each VTK mapper renders and VTK's ray caster,
// an independent implementation of the same emission-absorption model, agrees with tetray's image
// to a few 8-bit levels on average. VTK's projected tetrahedra approximate the integral, so only
// their presence is checked.
#include <gtest/gtest.h>
#include <json/json.h>

#include <cstdlib>
#include <string>

#include "support/json_output.hpp"

namespace tetray::testing {
namespace {

// The bench on a tiny scene; the image is large enough that the silhouette, where the two
// renderers' entries differ most, is a small part of it.
std::string tiny_bench(int cells, int pixels) {
  return std::string(TETRAY_BENCH_EXECUTABLE) + " --sizes " + std::to_string(cells) +
         " --size-px " + std::to_string(pixels) + " --steps 1 --threads 2";
}

TEST(VtkVolumePeer, WithoutADisplayItIsSkippedSayingWhy) {
  const Json::Value root =
      run_for_json("env -u DISPLAY " + tiny_bench(4, 32), "tetray_vtk_peer_none.json");
  const Json::Value& peer = root["scenes"][0]["walk"]["vtk_volume"];
  EXPECT_NE(peer["skipped"].asString().find("no X display"), std::string::npos) << peer;
  EXPECT_FALSE(peer.isMember("runs"));
}

// Registered in the unsanitized build only: the sanitized bench would run Mesa's JIT-compiled
// rasterizer under AddressSanitizer, not tetray's code, and far slower.
TEST(VtkVolumePeerUnderXvfb, TheRayCasterAgreesWithTetray) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0)
      << "xvfb-run is not installed (scripts/setup.sh installs Debian's xvfb): no display";
  // Mesa's and X's own allocations outlive main (no leak check); a hung X server ends.
  const Json::Value root = run_for_json(
      "ASAN_OPTIONS=detect_leaks=0 xvfb-run -a -s '-screen 0 640x480x24' " + tiny_bench(6, 128),
      "tetray_vtk_peer_xvfb.json");
  const Json::Value& peer = root["scenes"][0]["walk"]["vtk_volume"];
  ASSERT_FALSE(peer.isMember("skipped")) << peer;
  ASSERT_EQ(peer["runs"].size(), 3u) << peer;
  EXPECT_GT(peer["tetray_no_termination_ms"].asDouble(), 0);
  for (const Json::Value& run : peer["runs"]) {
    EXPECT_GT(run["render_ms"].asDouble(), 0) << run;
    const bool ray_cast = run["mapper"].asString().rfind("ray cast", 0) == 0;
    if (ray_cast) {
      EXPECT_LT(run["mean_rgb_difference"].asDouble(), 0.012) << run;
    }
    EXPECT_GT(run["max_rgb_difference"].asDouble(), 0) << run;  // VTK's image, not tetray's
  }
}

}  // namespace
}  // namespace tetray::testing
