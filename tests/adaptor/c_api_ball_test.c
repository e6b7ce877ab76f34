/* The C API end to end against an analytic answer: a ball of radius 0.6 (a level set of the
 * distance to the centre of a mesh of tets, or of hexahedra the adaptor splits) seen from
 * distance 3 must cover as many pixels of the PNG as the camera geometry and the mesh's
 * interpolation error allow (tests/support/ball_image.h); a cell tetray cannot split is refused.
 * Exits non-zero on any failure. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ball_image.h"
#include "support/c_check.h"
#include "tetray/adaptor.h"

enum { kCells = 16, kSide = 64 };

/* The cells the ball's box is given as. */
enum Cells { kTets, kHexahedra };

/* Renders the ball through the C API into dir/<name>/<name>_000000.png and checks its pixel
 * count. */
static void render_ball(const char* dir, const char* name, enum Cells cells) {
  char yaml[1024];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, quiet: true, formats: [png], writer_queue_depth: 0}\n"
           "scenes:\n"
           "  - name: %s\n"
           "    field: distance\n"
           "    isovalues: [0.6]\n"
           "    camera: {eye: [0, 0, 3], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
           "    image: {width: %d, height: %d}\n",
           dir, name, kSide, kSide);
  tetray_adaptor* a = NULL;
  check(tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &a) == TETRAY_OK && a != NULL, "create");

  const int64_t points = tetray_ball_point_count(kCells), tets = tetray_ball_tet_count(kCells);
  const int64_t hexes = tetray_ball_hex_count(kCells);
  double* xyz = malloc(3 * points * sizeof *xyz);
  double* distance = malloc(points * sizeof *distance);
  int64_t* connectivity = malloc(4 * tets * sizeof *connectivity);
  int64_t* offsets = malloc((hexes + 1) * sizeof *offsets);
  uint8_t* types = malloc(hexes * sizeof *types);
  tetray_ball_mesh(kCells, xyz, connectivity, distance);
  if (cells == kTets) {
    check(tetray_set_mesh(a, xyz, TETRAY_FLOAT64, points, NULL, TETRAY_FLOAT64, connectivity,
                          TETRAY_INT64, tets, NULL, NULL) == TETRAY_OK,
          "set_mesh");
  } else {
    tetray_ball_hexahedra(kCells, connectivity);
    for (int64_t c = 0; c <= hexes; ++c) offsets[c] = 8 * c;
    for (int64_t c = 0; c < hexes; ++c) types[c] = 12; /* VTK_HEXAHEDRON */
    check(tetray_set_mesh(a, xyz, TETRAY_FLOAT64, points, NULL, TETRAY_FLOAT64, NULL, TETRAY_INT64,
                          0, NULL, NULL) == TETRAY_OK,
          "set_mesh without tets");
    check(tetray_set_cells(a, types, offsets, connectivity, TETRAY_INT64, hexes, NULL) == TETRAY_OK,
          "set_cells");
  }
  check(tetray_set_field(a, "distance", distance, TETRAY_FLOAT64, points) == TETRAY_OK,
        "set_field");
  check(tetray_execute(a, 0, 0.0, TETRAY_CHANGED_ALL) == TETRAY_OK, "execute");
  check(tetray_finalize(a) == TETRAY_OK, "finalize");
  tetray_destroy(a);

  char png[1200];
  snprintf(png, sizeof png, "%s/%s/%s_000000.png", dir, name, name);
  const int64_t covered = tetray_png_covered_pixels(png);
  int64_t fewest = 0, most = 0;
  tetray_ball_pixel_bounds(kCells, 0.6, 3.0, 40.0, kSide, kSide, &fewest, &most);
  printf("c_api_ball_test: %s: %lld pixels covered, expected %lld to %lld\n", name,
         (long long)covered, (long long)fewest, (long long)most);
  check(covered >= fewest && covered <= most, "the ball covers the pixels its geometry predicts");
  free(xyz);
  free(distance);
  free(connectivity);
  free(offsets);
  free(types);
}

/* A hexahedron of the wrong node count is refused by execute, naming the cell. */
static void refuse_bad_cell(const char* dir) {
  char yaml[512];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, quiet: true, formats: [png]}\n"
           "scenes: [{name: bad, field: f, isovalues: [0.5]}]\n",
           dir);
  tetray_adaptor* a = NULL;
  check(tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &a) == TETRAY_OK, "create");
  const double xyz[24] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const double f[8] = {0, 1, 0, 1, 0, 1, 0, 1};
  const int32_t connectivity[7] = {0, 1, 2, 3, 4, 5, 6}, offsets[2] = {0, 7};
  const uint8_t types[1] = {12};
  check(tetray_set_mesh(a, xyz, TETRAY_FLOAT64, 8, NULL, TETRAY_FLOAT64, NULL, TETRAY_INT32, 0,
                        NULL, NULL) == TETRAY_OK,
        "set_mesh");
  check(tetray_set_cells(a, types, offsets, connectivity, TETRAY_INT32, 1, NULL) == TETRAY_OK,
        "set_cells");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 8) == TETRAY_OK, "set_field");
  check(tetray_execute(a, 0, 0.0, TETRAY_CHANGED_ALL) == TETRAY_INVALID_ARGUMENT,
        "a 7-node hexahedron is refused");
  check(strstr(tetray_last_error(), "cell 0 (VTK cell type 12) has 7 nodes, not 8") != NULL,
        "the message names the cell");
  check(tetray_set_cells(a, types, offsets, connectivity, 5, 1, NULL) == TETRAY_INVALID_ARGUMENT,
        "a bad index type is refused");
  tetray_destroy(a);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  char dir[] = "/tmp/tetray_c_ball_XXXXXX";
  check(mkdtemp(dir) != NULL, "mkdtemp");
  render_ball(dir, "ball", kTets);
  render_ball(dir, "ball_of_hexahedra", kHexahedra);
  refuse_bad_cell(dir);
  char command[1200];
  snprintf(command, sizeof command, "rm -rf %s", dir);
  check(system(command) == 0, "cleanup");
  MPI_Finalize();
  return failures == 0 ? 0 : 1;
}
