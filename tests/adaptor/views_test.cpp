// Orbit views through the adaptor: a half turn about up mirrors a scene symmetric under it, a
// view equals the explicit camera it stands for, and the Cinema table (spec D) lists one row per
// view with its time, phi, theta, scene, step and files, replaced, not doubled, when a step is
// rendered again. An elevation reaching the pole of up fails creation. Keyframed camera paths:
// at a keyframe's time, halfway between two and outside their span the image is byte for byte
// the explicit camera's, and a bad path fails creation naming the key and the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "plane_scene.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// The plane z = 0 of f = z (inside the tets of a 3-cell box, not on their faces), colored by
// g = x, seen head-on from z = 5; `camera` and `orbit` lines replace or add to that (an empty
// `camera`: no camera key).
std::string config(const fs::path& out, const std::string& scene_lines,
                   const std::string& camera =
                       "{eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0], "
                       "fov_deg: 40}") {
  return "output: {directory: " + out.string() +
         ", quiet: true}\n"
         "scenes:\n"
         "  - name: plane\n"
         "    field: f\n"
         "    isovalues: [0]\n"
         "    color_by: g\n"
         "    colormap: coolwarm\n"
         "    color_range: [-1, 1]\n" +
         (camera.empty() ? "" : "    camera: " + camera + "\n") +
         "    image: {width: 64, height: 48}\n" + scene_lines;
}

class Views : public ::testing::Test {
 protected:
  Status run(const std::string& yaml, const std::vector<int>& steps = {1}) {
    Status status;
    auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status);
    if (!adaptor) return status;
    for (int step : steps) {
      status = adaptor->execute(step, 0.5 * step, scene_.view(), scene_.fields());
      if (!status.ok()) return status;
    }
    return adaptor->finalize();
  }

  static PngPixels view_image(const fs::path& out, int step, int view) {
    const std::string name =
        "plane_00000" + std::to_string(step) + "_view00" + std::to_string(view) + ".png";
    return read_png_rgba8((out / "plane" / name).string());
  }

  ScratchDir dir_;
  PlaneScene scene_ = make_plane_scene(3);
};

// Pixels whose RGBA differs by more than 2 levels in some channel between a(x, y) and
// b(mirror ? W-1-x : x, y).
int differing_pixels(const PngPixels& a, const PngPixels& b, bool mirror) {
  int count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const int bx = mirror ? a.width - 1 - x : x;
      const std::size_t p = 4 * (static_cast<std::size_t>(y) * a.width + x);
      const std::size_t q = 4 * (static_cast<std::size_t>(y) * b.width + bx);
      bool differs = false;
      for (int c = 0; c < 4; ++c) differs = differs || std::abs(a.rgba[p + c] - b.rgba[q + c]) > 2;
      count += differs;
    }
  }
  return count;
}

TEST_F(Views, HalfTurnMirrorsASymmetricScene) {
  const fs::path out = dir_.path() / "out";
  const Status status = run(config(out, "    orbit: {azimuth: [0, 180]}\n"));
  ASSERT_TRUE(status.ok()) << status.message;
  const PngPixels front = view_image(out, 1, 0), back = view_image(out, 1, 1);
  ASSERT_TRUE(front.error.empty() && back.error.empty()) << front.error << back.error;
  // Seen from behind, x runs the other way: the back view is the front view mirrored. The front
  // view itself is far from mirror-symmetric (blue at -x, red at +x), so this is no accident.
  EXPECT_EQ(differing_pixels(front, back, true), 0);
  EXPECT_GT(differing_pixels(front, front, true), front.width * front.height / 8);
}

// The image of an explicit camera with its eye at `eye`, written under `out`.
std::string explicit_camera(double x, double y, double z) {
  char camera[160];
  std::snprintf(camera, sizeof camera,
                "{eye: [%.17g, %.17g, %.17g], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}", x,
                y, z);
  return camera;
}

