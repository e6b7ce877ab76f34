#include "plane_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "render/scene/camera.hpp"

namespace tetray::testing {

MeshView PlaneScene::view() const {
  return {PointsView::of(std::span<const double>(mesh.points)),
          TetsView::of(std::span<const std::int64_t>(mesh.tets))};
}

std::vector<FieldView> PlaneScene::fields() const {
  return {FieldView::of("f", std::span<const double>(f)),
          FieldView::of("g", std::span<const double>(g))};
}

PlaneScene make_plane_scene(int cells) {
  PlaneScene s;
  s.mesh = make_box_mesh({{cells, cells, cells}});
  for (std::size_t p = 0; p < s.mesh.point_count(); ++p) {
    s.f.push_back(s.mesh.points[3 * p + 2]);
    s.g.push_back(s.mesh.points[3 * p]);
  }
  return s;
}

std::string plane_config(const std::string& directory, const std::string& output_keys,
                         const std::string& top_lines, const std::string& scene_lines) {
  return "output: {directory: " + directory + ", quiet: true" + output_keys + "}\n" + top_lines +
         "scenes:\n"
         "  - name: plane\n"
         "    field: f\n"
         "    isovalues: [" +
         std::to_string(kIso) +
         "]\n"
         "    camera: {eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: " +
         std::to_string(kImageWidth) + ", height: " + std::to_string(kImageHeight) + "}\n" +
         scene_lines;
}

ExpectedHits expected_plane_hits() {
  render::Camera camera;
  camera.eye = {0, 0, 5};
  camera.width = kImageWidth;
  camera.height = kImageHeight;
  const render::CameraFrame frame = render::make_frame(camera);
  ExpectedHits hits;
  for (int j = 0; j < kImageHeight; ++j) {
    for (int i = 0; i < kImageWidth; ++i) {
      const render::Vec3d d = render::pixel_direction(frame, camera, i, j);
      const double s = (kIso - camera.eye.z) / d.z;
      const double reach = std::max(std::abs(s * d.x), std::abs(s * d.y));
      if (reach < 1 - 1e-3)
        ++hits.sure;
      else if (reach <= 1 + 1e-3)
        ++hits.edge;
    }
  }
  return hits;
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string c; std::getline(fields, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

std::string cell(const std::vector<std::vector<std::string>>& csv, std::size_t row,
                 const std::string& column) {
  const auto& header = csv.at(0);
  const auto at = std::find(header.begin(), header.end(), column);
  if (at == header.end() || row >= csv.size()) return "<missing>";
  return csv[row].at(static_cast<std::size_t>(at - header.begin()));
}

std::unique_ptr<Adaptor> make_adaptor(const std::string& yaml) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status);
  EXPECT_TRUE(status.ok()) << status.message;
  return adaptor;
}

Status run_plane_step(Adaptor& a, const PlaneScene& s, std::int64_t step, const Changes& c,
                      ExecuteReport* report) {
  const auto fields = s.fields();
  return a.execute(step, 0.1 * static_cast<double>(step), s.view(), fields, c, report);
}

}  // namespace tetray::testing
