// The viewer page in headless Chromium: an orbit's images written by the adaptor, the page
// opened from disk with a first image chosen by URL parameters, one slider moved by the page's
// own input handler, the DOM dumped; the image the page then shows (and the browser loaded) must
// be the file the Cinema table lists for that time and view. Skipped when chromium is absent
// (scripts/setup.sh installs it, so CI runs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

std::string find_chromium() {
  for (const char* name : {"chromium", "chromium-browser"}) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path != nullptr ? path : "/usr/bin");
    for (std::string dir; std::getline(dirs, dir, ':');) {
      const fs::path candidate = fs::path(dir) / name;
      if (fs::exists(candidate)) return candidate.string();
    }
  }
  return {};
}

class Viewer : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = find_chromium();
    ASSERT_FALSE(chromium_.empty())
        << "chromium is not installed (scripts/setup.sh installs it): the viewer page cannot be "
           "tested";
    Status status;
    auto adaptor = Adaptor::create_from_yaml(
        MPI_COMM_WORLD, plane_config(out_.string(), "", "", "    orbit: {azimuth: [0, 90]}\n"),
        status);
    ASSERT_TRUE(adaptor) << status.message;
    for (int step : {0, 1, 2}) {
      ASSERT_TRUE(adaptor->execute(step, 0.5 * step, scene_.view(), scene_.fields()).ok());
    }
    ASSERT_TRUE(adaptor->finalize().ok());
  }

  // The page's DOM after it loaded with these URL parameters (and any slider move they ask).
  std::string dom(const std::string& query) {
    const fs::path dump = dir_.path() / "dom.html";
    const std::string command =
        "timeout 60 " + chromium_ +
        " --headless --no-sandbox --disable-gpu --disable-background-networking"
        " --disable-component-update --disable-sync --no-first-run --disable-dev-shm-usage"
        " --user-data-dir=" +
        (dir_.path() / "profile").string() + " --virtual-time-budget=10000 --dump-dom 'file://" +
        (out_ / "index.html").string() + "?" + query + "' > " + dump.string() + " 2> " +
        (dir_.path() / "chromium.log").string();
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return slurp(dump);
  }

  // The image the page shows: the src of #image once the browser has loaded it (empty while
  // none has).
  static std::string shown(const std::string& page) {
    const std::size_t image = page.find("id=\"image\"");
    if (image == std::string::npos) return "(no image element)";
    const std::size_t end = page.find('>', image);
    const std::size_t at = page.find("data-shown=\"", image);
    if (at == std::string::npos || at > end) return "(nothing loaded)";
    const std::size_t from = at + 12;
    return page.substr(from, page.find('"', from) - from);
  }

  ScratchDir dir_;
  const fs::path out_ = dir_.path() / "out";
  PlaneScene scene_ = make_plane_scene(2);
  std::string chromium_;
};

TEST_F(Viewer, TheTimeSliderShowsTheNextStepsImage) {
  EXPECT_EQ(shown(dom("scene=plane&time=1&view=1")), "plane.cdb/../plane/plane_000001_view001.png");
  EXPECT_EQ(shown(dom("scene=plane&time=1&view=1&move=time")),
            "plane.cdb/../plane/plane_000002_view001.png");
}

TEST_F(Viewer, TheViewSliderShowsTheNextView) {
  EXPECT_EQ(shown(dom("scene=plane&time=2&move=view")),
            "plane.cdb/../plane/plane_000002_view001.png");
}

TEST_F(Viewer, AMissingImageIsReportedNotShown) {
  fs::remove(out_ / "plane" / "plane_000000_view000.png");
  const std::string page = dom("scene=plane&time=0&view=0");
  EXPECT_EQ(shown(page), "");
  EXPECT_NE(page.find("cannot load plane.cdb/../plane/plane_000000_view000.png"),
            std::string::npos);
}

}  // namespace
}  // namespace tetray::testing
