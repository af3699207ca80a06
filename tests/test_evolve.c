/* SPDX-License-Identifier: MIT
 * st_evolve_run with an evaluator of its own (stEvolveEvaluator): the hook apps/evolve's MPI
 * ranks use. Tasks evaluated elsewhere, in another order, give the same files; an evaluator
 * that breaks down stops the run with its message and the last generation's checkpoint. */
#include <stdlib.h>

#include "selftalk/evolve.h"
#include "test_util.h"

#define GENS 3

/* evaluates the tasks last first, with a protocol and a workspace of its own; fails (as a
 * lost process would) at generation fail_at */
typedef struct reverser {
  stProtocol *p;
  stIntegratedDef idef;
  stWorkspace ws;
  int calls, fail_at, bad_task;
} reverser;

static stStatus reverse_eval(void *self, const stConfig *cfg, const stEvolveTask *tasks, int n,
                             stEvolveResult *results, char *err, size_t errsz) {
  reverser *r = self;
  if (!r->p) {
    if (st_protocol_create(cfg, &r->p, err, errsz)) return ST_ERR_ARG;
    st_integrated_def_from_config(cfg, &r->idef);
  }
  if (tasks[0].generation == r->fail_at) {
    snprintf(err, errsz, "test evaluator: lost at generation %d", r->fail_at);
    return ST_ERR_IO;
  }
  r->calls++;
  for (int i = n - 1; i >= 0; i--)
    st_evolve_task_run(r->p, &r->idef, &r->ws, &tasks[i], &results[i]);
  if (r->bad_task >= 0) {
    results[r->bad_task].status = ST_ERR_RANGE;
    snprintf(results[r->bad_task].err, sizeof results[r->bad_task].err, "made up");
  }
  return ST_OK;
}

static void small_config(stConfig *c) {
  st_config_default(c);
  c->stage_stages = ST_STAGES_SIMPLE;
  c->ga_population = 12;
  c->ga_elites = 2;
  c->ga_parents = 4;
  c->ga_success_genotypes = 12;
  c->run_seed = 7;
}

static char *slurp(const char *dir, const char *name) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  char *buf = calloc(1, 1 << 20);
  if (buf) buf[fread(buf, 1, (1 << 20) - 1, f)] = 0;
  fclose(f);
  return buf;
}

static int same_file(const char *d1, const char *d2, const char *name) {
  char *a = slurp(d1, name), *b = slurp(d2, name);
  const int same = a && b && !strcmp(a, b);
  if (!same) fprintf(stderr, "\n  %s differs between %s and %s\n", name, d1, d2);
  free(a);
  free(b);
  return same;
}

static stStatus run_with(const stConfig *c, const char *dir, const stEvolveEvaluator *ev,
                         char *err, size_t errsz) {
  stEvolveDef def = {c, dir, 1, GENS, 0, NULL, ev};
  return st_evolve_run(&def, err, errsz);
}

static void free_reverser(reverser *r) {
  st_workspace_free(&r->ws);
  st_protocol_destroy(r->p);
}

static void test_evaluator_same_files(void) {
  stConfig c;
  small_config(&c);
  char d1[512], d2[512], err[1024] = "";
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(d1, sizeof d1));
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(d2, sizeof d2));
  CU_ASSERT_EQUAL_FATAL(run_with(&c, d1, NULL, err, sizeof err), ST_OK);
  reverser r = {NULL, {0}, {NULL, NULL, NULL}, 0, -1, -1};
  stEvolveEvaluator ev = {reverse_eval, &r};
  CU_ASSERT_EQUAL(run_with(&c, d2, &ev, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(r.calls, GENS);
  static const char *files[] = {"config.ini", "fitness.csv", "best.genome", "population.genome",
                                "checkpoint"};
  for (int i = 0; i < 5; i++) CU_ASSERT(same_file(d1, d2, files[i]));
  free_reverser(&r);
}

static void test_evaluator_breakdown(void) {
  stConfig c;
  small_config(&c);
  char d[512], err[1024] = "";
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(d, sizeof d));
  reverser r = {NULL, {0}, {NULL, NULL, NULL}, 0, 1, -1};
  stEvolveEvaluator ev = {reverse_eval, &r};
  CU_ASSERT_EQUAL(run_with(&c, d, &ev, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "test evaluator: lost at generation 1");
  /* the checkpoint is generation 0's (the next to evaluate: 1), fitness.csv has its one row */
  char *ck = slurp(d, "checkpoint"), *csv = slurp(d, "fitness.csv");
  ST_ASSERT_CONTAINS(ck, "# generation 1\n");
  int rows = 0;
  for (const char *s = csv; s && *s; s++) rows += *s == '\n';
  CU_ASSERT_EQUAL(rows, 2);
  free(ck);
  free(csv);
  free_reverser(&r);
}

static void test_evaluator_bad_task(void) {
  stConfig c;
  small_config(&c);
  char d[512], err[1024] = "";
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(d, sizeof d));
  reverser r = {NULL, {0}, {NULL, NULL, NULL}, 0, -1, 5};
  stEvolveEvaluator ev = {reverse_eval, &r};
  CU_ASSERT_EQUAL(run_with(&c, d, &ev, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "evaluating genotype 5: made up");
  free_reverser(&r);
}

void st_suite_evolve(void) {
  ST_ADD_SUITE("evolve");
  ST_ADD_TEST(test_evaluator_same_files);
  ST_ADD_TEST(test_evaluator_breakdown);
  ST_ADD_TEST(test_evaluator_bad_task);
}
