/* A ball seen through the adaptor, for the end-to-end tests in C, Fortran and C++: a tet mesh
 * of the box [-1, 1]^3 carrying the distance to its centre, whose level set r is a polyhedral
 * ball, and the range of pixel counts its image must cover, derived from the camera of
 * docs/architecture.md §3 and the interpolation error of the mesh. */
#ifndef TETRAY_TESTS_SUPPORT_BALL_IMAGE_H
#define TETRAY_TESTS_SUPPORT_BALL_IMAGE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The box cut into cells^3 cubes of side h = 2 / cells, each into 6 positively oriented Kuhn
 * tets around its (0,0,0)-(1,1,1) diagonal. */
int64_t tetray_ball_point_count(int cells);
int64_t tetray_ball_tet_count(int cells);
/* Fills xyz (3 per point), tets (4 per tet, 0-based) and distance (|x|, one per point). */
void tetray_ball_mesh(int cells, double* xyz, int64_t* tets, double* distance);

/* The same cubes as VTK hexahedra (8 point indices each, VTK's node order: the bottom face
 * counter-clockwise seen from above, then the top face), for tetray_set_cells. Every tet the
 * adaptor splits them into lies in its cube, so the pixel bounds below hold for them too. */
int64_t tetray_ball_hex_count(int cells);
void tetray_ball_hexahedra(int cells, int64_t* connectivity);

/* The ball of level `radius` seen from the eye (0, 0, eye_distance) looking at the origin, up
 * +y, vertical field of view fov_deg, width x height pixels: the fewest and most pixels its image
 * may cover. */
void tetray_ball_pixel_bounds(int cells, double radius, double eye_distance, double fov_deg,
                              int width, int height, int64_t* fewest, int64_t* most);

/* Pixels with non-zero alpha in the PNG at `path` (a transparent background shows the misses);
 * -1 when the file cannot be read. */
int64_t tetray_png_covered_pixels(const char* path);

#ifdef __cplusplus
}
#endif

#endif
