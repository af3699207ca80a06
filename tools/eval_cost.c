/* SPDX-License-Identifier: MIT
 * eval_cost: what evaluating one individual (or running one post-evaluation trial) costs, one
 * by one, on one thread: the unit of work evolve hands to a thread or an MPI rank
 * (docs/PROTOCOL.md, "Evaluation across processes": the scaling model reads this) and the unit
 * tools/replicate_cost.py prices the study in (`make -f tools/replicate.mk cost`). A
 * diagnostic, not part of the protocol.
 *
 *   build/eval_cost CONFIG [--population FILE] [--generation G] [--count N] [--spread]
 *                   [--stage simple-prim|main-prim] [--posteval TEST [--caretaker]]
 *                   [section.key=value]...
 *
 * Evaluation (the default): the first N genotypes (default ga.population; --spread: N spread
 * evenly over the file) of FILE (default the config's stage.init_population; a population file
 * or a run's checkpoint) in the config's last primitive stage (main-prim for prims; --stage
 * names another) or, for an integrated config, in the integrated stage (genotypes of
 * network.arch), at generation G's trials (default 0), as st_evolve_run's threads do
 * (st_evolve_task_run). Prints `individual,cpu_s,wall_s,fitness,successes` rows.
 *
 * --posteval TEST (integration, robustness, generalisation): N trials of the test's table
 * (default 8), trial k * trials / N run by genotype k of FILE (modulo its count: the best
 * first, as the tests take them), with the test's words (--caretaker: the generalisation test's
 * caretaker variant), as st_post_run's threads do. Prints `individual,trial,cpu_s,wall_s,
 * success,steps_run` rows.
 *
 * CPU is the thread's CPU time, which other work on the machine barely moves. After the rows,
 * a `# ` summary (min, median, max, mean) and a `# plan: key=value ...` line: what one job of
 * the config runs - population and generations (ga.max_generations, or
 * ga.integrated_generations), or a test's trials per individual and individuals per input.
 * --count 0 prints the plan alone (the config and the population read, nothing simulated). */
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

#define USAGE                                                                                   \
  "usage: eval_cost CONFIG [--population FILE] [--generation G] [--count N] [--spread] "        \
  "[--stage simple-prim|main-prim] [--posteval integration|robustness|generalisation "          \
  "[--caretaker]] [section.key=value]..."

typedef struct options {
  const char *config, *population;
  int generation, count, spread, stage, test, caretaker;
  const char *sets[64];
  int nsets;
} options;

static int int_arg(const char *v) {
  char *end;
  const long x = strtol(v, &end, 10);
  if (*end || end == v || x < 0 || x > 1000000) die("expected an integer >= 0");
  return (int)x;
}

static int stage_arg(const char *v) {
  for (int s = 0; s < ST_STAGE_COUNT; s++)
    if (!strcmp(v, st_stage_name((stStage)s))) return s;
  die("--stage: expected simple-prim or main-prim");
  return -1;
}

