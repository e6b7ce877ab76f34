// A scene with an analytic answer for adaptor tests: the box [-1,1]^3 (Kuhn tets) carrying
// f = z, whose isosurface f = iso is the square z = iso, |x|, |y| <= 1, seen head-on by an
// explicit camera on the z axis. The number of pixels that see it follows from the camera alone.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {

inline constexpr int kImageWidth = 64;
inline constexpr int kImageHeight = 48;
inline constexpr double kIso = 0.25;

struct PlaneScene {
  BoxMesh mesh;
  std::vector<double> f;  // = z
  std::vector<double> g;  // = x, a second field (color_by)

  MeshView view() const;
  std::vector<FieldView> fields() const;
};

PlaneScene make_plane_scene(int cells);

// The YAML of one scene "plane" rendering f at kIso into `directory`, with more keys of the
// output map (e.g. ", writer_queue_depth: 0"), more top-level lines, and more scene lines
// (indented by 4 spaces).
std::string plane_config(const std::string& directory, const std::string& output_keys = "",
                         const std::string& top_lines = "", const std::string& scene_lines = "");

// The adaptor of `yaml` on MPI_COMM_WORLD; a failed create fails the test (and gives null).
std::unique_ptr<Adaptor> make_adaptor(const std::string& yaml);

// Step `step` of the scene at time 0.1 step.
Status run_plane_step(Adaptor& a, const PlaneScene& s, std::int64_t step, const Changes& c = {},
                      ExecuteReport* report = nullptr);

// Pixels whose ray surely hits the square, and those too close to its edge to call.
struct ExpectedHits {
  std::uint64_t sure = 0;
  std::uint64_t edge = 0;
};
ExpectedHits expected_plane_hits();

// The CSV rows of a file (header first), split into cells.
std::vector<std::vector<std::string>> read_csv(const std::string& path);
// The value of `column` in `row` of a CSV with `header`.
std::string cell(const std::vector<std::vector<std::string>>& csv, std::size_t row,
                 const std::string& column);

}  // namespace tetray::testing
