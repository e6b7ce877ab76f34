#include "adaptor/step/probes.hpp"

#include <limits>

#include "adaptor/input/input_views.hpp"
#include "adaptor/output/line_file.hpp"
#include "adaptor/output/probe_files.hpp"
#include "render/parallel/owner_reduce.hpp"
#include "render/walk/point_locate.hpp"

namespace tetray {
namespace {

double field_value(const FieldView& field, std::size_t point) {
  if (point >= field.count) return std::numeric_limits<double>::quiet_NaN();
  return field.type == ScalarType::float32 ? static_cast<const float*>(field.values)[point]
                                           : static_cast<const double*>(field.values)[point];
}

// This rank's answers for one set: held[i] and, if so, the fields at point i.
void sample_locally(const config::ProbeSet& set, const FieldVolume& volume,
                    std::span<const FieldView> fields, std::vector<std::uint8_t>& held,
                    std::vector<double>& values) {
  const render::TetVolume& store = volume.volume();
  const std::vector<std::size_t> point_of = render::vertex_points(store);
  std::vector<FieldView> views;
  for (const std::string& name : set.fields) views.push_back(field_or_empty(fields, name));
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const std::optional<render::PointLocation> at =
        render::locate_point(store, volume.bvh(), set.points[i] - store.origin);
    if (!at) continue;
    held[i] = 1;
    const render::Tet& tet = store.tets[at->tet];
    for (std::size_t f = 0; f < views.size(); ++f) {
      double sum = 0;
      for (int c = 0; c < 4; ++c) {
        if (at->weight[c] == 0) continue;
        sum += at->weight[c] * field_value(views[f], point_of[tet.v[c]]);
      }
      values[i * views.size() + f] = sum;
    }
  }
}

}  // namespace

std::string ProbeSampler::prepare(const std::string& directory) const {
  return write_probe_headers(directory, sets_);
}

std::string ProbeSampler::sample(const Communicator& comm, int root, const FieldVolume* volume,
                                 std::span<const FieldView> fields, std::int64_t step, double time,
                                 const std::string& directory) const {
  std::string error;
  for (const config::ProbeSet& set : sets_) {
    std::vector<std::uint8_t> held(set.points.size(), 0);
    std::vector<double> values(set.points.size() * set.fields.size(), 0.0);
    if (volume != nullptr && error.empty()) {
      const Status local = guarded("probes", [&] {
        sample_locally(set, *volume, fields, held, values);
        return Status::success();
      });
      if (!local.ok()) {
        error = local.message;
        std::fill(held.begin(), held.end(), std::uint8_t{0});
      }
    }
    if (comm.size > 1) {
      const int rc =
          render::gather_from_lowest_holder(held, values, set.fields.size(), root, comm.comm);
      if (rc != MPI_SUCCESS) return "gathering probe set '" + set.name + "': " + mpi_error_text(rc);
    }
    if (comm.rank != root || !error.empty()) continue;
    error = append_probe_rows(directory, set, step, time, held, values);
  }
  return error;
}

}  // namespace tetray