TEST_F(Views, AViewIsTheCameraItStandsFor) {
  const fs::path orbit = dir_.path() / "orbit";
  ASSERT_TRUE(run(config(orbit, "    orbit: {azimuth: [30], elevation: [30]}\n")).ok());
  // phi 30 about +y turns +z towards +x; theta 30 raises the eye towards +y.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const PngPixels viewed = view_image(orbit, 1, 0);
  ASSERT_TRUE(viewed.error.empty()) << viewed.error;
  const auto image_from = [&](const char* name, double x, double y, double z) {
    const fs::path out = dir_.path() / name;
    EXPECT_TRUE(run(config(out, "", explicit_camera(x, y, z))).ok());
    return read_png_rgba8((out / "plane" / "plane_000001.png").string());
  };
  const PngPixels same = image_from("same", 5 * c * s, 5 * s, 5 * c * c);
  EXPECT_LE(differing_pixels(viewed, same, false), viewed.width * viewed.height / 200);
  // The test tells the angles apart: with either sign turned the other way, the image changes.
  for (const auto& [name, x, y] :
       {std::tuple{"below", 5 * c * s, -5 * s}, std::tuple{"left", -5 * c * s, 5 * s}}) {
    const PngPixels other = image_from(name, x, y, 5 * c * c);
    EXPECT_GT(differing_pixels(viewed, other, false), viewed.width * viewed.height / 50) << name;
  }
}

TEST_F(Views, CinemaTableListsEveryView) {
  const fs::path out = dir_.path() / "out";
  const std::string yaml = config(out, "    orbit: {azimuth: [0, 90, 180], elevation: [0, 30]}\n");
  ASSERT_TRUE(run(yaml, {0, 1}).ok());
  ASSERT_TRUE(run(yaml, {1}).ok());  // rendered again: its rows replaced
  const fs::path table = out / "plane.cdb" / "data.csv";
  const auto rows = read_csv(table.string());
  ASSERT_EQ(rows.size(), 1u + 2u * 6u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"time", "phi", "theta", "scene", "step", "FILE",
                                               "FILE_exr"}));
  std::set<std::string> seen;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const std::string step = cell(rows, r, "step");
    EXPECT_EQ(cell(rows, r, "time"), step == "0" ? "0" : "0.5");
    EXPECT_EQ(cell(rows, r, "scene"), "plane");
    const std::string phi = cell(rows, r, "phi"), theta = cell(rows, r, "theta");
    EXPECT_TRUE(phi == "0" || phi == "90" || phi == "180") << phi;
    EXPECT_TRUE(theta == "0" || theta == "30") << theta;
    // Elevation-major: view = 3 * (theta index) + (phi index).
    const int view = (theta == "30" ? 3 : 0) + (phi == "0" ? 0 : phi == "90" ? 1 : 2);
    const std::string stem = "../plane/plane_00000" + step + "_view00" + std::to_string(view);
    EXPECT_EQ(cell(rows, r, "FILE"), stem + ".png");
    EXPECT_EQ(cell(rows, r, "FILE_exr"), stem + ".exr");
    EXPECT_TRUE(fs::is_regular_file(out / "plane.cdb" / (stem + ".png")));
    EXPECT_TRUE(seen.insert(stem).second) << "listed twice: " << stem;
  }
  // One log row per rendered view: 12 of the first run, 6 of the second. The BVH is built once
  // per step, charged to the first view; the other views only trace from it.
  const auto log = read_csv((out / "tetray_log.csv").string());
  ASSERT_EQ(log.size(), 1u + 18u);
  int bvh_rows = 0;
  for (std::size_t r = 1; r < log.size(); ++r) {
    bvh_rows += cell(log, r, "bvh_update") != "none" || cell(log, r, "bvh_ms") != "0.000";
  }
  EXPECT_GE(bvh_rows, 2);  // each run builds the BVH at its first step
  EXPECT_LE(bvh_rows, 3);  // at most once per step: never per view
}

TEST_F(Views, WithoutAnOrbitTheTableHasTheCamerasView) {
  const fs::path out = dir_.path() / "out";
  ASSERT_TRUE(run(config(out, "")).ok());
  const auto rows = read_csv((out / "plane.cdb" / "data.csv").string());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(cell(rows, 1, "phi"), "0");
  EXPECT_EQ(cell(rows, 1, "theta"), "0");
  EXPECT_EQ(cell(rows, 1, "FILE"), "../plane/plane_000001.png");
}

