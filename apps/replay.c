/* SPDX-License-Identifier: MIT
 * replay: runs one trial of a saved genotype and writes its per-step trace (SPEC §9).
 *
 *   replay GENOME CONFIG --trial K [--out trace.csv] [--exact] [--stage simple|main]
 *          [--generation G] [--index I] [--force OUT=VALUE[@STEP]]... [--set section.key=value]...
 *
 * K = 0..15 (primitive K/4: reach, open, grasp, move; posture and object position K%4).
 * The genotypes are of network.arch's architecture (base for the primitive stages' runs; A or
 * B replays an integrated-stage genotype on the primitive trials, without the secondary input).
 * --generation picks the trials' random offsets; --index the genotype of GENOME (a number, or
 * "last"). Without --index: in a file of per-generation bests (evolve's best.genome, whose
 * records carry "# generation G") the record of generation G, or the last record and its
 * generation when --generation is not given either; otherwise the first genotype (the best in
 * population.genome) with generation 0. Prints the genotype chosen and a one-line summary.
 * --exact prints the trace's reals with 17 significant digits (they read back bit for bit: for
 * comparing runs, and the golden results of tests/check_golden.sh) instead of 9.
 * --force overrides network output OUT (0..11 the DOF of SPEC §3, 12 focus) with VALUE (0..1)
 * from step STEP on (default 0): what the individual would do with, e.g., its thumb opposed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/trial.h"

static const char *prog = "replay";

#define MAX_FORCE 32
#define MAX_STEP 100000 /* far beyond any trial; keeps the step an int */

/* --force OUT=VALUE[@STEP] */
static stForce force_arg(const char *v) {
  stForce f = {0, 0.0, 0};
  char *end;
  long out = strtol(v, &end, 10);
  int ok = end != v && *end == '=';
  if (ok) {
    const char *s = end + 1;
    f.value = strtod(s, &end);
    ok = end != s;
  }
  long from = 0;
  if (ok && *end == '@') {
    const char *s = end + 1;
    from = strtol(s, &end, 10);
    ok = end != s;
  }
  if (!ok || *end)
    app_die(prog, "--force '%s': expected OUT=VALUE or OUT=VALUE@STEP (e.g. 9=1@20)", v);
  if (out < 0 || out > ST_NET_OUT_FOCUS)
    app_die(prog, "--force '%s': output %ld (expected 0..%d: the 12 DOF, then focus)", v, out,
            ST_NET_OUT_FOCUS);
  if (!(f.value >= 0.0 && f.value <= 1.0))
    app_die(prog, "--force '%s': value %g (expected 0..1)", v, f.value);
  if (from < 0 || from > MAX_STEP)
    app_die(prog, "--force '%s': step %ld (expected 0..%d)", v, from, MAX_STEP);
  f.output = (int)out;
  f.from_step = (int)from;
  return f;
}

typedef struct traceCtx {
  FILE *f;
  int digits; /* significant digits of the trace's reals: 9, or 17 with --exact */
} traceCtx;

static void header(FILE *f) {
  fprintf(f, "step");
  for (int d = 0; d < ST_NDOF; d++) fprintf(f, ",q%d", d);
  fprintf(f, ",palm_x,palm_y,palm_z,obj_x,obj_y,obj_z,target_x,target_y,target_z");
  for (int i = 0; i < ST_NTOUCH; i++) fprintf(f, ",touch%d", i);
  fprintf(f, ",focus_out,focus_target,ling_reach,ling_open,ling_grasp,ling_move,S,P,success_now,"
             "event,d_r,d_g,d_m,d_mhat,h,p,touching,lifted\n");
}

static void real(const traceCtx *c, double x) { fprintf(c->f, ",%.*g", c->digits, x); }

