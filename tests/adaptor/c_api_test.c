/* The C API from C: create, set views, will_render, execute, the report, errors with their
 * message (cleared by a later success), a scene skipped for a missing field, and a config error
 * without a handle. One tet carrying f = z and g = x, rendered every second step; exits non-zero
 * on any failure. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "support/c_check.h"
#include "tetray/adaptor.h"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  char dir[] = "/tmp/tetray_c_api_XXXXXX";
  check(mkdtemp(dir) != NULL, "mkdtemp");
  char yaml[1024];
  snprintf(yaml, sizeof yaml,
           "output: {directory: %s, quiet: true, formats: [png], writer_queue_depth: 0}\n"
           "trigger: {every: 2}\n"
           "scenes:\n"
           "  - {name: tet, field: f, isovalues: [0.25], image: {width: 32, height: 32}}\n"
           "  - {name: by_g, field: f, isovalues: [0.25], color_by: g,\n"
           "     image: {width: 32, height: 32}}\n",
           dir);
  tetray_adaptor* a = NULL;
  check(tetray_create_from_yaml(MPI_COMM_WORLD, yaml, &a) == TETRAY_OK && a != NULL, "create");

  const float xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tets[4] = {0, 1, 2, 3};
  const double f[4] = {0, 0, 0, 1};
  const double g[4] = {0, 1, 0, 0};
  check(tetray_set_mesh(a, xyz, TETRAY_FLOAT32, 4, NULL, TETRAY_FLOAT64, tets, TETRAY_INT32, 1,
                        NULL, NULL) == TETRAY_OK,
        "set_mesh");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 4) == TETRAY_OK, "set_field");
  check(tetray_set_field(a, "g", g, TETRAY_FLOAT64, 4) == TETRAY_OK, "set_field g");
  int will = -1;
  check(tetray_will_render(a, 0, 0.0, &will) == TETRAY_OK && will == 1, "step 0 will render");
  check(tetray_will_render(a, 1, 0.1, &will) == TETRAY_OK && will == 0, "step 1 will not");
  check(tetray_will_render(a, 1, 0.1, NULL) == TETRAY_INVALID_ARGUMENT, "will_render NULL");
  check(tetray_execute(a, 0, 0.0, TETRAY_CHANGED_ALL) == TETRAY_OK, "execute");
  check(strcmp(tetray_last_error(), "") == 0, "no message after a success");
  tetray_report report;
  check(tetray_get_report(a, &report) == TETRAY_OK && report.rendered == 1 &&
            report.scenes_rendered == 2 && report.scenes_skipped == 0 &&
            strcmp(report.bvh_decision, "rebuild") == 0,
        "report after a rendered step");
  check(tetray_execute(a, 1, 0.1, TETRAY_CHANGED_FIELDS) == TETRAY_OK, "off-trigger execute");
  check(tetray_get_report(a, &report) == TETRAY_OK && report.rendered == 0 &&
            report.scenes_rendered == 0 && strcmp(report.bvh_decision, "none") == 0,
        "report after an off-trigger step");
  char png[1200];
  snprintf(png, sizeof png, "%s/tet/tet_000000.png", dir);
  check(access(png, R_OK) == 0, "the PNG exists");

  /* A field with the wrong size: a clear error, then the next good step works. */
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 3) == TETRAY_OK, "set short field");
  check(tetray_execute(a, 2, 0.2, TETRAY_CHANGED_FIELDS) == TETRAY_INVALID_ARGUMENT,
        "short field is invalid");
  check(strstr(tetray_last_error(), "3 values but the mesh has 4 points") != NULL,
        "message names the sizes");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 4) == TETRAY_OK, "set field again");
  check(strcmp(tetray_last_error(), "") == 0, "the old message is gone after a success");
  check(tetray_execute(a, 4, 0.4, TETRAY_CHANGED_FIELDS) == TETRAY_OK, "execute after error");

  /* Without g, the scene colored by it is skipped; the other renders. */
  check(tetray_clear_fields(a) == TETRAY_OK, "clear fields");
  check(tetray_set_field(a, "f", f, TETRAY_FLOAT64, 4) == TETRAY_OK, "set f alone");
  check(tetray_execute(a, 6, 0.6, TETRAY_CHANGED_FIELDS) == TETRAY_PARTIAL, "partial");
  check(strstr(tetray_last_error(), "scene 'by_g' skipped: field 'g'") != NULL,
        "message names the skipped scene and the field");
  const char* skipped = NULL;
  check(tetray_get_report(a, &report) == TETRAY_OK && report.rendered == 1 &&
            report.scenes_rendered == 1 && report.scenes_skipped == 1,
        "report counts the skipped scene");
  check(tetray_get_skipped_scene(a, 0, &skipped) == TETRAY_OK && strcmp(skipped, "by_g") == 0,
        "the skipped scene by name");
  check(tetray_get_skipped_scene(a, 1, &skipped) == TETRAY_INVALID_ARGUMENT, "index past the end");
  snprintf(png, sizeof png, "%s/tet/tet_000006.png", dir);
  check(access(png, R_OK) == 0, "the other scene's PNG exists");
  snprintf(png, sizeof png, "%s/by_g/by_g_000006.png", dir);
  check(access(png, F_OK) != 0, "no PNG of the skipped scene");
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
