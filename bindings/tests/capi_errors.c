/* Error paths of the C API (bindings/c/mpm3d.h), compiled as C99:
 *   capi_errors GOOD_DECK WORKDIR
 * Every failure must give a non-zero code and a message that says what went wrong,
 * never a crash or an abort; the handle stays usable after a failed call. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpm3d.h"

static int failures = 0;

#define CHECK(cond, ...)                                  \
  do {                                                    \
    if (!(cond)) {                                        \
      ++failures;                                         \
      fprintf(stderr, "%s:%d: FAILED: %s: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                       \
      fprintf(stderr, "\n");                              \
    }                                                     \
  } while (0)

/* rc must be `code` and the message must contain every non-null needle. */
static void expect_error(int rc, int code, const char* call, const char* n1, const char* n2) {
  const char* msg = mpm3d_last_error();
  CHECK(msg != NULL, "%s: null message", call);
  if (!msg) return;
  CHECK(rc == code, "%s: code %d, expected %d (message '%s')", call, rc, code, msg);
  CHECK(msg[0] != '\0', "%s: empty message", call);
  CHECK(!n1 || strstr(msg, n1), "%s: message '%s' does not mention '%s'", call, msg, n1);
  CHECK(!n2 || strstr(msg, n2), "%s: message '%s' does not mention '%s'", call, msg, n2);
  printf("  %-34s -> %d: %s\n", call, rc, msg);
}

