#include "render/parallel/shared_gradients.hpp"

#include <algorithm>

#include "render/update/vertex_gradients.hpp"
#include "render/walk/face_adjacency.hpp"

namespace tetray::render {
namespace {

// The caller's points on the boundary faces of the rank's tets, ascending.
std::vector<std::uint32_t> boundary_points(const TetVolume& volume) {
  const auto adjacency = build_face_adjacency<Tet16>(volume);
  const std::vector<std::size_t> point = vertex_points(volume);
  std::vector<std::uint32_t> points;
  points.reserve(3 * adjacency.boundary.size());
  for (const BoundaryFaceRef& face : adjacency.boundary) {
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
PointKey key_of(const T* xyz, std::uint32_t p) {
  const auto exact = [](T c) { return c == 0 ? 0.0 : static_cast<double>(c); };
  return {exact(xyz[3 * p]), exact(xyz[3 * p + 1]), exact(xyz[3 * p + 2])};
}

std::uint32_t vertex_of(const TetVolume& volume, std::uint32_t point) {
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
int combine_shared(const TetVolume& volume, std::span<const std::uint32_t> points,
                   LargeArray<V>& per_vertex, Combine&& combine) {
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

ProtocolStatus failed(const char* what, int rc) {
  return mpi_failure(std::string("smooth shading: ") + what, rc);
}

}  // namespace

ProtocolStatus SharedGradients::match(const TetVolume& volume, const PointSource& points,
                                      MPI_Comm comm) {
  std::vector<std::uint32_t> candidates = boundary_points(volume);
  // A step that brings fewer points than the volume knows keeps the others' values (volume
  // update): they are not matched.
  std::erase_if(candidates, [&](std::uint32_t p) { return p >= points.count; });
  std::vector<PointKey> keys(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    keys[i] = points.xyz_kind == ScalarKind::f32
                  ? key_of(static_cast<const float*>(points.xyz), candidates[i])
                  : key_of(static_cast<const double*>(points.xyz), candidates[i]);
  }
  if (int rc = shared_.build(keys, comm); rc != MPI_SUCCESS) return failed("matching", rc);
  points_.clear();
  for (std::uint32_t i : shared_.shared()) points_.push_back(candidates[i]);
  return ProtocolStatus::success();
}

ProtocolStatus SharedGradients::compute(TetVolume& volume, std::span<const float> isovalues) const {
  std::vector<std::uint8_t> needed = vertices_of_surfaces(volume, isovalues);
  if (!needed.empty())
    for (std::uint32_t p : points_) needed[vertex_of(volume, p)] = 1;
  LargeArray<VertexExponents> exponents;
  LargeArray<std::int32_t> tet_counts;
  LargeArray<VertexSums> sums;
  const GradientPlan plan = plan_gradients(volume, needed);
  gradient_exponents(volume, plan, exponents, tet_counts);
  const auto max = [&](auto values, std::size_t width) { return shared_.max(values, width); };
  const auto sum = [&](auto values, std::size_t width) { return shared_.sum(values, width); };
  int rc = combine_shared(volume, points_, exponents, max);
  if (rc != MPI_SUCCESS) return failed("exponents", rc);
  rc = combine_shared(volume, points_, tet_counts, sum);
  if (rc != MPI_SUCCESS) return failed("tet counts", rc);
  gradient_sums(volume, plan, exponents, tet_counts, sums);
  rc = combine_shared(volume, points_, sums, sum);
  if (rc != MPI_SUCCESS) return failed("sums", rc);
  gradients_from_sums(volume, exponents, sums, needed);
  return ProtocolStatus::success();
}

}  // namespace tetray::render
