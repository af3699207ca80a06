/* SPDX-License-Identifier: MIT
 * bench: speed of the simulation with a network in the loop.
 *
 *   bench [--mode kinematic|dynamic] [--threads N] [--reps R] [--trials T] [--no-baseline]
 *         [--baseline section.key=value[;key=value...]] [--config FILE] [--set k=v] [--rows]
 *         [--only random|press|held]
 *
 * Runs T trials of 60 control steps (50 ms each) per repetition, random genotypes, one world
 * per thread, and prints the median over R repetitions:
 *   mode=kinematic steps_per_s=... per_core=... threads=...
 *   mode=dynamic steps_per_s=... per_core=... threads=... bodies=... substep=... iterations=...
 * Every trial is an episode of the library's loop (st_episode_run: words, sensing, the network,
 * the world, a scorer that only sums a checksum), so what is timed is what evolution runs.
 * Kinematic trials start from a reach-like posture with the reach word; dynamic ones are the 16
 * main-prim trials of generation 0 (st_trial_spec: their postures, offsets and object-table
 * switch), cut to 60 steps. The same-run baseline is, in
 * kinematic mode, the brute-force contact detection; in dynamic mode the same trials with
 * dynamics.substep=0.005 (or the --baseline override). Dynamic mode also prints the contact-rich
 * figure held=...: the four move starts (the ball in a stable grasp) with the table gone from
 * the first step and the hand frozen at its start posture, 60 steps each; held_kept counts the
 * trials whose ball is still above the table at the end. And press=...: the hand closing on the
 * ball on the table, from the four grasp starts (the scripted controller's grasp, recorded once
 * from the step before its hand starts closing and replayed, 60 steps; press_kept counts the
 * balls still above the table top). The baseline line repeats cpu, press and held for the
 * baseline's configuration, measured interleaved (so --set KEY=on --baseline KEY=off is a
 * same-run before / after of a key). --rows prints, per scenario, what ODE's step solved: the
 * share of sub-steps with the robot in ODE, the contact points per such sub-step by pair kind
 * and the LCP rows (6 per hinge in ODE's step + 3 per contact point), the sub-steps redone
 * by dynamics.motor_active_set and by dynamics.adaptive_joints, and with dynamics.lcp other
 * than dense what its reduction took (dynamics.lcp = warm: the shares of the reduced LCPs
 * solved directly and left to ODE's Dantzig). --only runs one scenario (for
 * profiling). What is timed is what is named: the control steps alone (in the random trials,
 * the episode from its first step on: sensing, the network, the world), each thread's CPU time
 * and wall time summed over the trials; creating the worlds and resetting them before each
 * trial are timed apart and printed on their own line (setup=...), not in the rates. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app_common.h"
#include "press_plan.h"
#include "selftalk/evolve.h"
#include "selftalk/scripted.h"
#include "selftalk/trial.h"

static const char *prog = "bench";

static double now(void) { return app_seconds(APP_WALL); }

/* CPU seconds of the calling thread: per-core rates that another load on the machine barely
 * moves (wall-clock rates are printed beside them) */
static double cpu_now(void) { return app_seconds(APP_THREAD_CPU); }

/* what a thread spent: on the control steps, and apart from them on creating worlds and on
 * resetting them before each trial (CPU and wall seconds) */
typedef struct spent {
  double step_cpu, step_wall, create_cpu, reset_cpu;
  long steps, creates, resets;
} spent;

static void spent_merge(spent *to, const spent *from) {
  to->step_cpu += from->step_cpu, to->step_wall += from->step_wall;
  to->create_cpu += from->create_cpu, to->reset_cpu += from->reset_cpu;
  to->steps += from->steps, to->creates += from->creates, to->resets += from->resets;
}

