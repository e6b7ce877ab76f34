/* The C API from C: create, set views, execute, the report, errors with their message, and a
 * config error without a handle. One tet carrying f = z; exits non-zero on any failure. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tetray/adaptor.h"

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "FAILED: %s (last error: %s)\n", what, tetray_last_error());
    ++failures;
  }
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  char dir[] = "/tmp/tetray_c_api_XXXXXX";
  check(mkdtemp(dir) != NULL, "mkdtemp");
  char yaml[1024];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, quiet: true, formats: [png], writer_queue_depth: 0}\n"
           "scenes:\n"
           "  - {name: tet, field: f, isovalues: [0.25], image: {width: 32, height: 32}}\n",
           dir);
  tetray_adaptor* a = NULL;
  check(tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &a) == TETRAY_OK && a != NULL, "create");

  const float xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tets[4] = {0, 1, 2, 3};
  const double f[4] = {0, 0, 0, 1};
  check(tetray_set_mesh(a, xyz, TETRAY_FLOAT32, 4, NULL, TETRAY_FLOAT64, tets, TETRAY_INT32, 1,
                        NULL, NULL) == TETRAY_OK,
        "set_mesh");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 4) == TETRAY_OK, "set_field");
  check(tetray_execute(a, 0, 0.0, TETRAY_CHANGED_ALL) == TETRAY_OK, "execute");
  tetray_report report;
  check(tetray_get_report(a, &report) == TETRAY_OK && report.rendered == 1 &&
            report.scenes_rendered == 1,
        "report after a rendered step");
  char png[1200];
  snprintf(png, sizeof png, "%s/tet/tet_000000.png", dir);
  check(access(png, R_OK) == 0, "the PNG exists");

  /* A field with the wrong size: a clear error, then the next good step works. */
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 3) == TETRAY_OK, "set short field");
  check(tetray_execute(a, 1, 0.1, TETRAY_CHANGED_FIELDS) == TETRAY_INVALID_ARGUMENT,
        "short field is invalid");
  check(strstr(tetray_last_error(), "3 values but the mesh has 4 points") != NULL,
        "message names the sizes");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 4) == TETRAY_OK, "set field again");
  check(tetray_execute(a, 2, 0.2, TETRAY_CHANGED_FIELDS) == TETRAY_OK, "execute after error");
  check(tetray_set_mesh(a, xyz, 7, 4, NULL, TETRAY_FLOAT64, tets, TETRAY_INT32, 1, NULL, NULL) ==
            TETRAY_INVALID_ARGUMENT,
        "bad scalar type");
  check(tetray_finalize(a) == TETRAY_OK, "finalize");
  tetray_destroy(a);

  tetray_adaptor* bad = NULL;
  check(
      tetray_create_from_yaml(MPI_COMM_WORLD, "scenes: [{name: s}]", &bad) == TETRAY_CONFIG_ERROR &&
          bad == NULL,
      "config error");
  check(strstr(tetray_last_error(), "scenes[0].field") != NULL, "config message names the key");
  check(tetray_execute(NULL, 0, 0, 0) == TETRAY_NOT_INITIALIZED, "null handle");

  char command[1200];
  snprintf(command, sizeof command, "rm -rf %s", dir);
  check(system(command) == 0, "cleanup");
  MPI_Finalize();
  if (failures == 0) printf("c_api_test: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
