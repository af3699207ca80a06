/* SPDX-License-Identifier: MIT
 * bench: speed of the simulation with a network in the loop.
 *
 *   bench [--mode kinematic|dynamic] [--threads N] [--reps R] [--trials T] [--no-baseline]
 *         [--baseline section.key=value] [--config FILE] [--set k=v]
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
 * trials whose ball is still above the table at the end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app_common.h"
#include "selftalk/evolve.h"
#include "selftalk/trial.h"

static const char *prog = "bench";

static double now(void) { return app_seconds(APP_WALL); }

/* CPU seconds of the whole process: per-core rates that another load on the machine barely
 * moves (wall-clock rates are printed beside them) */
static double cpu_now(void) { return app_seconds(APP_PROCESS_CPU); }

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* the bench's scorer: a checksum of every step's state, so nothing is optimised away; the
 * episode runs its full length unless the simulation diverges */
static int sum_step(void *self, stTraceStep *ts) {
  *(double *)self += ts->q->d_r + ts->world->contacts.arm_table + ts->world->obj[2];
  return ts->unstable ? ST_END_FAILURE : -1;
}

/* one episode of the library's loop on the workspace's world for its mode, the network np
 * hearing the word of primitive prim; returns the checksum */
static double bench_trial(const stProtocol *p, stWorkspace *ws, const stNetParams *np,
                          const stEpisodeSpec *e, int prim) {
  double sum = 0;
  stNetController nc;
  const stController ctl = st_net_controller(&nc, np, NULL, 0);
  const stWords words = {ST_WORDS_FIXED, prim, p->cfg.network_linguistic_input, 0.0};
  const stScorer sc = {NULL, sum_step, NULL, &sum};
  char err[256];
  if (st_episode_run(p, ws, e, &ctl, &words, &sc, NULL, NULL, err, sizeof err))
    app_die(prog, "%s", err);
  return sum;
}

/* the contact-rich case: the ball in the hand of a move start, table gone, commands frozen;
 * returns 1 when the ball is still above the table top at the end */
static int held_trial(stWorld *w, const stScene *scene, const double *q0, const double *obj,
                      const double *target, int steps, uint64_t seed) {
  st_world_set_seed(w, seed);
  st_world_reset(w, q0, obj, target);
  st_world_set_object_table_collision(w, 0);
  double y[ST_NET_MAX_OUT] = {0};
  memcpy(y, q0, sizeof(double) * ST_NDOF);
  for (int t = 0; t < steps && !st_world_unstable(w); t++) st_world_step(w, y);
  return !st_world_unstable(w) && w->obj[2] > scene->table_hi[2];
}

/* T held trials on the given threads (trial t: move start t mod 4; with solver step the same
 * start gives the same trajectory); returns the elapsed time and counts the balls kept */
static double held_run(const stRobot *robot, const stScene *scene, const stDynDef *def,
                       const double (*q0)[ST_NPOSTURE][ST_NDOF], int trials, int steps, int threads,
                       long *kept) {
  double t0 = now();
  long k_sum = 0;
#pragma omp parallel num_threads(threads) reduction(+ : k_sum)
  {
    stWorld *w = NULL;
    char e[256];
    if (st_world_create_dynamic(robot, scene, def, &w, e, sizeof e) == ST_OK) {
#pragma omp for schedule(dynamic, 1)
      for (int t = 0; t < trials; t++) {
        const int k = t % ST_NPOSTURE;
        k_sum += held_trial(w, scene, q0[ST_PRIM_MOVE][k], scene->obj_pos[k], scene->target[k % 2],
                            steps, (uint64_t)t);
      }
      st_world_destroy(w);
    } else {
#pragma omp critical
      fprintf(stderr, "%s: %s\n", prog, e);
    }
  }
  *kept += k_sum;
  return now() - t0;
}

typedef struct dynStats {
  long substeps, ode_substeps, unstable;
} dynStats;

/* T dynamic trials on the given threads; returns the elapsed time, fills per_trial */
static double dyn_run(const stProtocol *p, const stDynDef *def, const stNetParams *np, int ngenome,
                      int trials, int steps, int threads, double *per_trial, dynStats *stats,
                      stDynInfo *info) {
  double t0 = now();
  long sub = 0, ode = 0, unst = 0;
#pragma omp parallel num_threads(threads) reduction(+ : sub, ode, unst)
  {
    stWorld *w = NULL;
    char e[256];
    if (st_world_create_dynamic(p->robot, &p->scene, def, &w, e, sizeof e) == ST_OK) {
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
        per_trial[t] = bench_trial(p, &ws, &np[t % ngenome], &ep, prim);
        stDynInfo in;
        st_world_dynamic_info(w, &in);
        sub += (long)in.substeps * w->step;
        ode += in.dyn_substeps;
        unst += st_world_unstable(w);
      }
      st_world_destroy(w);
    } else {
#pragma omp critical
      fprintf(stderr, "%s: %s\n", prog, e);
    }
  }
  stats->substeps += sub;
  stats->ode_substeps += ode;
  stats->unstable += unst;
  return now() - t0;
}

