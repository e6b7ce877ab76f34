// The packet frustum (render/packet_frustum.hpp) culls for whole packets, so it must be
// conservative: a tet or box it rejects is met by no pixel ray of the tile, checked here in
// double precision against every pixel's exact ray, on tets placed across the frustum's sides,
// far from the origin, behind the eye and beyond a depth bound. And it must cull what lies
// clearly outside, or it saves nothing. Every copy of the frustum's code is checked: the
// baseline's and each instruction-set variant's (culling_copies.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include "culling_copies.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/isopolygon.hpp"
#include "render/trace/packet_frustum.hpp"

namespace tetray::test {
namespace {

using render::Vec3d;
using render::Vec3f;
using Points = std::array<Vec3d, 4>;

constexpr int kTile = 16;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Four points relative to the eye, component c of point k at [c][k].
using Lanes = render::EyeRelativeTet;

// A tile of kTile x kTile pixels (its part in the image) and its frustum, made and tested by one
// copy of the frustum's code.
struct Tile {
  render::Camera camera;
  render::CameraFrame frame;
  Vec3f eye;  // the packet's float eye, relative to the origin
  int x0 = 0, y0 = 0;
  const render::CullingKernels* kernels = nullptr;
  render::PacketFrustum frustum;

  bool misses_hull(const Lanes& q) const { return kernels->misses_hull(frustum, q); }
  bool outside_depths(const Lanes& q, float tmax_bound) const {
    return kernels->outside_depths(frustum, q, tmax_bound);
  }
  bool misses_box(Vec3f lo, Vec3f hi) const { return kernels->misses_box(frustum, lo, hi); }
};

Tile make_tile(const render::CullingKernels& kernels, const render::Camera& camera, Vec3d origin,
               float magnitude, int x0, int y0) {
  Tile tile{camera, render::make_frame(camera), {}, x0, y0, &kernels, {}};
  tile.eye = static_cast<Vec3f>(camera.eye - origin);
  tile.frustum =
      kernels.packet_frustum(camera, tile.frame, x0, y0, std::min(x0 + kTile, camera.width) - 1,
                             std::min(y0 + kTile, camera.height) - 1, magnitude);
  return tile;
}

// Parameter interval [t_in, t_out] (t >= 0) of the ray inside the convex hull of a
// non-degenerate tet, from its four face planes; nullopt when the ray misses it.
std::optional<std::array<double, 2>> ray_in_tet(Vec3d eye, Vec3d d, const Points& p) {
  double t_in = 0, t_out = std::numeric_limits<double>::infinity();
  for (int face = 0; face < 4; ++face) {
    const Vec3d a = p[(face + 1) % 4], b = p[(face + 2) % 4], c = p[(face + 3) % 4];
    Vec3d n = cross(b - a, c - a);
    if (dot(n, p[face] - a) > 0) n = -n;  // outward: away from the opposite vertex
    const double along = dot(n, d), offset = dot(n, eye - a);
    if (along == 0) {
      if (offset > 0) return std::nullopt;
      continue;
    }
    const double t = -offset / along;
    if (along < 0) {
      t_in = std::max(t_in, t);
    } else {
      t_out = std::min(t_out, t);
    }
  }
  if (t_in > t_out) return std::nullopt;
  return std::array<double, 2>{t_in, t_out};
}

std::optional<std::array<double, 2>> ray_in_box(Vec3d eye, Vec3d d, Vec3d lo, Vec3d hi) {
  double t_in = 0, t_out = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double t0 = (lo[a] - eye[a]) / d[a], t1 = (hi[a] - eye[a]) / d[a];
    t_in = std::max(t_in, std::min(t0, t1));
    t_out = std::min(t_out, std::max(t0, t1));
  }
  if (t_in > t_out) return std::nullopt;
  return std::array<double, 2>{t_in, t_out};
}

// The renderer's own isopolygon of the tet for values `f` and isovalue 0, corners in double
// (a triangle repeats its first corner); empty when the tet holds none.
std::vector<Vec3d> renderer_isopolygon(const Points& p, const std::array<float, 4>& f) {
  render::TetVolume volume;
  for (int k = 0; k < 4; ++k) {
    const Vec3f v = static_cast<Vec3f>(p[k]);
    volume.vertices.push_back({v.x, v.y, v.z, f[k]});
  }
  const render::TetCorners corners = render::load_corners(volume, {{0, 1, 2, 3}});
  const int case_index = render::iso_case(corners, 0.0f);
  if (case_index == 0 || case_index == 15) return {};
  const render::Isopolygon poly = render::extract_isopolygon(corners, case_index, 0.0f);
  alignas(16) float lanes[3][4];
  for (int c = 0; c < 3; ++c) poly.xyz[c].store_aligned(lanes[c]);
  std::vector<Vec3d> polygon;
  for (int k = 0; k < 4; ++k) polygon.push_back({lanes[0][k], lanes[1][k], lanes[2][k]});
  return polygon;
}

// Parameter of the ray where it meets the convex polygon, as a point interval; nullopt when it
// misses it (or the polygon has no area).
std::optional<std::array<double, 2>> ray_in_polygon(Vec3d eye, Vec3d d,
                                                    const std::vector<Vec3d>& c) {
  if (c.empty()) return std::nullopt;
  const Vec3d normal = cross(c[2] - c[0], c[3] - c[1]);
  const double along = dot(normal, d);
  if (along == 0) return std::nullopt;
  const double t = dot(normal, c[0] - eye) / along;
  if (t < 0) return std::nullopt;
  const Vec3d x = eye + t * d;
  bool below = false, above = false;
  for (int k = 0; k < 4; ++k) {
    const double side = dot(cross(c[(k + 1) % 4] - c[k], x - c[k]), normal);
    below |= side < 0;
    above |= side > 0;
  }
  if (below && above) return std::nullopt;
  return std::array<double, 2>{t, t};
}

// The first pixel ray of the tile (with its parameter interval) that `meets` returns one for.
template <typename Meets>
std::string ray_that_meets(const Tile& tile, Meets&& meets) {
  const Vec3d eye = static_cast<Vec3d>(tile.eye);
  const int x1 = std::min(tile.x0 + kTile, tile.camera.width);
  const int y1 = std::min(tile.y0 + kTile, tile.camera.height);
  for (int j = tile.y0; j < y1; ++j)
    for (int i = tile.x0; i < x1; ++i) {
      const Vec3d d = render::pixel_direction(tile.frame, tile.camera, i, j);
      if (const auto t = meets(eye, d))
        return "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") t in [" +
               std::to_string((*t)[0]) + ", " + std::to_string((*t)[1]) + "]";
    }
  return "";
}

// q = p - eye in float, as the renderer computes it from float vertices.
void relative_lanes(const Points& p, Vec3f eye, Lanes& q) {
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) q[c][k] = static_cast<float>(p[k][c]) - eye[c];
}

