/* The C API end to end against an analytic answer: a ball of radius 0.6 (a level set of the
 * distance to the centre of a tet mesh) seen from distance 3 must cover as many pixels of the PNG
 * as the camera geometry and the mesh's interpolation error allow (tests/support/ball_image.h).
 * Exits non-zero on any failure. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "ball_image.h"
#include "support/c_check.h"
#include "tetray/adaptor.h"

enum { kCells = 16, kSide = 64 };

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  char dir[] = "/tmp/tetray_c_ball_XXXXXX";
  check(mkdtemp(dir) != NULL, "mkdtemp");
  char yaml[1024];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, quiet: true, formats: [png], writer_queue_depth: 0}\n"
           "scenes:\n"
           "  - name: ball\n"
           "    field: distance\n"
           "    isovalues: [0.6]\n"
           "    camera: {eye: [0, 0, 3], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
           "    image: {width: %d, height: %d}\n",
           dir, kSide, kSide);
  tetray_adaptor* a = NULL;
  check(tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &a) == TETRAY_OK && a != NULL, "create");

  const int64_t points = tetray_ball_point_count(kCells), tets = tetray_ball_tet_count(kCells);
  double* xyz = malloc(3 * points * sizeof *xyz);
  double* distance = malloc(points * sizeof *distance);
  int64_t* connectivity = malloc(4 * tets * sizeof *connectivity);
  tetray_ball_mesh(kCells, xyz, connectivity, distance);
  check(tetray_set_mesh(a, xyz, TETRAY_FLOAT64, points, NULL, TETRAY_FLOAT64, connectivity,
                        TETRAY_INT64, tets, NULL, NULL) == TETRAY_OK,
        "set_mesh");
  check(tetray_set_field(a, "distance", distance, TETRAY_FLOAT64, points) == TETRAY_OK,
        "set_field");
  check(tetray_execute(a, 0, 0.0, TETRAY_CHANGED_ALL) == TETRAY_OK, "execute");
  check(tetray_finalize(a) == TETRAY_OK, "finalize");
  tetray_destroy(a);

  char png[1200];
  snprintf(png, sizeof png, "%s/ball/ball_000000.png", dir);
  const int64_t covered = tetray_png_covered_pixels(png);
  int64_t fewest = 0, most = 0;
  tetray_ball_pixel_bounds(kCells, 0.6, 3.0, 40.0, kSide, kSide, &fewest, &most);
  printf("c_api_ball_test: %lld pixels covered, expected %lld to %lld\n", (long long)covered,
         (long long)fewest, (long long)most);
  check(covered >= fewest && covered <= most, "the ball covers the pixels its geometry predicts");

  free(xyz);
  free(distance);
  free(connectivity);
  char command[1200];
  snprintf(command, sizeof command, "rm -rf %s", dir);
  check(system(command) == 0, "cleanup");
  MPI_Finalize();
  return failures == 0 ? 0 : 1;
}