TEST_F(Views, ElevationAtThePoleFailsCreation) {
  Status status;
  const std::string yaml = config(dir_.path() / "x", "    orbit: {elevation: [0, 89.5]}\n",
                                  "{eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0]}");
  EXPECT_EQ(Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status), nullptr);
  EXPECT_NE(status.message.find("orbit.elevation[1]"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("pole"), std::string::npos) << status.message;
}

// Two cameras far enough apart that their images differ in most pixels: A head-on with a narrow
// field of view, B from above right, rolled 45 degrees about its view and wider. Halfway between
// them (eye, look_at and fov averaged, up renormalized) every number is exact in binary, so the
// interpolated camera and the explicit one are the same bits.
const std::string kCameraA = "eye: [0, 0, 5], look_at: [0, 0, 0], up: [-1, 1, 0], fov_deg: 30";
const std::string kCameraB = "eye: [2, 1, 3], look_at: [0.5, 0, 0], up: [1, 1, 0], fov_deg: 50";
const std::string kCameraHalfway =
    "eye: [1, 0.5, 4], look_at: [0.25, 0, 0], up: [0, 1, 0], fov_deg: 40";

// The scene lines of a camera path through A at time `ta` and B at time `tb`.
std::string path_a_to_b(double ta, double tb) {
  return "    camera_path:\n      keyframes:\n        - {time: " + std::to_string(ta) + ", " +
         kCameraA + "}\n        - {time: " + std::to_string(tb) + ", " + kCameraB + "}\n";
}

class CameraPaths : public Views {
 protected:
  // The image of step `step` under `out` (a scene without an orbit).
  static PngPixels step_image(const fs::path& out, int step) {
    return read_png_rgba8(
        (out / "plane" / ("plane_00000" + std::to_string(step) + ".png")).string());
  }

  // The image of the explicit camera `camera` (one step, written under `name`).
  PngPixels explicit_image(const char* name, const std::string& camera) {
    const fs::path out = dir_.path() / name;
    EXPECT_TRUE(run(config(out, "", "{" + camera + "}")).ok());
    return step_image(out, 1);
  }

  // Renders the path through A at `ta` and B at `tb` at `steps` (time 0.5 x step).
  fs::path run_path(double ta, double tb, const std::vector<int>& steps) {
    const fs::path out = dir_.path() / "path";
    const Status status = run(config(out, path_a_to_b(ta, tb), ""), steps);
    EXPECT_TRUE(status.ok()) << status.message;
    return out;
  }

  void expect_same(const PngPixels& a, const PngPixels& b, const char* what) {
    ASSERT_TRUE(a.error.empty() && b.error.empty()) << what << ": " << a.error << b.error;
    EXPECT_EQ(a.width, b.width) << what;
    EXPECT_TRUE(a.rgba == b.rgba) << what << ": " << differing_pixels(a, b, false)
                                  << " pixels differ";
  }
};

TEST_F(CameraPaths, AtAKeyframesTimeTheImageIsItsCamera) {
  const fs::path out = run_path(0.5, 1.5, {1, 3});  // times 0.5 and 1.5
  const PngPixels a = explicit_image("a", kCameraA), b = explicit_image("b", kCameraB);
  expect_same(step_image(out, 1), a, "step 1, keyframe A");
  expect_same(step_image(out, 3), b, "step 3, keyframe B");
  EXPECT_GT(differing_pixels(a, b, false), a.width * a.height / 4);  // the test tells them apart
  // One view per step: Cinema's phi and theta are 0, the camera's motion is in `time`.
  const auto rows = read_csv((out / "plane.cdb" / "data.csv").string());
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(cell(rows, r, "phi"), "0");
    EXPECT_EQ(cell(rows, r, "theta"), "0");
  }
}

