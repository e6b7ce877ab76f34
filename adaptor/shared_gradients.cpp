#include "shared_gradients.hpp"

#include <algorithm>

#include "collective.hpp"
#include "render/update/vertex_gradients.hpp"
#include "render/walk/face_adjacency.hpp"

namespace tetray {
namespace {

// The caller's points on the boundary faces of the rank's tets, ascending.
std::vector<std::uint32_t> boundary_points(const render::TetVolume& volume) {
  const auto adjacency = render::build_face_adjacency<render::Tet16>(volume);
  const std::vector<std::size_t> point = render::vertex_points(volume);
  std::vector<std::uint32_t> points;
  points.reserve(3 * adjacency.boundary.size());
  for (const render::BoundaryFaceRef& face : adjacency.boundary) {
    for (std::uint32_t c = 0; c < 4; ++c) {
      if (c != face.opposite)
        points.push_back(static_cast<std::uint32_t>(point[volume.tets[face.tet].v[c]]));
    }
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

template <typename T>
render::PointKey key_of(const T* xyz, std::uint32_t p) {
  const auto exact = [](T c) { return c == 0 ? 0.0 : static_cast<double>(c); };
  return {exact(xyz[3 * p]), exact(xyz[3 * p + 1]), exact(xyz[3 * p + 2])};
}

std::uint32_t vertex_of(const render::TetVolume& volume, std::uint32_t point) {
  return volume.point_vertex.empty() ? point : volume.point_vertex[point];
}

// A vertex's values as a row of `combine_shared`'s exchange.
template <typename T, std::size_t W>
std::span<T> row_of(std::array<T, W>& values) {
  return values;
}
inline std::span<std::int32_t> row_of(std::int32_t& value) { return {&value, 1}; }

// Replaces the per-vertex values of the shared points by what `combine` makes of them over the
// ranks.
template <typename V, typename Combine>
int combine_shared(const render::TetVolume& volume, std::span<const std::uint32_t> points,
                   render::LargeArray<V>& per_vertex, Combine&& combine) {
  V probe{};  // per_vertex may be empty
  using T = typename decltype(row_of(probe))::element_type;
  const std::size_t width = row_of(probe).size();
  std::vector<T> values;
  values.reserve(width * points.size());
  for (std::uint32_t p : points) {
    const std::span<T> row = row_of(per_vertex[vertex_of(volume, p)]);
    values.insert(values.end(), row.begin(), row.end());
  }
  if (int rc = combine(std::span<T>(values), width); rc != MPI_SUCCESS) return rc;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::copy_n(&values[width * i], width,
                row_of(per_vertex[vertex_of(volume, points[i])]).begin());
  }
  return MPI_SUCCESS;
}

std::string failed(const char* what, int rc) {
  return std::string("smooth shading: ") + what + ": " + mpi_error_text(rc);
}

}  // namespace

std::string SharedGradients::match(const render::TetVolume& volume, const PointsView& points,
                                   MPI_Comm comm) {
  std::vector<std::uint32_t> candidates = boundary_points(volume);
  // A step that brings fewer points than the volume knows keeps the others' values (volume
  // update): they are not matched.
  std::erase_if(candidates, [&](std::uint32_t p) { return p >= points.count; });
  std::vector<render::PointKey> keys(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    keys[i] = points.type == ScalarType::float32
                  ? key_of(static_cast<const float*>(points.xyz), candidates[i])
                  : key_of(static_cast<const double*>(points.xyz), candidates[i]);
  }
  if (int rc = shared_.build(keys, comm); rc != MPI_SUCCESS) return failed("matching", rc);
  points_.clear();
  for (std::uint32_t i : shared_.shared()) points_.push_back(candidates[i]);
  return {};
}

std::string SharedGradients::compute(render::TetVolume& volume) const {
  render::LargeArray<render::VertexExponents> exponents;
  render::LargeArray<std::int32_t> tet_counts;
  render::LargeArray<render::VertexSums> sums;
  render::gradient_exponents(volume, exponents, tet_counts);
  const auto max = [&](auto values, std::size_t width) { return shared_.max(values, width); };
  const auto sum = [&](auto values, std::size_t width) { return shared_.sum(values, width); };
  int rc = combine_shared(volume, points_, exponents, max);
  if (rc != MPI_SUCCESS) return failed("exponents", rc);
  rc = combine_shared(volume, points_, tet_counts, sum);
  if (rc != MPI_SUCCESS) return failed("tet counts", rc);
  render::gradient_sums(volume, exponents, tet_counts, sums);
  rc = combine_shared(volume, points_, sums, sum);
  if (rc != MPI_SUCCESS) return failed("sums", rc);
  render::gradients_from_sums(volume, exponents, sums);
  return {};
}

}  // namespace tetray