static void write_file(const char* path, const char* text) {
  FILE* f = fopen(path, "w");
  if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
    fprintf(stderr, "cannot write %s\n", path);
    exit(2);
  }
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: capi_errors GOOD_DECK WORKDIR\n");
    return 2;
  }
  const char* good = argv[1];
  char path[4200], bad[2048];
  mpm3d_sim* sim = (mpm3d_sim*)&failures; /* must be reset to NULL on failure */
  int rc;

  printf("mpm3d %s, Fortran kernels: %d\n", mpm3d_version(), mpm3d_have_fortran_kernels());

  /* A missing deck. */
  snprintf(path, sizeof path, "%s/no_such_deck.mpm", argv[2]);
  remove(path);
  rc = mpm3d_open(path, &sim);
  expect_error(rc, MPM3D_ERR_IO, "open(missing file)", path, "cannot open");
  CHECK(sim == NULL, "the handle is not NULL after a failed open");

  /* A deck with an error on line 4: the message is FILE:LINE: problem. */
  snprintf(bad, sizeof bad, "%s/bad_keyword.mpm", argv[2]);
  write_file(bad,
             "mpm3d *** a deck with an unknown keyword\n"
             "nbmp 8\n"
             "! line 3 is a comment\n"
             "frobnicate 1 2 3\n"
             "endi\n");
  snprintf(path, sizeof path, "%s:4:", bad);
  rc = mpm3d_open(bad, &sim);
  expect_error(rc, MPM3D_ERR_DECK, "open(unknown keyword)", path, "frobnicate");
  CHECK(sim == NULL, "the handle is not NULL after a failed open");

  /* A bad number on line 3. */
  write_file(bad, "mpm3d *** a deck with a bad number\nnbmp 8\nendtime 1.0x\nendi\n");
  snprintf(path, sizeof path, "%s:3:", bad);
  rc = mpm3d_open(bad, &sim);
  expect_error(rc, MPM3D_ERR_DECK, "open(bad number)", path, NULL);

  /* A deck that ends before endi. */
  write_file(bad, "mpm3d *** a truncated deck\nnbmp 8\nnmat 1\n");
  rc = mpm3d_open(bad, &sim);
  expect_error(rc, MPM3D_ERR_DECK, "open(no endi)", bad, "endi");

  /* Null arguments. */
  rc = mpm3d_open(NULL, &sim);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "open(NULL path)", "null", NULL);
  rc = mpm3d_open(good, NULL);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "open(NULL out)", "null", NULL);
  rc = mpm3d_step(NULL, 1);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "step(NULL)", "null handle", NULL);
  CHECK(isnan(mpm3d_time(NULL)), "time of a null handle is not NaN");
  expect_error(MPM3D_ERR_ARGUMENT, MPM3D_ERR_ARGUMENT, "time(NULL)", "mpm3d_time", NULL);
  CHECK(mpm3d_steps(NULL) == -1 && mpm3d_num_particles(NULL) == -1, "integer getters of a null handle");
  mpm3d_close(NULL); /* no-op */
  CHECK(mpm3d_last_error()[0] == '\0', "close(NULL) left a message");

  /* A good deck. */
  rc = mpm3d_open(good, &sim);
  CHECK(rc == MPM3D_OK && sim != NULL, "open(%s): %d %s", good, rc, mpm3d_last_error());
  if (rc != MPM3D_OK) return 1;
  CHECK(mpm3d_last_error()[0] == '\0', "a message after a successful open");
  const int np = mpm3d_num_particles(sim);
  CHECK(np > 0, "no particles");
  const long n3 = 3L * np;
  double* buf = (double*)calloc((size_t)(6L * np + 1), sizeof(double));

  /* Array names and sizes. */
  rc = mpm3d_get_array(sim, "pressure", buf, np);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "get_array(unknown name)", "pressure", "position");
  rc = mpm3d_set_array(sim, "Position", buf, n3);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "set_array(wrong case)", "Position", NULL);
  CHECK(mpm3d_array_size(sim, "nonsense") == -1, "array_size of an unknown name");
  CHECK(mpm3d_array_size(sim, "velocity") == n3, "array_size(velocity)");
  CHECK(mpm3d_array_size(sim, "mass") == np, "array_size(mass)");
  rc = mpm3d_get_array(sim, "position", buf, n3 - 1);
  snprintf(path, sizeof path, "need %ld", n3);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "get_array(short buffer)", "wrong size", path);
  rc = mpm3d_set_array(sim, "stress", buf, n3);
  snprintf(path, sizeof path, "need %ld", 6L * np);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "set_array(wrong size)", "stress", path);
  rc = mpm3d_get_array(sim, "mass", NULL, np);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "get_array(NULL)", "null", NULL);
  rc = mpm3d_get_array(sim, NULL, buf, np);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "get_array(NULL name)", "null", NULL);

  /* Kernels. */
  rc = mpm3d_set_kernel(sim, "cobol");
  expect_error(rc, MPM3D_ERR_KERNEL, "set_kernel(cobol)", "cobol", NULL);
  rc = mpm3d_set_kernel(sim, "stress=cobol");
  expect_error(rc, MPM3D_ERR_KERNEL, "set_kernel(stress=cobol)", "cobol", NULL);
  rc = mpm3d_set_kernel(sim, "flux=cxx");
  expect_error(rc, MPM3D_ERR_KERNEL, "set_kernel(flux=cxx)", "flux", NULL);
  if (!mpm3d_have_fortran_kernels()) {
    rc = mpm3d_set_kernel(sim, "fortran");
    expect_error(rc, MPM3D_ERR_KERNEL, "set_kernel(fortran, not built)", "Fortran", NULL);
  }
  CHECK(mpm3d_set_kernel(sim, "cxx") == MPM3D_OK, "set_kernel(cxx): %s", mpm3d_last_error());

  /* Steps and threads. */
  rc = mpm3d_step(sim, -1);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "step(-1)", "negative", NULL);
  rc = mpm3d_set_threads(0);
  expect_error(rc, MPM3D_ERR_ARGUMENT, "set_threads(0)", "thread", NULL);
  CHECK(mpm3d_steps(sim) == 0, "a failed call took a step");
  CHECK(mpm3d_step(sim, 2) == MPM3D_OK, "step(2) after failed calls: %s", mpm3d_last_error());
  CHECK(mpm3d_steps(sim) == 2, "steps %ld", mpm3d_steps(sim));

  /* Checkpoint after 2 steps, 3 more steps; a second handle restarted from it takes the
   * same 3 steps to the same bits. A missing checkpoint is an I/O error. */
  {
    mpm3d_sim* twin = NULL;
    double* a = (double*)malloc(sizeof(double) * (size_t)n3);
    double* b = (double*)malloc(sizeof(double) * (size_t)n3);
    snprintf(path, sizeof path, "%s/capi_checkpoint.h5", argv[2]);
    CHECK(mpm3d_write_checkpoint(sim, path) == MPM3D_OK, "write_checkpoint: %s", mpm3d_last_error());
    CHECK(mpm3d_open(good, &twin) == MPM3D_OK, "open twin: %s", mpm3d_last_error());
    rc = mpm3d_restart(twin, "/no/such/checkpoint.h5");
    expect_error(rc, MPM3D_ERR_IO, "restart(missing file)", "checkpoint", "cannot open");
    CHECK(mpm3d_steps(twin) == 0, "a failed restart changed the handle");
    CHECK(mpm3d_restart(twin, path) == MPM3D_OK, "restart: %s", mpm3d_last_error());
    CHECK(mpm3d_steps(twin) == 2, "restarted handle at step %ld", mpm3d_steps(twin));
    CHECK(mpm3d_step(sim, 3) == MPM3D_OK && mpm3d_step(twin, 3) == MPM3D_OK, "steps after the checkpoint");
    CHECK(mpm3d_get_array(sim, "position", a, n3) == MPM3D_OK, "get position");
    CHECK(mpm3d_get_array(twin, "position", b, n3) == MPM3D_OK, "get position (twin)");
    CHECK(memcmp(a, b, sizeof(double) * (size_t)n3) == 0, "restarted handle differs after 3 steps");
    CHECK(mpm3d_time(sim) == mpm3d_time(twin), "times differ");
    free(a);
    free(b);
    mpm3d_close(twin);
    mpm3d_close(sim);
    CHECK(mpm3d_open(good, &sim) == MPM3D_OK, "reopen: %s", mpm3d_last_error());
    CHECK(mpm3d_step(sim, 2) == MPM3D_OK, "step(2) after reopening: %s", mpm3d_last_error());
  }

  /* State file in a directory that does not exist. */
  snprintf(path, sizeof path, "%s/no_such_dir/state.h5", argv[2]);
  rc = mpm3d_write_state(sim, path);
  expect_error(rc, MPM3D_ERR_IO, "write_state(missing directory)", path, NULL);
  rc = mpm3d_write_state(sim, "");
  expect_error(rc, MPM3D_ERR_ARGUMENT, "write_state(\"\")", "file name", NULL);

  /* A numerical breakdown: a NaN velocity is reported after the step, naming the particle. */
  CHECK(mpm3d_get_array(sim, "velocity", buf, n3) == MPM3D_OK, "get velocity: %s", mpm3d_last_error());
  buf[3 * 4 + 1] = NAN; /* particle 5, y */
  CHECK(mpm3d_set_array(sim, "velocity", buf, n3) == MPM3D_OK, "set velocity: %s", mpm3d_last_error());
  rc = mpm3d_step(sim, 5);
  expect_error(rc, MPM3D_ERR_HEALTH, "step(NaN velocity)", "particle", "non-finite");
  CHECK(mpm3d_steps(sim) == 3, "the run did not stop after the failing step (steps %ld)", mpm3d_steps(sim));
  snprintf(path, sizeof path, "%s/after_breakdown.h5", argv[2]);
  CHECK(mpm3d_write_state(sim, path) == MPM3D_OK, "write_state after a breakdown: %s", mpm3d_last_error());

  free(buf);
  mpm3d_close(sim);
  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("all error paths behave\n");
  return 0;
}
