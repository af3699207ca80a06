/* SPDX-License-Identifier: MIT
 * trial_sweep: the genotypes of a genome file (a run's checkpoint, population.genome or
 * best.genome) on chosen primitive-stage trials over the trial tables of many generations: which
 * of a population solve a trial a run stalls on, and for which offsets. A diagnostic (issue 46,
 * docs/PROTOCOL.md "Why main-prim runs stall at 15 of 16"), not part of the protocol.
 *
 *   build/trial_sweep CONFIG GENOME [--trials LIST] [--generations FIRST:LAST] [--count N]
 *                     [--stage simple|main] [--threads N] [--set section.key=value]...
 *
 * LIST: comma-separated trial indices (default 0..15). Genotypes 0..N-1 of GENOME (default:
 * all). Each trial runs as evolution would have run it for genotype I at generation G: G's
 * trial table (offsets) and the solver key of individual I (st_trial_seed_key). One line per
 * (generation, genotype, trial), in that order whatever --threads:
 *   G I T success=0|1 steps=N sum_S=S sum_P=P min_d_r=M final_d_r=F first_success_step=K
 * palm=X,Y,Z obj=X,Y,Z
 * (d_r in m: the least and the last of the trial; palm centre and object centre after the last
 * step). Exit 0 unless a trial could not run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/selftalk.h"

static void die(const char *fmt, const char *a) {
  fprintf(stderr, "trial_sweep: ");
  fprintf(stderr, fmt, a);
  fprintf(stderr, "\n");
  exit(2);
}

typedef struct sweepRow {
  int success, steps, first;
  double sum_s, sum_p, min_d_r, final_d_r;
  double palm[3], obj[3]; /* after the last step */
  char why[1024];
} sweepRow;

static void on_step(void *ctx, const stTraceStep *ts) {
  sweepRow *r = ctx;
  if (ts->q->d_r < r->min_d_r) r->min_d_r = ts->q->d_r;
  r->final_d_r = ts->q->d_r;
  memcpy(r->palm, ts->world->p[ts->world->robot->palm_body], sizeof r->palm);
  memcpy(r->obj, ts->world->obj, sizeof r->obj);
}

int main(int argc, char **argv) {
  static const char usage[] =
      "usage: trial_sweep CONFIG GENOME [--trials LIST] [--generations FIRST:LAST] [--count N] "
      "[--stage simple|main] [--threads N] [--set section.key=value]...";
  const char *config = NULL, *genome = NULL, *trials_arg = NULL;
  const char **sets = calloc((size_t)argc, sizeof *sets);
  int nsets = 0, first = 0, last = 0, count = -1, threads = 1;
  stStage stage = ST_STAGE_MAIN;
  if (!sets) die("%s", "out of memory");
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    char *end = NULL;
    if (!strcmp(a, "--trials") && i + 1 < argc) trials_arg = argv[++i];
    else if (!strcmp(a, "--generations") && i + 1 < argc) {
      const char *v = argv[++i];
      first = (int)strtol(v, &end, 10);
      if (end == v || *end != ':') die("--generations '%s': expected FIRST:LAST", v);
      const char *w = end + 1;
      last = (int)strtol(w, &end, 10);
      if (end == w || *end || first < 0 || last < first) die("--generations '%s': expected FIRST:LAST", v);
    } else if (!strcmp(a, "--count") && i + 1 < argc) {
      count = (int)strtol(argv[++i], &end, 10);
      if (*end || count < 1) die("--count '%s': expected a positive number", argv[i]);
    } else if (!strcmp(a, "--threads") && i + 1 < argc) {
      threads = (int)strtol(argv[++i], &end, 10);
      if (*end || threads < 1 || threads > 1024) die("--threads '%s': expected 1..1024", argv[i]);
    } else if (!strcmp(a, "--stage") && i + 1 < argc) {
      const char *v = argv[++i];
      if (!strcmp(v, "simple")) stage = ST_STAGE_SIMPLE;
      else if (!strcmp(v, "main")) stage = ST_STAGE_MAIN;
      else die("--stage '%s': expected simple or main", v);
    } else if (!strcmp(a, "--set") && i + 1 < argc) sets[nsets++] = argv[++i];
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      printf("%s\n", usage);
      return 0;
    } else if (a[0] == '-') die("unknown or incomplete option '%s'", a);
    else if (!config) config = a;
    else if (!genome) genome = a;
    else die("unexpected argument '%s'", a);
  }
  if (!config || !genome) die("%s", usage);

  char err[1024];
  stConfig cfg;
  st_config_default(&cfg);
  if (st_config_load(config, &cfg, err, sizeof err)) die("%s", err);
  if (nsets && st_config_set_all(&cfg, sets, nsets, err, sizeof err)) die("%s", err);
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) die("%s", err);
  const int ntab = st_stage_trials(p, stage);

  int trials[ST_MAIN_TRIALS_MAX], ntrials = 0;
  if (trials_arg) {
    const char *c = trials_arg;
    for (;;) {
      char *end;
      const long t = strtol(c, &end, 10);
      if (end == c || t < 0 || t >= ntab || ntrials >= ST_MAIN_TRIALS_MAX)
        die("--trials '%s': expected comma-separated trial indices of the stage", trials_arg);
      trials[ntrials++] = (int)t;
      if (!*end) break;
      if (*end != ',') die("--trials '%s': expected comma-separated trial indices", trials_arg);
      c = end + 1;
    }
  } else {
    for (int t = 0; t < ST_PRIM_TRIALS; t++) trials[ntrials++] = t;
  }

  stGenomeSet set;
  if (st_genome_set_read(genome, 0, &set, err, sizeof err)) die("%s", err);
  if (count < 0 || count > set.count) count = set.count;
  stNetParams *net = calloc((size_t)count, sizeof *net);
  if (!net) die("%s", "out of memory");
  for (int i = 0; i < count; i++)
    if (st_net_decode(&p->net, ST_ARCH_BASE, &set.genome[i], &net[i], err, sizeof err)) die("%s", err);

  const int ngen = last - first + 1;
  const long n = (long)ngen * count * ntrials;
  sweepRow *rows = calloc((size_t)n, sizeof *rows);
  if (!rows) die("%s", "out of memory");