// Whether the tet keeps a volume that its face planes resolve (rounding to float flattens tiny
// tets far from the origin; the face-plane test needs a solid).
bool is_solid(const Points& p) {
  double edge = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) edge = std::max(edge, length(p[a] - p[b]));
  return std::abs(dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0])) > 1e-6 * edge * edge * edge;
}

// Rounds the points to float, as the renderer stores them.
Points as_stored(Points p) {
  for (Vec3d& v : p) v = static_cast<Vec3d>(static_cast<Vec3f>(v));
  return p;
}

// A point at image position (px, py) in pixels and view depth `depth` from the camera's eye.
Vec3d at_pixel(const Tile& tile, double px, double py, double depth) {
  return tile.camera.eye +
         depth * tile.frame.direction_at(px, py, tile.camera.width, tile.camera.height);
}

// A small tet around a point: its size is `pixels` pixel footprints at that depth.
Points tet_around(const Tile& tile, Vec3d center, double depth, double pixels, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const double footprint = 2 * tile.frame.scale_y / tile.camera.height * std::abs(depth);
  Points p;
  for (Vec3d& v : p) v = center + pixels * footprint * Vec3d{unit(rng), unit(rng), unit(rng)};
  return p;
}

struct Counts {
  int culled = 0, tested = 0;
};

