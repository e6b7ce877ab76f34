#include "render/walk/entry_bins.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "render/scene/screen_bound.hpp"
#include "render/walk/face_crossing.hpp"

namespace tetray::render {
namespace {

// Whether a ray from `eye` (local) can enter the domain through the face: the eye is not on
// the tet's side of the face's plane (rounding taken generously: a face seen edge-on is kept).
bool faces_eye(const TetVolume& volume, const BoundaryFace& face, Vec3d eye) {
  const Vec3d a = vertex_position(volume, face.vertex[0]);
  const Vec3d n = cross(vertex_position(volume, face.vertex[1]) - a,
                        vertex_position(volume, face.vertex[2]) - a);
  const Vec3d inward = dot(n, vertex_position(volume, face.opposite_vertex) - a) > 0 ? n : -1.0 * n;
  const Vec3d to_eye = eye - a;
  return dot(inward, to_eye) <= 1e-9 * length(inward) * length(to_eye);
}

struct TileRect {
  int x0, y0, x1, y1;  // tiles, inclusive
};

// Where a face projects: tiles, nowhere a ray from the eye can reach it (every corner behind
// the eye), or across the eye's plane (it projects nowhere: every ray must test it).
enum class Placement { tiles, behind, across };

// The tiles a triangle of points in front of the eye covers: the pixel rectangle of its corners'
// projections (pixel_position), widened by a thousandth of a pixel for rounding.
Placement place(const CameraFrame& frame, const Camera& camera, const Vec3d (&corner)[3],
                TileRect& tiles) {
  int behind = 0;
  for (const Vec3d& point : corner) {
    const Vec3d d = point - frame.eye;
    behind += dot(d, frame.forward) < -1e-6 * std::max(1.0, length(d));
  }
  if (behind == 3) return Placement::behind;
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (const Vec3d& point : corner) {
    const std::optional<PixelPoint> at = pixel_position(frame, camera, point);
    if (!at) return Placement::across;
    x_lo = std::min(x_lo, at->x);
    x_hi = std::max(x_hi, at->x);
    y_lo = std::min(y_lo, at->y);
    y_hi = std::max(y_hi, at->y);
  }
  // Pixel i's ray passes through x = i + 0.5: the pixels whose centres lie in the rectangle.
  constexpr double kMargin = 1e-3;
  const double i0 = std::ceil(x_lo - kMargin - 0.5), i1 = std::floor(x_hi + kMargin - 0.5);
  const double j0 = std::ceil(y_lo - kMargin - 0.5), j1 = std::floor(y_hi + kMargin - 0.5);
  if (i1 < 0 || j1 < 0 || i0 > camera.width - 1 || j0 > camera.height - 1 || i0 > i1 || j0 > j1) {
    tiles = {0, 0, -1, -1};  // no pixel's centre
    return Placement::tiles;
  }
  const auto tile = [](double pixel, int size) {
    return static_cast<int>(std::clamp(pixel, 0.0, size - 1.0)) / EntryBins::kTile;
  };
  tiles = {tile(i0, camera.width), tile(j0, camera.height), tile(i1, camera.width),
           tile(j1, camera.height)};
  return Placement::tiles;
}

}  // namespace

EntryBins bin_entry_faces(const TetVolume& volume, const BoundaryFaces& boundary,
                          const Camera& camera) {
  EntryBins bins;
  bins.tiles_x = (camera.width + EntryBins::kTile - 1) / EntryBins::kTile;
  bins.tiles_y = (camera.height + EntryBins::kTile - 1) / EntryBins::kTile;
  const std::size_t tiles = static_cast<std::size_t>(bins.tiles_x) * bins.tiles_y;
  const CameraFrame frame = make_frame(camera);
  const Vec3d eye = camera.eye - volume.origin;
  // Each facing face's tiles, then a counting sort into the tiles in face order.
  std::vector<std::pair<std::uint32_t, TileRect>> placed;
  std::uint64_t total = 0;
  for (std::uint32_t f = 0; f < boundary.faces.size(); ++f) {
    const BoundaryFace& face = boundary.faces[f];
    if (!faces_eye(volume, face, eye)) continue;
    Vec3d corner[3];
    for (int c = 0; c < 3; ++c) corner[c] = vertex_position(volume, face.vertex[c]) + volume.origin;
    TileRect t{};
    const Placement where = place(frame, camera, corner, t);
    if (where == Placement::behind) continue;
    if (where == Placement::across) {
      bins.everywhere.push_back(f);
      continue;
    }
    if (t.x0 > t.x1) continue;  // between pixel centres or off the image
    placed.push_back({f, t});
    total +=
        static_cast<std::uint64_t>(t.x1 - t.x0 + 1) * static_cast<std::uint64_t>(t.y1 - t.y0 + 1);
  }
  // Faces spread over many tiles (slivers across the image, faces near the eye) would make the
  // lists larger than the tree is worth: the rays then search the tree. Below the cap every
  // count fits the 32-bit offsets.
  if (total > 16 * (static_cast<std::uint64_t>(boundary.faces.size()) + tiles) ||
      total > std::numeric_limits<std::uint32_t>::max()) {
    return EntryBins{};
  }
  const auto for_each_tile = [&](const TileRect& t, auto&& visit) {
    for (int y = t.y0; y <= t.y1; ++y) {
      for (int x = t.x0; x <= t.x1; ++x) visit(static_cast<std::size_t>(y * bins.tiles_x + x));
    }
  };
  bins.begin.assign(tiles + 1, 0);
  for (const auto& entry : placed)
    for_each_tile(entry.second, [&](std::size_t k) { ++bins.begin[k + 1]; });
  for (std::size_t k = 0; k < tiles; ++k) bins.begin[k + 1] += bins.begin[k];
  bins.faces.resize(bins.begin[tiles]);
  std::vector<std::uint32_t> cursor(bins.begin.begin(), bins.begin.end() - 1);
  for (const auto& [f, t] : placed) {
    for_each_tile(t, [&, face = f](std::size_t k) { bins.faces[cursor[k]++] = face; });
  }
  return bins;
}

}  // namespace tetray::render
