#include "ball_image.h"

#include <math.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

int64_t tetray_ball_point_count(int cells) {
  const int64_t side = cells + 1;
  return side * side * side;
}

int64_t tetray_ball_tet_count(int cells) { return 6 * (int64_t)cells * cells * cells; }

static int64_t point_index(int cells, int i, int j, int k) {
  return ((int64_t)k * (cells + 1) + j) * (cells + 1) + i;
}

void tetray_ball_mesh(int cells, double* xyz, int64_t* tets, double* distance) {
  const double h = 2.0 / cells;
  for (int k = 0; k <= cells; ++k) {
    for (int j = 0; j <= cells; ++j) {
      for (int i = 0; i <= cells; ++i) {
        const int64_t p = point_index(cells, i, j, k);
        const double x = -1 + i * h, y = -1 + j * h, z = -1 + k * h;
        xyz[3 * p] = x;
        xyz[3 * p + 1] = y;
        xyz[3 * p + 2] = z;
        distance[p] = sqrt(x * x + y * y + z * z);
      }
    }
  }
  /* Each permutation (a, b, c) of the axes walks from corner (0,0,0) along a, then b, then c;
   * its tet has the orientation of the permutation, so the odd ones swap their last two. */
  static const int permutations[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                         {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  int64_t t = 0;
  for (int k = 0; k < cells; ++k) {
    for (int j = 0; j < cells; ++j) {
      for (int i = 0; i < cells; ++i) {
        for (int q = 0; q < 6; ++q) {
          int corner[3] = {i, j, k};
          int64_t v[4];
          v[0] = point_index(cells, i, j, k);
          for (int s = 0; s < 3; ++s) {
            ++corner[permutations[q][s]];
            v[s + 1] = point_index(cells, corner[0], corner[1], corner[2]);
          }
          if (q >= 3) {
            const int64_t last = v[3];
            v[3] = v[2];
            v[2] = last;
          }
          memcpy(&tets[4 * t], v, sizeof v);
          ++t;
        }
      }
    }
  }
}

int64_t tetray_ball_hex_count(int cells) { return (int64_t)cells * cells * cells; }

void tetray_ball_hexahedra(int cells, int64_t* connectivity) {
  static const int corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  int64_t* out = connectivity;
  for (int k = 0; k < cells; ++k) {
    for (int j = 0; j < cells; ++j) {
      for (int i = 0; i < cells; ++i) {
        for (int c = 0; c < 8; ++c) {
          *out++ = point_index(cells, i + corners[c][0], j + corners[c][1], k + corners[c][2]);
        }
      }
    }
  }
}

/* The largest amount by which the linear interpolant I f of f = |x| exceeds f at a point of its
 * level set I f = r (I f >= f, f being convex). On a simplex, I f - f <= R^2 / 2 max |D^2 f|
 * (Waldron 1998, "The error in linear interpolation at the vertices of a simplex"), with R the
 * radius of the smallest ball holding the simplex: h sqrt(3) / 2 for a Kuhn tet, whose long
 * diagonal is a diameter of its cube's sphere. |D^2 f| = 1 / |x|, and every point of a tet meeting
 * the level set lies farther than r - e - h sqrt(3) from the centre, so e (r - h sqrt(3) - e) <=
 * 3 h^2 / 8: e is at most the smaller root, the branch that vanishes as h does. */
static double interpolation_excess(int cells, double radius) {
  const double h = 2.0 / cells;
  const double a = radius - h * sqrt(3.0), b = 3 * h * h / 8;
  return (a - sqrt(a * a - 4 * b)) / 2;
}

void tetray_ball_pixel_bounds(int cells, double radius, double eye_distance, double fov_deg,
                              int width, int height, int64_t* fewest, int64_t* most) {
  /* The solid I f <= r lies between the balls of radius r - e and r, and a pixel's ray meets a
   * ball of radius rho centred on the view axis when sin(angle to the axis) < rho / d. Pixel
   * centres within 1e-6 of either circle are left out of the lower and counted in the upper
   * count: the renderer's float rays may fall either side. */
  const double sin_inner = (radius - interpolation_excess(cells, radius)) / eye_distance - 1e-6;
  const double sin_outer = radius / eye_distance + 1e-6;
  const double tan_half = tan(fov_deg * acos(-1.0) / 360);
  *fewest = 0;
  *most = 0;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const double x = (2 * (i + 0.5) / width - 1) * tan_half * width / height;
      const double y = (1 - 2 * (j + 0.5) / height) * tan_half;
      const double sin_angle = sqrt((x * x + y * y) / (1 + x * x + y * y));
      *fewest += sin_angle < sin_inner;
      *most += sin_angle <= sin_outer;
    }
  }
}

int64_t tetray_png_covered_pixels(const char* path) {
  png_image image;
  memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path)) return -1;
  image.format = PNG_FORMAT_RGBA;
  png_bytep pixels = malloc(PNG_IMAGE_SIZE(image));
  if (pixels == NULL || !png_image_finish_read(&image, NULL, pixels, 0, NULL)) {
    free(pixels);
    png_image_free(&image);
    return -1;
  }
  int64_t covered = 0;
  for (size_t p = 0; p < (size_t)image.width * image.height; ++p) covered += pixels[4 * p + 3] > 0;
  free(pixels);
  return covered;
}