// Random tets around the tile's frustum, from behind the eye to depth `far`, of 0.02 to
// `pixels` pixel footprints: neither a culled tet's hull nor its isopolygon as the renderer
// computes it (whose corners may leave the hull by rounding) may be met by a ray.
void check_conservative(const Tile& tile, double far, double pixels, std::mt19937& rng,
                        Counts& counts, const std::string& label) {
  std::uniform_real_distribution<double> column(tile.x0 - 6.0, tile.x0 + kTile + 6.0);
  std::uniform_real_distribution<double> row(tile.y0 - 6.0, tile.y0 + kTile + 6.0);
  std::uniform_real_distribution<double> depth(-0.2 * far, far), size(0.02, pixels);
  std::uniform_real_distribution<float> value(-1, 1);
  for (int n = 0; n < 400; ++n) {
    const double z = depth(rng);
    const Points p =
        as_stored(tet_around(tile, at_pixel(tile, column(rng), row(rng), z), z, size(rng), rng));
    if (!is_solid(p)) continue;
    Lanes q;
    relative_lanes(p, tile.eye, q);
    ++counts.tested;
    if (!tile.misses_hull(q) && !tile.outside_depths(q, kInfinity)) continue;
    ++counts.culled;
    EXPECT_EQ(ray_that_meets(tile, [&](Vec3d e, Vec3d d) { return ray_in_tet(e, d, p); }), "")
        << label << ": a culled tet is met by a ray, tet " << n;
    const std::vector<Vec3d> polygon =
        renderer_isopolygon(p, {value(rng), value(rng), value(rng), value(rng)});
    EXPECT_EQ(ray_that_meets(tile, [&](Vec3d e, Vec3d d) { return ray_in_polygon(e, d, polygon); }),
              "")
        << label << ": a culled tet's isopolygon is met by a ray, tet " << n;
  }
}

std::vector<render::Camera> frustum_cameras() {
  std::vector<render::Camera> cameras;
  const double fovs[] = {20, 40, 100};
  const int sizes[][2] = {{1024, 1024}, {100, 37}, {40, 300}};
  const Vec3d eyes[] = {{2.5, 1.8, 3.2}, {-3, 0.2, 0.1}, {0.3, -4, 0.02}};
  for (int k = 0; k < 3; ++k) {
    render::Camera c;
    c.eye = eyes[k];
    c.look_at = {0.1, -0.2, 0.3};
    c.up = k == 2 ? Vec3d{0, 0, 1} : Vec3d{0, 1, 0};
    c.fov_deg = fovs[k];
    c.width = sizes[k][0];
    c.height = sizes[k][1];
    cameras.push_back(c);
  }
  return cameras;
}

// Tiles at the image's corners, edges (partial tiles) and inside.
std::vector<std::array<int, 2>> tile_corners(const render::Camera& c) {
  const int last_x = (c.width - 1) / kTile * kTile, last_y = (c.height - 1) / kTile * kTile;
  return {{0, 0},
          {last_x, last_y},
          {last_x / 2 / kTile * kTile, 0},
          {last_x / 2 / kTile * kTile, last_y / 2 / kTile * kTile}};
}

class PacketFrustum : public CullingCopies {};
TETRAY_FOR_EACH_CULLING_COPY(PacketFrustum);

TEST_P(PacketFrustum, CulledTetsAreMetByNoRay) {
  std::mt19937 rng(5);
  Counts counts;
  for (const render::Camera& camera : frustum_cameras())
    for (const auto& corner : tile_corners(camera)) {
      const Tile tile = make_tile(kernels(), camera, {}, 10.0f, corner[0], corner[1]);
      check_conservative(tile, 3.0, 3.0, rng, counts,
                         "tile " + std::to_string(corner[0]) + "," + std::to_string(corner[1]));
    }
  // Most of the tets lie beside the tile, outside it by up to 6 pixels.
  EXPECT_GT(counts.culled, counts.tested / 3);
}

// Far from the origin float coordinates are coarse: at 1e5 an ulp is 0.008, the footprint of
// 10 pixels at depth 1 here, so isopolygon corners leave their tet's hull by many pixels'
// footprints and the slack must cover that.
TEST_P(PacketFrustum, CulledTetsAreMetByNoRayFarFromTheOrigin) {
  std::mt19937 rng(9);
  Counts counts;
  for (const double offset : {1e3, 1e5}) {
    for (render::Camera camera : frustum_cameras()) {
      const Vec3d shift{offset, -0.7 * offset, 0.4 * offset};
      camera.eye = camera.eye + shift;
      camera.look_at = camera.look_at + shift;
      for (const auto& corner : tile_corners(camera)) {
        const Tile tile = make_tile(kernels(), camera, {}, static_cast<float>(1.1 * offset),
                                    corner[0], corner[1]);
        check_conservative(tile, 30.0, 20.0, rng, counts, "far tile");
      }
    }
  }
  EXPECT_GT(counts.culled, counts.tested / 3);
}

