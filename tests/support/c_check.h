/* The check of the C tests: a failed check prints what failed and the C API's last error, and is
 * counted; the test's main returns non-zero when any failed. */
#ifndef TETRAY_TESTS_C_CHECK_H
#define TETRAY_TESTS_C_CHECK_H

#include <stdio.h>

#include "tetray/adaptor.h"

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "FAILED: %s (last error: %s)\n", what, tetray_last_error());
    ++failures;
  }
}

#endif /* TETRAY_TESTS_C_CHECK_H */
