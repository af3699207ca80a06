/* SPDX-License-Identifier: MIT
 * scripted: the hand-written controller of selftalk/scripted.h on the 16 main-prim trials and
 * the 8 integrated trials (4 reach postures x 2 targets) - the proof that every primitive is
 * physically achievable in dynamic mode.
 *
 *   scripted [--config FILE] [--set section.key=value]... [--trace DIR] [--only NAME]
 *            [--threads N]
 *
 * Prints one line per trial, in this order:
 *   trial main-prim PRIMITIVE K success=0|1 steps=N           (PRIMITIVE reach..move, K 0..3)
 *   trial integrated move-object-to-target K success=0|1 steps=N   (K = 2 posture + target)
 * then "scripted: N passed, M failed"; exits 0 only when every trial run succeeded. Main-prim
 * trials are those of generation 0 (their random offsets), scored by the library; steps is
 * the number of control steps simulated; integrated trials last at most integrated.steps
 * (240: 12 s). --trace DIR
 * writes DIR/main_PRIMITIVE_K.csv and DIR/integrated_K.csv, one row per step: the trace CSV
 * of replay --out (selftalk/trace.h, which tools/draw_trial.py and tools/trial_video.py read)
 * with a last column, the controller's phase. --only runs the trials whose file name (without .csv)
 * starts with NAME. --threads (default run.threads, 0 = one per core) changes no result.
 *
 * --generations FIRST:LAST sweeps the main-prim trials (those --only selects) over the trial
 * tables of generations FIRST..LAST of the configuration's seed (their object and target
 * offsets, and the solver key of each generation's individual 0: what an evolution run with
 * that seed asked of its population), the integrated trials not run:
 *   sweep G main-prim PRIMITIVE K success=0|1 steps=N min_d_r=M final_d_r=F obj=X,Y
 * (M the least d_r of the trial, m; X, Y the object centre), then per trial
 *   sweep main-prim PRIMITIVE K solved=S of N min_d_r_worst=M (generation G)
 * (the largest per-trial least d_r and its generation), then "scripted: N passed, M failed".
 * With --trace DIR each trial's trace is DIR/main_PRIMITIVE_K_gG.csv. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app_common.h"
#include "selftalk/evolve.h"
#include "selftalk/scripted.h"
#include "selftalk/trace.h"

static const char *prog = "scripted";
static const char *usage = "usage: scripted [--config FILE] [--set section.key=value]... "
                           "[--trace DIR] [--only NAME] [--threads N] [--generations FIRST:LAST]";

enum { NMAIN = ST_PRIM_TRIALS, NINT = 2 * ST_NPOSTURE, NALL = NMAIN + NINT };

/* the trace's phase column: what the controller is doing */
static const char *phase_of(const void *s) { return st_scripted_phase(s); }

/* --generations: the least and the last d_r of a trial */
typedef struct sweepTrace {
  double min_d_r, final_d_r;
  stTraceCsv csv; /* csv.f NULL: no file */
} sweepTrace;

static void sweep_trace(void *ctx, const stTraceStep *ts) {
  sweepTrace *t = ctx;
  if (ts->q->d_r < t->min_d_r) t->min_d_r = ts->q->d_r;
  t->final_d_r = ts->q->d_r;
  if (t->csv.f) st_trace_csv_row(&t->csv, ts);
}