/* a world created on the calling thread, the time counted as creation */
static stWorld *create_timed(const stProtocol *p, const stDynDef *def, spent *sp, char *e,
                             size_t esz) {
  const double c0 = cpu_now();
  stWorld *w = NULL;
  if (st_world_create_dynamic(p->robot, &p->scene, def, &w, e, esz) != ST_OK) w = NULL;
  sp->create_cpu += cpu_now() - c0;
  sp->creates++;
  return w;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* the bench's scorer: a checksum of every step's state, so nothing is optimised away; the
 * episode runs its full length unless the simulation diverges. begin (after the episode's reset)
 * marks where the steps start. */
typedef struct benchScore {
  double sum, cpu0, wall0;
} benchScore;

static void sum_begin(void *self) {
  benchScore *b = self;
  b->cpu0 = cpu_now();
  b->wall0 = now();
}

static int sum_step(void *self, stTraceStep *ts) {
  ((benchScore *)self)->sum += ts->q->d_r + ts->world->contacts.arm_table + ts->world->obj[2];
  return ts->unstable ? ST_END_FAILURE : -1;
}

/* one episode of the library's loop on the workspace's world for its mode, the network np
 * hearing the word of primitive prim; returns the checksum. With sp: the reset (and the
 * controller's) counted apart from the steps. */
static double bench_trial(const stProtocol *p, stWorkspace *ws, const stNetParams *np,
                          const stEpisodeSpec *e, int prim, spent *sp) {
  benchScore b = {0, 0, 0};
  stNetController nc;
  const stController ctl = st_net_controller(&nc, np, NULL, 0);
  const stWords words = {ST_WORDS_FIXED, prim, p->cfg.network_linguistic_input, 0.0};
  const stScorer sc = {sum_begin, sum_step, NULL, &b};
  char err[256];
  const double c0 = cpu_now();
  if (st_episode_run(p, ws, e, &ctl, &words, &sc, NULL, NULL, err, sizeof err))
    app_die(prog, "%s", err);
  if (sp) {
    const double c1 = cpu_now(), w1 = now();
    sp->reset_cpu += b.cpu0 - c0;
    sp->resets++;
    sp->step_cpu += c1 - b.cpu0;
    sp->step_wall += w1 - b.wall0;
    sp->steps += ws->dyn ? ws->dyn->step : e->steps;
  }
  return b.sum;
}

/* what the ODE step solved over some trials: sub-steps, those with the robot in ODE, contact
 * points by pair kind (stDynInfo) */
typedef struct dynStats {
  long substeps, ode_substeps, unstable, redos, aredos, hinge_substeps;
  long lcps, lcp_reduced, lcp_rows, lcp_unbounded, lcp_orders; /* dynamics.lcp = schur ... */
  long lcp_direct, lcp_fallbacks;                              /* ... warm */
  long points[ST_DYN_PAIR_COUNT];
} dynStats;

static void stats_add(dynStats *st, const stWorld *w) {
  stDynInfo in;
  st_world_dynamic_info(w, &in);
  st->substeps += (long)in.substeps * w->step;
  st->ode_substeps += in.dyn_substeps;
  st->unstable += st_world_unstable(w);
  st->redos += in.motor_redos;
  st->aredos += in.adaptive_redos;
  st->hinge_substeps += in.dyn_hinge_substeps;
  st->lcps += in.lcp_solves;
  st->lcp_reduced += in.lcp_reduced;
  st->lcp_rows += in.lcp_reduced_rows;
  st->lcp_unbounded += in.lcp_unbounded_rows;
  st->lcp_orders += in.lcp_orderings;
  st->lcp_direct += in.lcp_direct;
  st->lcp_fallbacks += in.lcp_fallbacks;
  for (int k = 0; k < ST_DYN_PAIR_COUNT; k++) st->points[k] += in.contact_points[k];
}

/* adds one thread's counts to the run's (callers hold the lock) */
static void stats_merge(dynStats *to, const dynStats *from) {
  to->substeps += from->substeps;
  to->ode_substeps += from->ode_substeps;
  to->unstable += from->unstable;
  to->redos += from->redos;
  to->aredos += from->aredos;
  to->hinge_substeps += from->hinge_substeps;
  to->lcps += from->lcps;
  to->lcp_reduced += from->lcp_reduced;
  to->lcp_rows += from->lcp_rows;
  to->lcp_unbounded += from->lcp_unbounded;
  to->lcp_orders += from->lcp_orders;
  to->lcp_direct += from->lcp_direct;
  to->lcp_fallbacks += from->lcp_fallbacks;
  for (int k = 0; k < ST_DYN_PAIR_COUNT; k++) to->points[k] += from->points[k];
}

/* the contact-rich cases:
 *   held:  the ball in the hand of a move start, the table gone, commands frozen;
 *   press: the hand closing on the ball on the table (pressPlan, below; plan non-NULL).
 * Returns 1 when the ball is still above the table top at the end (held: kept in the hand). */
typedef struct pressPlan pressPlan;
static int fixed_trial(stWorld *w, const stScene *scene, const double *q0, const double *obj,
                       const double *target, const double (*plan_y)[ST_NDOF], int steps,
                       uint64_t seed, dynStats *st, spent *sp) {
  const double c0 = cpu_now();
  st_world_set_seed(w, seed);
  st_world_reset(w, q0, obj, target);
  if (!plan_y) st_world_set_object_table_collision(w, 0);
  double y[ST_NET_MAX_OUT] = {0};
  memcpy(y, q0, sizeof(double) * ST_NDOF);
  const double c1 = cpu_now(), w1 = now();
  int t = 0;
  for (; t < steps && !st_world_unstable(w); t++) {
    if (plan_y) memcpy(y, plan_y[t], sizeof(double) * ST_NDOF);
    st_world_step(w, y);
  }
  sp->step_wall += now() - w1;
  sp->step_cpu += cpu_now() - c1;
  sp->reset_cpu += c1 - c0;
  sp->resets++;
  sp->steps += t;
  stats_add(st, w);
  return !st_world_unstable(w) && w->obj[2] > scene->table_hi[2];
}

static void plan_trial(const pressPlan *plan, int k, const double **q0, const double **obj,
                       const double **target, const double (**y)[ST_NDOF]);

/* T contact-rich trials on the given threads (trial t: start t mod 4 of press with a plan, else
 * of held; with solver step the same start gives the same trajectory); adds the time spent to
 * *sp and counts the balls kept */
static void fixed_run(const stProtocol *p, const stDynDef *def, const pressPlan *plan,
                      int trials, int steps, int threads, long *kept, dynStats *stats,
                      stDynInfo *info, spent *sp) {
  long k_sum = 0;
#pragma omp parallel num_threads(threads) reduction(+ : k_sum)
  {
    char e[256];
    dynStats mine;
    spent my;
    memset(&mine, 0, sizeof mine);
    memset(&my, 0, sizeof my);
    stWorld *w = create_timed(p, def, &my, e, sizeof e);
    if (w) {
#pragma omp single
      st_world_dynamic_info(w, info);
#pragma omp for schedule(dynamic, 1)
      for (int t = 0; t < trials; t++) {
        const int k = t % ST_NPOSTURE;
        const double *q0 = p->posture[ST_PRIM_MOVE][k], *obj = p->scene.obj_pos[k];
        const double *target = p->scene.target[k % 2];
        const double(*y)[ST_NDOF] = NULL;
        if (plan) plan_trial(plan, k, &q0, &obj, &target, &y);
        k_sum += fixed_trial(w, &p->scene, q0, obj, target, y, steps, (uint64_t)t, &mine, &my);
      }
      st_world_destroy(w);
    } else {
#pragma omp critical
      fprintf(stderr, "%s: %s\n", prog, e);
    }
#pragma omp critical
    {
      stats_merge(stats, &mine);
      spent_merge(sp, &my);
    }
  }
  *kept += k_sum;
}

/* one line of what the solver had to do in a scenario: the share of sub-steps with the robot in
 * ODE, and per such sub-step the contact points by pair kind and the LCP rows (6 per hinge in
 * ODE's step, 3 per contact point) */
static void print_rows(const char *name, const dynStats *st) {
  const double ode = st->ode_substeps > 0 ? (double)st->ode_substeps : 1.0;
  long all = 0;
  for (int k = 0; k < ST_DYN_PAIR_COUNT; k++) all += st->points[k];
  printf("rows scenario=%s robot_in_ode=%.0f%% points_per_ode_substep=%.2f robot_table=%.2f "
         "robot_ball=%.2f robot_base=%.2f object_table=%.2f object_floor=%.2f joint_rows=%.1f "
         "lcp_rows=%.1f motor_redos=%.3f adaptive_redos=%.3f\n",
         name, st->substeps ? 100.0 * (double)st->ode_substeps / (double)st->substeps : 0.0,
         (double)all / ode, (double)st->points[ST_DYN_PAIR_ROBOT_TABLE] / ode,
         (double)st->points[ST_DYN_PAIR_ROBOT_BALL] / ode,
         (double)st->points[ST_DYN_PAIR_ROBOT_BASE] / ode,
         (double)st->points[ST_DYN_PAIR_OBJECT_TABLE] / ode,
         (double)st->points[ST_DYN_PAIR_OBJECT_FLOOR] / ode,
         6.0 * (double)st->hinge_substeps / ode,
         6.0 * (double)st->hinge_substeps / ode + 3.0 * (double)all / ode,
         (double)st->redos / ode, (double)st->aredos / ode);
  if (st->lcps) { /* dynamics.lcp = schur: what the reduction took */
    const double red = st->lcp_reduced > 0 ? (double)st->lcp_reduced : 1.0;
    printf("lcp scenario=%s reduced=%.0f%% rows_per_reduced=%.1f unbounded=%.1f bounded=%.1f "
           "orders_computed=%.1f%% direct=%.1f%% fallback=%.1f%%\n", name,
           100.0 * (double)st->lcp_reduced / (double)st->lcps, (double)st->lcp_rows / red,
           (double)st->lcp_unbounded / red, (double)(st->lcp_rows - st->lcp_unbounded) / red,
           100.0 * (double)st->lcp_orders / red, 100.0 * (double)st->lcp_direct / red,
           100.0 * (double)st->lcp_fallbacks / red);
  }
}

/* T dynamic trials on the given threads; adds the time spent to *sp, fills per_trial */
static void dyn_run(const stProtocol *p, const stDynDef *def, const stNetParams *np, int ngenome,
                    int trials, int steps, int threads, double *per_trial, dynStats *stats,
                    stDynInfo *info, spent *sp) {
#pragma omp parallel num_threads(threads)
  {
    dynStats mine;
    spent my;
    memset(&mine, 0, sizeof mine);
    memset(&my, 0, sizeof my);
    char e[256];
    stWorld *w = create_timed(p, def, &my, e, sizeof e);
    if (w) {
      stWorkspace ws = {NULL, w, NULL}; /* the episodes run on this world, with its def */
#pragma omp single
      st_world_dynamic_info(w, info);
#pragma omp for schedule(dynamic, 4)
      for (int t = 0; t < trials; t++) {
        const int prim = t % ST_NPRIM, k = (t / ST_NPRIM) % ST_NPOSTURE;
        stTrialSpec spec;
        st_trial_spec(p, ST_STAGE_MAIN, 0, prim * ST_NPOSTURE + k, &spec);
        stEpisodeSpec ep;
        stWords unused;
        st_trial_episode(p, &spec, (uint64_t)t, &ep, &unused);
        ep.steps = steps;
        per_trial[t] = bench_trial(p, &ws, &np[t % ngenome], &ep, prim, &my);
        stats_add(&mine, w);
      }
      st_world_destroy(w);
    } else {
#pragma omp critical
      fprintf(stderr, "%s: %s\n", prog, e);
    }
#pragma omp critical
    {
      stats_merge(stats, &mine);
      spent_merge(sp, &my);
    }
  }
}

/* one configuration's figures over the repetitions: per repetition, control steps per wall
 * second and per CPU-second of the random-network trials, the press and the held trials */
typedef struct dynFigures {
  double *rate, *cpu, *press, *pcpu, *held, *hcpu;
  long press_kept, held_kept;
  dynStats st, pst, hst;
  stDynInfo info;
  spent setup; /* creation and resets, every scenario and repetition (the steps' too) */
} dynFigures;

static void figures_alloc(dynFigures *f, int reps) {
  memset(f, 0, sizeof *f);
  double **a[6] = {&f->rate, &f->cpu, &f->press, &f->pcpu, &f->held, &f->hcpu};
  for (int i = 0; i < 6; i++)
    if (!(*a[i] = calloc((size_t)reps, sizeof(double)))) app_die(prog, "out of memory");
}

static void figures_free(dynFigures *f) {
  double *a[6] = {f->rate, f->cpu, f->press, f->pcpu, f->held, f->hcpu};
  for (int i = 0; i < 6; i++) free(a[i]);
}

/* the medians (each array sorted) */
static void figures_median(dynFigures *f, int reps) {
  double *a[6] = {f->rate, f->cpu, f->press, f->pcpu, f->held, f->hcpu};
  for (int i = 0; i < 6; i++) qsort(a[i], (size_t)reps, sizeof(double), cmp_double);
}

/* the press trials (apps/press_plan.h): the scripted grasp from the four grasp starts with the
 * table kept on, recorded once per configuration (untimed); a timed press trial replays
 * PRESS_STEPS of its commands from rest */
enum { PRESS_STEPS = 60 };
struct pressPlan {
  double q0[ST_NPOSTURE][ST_NDOF];
  double obj[ST_NPOSTURE][3], target[ST_NPOSTURE][3];
  double y[ST_NPOSTURE][PRESS_STEPS][ST_NDOF];
};

static void plan_trial(const pressPlan *plan, int k, const double **q0, const double **obj,
                       const double **target, const double (**y)[ST_NDOF]) {
  *q0 = plan->q0[k];
  *obj = plan->obj[k];
  *target = plan->target[k];
  *y = plan->y[k];
}

static void press_record(const stProtocol *p, const stDynDef *def, pressPlan *plan) {
  char err[1024];
  for (int k = 0; k < ST_NPOSTURE; k++)
    if (st_press_plan(p, def, k, PRESS_STEPS, plan->q0[k], plan->obj[k], plan->target[k],
                      plan->y[k][0], err, sizeof err))
      app_die(prog, "press: %s", err);
}

/* repetition r of one configuration: the random-network trials, then press, then held */
static void figures_rep(const stProtocol *p, const stDynDef *def, const pressPlan *plan,
                        const stNetParams *np, int ngenome, int trials, int steps, int threads,
                        const char *only, double *per_trial, dynFigures *f, int r) {
  const int fixed_trials = 4 * ST_NPOSTURE;
  /* rates of the steps alone: per CPU-second summed over the threads, and per wall second with
   * the threads' step times overlapping */
  if (!only || !strcmp(only, "random")) {
    spent sp = {0, 0, 0, 0, 0, 0, 0};
    dyn_run(p, def, np, ngenome, trials, steps, threads, per_trial, &f->st, &f->info, &sp);
    f->rate[r] = (double)sp.steps * threads / sp.step_wall;
    f->cpu[r] = (double)sp.steps / sp.step_cpu;
    spent_merge(&f->setup, &sp);
  }
  if (!only || !strcmp(only, "press")) {
    spent sp = {0, 0, 0, 0, 0, 0, 0};
    fixed_run(p, def, plan, fixed_trials, PRESS_STEPS, threads, &f->press_kept, &f->pst, &f->info,
              &sp);
    f->press[r] = (double)sp.steps * threads / sp.step_wall;
    f->pcpu[r] = (double)sp.steps / sp.step_cpu;
    spent_merge(&f->setup, &sp);
  }
  if (!only || !strcmp(only, "held")) {
    spent sp = {0, 0, 0, 0, 0, 0, 0};
    fixed_run(p, def, NULL, fixed_trials, steps, threads, &f->held_kept, &f->hst, &f->info, &sp);
    f->held[r] = (double)sp.steps * threads / sp.step_wall;
    f->hcpu[r] = (double)sp.steps / sp.step_cpu;
    spent_merge(&f->setup, &sp);
  }
}

/* the line of what the rates leave out: creating a world and resetting it, CPU ms each, and
 * their share of all the CPU time the scenarios took */
static void print_setup(const char *name, const spent *sp) {
  const double all = sp->step_cpu + sp->create_cpu + sp->reset_cpu;
  printf("setup=%s create_cpu_ms=%.3f creates=%ld reset_cpu_ms=%.4f resets=%ld "
         "share_of_cpu=%.1f%% (not in the rates)\n", name,
         sp->creates ? 1e3 * sp->create_cpu / (double)sp->creates : 0.0, sp->creates,
         sp->resets ? 1e3 * sp->reset_cpu / (double)sp->resets : 0.0, sp->resets,
         all > 0 ? 100.0 * (sp->create_cpu + sp->reset_cpu) / all : 0.0);
}

static int bench_dynamic(const stProtocol *p, const char *baseline_set, int baseline, int threads,
                         int reps, int trials, int rows, const char *only, const stNetParams *np,
                         int ngenome) {
  char err[1024];
  const stConfig *cfg = &p->cfg;
  stDynDef def, base_def;
  st_dyn_def_from_config(cfg, &def);
  stConfig bcfg = *cfg;
  /* one or more k=v separated by ';' */
  char sets[1024];
  snprintf(sets, sizeof sets, "%s", baseline_set);
  for (char *save = NULL, *kv = strtok_r(sets, ";", &save); kv; kv = strtok_r(NULL, ";", &save))
    if (st_config_set(&bcfg, kv, err, sizeof err)) app_die(prog, "--baseline: %s", err);
  st_dyn_def_from_config(&bcfg, &base_def);
  const int steps = 60;
  const long fixed_all = 4L * ST_NPOSTURE * reps;
  pressPlan *plan = malloc(2 * sizeof *plan);
  if (!plan) app_die(prog, "out of memory");
  press_record(p, &def, &plan[0]);
  if (baseline) press_record(p, &base_def, &plan[1]);
  double *per_trial = malloc(sizeof *per_trial * (size_t)trials);
  dynFigures f, b;
  figures_alloc(&f, reps);
  figures_alloc(&b, reps);
  for (int rr = 0; rr < 2 * reps; rr++) {
    const int is_base = rr % 2, r = rr / 2; /* interleaved so drifts hit both alike */
    if (is_base && !baseline) continue;
    figures_rep(p, is_base ? &base_def : &def, &plan[is_base], np, ngenome, trials, steps,
                threads, only, per_trial, is_base ? &b : &f, r);
  }
  figures_median(&f, reps);
  figures_median(&b, reps);
  const int m = reps / 2;
  const double med = f.rate[m], med_base = b.rate[m];
  printf("mode=dynamic steps_per_s=%.0f per_core=%.0f threads=%d bodies=%d substep=%g "
         "iterations=%d solver=%s reps=%d trials=%d steps_per_trial=%d robot_in_ode=%.0f%% "
         "unstable=%ld held=%.0f held_per_core=%.0f held_kept=%ld/%ld cpu_per_core=%.0f "
         "held_cpu_per_core=%.0f press=%.0f press_per_core=%.0f press_kept=%ld/%ld "
         "press_cpu_per_core=%.0f\n",
         med, med / threads, threads, f.info.bodies, def.substep, def.iterations,
         st_config_enum_name("dynamics", "solver", f.info.solver), reps, trials, steps,
         f.st.substeps ? 100.0 * (double)f.st.ode_substeps / (double)f.st.substeps : 0.0,
         f.st.unstable + f.pst.unstable + f.hst.unstable, f.held[m], f.held[m] / threads,
         f.held_kept, fixed_all, f.cpu[m], f.hcpu[m], f.press[m], f.press[m] / threads,
         f.press_kept, fixed_all, f.pcpu[m]);
  if (baseline)
    printf("baseline=%s steps_per_s=%.0f per_core=%.0f speedup=%.2f robot_in_ode=%.0f%% "
           "unstable=%ld cpu_per_core=%.0f cpu_speedup=%.2f press_cpu_per_core=%.0f "
           "press_speedup=%.2f press_kept=%ld/%ld held_cpu_per_core=%.0f held_speedup=%.2f "
           "held_kept=%ld/%ld\n",
           baseline_set, med_base, med_base / threads, med / med_base,
           b.st.substeps ? 100.0 * (double)b.st.ode_substeps / (double)b.st.substeps : 0.0,
           b.st.unstable + b.pst.unstable + b.hst.unstable, b.cpu[m], f.cpu[m] / b.cpu[m],
           b.pcpu[m], f.pcpu[m] / b.pcpu[m], b.press_kept, fixed_all, b.hcpu[m],
           f.hcpu[m] / b.hcpu[m], b.held_kept, fixed_all);
  print_setup("set", &f.setup);
  if (baseline) print_setup("baseline", &b.setup);
  if (rows) {
    print_rows("random", &f.st);
    print_rows("press", &f.pst);
    print_rows("held", &f.hst);
  }
  free(per_trial);
  free(plan);
  figures_free(&f);
  figures_free(&b);
  return 0;
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *mode = "kinematic";
  int threads = 0, reps = 5, trials = 0, baseline = 1, rows = 0;
  const char *baseline_set = "dynamics.substep=0.005";
  const char *only = NULL; /* dynamic: random, press or held alone (profiling) */
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    if (!strcmp(argv[i], "--mode") && i + 1 < argc) mode = argv[++i];
    else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = app_int_arg(prog, argv[i], argv[i + 1], 1);
      i++;
    }
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc) {
      reps = app_int_arg(prog, argv[i], argv[i + 1], 1);
      i++;
    }
    else if (!strcmp(argv[i], "--trials") && i + 1 < argc) {
      trials = app_int_arg(prog, argv[i], argv[i + 1], 1);
      i++;
    }
    else if (!strcmp(argv[i], "--no-baseline")) baseline = 0; /* e.g. for profiling */
    else if (!strcmp(argv[i], "--rows")) rows = 1;
    else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else if (!strcmp(argv[i], "--baseline") && i + 1 < argc) baseline_set = argv[++i];
    else app_die(prog, "unknown or incomplete option '%s' (see the header of apps/bench.c)", argv[i]);
  }
  const int dynamic = !strcmp(mode, "dynamic");
  if (!dynamic && strcmp(mode, "kinematic"))
    app_die(prog, "--mode '%s': not available (expected kinematic or dynamic)", mode);
  if (trials == 0) trials = dynamic ? 128 : 2000;
  if (reps < 1 || trials < 1 || threads < 0) app_die(prog, "--reps, --trials must be >= 1, --threads >= 0");
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  threads = st_thread_count(threads, &cfg);
  char err[1024];
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) app_die(prog, "%s", err);
  const int steps = 60;

  /* random genotypes, decoded once: evaluation is what is measured */
  enum { NGENOME = 64 };
  stNetParams *np = malloc(sizeof *np * NGENOME);
  for (int i = 0; i < NGENOME; i++) {
    stRng rng = st_rng_keyed(st_config_rng_seed(&cfg), ST_RNG_INIT, 0, (uint64_t)i, 0);
    stGenome g;
    st_genome_random(&g, ST_GENES_BASE, &rng);
    st_net_decode(NULL, ST_ARCH_BASE, &g, &np[i], NULL, 0);
  }
  if (dynamic) {
    int rc =
        bench_dynamic(p, baseline_set, baseline, threads, reps, trials, rows, only, np, NGENOME);
    free(np);
    st_protocol_destroy(p);
    return rc;
  }
  stEpisodeSpec ep; /* kinematic: a reach-like start; the object-table switch does not apply */
  memset(&ep, 0, sizeof ep);
  static const double deg[9] = {0, 0, -30, 30, 0, 60, 0, 0, 0};
  for (int d = 0; d < 9; d++)
    ep.qhat0[d] = st_robot_dof_qhat(p->robot, d, deg[d] * 3.14159265358979323846 / 180);
  ep.steps = steps;
  ep.table_off_step = -1;

  /* the baseline, measured in the same run: every geometry through ODE's narrow phase, no
   * culling (stWorld.reference_contacts); same trials, same results */
  double *rate = malloc(sizeof *rate * (size_t)reps), *base = malloc(sizeof *base * (size_t)reps);
  double check = 0, check_base = 0, *per_trial = malloc(sizeof *per_trial * (size_t)trials);
  for (int rr = 0; rr < 2 * reps; rr++) {
    const int reference = rr % 2, r = rr / 2; /* interleaved so drifts hit both alike */
    if (reference && !baseline) continue;
    double t0 = now(), sum = 0;
#pragma omp parallel num_threads(threads)
    {
      stWorld *w = NULL;
      char e[256];
      if (st_world_create(p->robot, &p->scene, &w, e, sizeof e) == ST_OK) {
        w->reference_contacts = reference;
        stWorkspace ws = {w, NULL, NULL}; /* the episodes run on this world */
#pragma omp for schedule(dynamic, 16)
        for (int t = 0; t < trials; t++) {
          stEpisodeSpec et = ep;
          memcpy(et.obj, p->scene.obj_pos[t % ST_NPOSTURE], sizeof et.obj);
          memcpy(et.target, p->scene.target[t % 2], sizeof et.target);
          per_trial[t] = bench_trial(p, &ws, &np[t % NGENOME], &et, ST_PRIM_REACH, NULL);
        }
        st_world_destroy(w);
      }
    }
    double dt = now() - t0;
    for (int t = 0; t < trials; t++) sum += per_trial[t]; /* in trial order: thread-independent */
    (reference ? base : rate)[r] = (double)trials * steps / dt;
    *(reference ? &check_base : &check) += sum;
  }
  qsort(rate, (size_t)reps, sizeof *rate, cmp_double);
  qsort(base, (size_t)reps, sizeof *base, cmp_double);
  double med = rate[reps / 2], med_base = base[reps / 2];
  printf("mode=%s steps_per_s=%.0f per_core=%.0f threads=%d reps=%d trials=%d steps_per_trial=%d\n",
         mode, med, med / threads, threads, reps, trials, steps);
  if (baseline)
    printf("baseline=reference_contacts steps_per_s=%.0f per_core=%.0f speedup=%.2f same_result=%s\n",
         med_base, med_base / threads, med / med_base, check == check_base ? "yes" : "NO");
  free(rate);
  free(base);
  free(per_trial);
  free(np);
  st_protocol_destroy(p);
  return 0;
}