TEST_P(PacketFrustum, CullsTetsClearlyOutsideBehindAndBeyond) {
  std::mt19937 rng(3);
  const render::Camera camera = frustum_cameras()[0];
  const Tile tile = make_tile(kernels(), camera, {}, 10.0f, 512, 256);
  std::uniform_real_distribution<double> along(0, kTile), away(2.5, 12), depth(0.5, 3);
  const double x0 = tile.x0, y0 = tile.y0, x1 = x0 + kTile, y1 = y0 + kTile;
  for (int n = 0; n < 200; ++n) {
    // A tet of at most one pixel, at least 2.5 pixels beside one side of the tile's pixel
    // centers (which span [x0 + 0.5, x1 - 0.5]).
    const double z = depth(rng), a = along(rng), b = away(rng);
    const double positions[4][2] = {{x0 + 0.5 - b, y0 + a},
                                    {x1 - 0.5 + b, y0 + a},
                                    {x0 + a, y0 + 0.5 - b},
                                    {x0 + a, y1 - 0.5 + b}};
    const auto& pixel = positions[n % 4];
    const Points p = as_stored(tet_around(tile, at_pixel(tile, pixel[0], pixel[1], z), z, 1, rng));
    Lanes q;
    relative_lanes(p, tile.eye, q);
    EXPECT_TRUE(tile.misses_hull(q)) << "side " << n % 4;
  }
  // Behind the eye, across the view axis (outside no single side plane).
  const Points behind =
      as_stored(tet_around(tile, at_pixel(tile, x0 + 8, y0 + 8, -1), -1, 40, rng));
  Lanes q;
  relative_lanes(behind, tile.eye, q);
  EXPECT_TRUE(tile.outside_depths(q, kInfinity));
  // In the middle of the tile at depth 2: beyond a bound of 1.5, not beyond 2.5.
  const Points ahead = as_stored(tet_around(tile, at_pixel(tile, x0 + 8, y0 + 8, 2), 2, 3, rng));
  relative_lanes(ahead, tile.eye, q);
  EXPECT_FALSE(tile.misses_hull(q));
  EXPECT_FALSE(tile.outside_depths(q, kInfinity));
  EXPECT_TRUE(tile.outside_depths(q, 1.5f));
  EXPECT_FALSE(tile.outside_depths(q, 2.5f));
}

TEST_P(PacketFrustum, CulledBoxesAreMetByNoRay) {
  std::mt19937 rng(11);
  int culled = 0;
  for (const render::Camera& camera : frustum_cameras())
    for (const auto& corner : tile_corners(camera)) {
      const Tile tile = make_tile(kernels(), camera, {}, 10.0f, corner[0], corner[1]);
      std::uniform_real_distribution<double> column(tile.x0 - 30.0, tile.x0 + kTile + 30.0);
      std::uniform_real_distribution<double> row(tile.y0 - 30.0, tile.y0 + kTile + 30.0);
      std::uniform_real_distribution<double> depth(0.2, 3.0), size(0.1, 20);
      for (int n = 0; n < 300; ++n) {
        const double z = depth(rng);
        const Points p =
            tet_around(tile, at_pixel(tile, column(rng), row(rng), z), z, size(rng), rng);
        Vec3f lo{kInfinity, kInfinity, kInfinity}, hi = -lo;
        for (const Vec3d& v : p) {
          lo = render::min(lo, static_cast<Vec3f>(v));
          hi = render::max(hi, static_cast<Vec3f>(v));
        }
        if (!tile.misses_box(lo - tile.eye, hi - tile.eye)) continue;
        ++culled;
        const Vec3d lo_d = static_cast<Vec3d>(lo), hi_d = static_cast<Vec3d>(hi);
        EXPECT_EQ(
            ray_that_meets(tile, [&](Vec3d e, Vec3d d) { return ray_in_box(e, d, lo_d, hi_d); }),
            "")
            << "a culled box is met by a ray";
      }
    }
  EXPECT_GT(culled, 100);
}

}  // namespace
}  // namespace tetray::test
