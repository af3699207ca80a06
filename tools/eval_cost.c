/* SPDX-License-Identifier: MIT
 * eval_cost: what evaluating one individual costs, individual by individual, on one thread: the
 * unit of work evolve hands to an MPI rank (docs/PROTOCOL.md, "Evaluation across processes":
 * the scaling model reads this). A diagnostic, not part of the protocol.
 *
 *   build/eval_cost CONFIG [--population FILE] [--generation G] [--count N] [section.key=value]...
 *
 * Evaluates the first N genotypes (default ga.population) of FILE (default the config's
 * stage.init_population) in the config's last primitive stage (main-prim for prims) at
 * generation G's trials (default 0), as st_evolve_run's threads do (st_evolve_task_run).
 * Prints `individual,cpu_s,wall_s,fitness,successes` rows (CPU: the thread's CPU time, which
 * other work on the machine barely moves), then a `# ` summary: min, median, max, mean. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "selftalk/selftalk.h"

static double clock_s(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void die(const char *msg) {
  fprintf(stderr, "eval_cost: %s\n", msg);
  exit(2);
}

typedef struct options {
  const char *config, *population;
  int generation, count;
  const char *sets[64];
  int nsets;
} options;

static int int_arg(const char *v) {
  char *end;
  const long x = strtol(v, &end, 10);
  if (*end || end == v || x < 0 || x > 1000000) die("expected an integer >= 0");
  return (int)x;
}

static void parse(int argc, char **argv, options *o) {
  memset(o, 0, sizeof *o);
  o->count = -1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--population") && i + 1 < argc) o->population = argv[++i];
    else if (!strcmp(a, "--generation") && i + 1 < argc) o->generation = int_arg(argv[++i]);
    else if (!strcmp(a, "--count") && i + 1 < argc) o->count = int_arg(argv[++i]);
    else if (a[0] != '-' && strchr(a, '=') && o->nsets < 64) o->sets[o->nsets++] = a;
    else if (a[0] != '-' && !o->config) o->config = a;
    else die("usage: eval_cost CONFIG [--population FILE] [--generation G] [--count N] [section.key=value]...");
  }
  if (!o->config) die("missing CONFIG");
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  options o;
  parse(argc, argv, &o);
  char err[1024];
  stConfig cfg;
  st_config_default(&cfg);
  if (st_config_load(o.config, &cfg, err, sizeof err) ||
      st_config_set_all(&cfg, o.sets, o.nsets, err, sizeof err))
    die(err);
  const unsigned stages = st_config_run_stages(&cfg);
  if (!(stages & (ST_CONFIG_SIMPLE_PRIM | ST_CONFIG_MAIN_PRIM))) die("a primitive-stage config");
  const char *path = o.population ? o.population : cfg.stage_init_population;
  if (!path[0]) die("no population: give --population FILE");
  stGenomeSet set;
  stProtocol *p = NULL;
  if (st_genome_set_read(path, ST_GENES_BASE, &set, err, sizeof err) ||
      st_protocol_create(&cfg, &p, err, sizeof err))
    die(err);
  stIntegratedDef idef;
  st_integrated_def_from_config(&cfg, &idef);
  const int n = o.count >= 0 && o.count < set.count ? o.count
                : cfg.ga_population < set.count ? cfg.ga_population : set.count;
  double *cpu = calloc((size_t)n + 1, sizeof *cpu);
  stWorkspace ws = {NULL, NULL, NULL};
  stEvolveTask t;
  stEvolveResult r;
  memset(&t, 0, sizeof t);
  t.stage = stages & ST_CONFIG_MAIN_PRIM ? ST_STAGE_MAIN : ST_STAGE_SIMPLE;
  t.generation = o.generation;
  printf("individual,cpu_s,wall_s,fitness,successes\n");
  double sum = 0.0;
  for (int i = 0; i < n; i++) {
    t.individual = i;
    t.genome = set.genome[i];
    const double c0 = clock_s(CLOCK_THREAD_CPUTIME_ID), w0 = clock_s(CLOCK_MONOTONIC);
    st_evolve_task_run(p, &idef, &ws, &t, &r);
    cpu[i] = clock_s(CLOCK_THREAD_CPUTIME_ID) - c0;
    sum += cpu[i];
    if (r.status) die(r.err);
    printf("%d,%.6f,%.6f,%.17g,%d\n", i, cpu[i], clock_s(CLOCK_MONOTONIC) - w0, r.fitness,
           r.eval.successes);
    fflush(stdout);
  }
  qsort(cpu, (size_t)n, sizeof *cpu, cmp_double);
  if (n > 0)
    printf("# %d individuals of %s, %s stage, generation %d: CPU per individual min %.4f s, "
           "median %.4f, max %.4f, mean %.4f\n", n, path, st_stage_name(t.stage), o.generation,
           cpu[0], cpu[n / 2], cpu[n - 1], sum / n);
  free(cpu);
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  st_genome_set_free(&set);
  return 0;
}
