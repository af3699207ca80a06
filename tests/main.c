/* SPDX-License-Identifier: MIT
 * CUnit runner: registers every suite (build/suites.inc), runs them, optionally only those
 * whose name contains argv[1], and exits non-zero on any failure: a failed assertion, a suite
 * that could not start, a test CUnit refused to register, or no test run at all. */
#define _POSIX_C_SOURCE 200809L
#include <CUnit/Basic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

#define SUITE(name) void st_suite_##name(void);
#include "suites.inc"
#undef SUITE

static char g_tmproot[256];

static void cleanup(void) {
  if (g_tmproot[0]) {
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_tmproot);
    if (system(cmd) != 0) fprintf(stderr, "warning: could not remove %s\n", g_tmproot);
  }
}

static const char *tmproot(void) {
  if (!g_tmproot[0]) {
    snprintf(g_tmproot, sizeof g_tmproot, "/tmp/selftalk_test_XXXXXX");
    if (!mkdtemp(g_tmproot)) {
      perror("mkdtemp");
      exit(1);
    }
    atexit(cleanup);
  }
  return g_tmproot;
}

const char *st_test_write_tmp(char *path, size_t n, const char *suffix, const char *text) {
  static int counter;
  snprintf(path, n, "%s/f%d%s", tmproot(), counter++, suffix);
  FILE *f = fopen(path, "w");
  if (!f) return NULL;
  fputs(text, f);
  fclose(f);
  return path;
}

const char *st_test_write_tmp_n(char *path, size_t n, const char *suffix, const void *data,
                                size_t len) {
  static int counter;
  snprintf(path, n, "%s/b%d%s", tmproot(), counter++, suffix);
  FILE *f = fopen(path, "wb");
  if (!f) return NULL;
  size_t w = fwrite(data, 1, len, f);
  if (fclose(f) != 0 || w != len) return NULL;
  return path;
}

const char *st_test_tmpdir(char *path, size_t n) {
  static int counter;
  snprintf(path, n, "%s/d%d", tmproot(), counter++);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "mkdir -p '%s'", path);
  return system(cmd) == 0 ? path : NULL;
}

static unsigned g_registration_errors;

static void registration_check(const char *what, const char *name) {
  if (CU_get_error() == CUE_SUCCESS) return;
  fprintf(stderr, "test registration: %s '%s': %s\n", what, name, CU_get_error_msg());
  g_registration_errors++;
}

CU_pSuite st_test_add_suite(const char *name) {
  CU_pSuite s = CU_add_suite(name, NULL, NULL);
  registration_check("suite", name);
  return s;
}

void st_test_add(CU_pSuite suite, const char *name, CU_TestFunc fn) {
  CU_add_test(suite, name, fn);
  registration_check("test", name);
}

static stTestFixture g_fixture;
static int g_fixture_loaded;

static void fixture_free(void) { st_robot_destroy(g_fixture.robot); }

const stTestFixture *st_test_fixture(void) {
  if (!g_fixture_loaded) {
    char err[512];
    g_fixture_loaded = 1;
    st_config_default(&g_fixture.cfg);
    if (st_robot_create(&g_fixture.cfg, &g_fixture.robot, err, sizeof err))
      fprintf(stderr, "\n  %s\n", err);
    st_scene_from_config(&g_fixture.cfg, &g_fixture.scene);
    atexit(fixture_free);
  }
  return &g_fixture;
}

stStatus st_test_net_trial(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                           const stNetParams *net, const stNetParams *rollin, const stForce *force,
                           int nforce, uint64_t key, stTrialResult *r, stTraceFn trace, void *ctx,
                           char *err, size_t errsz) {
  stStatus st = st_force_check(force, nforce, err, errsz);
  if (st) return st;
  stNetController nc, rc;
  stRollinController roll;
  stController ctl = st_net_controller(&nc, net, force, nforce);
  if (rollin) {
    const stController individual = ctl, elite = st_net_controller(&rc, rollin, NULL, 0);
    if ((st = st_rollin_controller(&roll, &elite, &individual, &ctl, err, errsz))) return st;
  }
  return st_trial_run(p, ws, t, &ctl, key, r, trace, ctx, err, errsz);
}

int main(int argc, char **argv) {
  if (CU_initialize_registry() != CUE_SUCCESS) return 1;
  const char *filter = argc > 1 ? argv[1] : NULL;
#define SUITE(name) \
  if (!filter || strstr(#name, filter)) st_suite_##name();
#include "suites.inc"
#undef SUITE
  CU_basic_set_mode(CU_BRM_VERBOSE);
  const CU_ErrorCode run_error = CU_basic_run_tests();
  const unsigned run = CU_get_number_of_tests_run();
  const unsigned tests_failed = CU_get_number_of_tests_failed();
  const unsigned asserts_failed = CU_get_number_of_failures(); /* includes suite set-up failures */
  const unsigned suites_failed = CU_get_number_of_suites_failed();
  /* failed checks: tests with a failed assertion, suites that could not run, tests never
   * registered, and the run itself when nothing ran (a filter that matches nothing) */
  const unsigned failed = tests_failed + suites_failed + g_registration_errors + (run == 0);
  printf("\nunit tests: %u passed, %u failed (%u failed assertions%s%s)\n", run - tests_failed,
         failed, asserts_failed, run == 0 ? "; no test ran" : "",
         g_registration_errors ? "; registration errors above" : "");
  CU_cleanup_registry();
  return (failed || asserts_failed || run_error != CUE_SUCCESS) ? 1 : 0;
}
