// The pinhole camera of docs/architecture.md §3. Every part of tetray (tracer, reference
// intersector, benchmark references, tests) generates its rays here, so all of them agree on a
// pixel's ray.
#pragma once

#include <string>
#include <vector>

#include "render/core/vec.hpp"

namespace tetray::render {

struct Camera {
  Vec3d eye{0, 0, 5};
  Vec3d look_at{0, 0, 0};
  Vec3d up{0, 1, 0};
  double fov_deg = 40.0;
  int width = 512;
  int height = 512;
};

// The orthonormal frame and image-plane scale derived from a Camera.
struct CameraFrame {
  Vec3d eye;
  Vec3d forward, right, up;  // right = forward x up, up = right x forward
  double scale_x = 0;        // tan(fov/2) * W/H
  double scale_y = 0;        // tan(fov/2)

  // Unnormalized direction through continuous image coordinates (px, py) in pixels, where the
  // center of pixel (i, j) is (i + 0.5, j + 0.5).
  Vec3d direction_at(double px, double py, int width, int height) const;
};

// The field of view a camera may have, in degrees (wider than 179 makes tan(fov/2) explode).
inline constexpr double kMinFovDeg = 1;
inline constexpr double kMaxFovDeg = 179;

// `v` as a unit vector whatever its scale ([1e-300, 1e-300, 0] is [1, 1, 0] / sqrt(2)); the zero
// vector stays zero.
Vec3d unit_direction(Vec3d v);

// What makes a camera unusable, or empty: a part that is not finite, a field of view outside
// [kMinFovDeg, kMaxFovDeg], eye on look_at, up zero or within 1e-6 rad of the view direction
// (either way). Scale-free: [1e-300, 0, 0] is a direction like [1, 0, 0]. The one check of every
// camera a user gives (the config, its keyframes, tetray-render's options).
std::string camera_problem(const Camera& camera);

// Always finite: a degenerate camera (NaN, up zero or along the view) gives the frame of the
// default Camera{} with the same image size.
CameraFrame make_frame(const Camera& camera);

// The ray through image coordinates (px, py) runs along forward + column_slope right + row_slope
// up (direction_at).
double column_slope(const CameraFrame& frame, double px, int width);
double row_slope(const CameraFrame& frame, double py, int height);

// Normalized ray direction through the center of pixel (i, j), in double precision.
Vec3d pixel_direction(const CameraFrame& frame, const Camera& camera, int i, int j);

// The same directions for a whole frame in float, from a term per column and a term per row
// (each pixel_direction's terms rounded to float), so a packet's set-up costs an add and a
// normalization per ray, in float: normalize(column + row) lies within a few float ulps of
// pixel_direction(frame, camera, i, j), and every packet layout and tile computes it the same way.
// (In double, the set-up of the rays took 7% of the tiled frame at 1M tets; in float, half as
// much.) The column terms are stored x, y, z apart (a packet's row is then normalized in SIMD)
// and repeated past the last column for a packet's width, so a packet over the image edge
// repeats the edge column's rays.
struct PixelDirections {
  static constexpr int kPastEdge = 32;              // columns repeated past the last one
  std::vector<float> column_x, column_y, column_z;  // forward + ndc_x(i) right
  std::vector<Vec3f> row;                           // ndc_y(j) up

  PixelDirections(const CameraFrame& frame, const Camera& camera);
};

// Depth of docs/architecture.md §3: distance along the view axis.
inline double view_depth(const CameraFrame& frame, Vec3d hit) {
  return dot(hit - frame.eye, frame.forward);
}

// A camera that looks at the box [lo, hi] from direction `from_direction` (pointing from the
// target towards the eye) so that the whole box fits the vertical and horizontal field of view.
// An empty or non-finite box is fitted as [-1, 1]^3.
Camera fit_camera(Vec3d lo, Vec3d hi, Vec3d from_direction, Vec3d up, double fov_deg, int width,
                  int height);

}  // namespace tetray::render