static void parse(int argc, char **argv, options *o) {
  memset(o, 0, sizeof *o);
  o->count = -1;
  o->stage = -1;
  o->test = -1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--population") && i + 1 < argc) o->population = argv[++i];
    else if (!strcmp(a, "--generation") && i + 1 < argc) o->generation = int_arg(argv[++i]);
    else if (!strcmp(a, "--count") && i + 1 < argc) o->count = int_arg(argv[++i]);
    else if (!strcmp(a, "--spread")) o->spread = 1;
    else if (!strcmp(a, "--stage") && i + 1 < argc) o->stage = stage_arg(argv[++i]);
    else if (!strcmp(a, "--posteval") && i + 1 < argc) {
      if ((o->test = st_post_test_parse(argv[++i])) < 0)
        die("--posteval: expected integration, robustness or generalisation");
    } else if (!strcmp(a, "--caretaker")) o->caretaker = 1;
    else if (a[0] != '-' && strchr(a, '=') && o->nsets < 64) o->sets[o->nsets++] = a;
    else if (a[0] != '-' && !o->config) o->config = a;
    else die(USAGE);
  }
  if (!o->config) die("missing CONFIG");
  if (o->caretaker && (o->test < 0 || st_post_test_info(o->test)->variant != ST_POST_CARETAKER))
    die("--caretaker goes with a --posteval test whose variant is the caretaker's words "
        "(generalisation)");
  if (o->test >= 0 && (o->spread || o->stage >= 0))
    die("--spread and --stage go with an evolution stage, not --posteval");
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* the `# ` summary of n CPU times (sorted here), each of one unit (individual, trial) */
static void summary(double *cpu, int n, const char *what, const char *unit) {
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += cpu[i];
  qsort(cpu, (size_t)n, sizeof *cpu, cmp_double);
  if (n > 0)
    printf("# %s: CPU per %s min %.4f s, median %.4f, max %.4f, mean %.4f\n", what, unit,
           cpu[0], cpu[n / 2], cpu[n - 1], sum / n);
}

/* an evolution stage: n genotypes of set, one task each */
static void evaluate(const options *o, const stConfig *cfg, const stProtocol *p,
                     const stIntegratedDef *idef, const stGenomeSet *set, const char *path,
                     int integrated, stStage stage) {
  const int n = o->count >= 0 && o->count < set->count ? o->count
                : cfg->ga_population < set->count ? cfg->ga_population : set->count;
  double *cpu = calloc((size_t)n + 1, sizeof *cpu);
  if (!cpu) die("out of memory");
  stWorkspace ws = {NULL, NULL, NULL};
  stEvolveTask t;
  stEvolveResult r;
  memset(&t, 0, sizeof t);
  t.integrated = integrated;
  t.stage = stage;
  t.generation = o->generation;
  printf("individual,cpu_s,wall_s,fitness,successes\n");
  for (int i = 0; i < n; i++) {
    t.individual = o->spread ? (int)((long)i * set->count / n) : i;
    t.genome = set->genome[t.individual];
    const double c0 = clock_s(CLOCK_THREAD_CPUTIME_ID), w0 = clock_s(CLOCK_MONOTONIC);
    st_evolve_task_run(p, idef, &ws, &t, &r);
    cpu[i] = clock_s(CLOCK_THREAD_CPUTIME_ID) - c0;
    if (r.status) die(r.err);
    printf("%d,%.6f,%.6f,%.17g,%d\n", t.individual, cpu[i], clock_s(CLOCK_MONOTONIC) - w0,
           r.fitness, integrated ? r.ieval.successes : r.eval.successes);
    fflush(stdout);
  }
  char what[1024];
  snprintf(what, sizeof what, "%d individuals of %s, %s stage, generation %d", n, path,
           integrated ? ST_INTEGRATED_STAGE_NAME : st_stage_name(stage), o->generation);
  summary(cpu, n, what, "individual");
  /* replace_generations: the chain stage's first phase (postures.vary_replace_generations),
   * cheaper than the rest (no varied trials), priced apart */
  printf("# plan: population=%d generations=%d replace_generations=%d\n", cfg->ga_population,
         integrated ? cfg->ga_integrated_generations : cfg->ga_max_generations,
         integrated ? 0 : cfg->postures_vary_replace_generations);
  free(cpu);
  st_workspace_free(&ws);
}