#pragma omp parallel num_threads(threads)
  {
    stWorkspace ws = {NULL, NULL, NULL};
#pragma omp for schedule(dynamic, 1)
    for (long j = 0; j < n; j++) {
      const int g = first + (int)(j / ((long)count * ntrials));
      const int ind = (int)(j / ntrials % count), ti = trials[j % ntrials];
      sweepRow *r = &rows[j];
      stTrialSpec t;
      st_trial_spec(p, stage, g, ti, &t);
      stTrialResult res;
      r->min_d_r = r->final_d_r = HUGE_VAL;
      stNetController nc;
      const stController ctl = st_net_controller(&nc, &net[ind], NULL, 0);
      if (st_trial_run(p, &ws, &t, &ctl, st_trial_seed_key(p, g, ind, ti), &res, on_step, r,
                       r->why, sizeof r->why))
        continue;
      r->success = res.success;
      r->steps = (int)res.steps_run;
      r->first = res.success_step;
      r->sum_s = res.sum_s;
      r->sum_p = res.sum_p;
    }
    st_workspace_free(&ws);
  }
  int failed = 0;
  for (long j = 0; j < n; j++) {
    const int g = first + (int)(j / ((long)count * ntrials));
    const int ind = (int)(j / ntrials % count), ti = trials[j % ntrials];
    const sweepRow *r = &rows[j];
    if (r->why[0]) {
      fprintf(stderr, "trial_sweep: generation %d genotype %d trial %d: %s\n", g, ind, ti, r->why);
      failed++;
      continue;
    }
    printf("%d %d %d success=%d steps=%d sum_S=%.6f sum_P=%.6f min_d_r=%.5f final_d_r=%.5f "
           "first_success_step=%d palm=%.4f,%.4f,%.4f obj=%.4f,%.4f,%.4f\n",
           g, ind, ti, r->success, r->steps, r->sum_s, r->sum_p, r->min_d_r, r->final_d_r, r->first,
           r->palm[0], r->palm[1], r->palm[2], r->obj[0], r->obj[1], r->obj[2]);
  }
  free(rows);
  free(net);
  free(sets);
  st_genome_set_free(&set);
  st_protocol_destroy(p);
  return failed ? 1 : 0;
}
