// Checks the mini-solver's first `skin` image against the geometry of its beam: the scene is the
// 0.5 level set of the interior indicator (1 at interior points, 0 on the boundary) on the box
// [lo, hi] cut into a grid of cells of size h, undeformed at step 0. On a cell with a boundary
// face the linear interpolant is at most the linear ramp from 0 on that face to 1 a cell inside,
// and it is 1 on every cell whose corners are all interior; so the solid the level set bounds
// holds the box [lo + h, hi - h] and lies in [lo + h/2, hi - h/2]. Every pixel whose ray (the
// reference camera of tests/support) meets the inner box must be covered in the PNG, and every
// pixel whose ray misses the outer box must be background.
//
// skin_check PNG EYE(3) LOOK_AT(3) UP(3) FOV_DEG LO(3) HI(3) CELLS(3); exits 1 on a failed check.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "support/png_read.hpp"
#include "support/reference_camera.hpp"

namespace {

using tetray::render::Vec3d;

struct Box {
  Vec3d lo, hi;
};

// The slab test: whether the ray from `eye` along `direction` meets the box at some t >= 0.
bool ray_meets(const Box& box, Vec3d eye, Vec3d direction) {
  double near = 0, far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double t0 = (box.lo[axis] - eye[axis]) / direction[axis];
    const double t1 = (box.hi[axis] - eye[axis]) / direction[axis];
    near = std::max(near, std::min(t0, t1));
    far = std::min(far, std::max(t0, t1));
  }
  return near <= far;
}

Box grown(const Box& box, const Vec3d& by) {
  Box b = box;
  for (int axis = 0; axis < 3; ++axis) {
    b.lo[axis] -= by[axis];
    b.hi[axis] += by[axis];
  }
  return b;
}

Vec3d vector_at(char** argv, int first) {
  return {std::atof(argv[first]), std::atof(argv[first + 1]), std::atof(argv[first + 2])};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 21) {
    std::fprintf(stderr,
                 "usage: skin_check PNG EYE(3) LOOK_AT(3) UP(3) FOV LO(3) HI(3) CELLS(3)\n");
    return 2;
  }
  const tetray::testing::PngPixels png = tetray::testing::read_png_rgba8(argv[1]);
  if (!png.error.empty()) {
    std::fprintf(stderr, "skin_check: %s\n", png.error.c_str());
    return 1;
  }
  tetray::render::Camera camera;
  camera.eye = vector_at(argv, 2);
  camera.look_at = vector_at(argv, 5);
  camera.up = vector_at(argv, 8);
  camera.fov_deg = std::atof(argv[11]);
  camera.width = png.width;
  camera.height = png.height;
  const Box beam{vector_at(argv, 12), vector_at(argv, 15)};
  const Vec3d cells = vector_at(argv, 18);
  Vec3d h;
  for (int axis = 0; axis < 3; ++axis) h[axis] = (beam.hi[axis] - beam.lo[axis]) / cells[axis];
  // A margin of 1e-6 of a cell keeps pixels whose ray grazes a box out of both checks.
  const Box inner = grown(beam, -(1 + 1e-6) * h), outer = grown(beam, -(0.5 - 1e-6) * h);

  const tetray::test::ReferenceCamera rays(camera);
  int must_cover = 0, may_cover = 0, covered = 0, wrong = 0;
  for (int j = 0; j < png.height; ++j) {
    for (int i = 0; i < png.width; ++i) {
      const Vec3d d = rays.pixel_direction(i, j);
      const bool in_inner = ray_meets(inner, camera.eye, d);
      const bool in_outer = ray_meets(outer, camera.eye, d);
      const bool is_covered = png.rgba[4 * (static_cast<std::size_t>(j) * png.width + i) + 3] > 0;
      must_cover += in_inner;
      may_cover += in_outer;
      covered += is_covered;
      if ((in_inner && !is_covered) || (!in_outer && is_covered)) {
        if (wrong++ < 5) {
          std::fprintf(stderr, "skin_check: pixel (%d, %d) is %s\n", i, j,
                       is_covered ? "covered outside the outer box" : "empty inside the inner box");
        }
      }
    }
  }
  std::printf("skin_check: %d pixels covered; %d must be, at most %d may be; %d wrong\n", covered,
              must_cover, may_cover, wrong);
  return wrong == 0 && must_cover > 0 ? 0 : 1;
}