static int bench_dynamic(const stProtocol *p, const char *baseline_set, int baseline, int threads,
                         int reps, int trials, const stNetParams *np, int ngenome) {
  char err[1024];
  const stConfig *cfg = &p->cfg;
  stDynDef def, base_def;
  st_dyn_def_from_config(cfg, &def);
  stConfig bcfg = *cfg;
  if (st_config_set(&bcfg, baseline_set, err, sizeof err)) app_die(prog, "--baseline: %s", err);
  st_dyn_def_from_config(&bcfg, &base_def);
  const int steps = 60;
  double *rate = malloc(sizeof *rate * (size_t)reps), *base = malloc(sizeof *base * (size_t)reps);
  double *per_trial = malloc(sizeof *per_trial * (size_t)trials);
  double *held = malloc(sizeof *held * (size_t)reps);
  double *cpu = malloc(sizeof *cpu * (size_t)reps), *bcpu = malloc(sizeof *bcpu * (size_t)reps);
  double *hcpu = malloc(sizeof *hcpu * (size_t)reps);
  const int held_trials = 4 * ST_NPOSTURE;
  long kept = 0;
  dynStats st = {0, 0, 0}, bst = {0, 0, 0};
  stDynInfo info, binfo;
  memset(&info, 0, sizeof info);
  memset(&binfo, 0, sizeof binfo);
  for (int rr = 0; rr < 2 * reps; rr++) {
    const int is_base = rr % 2, r = rr / 2; /* interleaved so drifts hit both alike */
    if (is_base && !baseline) continue;
    const double c0 = cpu_now();
    double dt = dyn_run(p, is_base ? &base_def : &def, np, ngenome, trials, steps, threads,
                        per_trial, is_base ? &bst : &st, is_base ? &binfo : &info);
    (is_base ? base : rate)[r] = (double)trials * steps / dt;
    (is_base ? bcpu : cpu)[r] = (double)trials * steps / (cpu_now() - c0);
    if (!is_base) {
      const double c1 = cpu_now();
      held[r] = (double)held_trials * steps /
                held_run(p->robot, &p->scene, &def, p->posture, held_trials, steps, threads, &kept);
      hcpu[r] = (double)held_trials * steps / (cpu_now() - c1);
    }
  }
  qsort(cpu, (size_t)reps, sizeof *cpu, cmp_double);
  qsort(bcpu, (size_t)reps, sizeof *bcpu, cmp_double);
  qsort(hcpu, (size_t)reps, sizeof *hcpu, cmp_double);
  qsort(rate, (size_t)reps, sizeof *rate, cmp_double);
  qsort(base, (size_t)reps, sizeof *base, cmp_double);
  qsort(held, (size_t)reps, sizeof *held, cmp_double);
  const double med = rate[reps / 2], med_base = base[reps / 2];
  printf("mode=dynamic steps_per_s=%.0f per_core=%.0f threads=%d bodies=%d substep=%g "
         "iterations=%d solver=%s reps=%d trials=%d steps_per_trial=%d robot_in_ode=%.0f%% "
         "unstable=%ld held=%.0f held_per_core=%.0f held_kept=%ld/%ld cpu_per_core=%.0f "
         "held_cpu_per_core=%.0f\n",
         med, med / threads, threads, info.bodies, def.substep, def.iterations,
         st_config_enum_name("dynamics", "solver", info.solver), reps, trials, steps,
         st.substeps ? 100.0 * (double)st.ode_substeps / (double)st.substeps : 0.0, st.unstable,
         held[reps / 2], held[reps / 2] / threads, kept, (long)held_trials * reps, cpu[reps / 2],
         hcpu[reps / 2]);
  if (baseline)
    printf("baseline=%s steps_per_s=%.0f per_core=%.0f speedup=%.2f robot_in_ode=%.0f%% "
           "unstable=%ld cpu_per_core=%.0f cpu_speedup=%.2f\n",
           baseline_set, med_base, med_base / threads, med / med_base,
           bst.substeps ? 100.0 * (double)bst.ode_substeps / (double)bst.substeps : 0.0,
           bst.unstable, bcpu[reps / 2], cpu[reps / 2] / bcpu[reps / 2]);
  free(rate);
  free(base);
  free(per_trial);
  free(held);
  free(cpu);
  free(bcpu);
  free(hcpu);
  return 0;
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *mode = "kinematic";
  int threads = 0, reps = 5, trials = 0, baseline = 1;
  const char *baseline_set = "dynamics.substep=0.005";
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
    stRng rng = st_rng_keyed(cfg.run_seed, ST_RNG_INIT, 0, (uint64_t)i, 0);
    stGenome g;
    st_genome_random(&g, ST_GENES_BASE, &rng);
    st_net_decode(NULL, ST_ARCH_BASE, &g, &np[i], NULL, 0);
  }
  if (dynamic) {
    int rc = bench_dynamic(p, baseline_set, baseline, threads, reps, trials, np, NGENOME);
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
          per_trial[t] = bench_trial(p, &ws, &np[t % NGENOME], &et, ST_PRIM_REACH);
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