TEST_F(CameraPaths, HalfwayTheImageIsTheInterpolatedCamera) {
  const fs::path out = run_path(0, 1, {1});  // time 0.5
  const PngPixels halfway = explicit_image("halfway", kCameraHalfway);
  expect_same(step_image(out, 1), halfway, "step 1, halfway");
  for (const auto& [name, camera] : {std::pair{"a", kCameraA}, std::pair{"b", kCameraB}}) {
    const PngPixels end = explicit_image(name, camera);
    EXPECT_GT(differing_pixels(halfway, end, false), halfway.width * halfway.height / 20) << name;
  }
}

TEST_F(CameraPaths, OutsideTheKeyframesTheEndKeyframeHolds) {
  const fs::path out = run_path(1, 2, {0, 1, 6});  // times 0, 0.5 (both before) and 3 (after)
  const PngPixels a = explicit_image("a", kCameraA);
  expect_same(step_image(out, 0), a, "step 0, before A");
  expect_same(step_image(out, 1), a, "step 1, before A");
  expect_same(step_image(out, 6), explicit_image("b", kCameraB), "step 6, after B");
}

// Written to a file: the message names the file, the key and the problem.
std::string create_error(const fs::path& file, const std::string& yaml) {
  std::FILE* f = std::fopen(file.string().c_str(), "w");
  if (f == nullptr) return "cannot write " + file.string();
  std::fputs(yaml.c_str(), f);
  std::fclose(f);
  Status status;
  const auto adaptor = Adaptor::create(MPI_COMM_WORLD, file.string(), status);
  return adaptor ? std::string("created") : status.message;
}

TEST_F(CameraPaths, ABadPathFailsCreationNamingTheKeyAndFile) {
  const std::string a = "{time: 0, " + kCameraA + "}", b = "{time: 1, " + kCameraB + "}";
  const auto path = [](const std::vector<std::string>& keyframes) {
    std::string lines = "    camera_path:\n      keyframes:\n";
    for (const std::string& k : keyframes) lines += "        - " + k + "\n";
    return lines;
  };
  const std::string key = "scenes[0].camera_path.keyframes";
  const struct {
    std::string scene_lines, camera, key, words;
  } cases[] = {
      {path({a}), "", key, "give 2 to"},
      {path({b, a}), "", key + "[1].time", "strictly increasing"},
      {path({a, "{time: 0, " + kCameraB + "}"}), "", key + "[1].time", "strictly increasing"},
      {path({a, "{time: 1, eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 0, 2]}"}), "", key + "[1]",
       "parallel to up"},
      {path({a, "{time: 1, eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 0, 0]}"}), "",
       key + "[1].up", "zero vector"},
      // Up turns through zero halfway between the keyframes.
      {path({"{time: 0, eye: [0, 0, 5], look_at: [0, 0, 0], up: [1, 0, 0]}",
             "{time: 1, eye: [0, 0, 5], look_at: [0, 0, 0], up: [-1, 0, 0]}"}),
       "", key + "[1]", "at time 0.5"},
      {path({a, "{eye: [0, 0, 5], look_at: [0, 0, 0]}"}), "", key + "[1].time", "missing"},
      {path({a, b}) + "    orbit: {azimuth: [0, 90]}\n", "", "scenes[0].orbit",
       "not allowed with camera_path"},
      {path({a, b}), "{eye: [0, 0, 5], look_at: [0, 0, 0]}", "scenes[0].camera",
       "not allowed with camera_path"},
  };
  const fs::path file = dir_.path() / "bad_path.yaml";
  for (const auto& c : cases) {
    const std::string message =
        create_error(file, config(dir_.path() / "x", c.scene_lines, c.camera));
    EXPECT_NE(message.find(file.string() + ":"), std::string::npos) << message;
    EXPECT_NE(message.find(c.key + ": "), std::string::npos) << c.key << " | " << message;
    EXPECT_NE(message.find(c.words), std::string::npos) << c.words << " | " << message;
  }
  // The good path of the same lines is created.
  EXPECT_EQ(create_error(file, config(dir_.path() / "x", path({a, b}), "")), "created");
}

}  // namespace
}  // namespace tetray::testing