/* the main-prim trials of generations first..last; returns the number of failures */
static int sweep(const stProtocol *p, const int *run, int first, int last, int threads,
                 const char *trace_dir) {
  const int ngen = last - first + 1;
  const long n = (long)ngen * NMAIN;
  int *success = calloc((size_t)n, sizeof *success), *steps = calloc((size_t)n, sizeof *steps);
  double *min_d = calloc((size_t)n, sizeof *min_d), *fin_d = calloc((size_t)n, sizeof *fin_d);
  double(*obj)[2] = calloc((size_t)n, sizeof *obj);
  char(*why)[1100] = calloc((size_t)n, sizeof *why);
  if (!success || !steps || !min_d || !fin_d || !obj || !why) app_die(prog, "out of memory");
  int failed_setup = 0;
#pragma omp parallel num_threads(threads) reduction(+ : failed_setup)
  {
    stWorkspace ws = {NULL, NULL, NULL};
    stScripted *s = NULL;
    char terr[1024];
    if (st_scripted_create(p, &s, terr, sizeof terr)) failed_setup++;
#pragma omp for schedule(dynamic, 1)
    for (long j = 0; j < n; j++) {
      const int g = first + (int)(j / NMAIN), i = (int)(j % NMAIN);
      if (!run[i] || !s) continue;
      stTrialSpec t;
      st_trial_spec(p, ST_STAGE_MAIN, g, i, &t);
      obj[j][0] = t.obj[0];
      obj[j][1] = t.obj[1];
      sweepTrace tr = {HUGE_VAL, HUGE_VAL, {NULL, 9, ST_ARCH_BASE, phase_of, s}};
      char path[1100];
      if (trace_dir) {
        snprintf(path, sizeof path, "%s/main_%s_%d_g%d.csv", trace_dir,
                 st_primitive_name(i / ST_NPOSTURE), i % ST_NPOSTURE, g);
        if (!(tr.csv.f = fopen(path, "w"))) {
          snprintf(why[j], sizeof why[j], "%.1000s: cannot write", path);
          continue;
        }
        st_trace_csv_header(&tr.csv);
      }
      stTrialResult r;
      const stStatus st = st_scripted_main_trial_at(p, &ws, s, g, i, &r, sweep_trace, &tr, terr,
                                                    sizeof terr);
      if (tr.csv.f && fclose(tr.csv.f) != 0 && !st)
        snprintf(why[j], sizeof why[j], "%.1000s: write error", path);
      if (st) snprintf(why[j], sizeof why[j], "%s", terr);
      if (st || why[j][0]) continue;
      success[j] = r.success;
      steps[j] = (int)r.steps_run;
      min_d[j] = tr.min_d_r;
      fin_d[j] = tr.final_d_r;
    }
    st_scripted_destroy(s);
    st_workspace_free(&ws);
  }
  if (failed_setup) app_die(prog, "cannot create the controller (out of memory)");
  int pass = 0, fail = 0;
  for (long j = 0; j < n; j++) {
    const int g = first + (int)(j / NMAIN), i = (int)(j % NMAIN);
    if (!run[i]) continue;
    if (why[j][0]) fprintf(stderr, "%s: generation %d: %s\n", prog, g, why[j]);
    printf("sweep %d main-prim %s %d success=%d steps=%d min_d_r=%.4f final_d_r=%.4f obj=%.4f,%.4f\n",
           g, st_primitive_name(i / ST_NPOSTURE), i % ST_NPOSTURE, success[j], steps[j], min_d[j],
           fin_d[j], obj[j][0], obj[j][1]);
    if (success[j] && !why[j][0]) pass++;
    else fail++;
  }
  for (int i = 0; i < NMAIN; i++) {
    if (!run[i]) continue;
    int solved = 0, worst_g = first;
    double worst = -1.0;
    for (int g = first; g <= last; g++) {
      const long j = (long)(g - first) * NMAIN + i;
      solved += success[j] && !why[j][0];
      if (min_d[j] > worst) worst = min_d[j], worst_g = g;
    }
    printf("sweep main-prim %s %d solved=%d of %d min_d_r_worst=%.4f (generation %d)\n",
           st_primitive_name(i / ST_NPOSTURE), i % ST_NPOSTURE, solved, ngen, worst, worst_g);
  }
  printf("scripted: %d passed, %d failed\n", pass, fail);
  free(success);
  free(steps);
  free(min_d);
  free(fin_d);
  free(obj);
  free(why);
  return fail == 0 && pass > 0 ? 0 : 1;
}

