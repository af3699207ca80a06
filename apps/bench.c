/* SPDX-License-Identifier: MIT
 * bench: speed of the simulation with a network in the loop.
 *
 *   bench [--mode kinematic] [--threads N] [--reps R] [--trials T] [--no-baseline]
 *         [--config FILE] [--set k=v]
 *
 * Runs T trials of 60 control steps (50 ms each) per repetition, random genotypes, one world
 * per thread, and prints the median over R repetitions:
 *   mode=kinematic steps_per_s=... per_core=... threads=... */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app_common.h"
#include "selftalk/net.h"
#include "selftalk/sensors.h"

static const char *prog = "bench";

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* one kinematic trial: sense, think, act; returns a checksum so nothing is optimised away */
static double kin_trial(stWorld *w, const stSensorDef *sd, const stNetParams *np, const double *q0,
                        const double *obj, const double *target, int steps) {
  stNetState ns;
  st_net_reset(np, &ns);
  st_world_reset(w, q0, obj, target);
  double in[ST_NET_MAX_IN], out[ST_NET_MAX_OUT], ling[4] = {10, 0, 0, 0}, sum = 0;
  int focus_target = 0;
  for (int t = 0; t < steps; t++) {
    stQuantities q;
    st_quantities(w, sd, &q);
    st_sensor_inputs(w, sd, &q, focus_target, t == 0, ling, 0, in, ST_NET_NIN);
    st_net_step(np, &ns, in, out);
    focus_target = st_focus_is_target(sd, out[ST_NET_OUT_FOCUS]);
    st_world_step_kinematic(w, out);
    sum += q.d_r + w->contacts.arm_table;
  }
  return sum;
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *mode = "kinematic";
  int threads = 0, reps = 5, trials = 2000, baseline = 1;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    if (!strcmp(argv[i], "--mode") && i + 1 < argc) mode = argv[++i];
    else if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--trials") && i + 1 < argc) trials = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--no-baseline")) baseline = 0; /* e.g. for profiling */
    else app_die(prog, "unknown or incomplete option '%s' (see the header of apps/bench.c)", argv[i]);
  }
  if (strcmp(mode, "kinematic")) app_die(prog, "--mode '%s': not available (expected kinematic)", mode);
  if (reps < 1 || trials < 1 || threads < 0) app_die(prog, "--reps, --trials must be >= 1, --threads >= 0");
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  if (threads == 0) threads = cfg.run_threads > 0 ? cfg.run_threads : omp_get_num_procs();
  char err[1024];
  stRobot *robot = NULL;
  if (st_robot_create(&cfg, &robot, err, sizeof err)) app_die(prog, "%s", err);
  stScene scene;
  st_scene_from_config(&cfg, &scene);
  stSensorDef sd;
  st_sensor_def_from_config(&cfg, &sd);
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
  double q0[ST_NDOF];
  static const double deg[9] = {0, 0, -30, 30, 0, 60, 0, 0, 0};
  for (int d = 0; d < 9; d++) q0[d] = st_robot_dof_qhat(robot, d, deg[d] * 3.14159265358979323846 / 180);
  q0[9] = q0[10] = q0[11] = 0;

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
      if (st_world_create(robot, &scene, &w, e, sizeof e) == ST_OK) {
        w->reference_contacts = reference;
#pragma omp for schedule(dynamic, 16)
        for (int t = 0; t < trials; t++)
          per_trial[t] = kin_trial(w, &sd, &np[t % NGENOME], q0, scene.obj_pos[t % 4], scene.target[t % 2], steps);
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
  st_robot_destroy(robot);
  return 0;
}
