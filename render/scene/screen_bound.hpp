// The pixels a box can cover in a camera's image: what a rank tells the compositor about where
// its part of the mesh can have hits (render/composite, CompositeOptions::active_hint), so that
// a rank covering a corner of a large image scans that corner, not the image.
#pragma once

#include <optional>

#include "render/core/vec.hpp"
#include "render/scene/camera.hpp"

namespace tetray::render {

// Half-open pixel rectangle [x0, x1) x [y0, y1), clipped to the image.
struct ScreenRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Continuous pixel coordinates of a point (world), the inverse of CameraFrame::direction_at:
// pixel (i, j) has its center at (i + 0.5, j + 0.5). Nothing when the point is not in front
// of the eye, where a projection means nothing.
struct PixelPoint {
  double x = 0, y = 0;
};
std::optional<PixelPoint> pixel_position(const CameraFrame& frame, const Camera& camera,
                                         const Vec3d& point);

// Every pixel whose center ray meets the box [lo, hi] lies in the returned rectangle (with a
// margin of two pixels for rounding); nothing when a corner of the box is not in front of the
// eye, where a projection bounds nothing.
std::optional<ScreenRect> screen_bound(const Camera& camera, const Vec3d& lo, const Vec3d& hi);

}  // namespace tetray::render