static void trial_name(int i, char *name, size_t n) {
  if (i < NMAIN) snprintf(name, n, "main_%s_%d", st_primitive_name(i / ST_NPOSTURE), i % ST_NPOSTURE);
  else snprintf(name, n, "integrated_%d", i - NMAIN);
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *trace_dir = NULL, *only = NULL;
  int threads = -1, gen_first = -1, gen_last = -1;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--trace") && i + 1 < argc) trace_dir = argv[++i];
    else if (!strcmp(a, "--only") && i + 1 < argc) only = argv[++i];
    else if (!strcmp(a, "--generations") && i + 1 < argc) {
      char *end, *mid;
      const char *v = argv[++i];
      const long f = strtol(v, &mid, 10);
      const long l = *mid == ':' ? strtol(mid + 1, &end, 10) : -1;
      if (mid == v || *mid != ':' || *end || end == mid + 1 || f < 0 || l < f || l > 1000000)
        app_die(prog, "--generations '%s': expected FIRST:LAST, 0 <= FIRST <= LAST", v);
      gen_first = (int)f;
      gen_last = (int)l;
    }
    else if (!strcmp(a, "--threads") && i + 1 < argc) {
      char *end;
      const long v = strtol(argv[++i], &end, 10);
      if (*end || end == argv[i] || v < 0 || v > 1024)
        app_die(prog, "--threads '%s': expected 0..1024 (0 = one per core)", argv[i]);
      threads = (int)v;
    } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      printf("%s\n", usage);
      return 0;
    } else {
      app_die(prog, "unknown or incomplete option '%s' (%s)", a, usage);
    }
  }
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  threads = st_thread_count(threads, threads < 0 ? &cfg : NULL); /* --threads 0: one per core */
  if (trace_dir && mkdir(trace_dir, 0777) != 0 && errno != EEXIST)
    app_die(prog, "%s: cannot create the directory", trace_dir);
  char err[1024];
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) app_die(prog, "%s", err);

  int run[NALL], success[NALL], steps[NALL], failed_setup = 0;
  char why[NALL][1100];
  for (int i = 0; i < NALL; i++) {
    char name[64];
    trial_name(i, name, sizeof name);
    run[i] = !only || !strncmp(name, only, strlen(only));
    success[i] = steps[i] = 0;
    why[i][0] = 0;
  }
  if (gen_first >= 0) {
    const int rc = sweep(p, run, gen_first, gen_last, threads, trace_dir);
    st_protocol_destroy(p);
    return rc;
  }
#pragma omp parallel num_threads(threads) reduction(+ : failed_setup)
  {
    stWorkspace ws = {NULL, NULL, NULL};
    stScripted *s = NULL;
    char terr[1024];
    if (st_scripted_create(p, &s, terr, sizeof terr)) failed_setup++;
#pragma omp for schedule(dynamic, 1)
    for (int i = 0; i < NALL; i++) {
      if (!run[i] || !s) continue;
      char name[64], path[1040];
      trial_name(i, name, sizeof name);
      stTraceCsv tc = {NULL, 9, ST_ARCH_BASE, phase_of, s};
      if (trace_dir) {
        snprintf(path, sizeof path, "%s/%s.csv", trace_dir, name);
        if (!(tc.f = fopen(path, "w"))) snprintf(why[i], sizeof why[i], "%s: cannot write", path);
        else st_trace_csv_header(&tc);
      }
      stStatus st;
      if (i < NMAIN) {
        stTrialResult r;
        st = st_scripted_main_trial(p, &ws, s, i, &r, tc.f ? st_trace_csv_fn : NULL, &tc, terr, sizeof terr);
        if (!st) {
          success[i] = r.success;
          steps[i] = (int)r.steps_run;
        }
      } else {
        const int k = (i - NMAIN) / 2, t = (i - NMAIN) % 2;
        stIntTrialResult r;
        st = st_scripted_integrated(p, &ws, s, k, t, &r, tc.f ? st_trace_csv_fn : NULL, &tc, terr,
                                    sizeof terr);
        if (!st) {
          success[i] = r.success;
          steps[i] = (int)r.steps_run;
        }
      }
      if (st) snprintf(why[i], sizeof why[i], "%s", terr);
      if (tc.f && fclose(tc.f) != 0) snprintf(why[i], sizeof why[i], "%s: write error", path);
    }
    st_scripted_destroy(s);
    st_workspace_free(&ws);
  }
  if (failed_setup) app_die(prog, "cannot create the controller (out of memory)");
  int pass = 0, fail = 0;
  for (int i = 0; i < NALL; i++) {
    if (!run[i]) continue;
    if (why[i][0]) fprintf(stderr, "%s: %s\n", prog, why[i]);
    if (i < NMAIN)
      printf("trial main-prim %s %d success=%d steps=%d\n", st_primitive_name(i / ST_NPOSTURE),
             i % ST_NPOSTURE, success[i], steps[i]);
    else
      printf("trial integrated move-object-to-target %d success=%d steps=%d\n", i - NMAIN,
             success[i], steps[i]);
    if (success[i] && !why[i][0]) pass++;
    else fail++;
  }
  printf("scripted: %d passed, %d failed\n", pass, fail);
  st_protocol_destroy(p);
  return fail == 0 && pass > 0 ? 0 : 1;
}