/* a post-evaluation test: n trials of its table, trial k * trials / n by genotype k */
static void trials(const options *o, const stConfig *cfg, const stProtocol *p,
                   const stIntegratedDef *idef, const stGenomeSet *set, const char *path) {
  char err[1024];
  const stPostTest test = (stPostTest)o->test;
  const stPostVariant variant = o->caretaker ? ST_POST_CARETAKER : ST_POST_OWN_WORDS;
  stPostDef pd;
  st_post_def_from_config(cfg, test, &pd);
  stWordSource words;
  if (st_post_words(idef, test, variant, &words, err, sizeof err)) die(err);
  const int n = o->count >= 0 ? o->count : 8;
  double *cpu = calloc((size_t)n + 1, sizeof *cpu);
  if (!cpu) die("out of memory");
  stWorkspace ws = {NULL, NULL, NULL};
  printf("individual,trial,cpu_s,wall_s,success,steps_run\n");
  for (int k = 0; k < n; k++) {
    const int i = k % set->count, ti = (int)((long)k * pd.trials / n);
    stPostTrial trial;
    st_post_trial(&pd, &p->scene, ti, &trial);
    stNetParams np;
    if (st_net_decode(&p->net, (stNetArch)cfg->network_arch, &set->genome[i], &np, err, sizeof err))
      die(err);
    stNetController nc;
    const stController ctl = st_net_controller(&nc, &np, NULL, 0);
    stPostResult r;
    const double c0 = clock_s(CLOCK_THREAD_CPUTIME_ID), w0 = clock_s(CLOCK_MONOTONIC);
    if (st_post_run_trial(p, idef, &ws, &trial, &ctl, words, &r, NULL, NULL, err, sizeof err))
      die(err);
    cpu[k] = clock_s(CLOCK_THREAD_CPUTIME_ID) - c0;
    printf("%d,%d,%.6f,%.6f,%d,%d\n", i, ti, cpu[k], clock_s(CLOCK_MONOTONIC) - w0, r.success,
           r.steps_run);
    fflush(stdout);
  }
  char what[1024];
  snprintf(what, sizeof what, "%d trials of the %s test%s by genotypes of %s", n,
           st_post_test_name(test), o->caretaker ? " (caretaker variant)" : "", path);
  summary(cpu, n, what, "trial");
  printf("# plan: trials=%d individuals=%d\n", pd.trials,
         test == ST_POST_INTEGRATION ? cfg->posteval_integration_top : 1);
  free(cpu);
  st_workspace_free(&ws);
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
  const int integrated = stages == ST_CONFIG_INTEGRATED;
  if (!integrated && !(stages & (ST_CONFIG_SIMPLE_PRIM | ST_CONFIG_MAIN_PRIM)))
    die("a primitive-stage or integrated-stage config");
  if (integrated && o.stage >= 0) die("--stage: an integrated config has no primitive stage");
  if (o.test >= 0 && !integrated && o.test != ST_POST_INTEGRATION)
    die("--posteval robustness and generalisation take an integrated config");
  stStage stage = stages & ST_CONFIG_MAIN_PRIM ? ST_STAGE_MAIN : ST_STAGE_SIMPLE;
  if (o.stage >= 0) {
    stage = (stStage)o.stage;
    if (!(stages & (stage == ST_STAGE_MAIN ? ST_CONFIG_MAIN_PRIM : ST_CONFIG_SIMPLE_PRIM)))
      die("--stage: the config does not run that stage");
  }
  const char *path = o.population ? o.population : cfg.stage_init_population;
  if (!path[0]) die("no population: give --population FILE");
  /* genotypes of the network evolved (primitive stages: base) or tested */
  const stNetArch arch = integrated ? (stNetArch)cfg.network_arch : ST_ARCH_BASE;
  stGenomeSet set;
  stProtocol *p = NULL;
  /* --count 0: the plan alone, without the simulator */
  if (st_genome_set_read(path, st_arch_ngenes(arch), &set, err, sizeof err) ||
      (o.count != 0 && st_protocol_create(&cfg, &p, err, sizeof err)))
    die(err);
  if (set.count < 1) die("no genotypes in the population");
  stIntegratedDef idef;
  st_integrated_def_from_config(&cfg, &idef);
  if (o.test >= 0) trials(&o, &cfg, p, &idef, &set, path);
  else evaluate(&o, &cfg, p, &idef, &set, path, integrated, stage);
  st_protocol_destroy(p);
  st_genome_set_free(&set);
  return 0;
}
