/* One tet carrying f = z, its 0.5 isosurface rendered through the installed tetray from C; the
 * image directory is the first argument. Exits non-zero on any failure. */
#include <stdio.h>
#include <string.h>
#include <tetray/adaptor.h>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  char yaml[512];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, formats: [png], quiet: true}\n"
           "scenes: [{name: tet, field: f, isovalues: [0.5], image: {width: 16, height: 16}}]\n",
           argc > 1 ? argv[1] : "consumer_out");
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int64_t tets[4] = {0, 1, 2, 3};
  const double f[4] = {0, 0, 0, 1};
  tetray_adaptor* adaptor = NULL;
  int status = tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &adaptor);
  if (status == TETRAY_OK) {
    status = tetray_set_mesh(adaptor, xyz, TETRAY_FLOAT64, 4, NULL, TETRAY_FLOAT64, tets,
                             TETRAY_INT64, 1, NULL, NULL);
  }
  if (status == TETRAY_OK) status = tetray_set_field(adaptor, "f", f, TETRAY_FLOAT64, 4);
  if (status == TETRAY_OK) status = tetray_execute(adaptor, 0, 0.0, TETRAY_CHANGED_ALL);
  if (status == TETRAY_OK) status = tetray_finalize(adaptor);
  if (status != TETRAY_OK) fprintf(stderr, "consumer: %s\n", tetray_last_error());
  tetray_destroy(adaptor);
  MPI_Finalize();
  return status == TETRAY_OK ? 0 : 1;
}