static void on_step(void *ctx, const stTraceStep *s) {
  const traceCtx *c = ctx;
  FILE *f = c->f;
  const stWorld *w = s->world;
  const stQuantities *q = s->q;
  static const char *const events[] = {"", "end_success", "end_failure", "end_quiet"};
  fprintf(f, "%d", s->step);
  for (int d = 0; d < ST_NDOF; d++) real(c, w->qhat[d]);
  const double *points[3] = {q->palm, w->obj, w->target};
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) real(c, points[i][k]);
  for (int i = 0; i < ST_NTOUCH; i++) fprintf(f, ",%d", w->contacts.touch[i]);
  real(c, s->out[ST_NET_OUT_FOCUS]);
  fprintf(f, ",%d", s->focus_target);
  for (int m = 0; m < ST_NET_NLING; m++) fprintf(f, ",%g", s->in[ST_NET_IN_LING + m]);
  real(c, s->S);
  real(c, s->P);
  fprintf(f, ",%d,%s", s->success_now,
          s->event >= ST_END_SUCCESS && s->event <= ST_END_QUIET ? events[s->event] : "");
  const double dist[6] = {q->d_r, q->d_g, q->d_m, q->d_mhat, q->h, q->p};
  for (int i = 0; i < 6; i++) real(c, dist[i]);
  fprintf(f, ",%d,%d\n", q->touching, q->lifted);
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *genome = NULL, *out = NULL, *stage_name = NULL;
  int trial = -1, generation = -1, index = -1, index_last = 0, nforce = 0, digits = 9;
  stForce force[MAX_FORCE];
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--trial") && i + 1 < argc) trial = app_int_arg(prog, a, argv[++i], 0);
    else if (!strcmp(a, "--out") && i + 1 < argc) out = argv[++i];
    else if (!strcmp(a, "--force") && i + 1 < argc) {
      if (nforce == MAX_FORCE) app_die(prog, "--force: at most %d", MAX_FORCE);
      force[nforce++] = force_arg(argv[++i]);
    }
    else if (!strcmp(a, "--stage") && i + 1 < argc) stage_name = argv[++i];
    else if (!strcmp(a, "--exact")) digits = 17;
    else if (!strcmp(a, "--generation") && i + 1 < argc) generation = app_int_arg(prog, a, argv[++i], 0);
    else if (!strcmp(a, "--index") && i + 1 < argc) {
      if (!strcmp(argv[++i], "last")) index_last = 1;
      else index = app_int_arg(prog, a, argv[i], 0);
    }
    else if (a[0] == '-' && a[1]) app_die(prog, "unknown or incomplete option '%s'", a);
    else if (!genome) genome = a;
    else if (!ca.config_path) ca.config_path = a;
    else app_die(prog, "unexpected argument '%s'", a);
  }
  if (!genome || !ca.config_path)
    app_die(prog, "usage: replay GENOME CONFIG --trial K [--out trace.csv] [--exact] "
                  "[--stage simple|main] [--generation G] [--index I] [--force OUT=VALUE[@STEP]]...");
  if (trial < 0 || trial >= ST_PRIM_TRIALS) app_die(prog, "--trial: expected 0..%d", ST_PRIM_TRIALS - 1);
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  stStage stage = cfg.stage_stages == 1 ? ST_STAGE_MAIN : ST_STAGE_SIMPLE;
  if (!stage_name && cfg.stage_stages == 2)
    app_die(prog, "%s runs simple-prim then main-prim: give --stage simple or --stage main",
            ca.config_path);
  if (stage_name) {
    if (!strcmp(stage_name, "simple")) stage = ST_STAGE_SIMPLE;
    else if (!strcmp(stage_name, "main")) stage = ST_STAGE_MAIN;
    else app_die(prog, "--stage '%s': expected simple or main", stage_name);
  }
  char err[1024];
  stGenomeSet set;
  /* network.arch: a genotype of the integrated stage (type A or B) replays primitive trials too */
  const stNetArch arch = (stNetArch)cfg.network_arch;
  if (st_genome_set_read(genome, st_arch_ngenes(arch), &set, err, sizeof err))
    app_die(prog, "%s (network.arch = %s)", err, st_arch_name(arch));
  if (index_last) index = set.count - 1;
  if (index >= set.count) app_die(prog, "--index %d: %s has %d genotypes", index, genome, set.count);
  if (index < 0) { /* not given: see the header comment */
    int history = set.count > 0 && set.generation[0] >= 0;
    for (int k = 1; history && k < set.count; k++) history = set.generation[k] > set.generation[k - 1];
    index = 0;
    if (history && generation < 0) index = set.count - 1;
    else if (history) {
      index = -1;
      for (int k = 0; k < set.count && index < 0; k++)
        if (set.generation[k] == generation) index = k;
      if (index < 0)
        app_die(prog, "--generation %d: %s has no genotype of that generation (it has %d..%d); "
                "give --index to replay another generation's genotype with these offsets",
                generation, genome, set.generation[0], set.generation[set.count - 1]);
    }
  }
  if (generation < 0) generation = set.generation[index] >= 0 ? set.generation[index] : 0;
  fprintf(stderr, "replay: genotype %d of %s, trial offsets of generation %d\n", index, genome,
          generation);
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) app_die(prog, "%s", err);
  stNetParams np;
  if (st_net_decode(&p->net, arch, &set.genome[index], &np, err, sizeof err)) app_die(prog, "%s", err);
  st_genome_set_free(&set);

  stTrialSpec t;
  st_trial_spec(p, stage, generation, trial, &t);
  FILE *f = NULL;
  if (out && !(f = fopen(out, "w"))) app_die(prog, "%s: cannot write", out);
  if (f) header(f);
  traceCtx ctx = {f, digits};
  stWorkspace ws = {NULL, NULL};
  stTrialResult r;
  uint64_t key = st_rng_keyed((uint64_t)cfg.run_seed, ST_RNG_TRIAL, (uint64_t)generation,
                              (uint64_t)index, (uint64_t)trial).key;
  if (st_trial_run_forced(p, &ws, &t, &np, force, nforce, key, &r, f ? on_step : NULL, &ctx, err,
                          sizeof err))
    app_die(prog, "%s", err);
  if (f && fclose(f) != 0) app_die(prog, "%s: write error", out);
  /* this trial's share of F_p: the primitive's N_p spans its four trials */
  long n_p = 0;
  for (int k = 0; k < ST_NPOSTURE; k++) {
    stTrialSpec o;
    st_trial_spec(p, stage, generation, t.primitive * ST_NPOSTURE + k, &o);
    n_p += o.steps;
  }
  double share = (r.success ? p->fitness.bonus : 0.0) + p->fitness.scale / (double)n_p * (r.sum_s - r.sum_p);
  static const char *ends[] = {"full", "success", "failure", "quiet"};
  printf("trial %d %s %s k=%d success=%d steps=%ld/%d end=%s first_success_step=%d sum_S=%.6f "
         "sum_P=%.6f F_contribution=%.6f\n",
         trial, st_stage_name(stage), st_primitive_name(t.primitive), t.k, r.success, r.steps_run,
         t.steps, ends[r.end], r.success_step, r.sum_s, r.sum_p, share);
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  return 0;
}
