#include "slab_partition.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace tetray::testing {

GyroidWithTemperature gyroid_with_temperature(const double (&c)[4]) {
  GyroidWithTemperature scene;
  const std::vector<double>& p = scene.gyroid.mesh.points;
  for (std::size_t k = 0; k < p.size(); k += 3)
    scene.temperature.push_back(c[0] + c[1] * p[k] + c[2] * p[k + 1] + c[3] * p[k + 2]);
  return scene;
}

void render_gyroid_with_temperature(MPI_Comm comm, const std::string& yaml,
                                    const GyroidWithTemperature& scene, const Slab& part) {
  TetsView tets = TetsView::of(std::span<const std::int64_t>(part.tets));
  tets.global_ids = part.ids.data();
  const MeshView mesh{PointsView::of(std::span<const double>(scene.gyroid.mesh.points)), tets};
  const FieldView fields[] = {
      FieldView::of("f", std::span<const double>(scene.gyroid.field)),
      FieldView::of("temperature", std::span<const double>(scene.temperature))};
  render_step_zero(comm, yaml, mesh, fields);
}

void render_step_zero(MPI_Comm comm, const std::string& yaml, const MeshView& mesh,
                      std::span<const FieldView> fields) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, yaml, status);
  ASSERT_TRUE(adaptor) << status.message;
  status = adaptor->execute(0, 0, mesh, fields);
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(adaptor->finalize().ok());
}

std::size_t differing_pixels(const PngPixels& a, const PngPixels& b) {
  std::size_t count = 0;
  for (std::size_t p = 0; p + 3 < a.rgba.size() && p + 3 < b.rgba.size(); p += 4)
    count += !std::equal(&a.rgba[p], &a.rgba[p + 4], &b.rgba[p]);
  return count;
}

}  // namespace tetray::testing
