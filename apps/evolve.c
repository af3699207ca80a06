/* SPDX-License-Identifier: MIT
 * evolve: runs the stages a config names (simple-prim, main-prim, or both in sequence).
 *
 *   evolve CONFIG [--seed N] [--out DIR] [--threads N] [--generations N] [--resume]
 *          [--set section.key=value]... [--help-config]
 *
 * Prints one progress line per generation; writes config.ini, fitness.csv, best.genome,
 * population.genome and an atomic checkpoint into DIR (default runs/CONFIGNAME-sSEED).
 * --resume continues a killed run from DIR/checkpoint and ends with the same files.
 * --generations N is the run's cap, ga.max_generations (ga.integrated_generations in the
 * integrated stage) set to N: config.ini records it; a resumed run may take another cap.
 *
 * Under mpirun (built with MPI: evolve_mpi.h) rank 0 does all of the above and the other ranks
 * evaluate the individuals; the files are the same for any number of ranks. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "evolve_mpi.h"
#include "selftalk/evolve.h"

static const char *prog = "evolve";

static void usage(FILE *f) {
  fprintf(f, "usage: evolve CONFIG [--seed N] [--out DIR] [--threads N] [--generations N] [--resume]\n"
             "              [--set section.key=value]... [--help-config]\n");
  if (app_mpi_built())
    fprintf(f, "       mpirun -n N evolve CONFIG ...  (built with MPI: rank 0 runs the GA and writes the "
               "files,\n              ranks 1..N-1 evaluate, each on --threads threads)\n");
}

int main(int argc, char **argv) {
  /* the other ranks of an MPI job evaluate what rank 0 hands them; they never read argv */
  if (app_mpi_start(&argc, &argv) == APP_MPI_WORKER) return app_mpi_serve();
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *out = NULL;
  int seed = -1, threads = 0, generations = 0, resume = 0;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--seed") && i + 1 < argc) seed = app_int_arg(prog, a, argv[++i], 0);
    else if (!strcmp(a, "--out") && i + 1 < argc) out = argv[++i];
    else if (!strcmp(a, "--threads") && i + 1 < argc) threads = app_int_arg(prog, a, argv[++i], 1);
    else if (!strcmp(a, "--generations") && i + 1 < argc) generations = app_int_arg(prog, a, argv[++i], 1);
    else if (!strcmp(a, "--resume")) resume = 1;
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) return usage(stdout), 0;
    else if (a[0] == '-' && a[1]) {
      usage(stderr);
      app_die(prog, "unknown or incomplete option '%s'", a);
    } else if (!ca.config_path) ca.config_path = a;
    else app_die(prog, "unexpected argument '%s'", a);
  }
  if (!ca.config_path) {
    usage(stderr);
    app_die(prog, "missing CONFIG");
  }
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  if (seed >= 0) cfg.run_seed = seed;
  char dir[1024];
  if (!out) {
    const char *base = strrchr(ca.config_path, '/');
    base = base ? base + 1 : ca.config_path;
    size_t n = strcspn(base, ".");
    snprintf(dir, sizeof dir, "runs/%.*s-s%d", (int)n, base, cfg.run_seed);
    out = dir;
  }
  printf("evolve: %s, seed %d, output in %s\n", ca.config_path, cfg.run_seed, out);
  /* the two settings that set a run's protocol apart most (SPEC 13): which starts, which solver */
  printf("evolve: reach starts %s (postures.reach_palm_down); contact %s%s\n",
         cfg.postures_reach_palm_down ? "palm down" : "position only, palm as the arm leaves it",
         cfg.stage_stages == ST_STAGES_SIMPLE ? "none (simple-prim is kinematic)" : "ODE, dynamics.lcp = ",
         cfg.stage_stages == ST_STAGES_SIMPLE ? "" : st_config_enum_name("dynamics", "lcp", cfg.dynamics_lcp));
  fflush(stdout);
  stEvolveDef def = {&cfg, out, threads, generations, resume, stdout,
                     app_mpi_evaluator(threads, out, stdout)};
  char err[2048];
  if (st_evolve_run(&def, err, sizeof err)) app_die(prog, "%s", err);
  return 0;
}
