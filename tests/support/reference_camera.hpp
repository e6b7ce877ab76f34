// The pinhole camera of docs/architecture.md §3 written out a second time, in double precision,
// for the reference intersector: it uses the renderer's Camera only as the scene's description
// and none of the renderer's camera or vector code, so a wrong frame in the renderer (a flipped
// up vector, a swapped axis) shows as a disagreement instead of being shared by both sides.
#pragma once

#include "render/core/vec.hpp"
#include "render/scene/camera.hpp"

namespace tetray::test {

using render::Vec3d;

class ReferenceCamera {
 public:
  explicit ReferenceCamera(const render::Camera& camera);

  Vec3d eye() const { return eye_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Unit direction of the ray through the centre of pixel (i, j), i the column from the left and
  // j the row from the top.
  Vec3d pixel_direction(int i, int j) const;
  // Distance of `point` along the view axis (docs/architecture.md §3, depth).
  double depth(Vec3d point) const;

 private:
  Vec3d eye_, forward_, right_, up_;
  double tan_half_fov_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace tetray::test
