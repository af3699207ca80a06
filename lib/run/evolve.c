/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include "selftalk/evolve.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "run/checkpoint.h"
#include "core/internal.h"
#include "selftalk/assemble.h"
#include "selftalk/fitnesscsv.h"
#include "selftalk/ga.h"
#include "selftalk/integrated.h"
#include "selftalk/io.h"
#include "selftalk/trial.h"

/* the primitive stages evolve the base network; network.arch names what the integrated stage
 * grows it into (thesis 2.9.2), so a run without that stage refuses another value of it */
static const stNetArch PRIM_ARCH = ST_ARCH_BASE;

typedef struct run {
  const stEvolveDef *def;
  const stConfig *cfg; /* &own: def->cfg with --generations as the run's cap key */
  stConfig own;
  int cap_changed;     /* resuming under another cap than config.ini's: written anew */
  stProtocol *proto;
  stGa *ga;
  int integrated;     /* the integrated stage (thesis 2.9); else the primitive stages */
  stIntegratedDef idef;
  stStage stages[2];
  int nstages;
  int stage_idx;      /* index into stages */
  int stage_gen;      /* generations done in the current stage */
  int limit;          /* total generations allowed */
  int threads;
  stWorkspace *ws;    /* one per thread */
  stEvaluation *eval; /* per individual (primitive stages) */
  stIntEvaluation *ieval; /* per individual (integrated stage) */
  stEvolveTask *tasks;    /* per individual: what to evaluate, */
  stEvolveResult *results; /* and what it gave */
  double *fitness;
  stGenome *sorted;   /* the final population, best first (before finish: scratch) */
  double *sorted_fit;
  stFitnessCsv fcsv;  /* fitness.csv's columns (plan_run) */
  double t_start;
  int done_here;      /* generations run by this process */
  char path[6][ST_PATH_MAX];
} run;

enum { P_CONFIG, P_CSV, P_BEST, P_POP, P_CKPT, P_PROBE };

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void hms(double s, char *buf, size_t n) {
  long t = (long)(s + 0.5);
  snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
}

static long long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long long)st.st_size : -1;
}

/* the out dir must exist (created) and take files, before any work */
/* a small file written whole; -1 with errno on any failure, the stream closed either way */
static int write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  const int bad = fputs(text, f) < 0;
  return fclose(f) != 0 || bad ? -1 : 0;
}

static stStatus prepare_dir(run *R, char *err, size_t errsz) {
  const char *dir = R->def->out_dir;
  char tmp[ST_PATH_MAX];
  size_t n = strlen(dir);
  if (n == 0 || n + 32 >= sizeof tmp) {
    st__errf(err, errsz, "output directory '%s': bad path", dir);
    return ST_ERR_IO;
  }
  /* mkdir -p */
  st__strlcpy(tmp, dir, sizeof tmp);
  for (char *p = tmp + 1; *p; p++)
    if (*p == '/') {
      *p = 0;
      mkdir(tmp, 0777);
      *p = '/';
    }
  if (mkdir(tmp, 0777) != 0 && errno != EEXIST) {
    st__errf(err, errsz, "output directory '%s': cannot create: %s", dir, strerror(errno));
    return ST_ERR_IO;
  }
  static const char *names[6] = {"config.ini", "fitness.csv", "best.genome", "population.genome",
                                 "checkpoint", ".write_probe"};
  for (int i = 0; i < 6; i++) snprintf(R->path[i], ST_PATH_MAX, "%s/%s", dir, names[i]);
  if (write_text(R->path[P_PROBE], "probe\n")) {
    st__errf(err, errsz, "output directory '%s': not writable: %s", dir, strerror(errno));
    return ST_ERR_IO;
  }
  remove(R->path[P_PROBE]);
  return ST_OK;
}

/* ---- checkpoint (lib/run/checkpoint.h) ---- */

/* what a checkpoint of this run may hold */
static stCheckpointRun checkpoint_run(const run *R) {
  stCheckpointRun cr = {R->nstages, R->cfg->ga_population,
                        st_arch_ngenes(R->integrated ? R->idef.arch : PRIM_ARCH), R->limit};
  return cr;
}

static stStatus write_checkpoint(run *R, int generation, int done, const stGenome *pop, int n,
                                 char *err, size_t errsz) {
  stCheckpoint c = {generation, R->stage_idx, R->stage_gen, done, file_size(R->path[P_CSV]),
                    file_size(R->path[P_BEST]), {0, NULL, NULL, NULL}};
  if (c.csv_bytes < 0 || c.best_bytes < 0) {
    st__errf(err, errsz, "%s: cannot measure %s and %s: %s", R->path[P_CKPT], R->path[P_CSV],
             R->path[P_BEST], strerror(errno));
    return ST_ERR_IO;
  }
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, R->path[P_CKPT], err, errsz);
  if (st) return st;
  if (st__checkpoint_write(af.f, &c, pop, n)) {
    st__errf(err, errsz, "%s: cannot write: %s", af.tmp, strerror(errno));
    st_atomic_abort(&af);
    return ST_ERR_IO;
  }
  return st_atomic_commit(&af, err, errsz);
}

/* ---- evaluation ---- */

static const char *stage_label(const run *R) {
  return R->integrated ? ST_INTEGRATED_STAGE_NAME : st_stage_name(R->stages[R->stage_idx]);
}

/* the generation's tasks: the individuals in GA order; with stage.handover_rollin = elite each
 * carries genotype 0 too, the previous generation's best (st_ga_next puts the elites first,
 * best first; generation 0: the initial population's first, best first in a saved population;
 * main-prim's first generation after simple-prim completes: simple-prim's last population
 * unchanged, in GA order, so its genotype 0 is the best of the generation before). It is the
 * population's own genotype 0, so a resumed run, whose checkpoint holds the
 * population, rolls in with the same elite */
static void make_tasks(run *R, int generation) {
  const int rollin = !R->integrated && st_stage_rollin_elite(R->proto, R->stages[R->stage_idx]);
  for (int i = 0; i < st_ga_def(R->ga)->population; i++) {
    stEvolveTask *t = &R->tasks[i];
    t->integrated = R->integrated;
    t->stage = R->stages[R->stage_idx];
    t->generation = generation;
    t->individual = i;
    t->genome = *st_ga_genome(R->ga, i);
    t->has_rollin = rollin;
    if (rollin) t->rollin = *st_ga_genome(R->ga, 0);
    else memset(&t->rollin, 0, sizeof t->rollin);
  }
}

int st_thread_count(int requested, const stConfig *cfg) {
  if (requested > 0) return requested;
  return cfg && cfg->run_threads > 0 ? cfg->run_threads : omp_get_num_procs();
}

/* every task on this process's threads */
static void evaluate_here(run *R) {
  const int n = st_ga_def(R->ga)->population;
#pragma omp parallel num_threads(R->threads)
  {
    stWorkspace *ws = &R->ws[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
    for (int i = 0; i < n; i++)
      st_evolve_task_run(R->proto, &R->idef, ws, &R->tasks[i], &R->results[i]);
  }
}

/* the genotypes' fitness, or the first that could not be evaluated */
static stStatus evaluate(run *R, int generation, char *err, size_t errsz) {
  const int n = st_ga_def(R->ga)->population;
  make_tasks(R, generation);
  const stEvolveEvaluator *ev = R->def->evaluator;
  stStatus st = ST_OK;
  if (!ev) evaluate_here(R);
  else if ((st = ev->evaluate(ev->self, R->cfg, R->tasks, n, R->results, err, errsz))) return st;
  for (int i = 0; i < n; i++) {
    const stEvolveResult *r = &R->results[i];
    if (r->status) {
      st__errf(err, errsz, "evaluating genotype %d: %s", i, r->err);
      return r->status;
    }
    R->eval[i] = r->eval;
    R->ieval[i] = r->ieval;
    R->fitness[i] = r->fitness;
  }
  return ST_OK;
}

/* ---- output ---- */

static stStatus append(const char *path, const char *text, char *err, size_t errsz) {
  FILE *f = fopen(path, "a");
  size_t n = strlen(text);
  if (!f || fwrite(text, 1, n, f) != n || fflush(f) != 0 || fsync(fileno(f)) != 0) {
    st__errf(err, errsz, "%s: cannot write: %s", path, strerror(errno));
    if (f) fclose(f);
    return ST_ERR_IO;
  }
  if (fclose(f) != 0) {
    st__errf(err, errsz, "%s: cannot write: %s", path, strerror(errno));
    return ST_ERR_IO;
  }
  return ST_OK;
}

/* the trials of kind k the run's fitness.csv has columns for: the most any of its primitive
 * stages has */
static int run_kind_trials(const run *R, stTrialKind k) {
  int n = 0;
  for (int i = 0; i < R->nstages && !R->integrated; i++) {
    const int m = st_trial_kind_count(R->cfg, R->stages[i], k);
    if (m > n) n = m;
  }
  return n;
}

static stStatus start_files(run *R, char *err, size_t errsz) {
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, R->path[P_CONFIG], err, errsz);
  if (st) return st;
  st_config_write(af.f, R->cfg);
  if ((st = st_atomic_commit(&af, err, errsz))) return st;
  char hdr[4096];
  st_csv_header_text(&R->fcsv.schema, hdr, sizeof hdr);
  if (write_text(R->path[P_CSV], hdr)) {
    st__errf(err, errsz, "%s: cannot write: %s", R->path[P_CSV], strerror(errno));
    return ST_ERR_IO;
  }
  if (write_text(R->path[P_BEST], "")) {
    st__errf(err, errsz, "%s: cannot write: %s", R->path[P_BEST], strerror(errno));
    return ST_ERR_IO;
  }
  remove(R->path[P_POP]);
  return ST_OK;
}

/* the temporary files a run killed mid-write left (accepted runs only: a refused one changes
 * nothing in the directory) */
static void remove_stale_tmp(const run *R) {
  for (int i = 0; i < P_PROBE; i++) st_atomic_clean(R->path[i]);
}

/* the run in the directory must have been made with the same configuration (threads aside) */
static stStatus same_config(run *R, char *err, size_t errsz) {
  stConfig old, cur = *R->cfg;
  st_config_default(&old);
  char e[512];
  if (st_config_load(R->path[P_CONFIG], &old, e, sizeof e)) {
    st__errf(err, errsz, "cannot resume: %s", e);
    return ST_ERR_PARSE;
  }
  old.run_threads = cur.run_threads = 0;
  /* the cap only ends the run (no generation before it depends on it): a run continues under
   * another --generations, and config.ini records the new one (rewrite_config) */
  int *oc = R->integrated ? &old.ga_integrated_generations : &old.ga_max_generations;
  int *cc = R->integrated ? &cur.ga_integrated_generations : &cur.ga_max_generations;
  R->cap_changed = *oc != *cc;
  *oc = *cc;
  /* the first key that differs, named with both values: what the --set to add is */
  for (int i = 0; i < st_config_nkeys(); i++) {
    if (!st_config_key_differs(&cur, &old, i)) continue;
    const stConfigKey *k = st_config_key(i);
    char was[ST_CONFIG_STR_MAX], now[ST_CONFIG_STR_MAX];
    st_config_format(&old, i, was, sizeof was);
    st_config_format(&cur, i, now, sizeof now);
    st__errf(err, errsz, "cannot resume: %s has %s.%s = %s, this run %s (resume needs the same "
             "config and --set options: --set %s.%s=%s)", R->path[P_CONFIG], k->section, k->name,
             was, now, k->section, k->name, was);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

/* ---- the initial population ---- */

/* primitive stages: stage.init_population, or none (random genotypes) */
static stStatus load_initial(run *R, stGenomeSet *set, char *err, size_t errsz) {
  const char *path = R->cfg->stage_init_population;
  memset(set, 0, sizeof *set);
  if (!path[0]) return ST_OK;
  stStatus st = st_genome_set_read(path, st_arch_ngenes(PRIM_ARCH), set, err, errsz);
  if (st) {
    st__err_key(err, errsz, "stage.init_population");
    return st;
  }
  if (set->count < R->cfg->ga_population) {
    st__errf(err, errsz, "key 'stage.init_population': %s has %d genotypes (expected at least "
             "ga.population = %d)", path, set->count, R->cfg->ga_population);
    st_genome_set_free(set);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

/* integrated stage: the top genotypes of the primitive runs, grown (selftalk/assemble.h) */
static stStatus assemble_initial(run *R, stGenomeSet *set, char *err, size_t errsz) {
  stAssembly a;
  stStatus st = st_assemble_population(R->cfg, &a, err, errsz);
  if (st) return st;
  memset(set, 0, sizeof *set);
  set->count = a.count;
  set->genome = a.genome; /* handed over: st_genome_set_free frees it */
  if (R->def->progress)
    fprintf(R->def->progress, "evolve: integrated stage (network %s) from the top %d of %d "
            "population files: %d genotypes%s\n", st_arch_name(R->idef.arch), R->cfg->integrated_top,
            a.nfiles, a.taken, a.taken < a.count ? ", repeated to fill the population" : "");
  return ST_OK;
}

/* the GA: base genotypes and every bit mutable (primitive stages), or the integrated network's
 * genotypes with only the new genes mutable at the integrated rate */
static stStatus make_ga(run *R, const stGenome *pop0, int npop0, char *err, size_t errsz) {
  const stConfig *cfg = R->cfg;
  stGaDef gd = st_ga_def_from_config(cfg);
  if (R->integrated) gd.mutation_rate = cfg->ga_mutation_rate_integrated;
  gd.ngenes = st_arch_ngenes(R->integrated ? R->idef.arch : PRIM_ARCH);
  uint8_t mask[ST_GENOME_MAX_GENES];
  st_genome_mask_new_genes(mask, gd.ngenes);
  return st_ga_create(&gd, pop0, npop0, R->integrated ? mask : NULL, &R->ga, err, errsz);
}

/* ---- one generation's records ---- */

typedef struct genStats {
  int best;
  double mean, worst;
  int all;      /* genotypes that complete the stage (completes) */
  int unstable; /* trials the simulation gave up on */
} genStats;

static genStats gen_stats(const run *R) {
  const int n = st_ga_def(R->ga)->population;
  genStats s = {st_ga_ranked(R->ga, 0), 0.0, INFINITY, 0, 0};
  for (int i = 0; i < n; i++) {
    s.mean += R->fitness[i] / n;
    if (R->fitness[i] < s.worst) s.worst = R->fitness[i];
    if (R->integrated) {
      s.unstable += R->ieval[i].unstable;
    } else {
      s.unstable += R->eval[i].unstable;
      s.all += st_evaluation_completes(R->cfg, &R->eval[i]);
    }
  }
  return s;
}

/* the generation's fitness.csv row: its fitness and its best's evaluation */
static void fitness_row(const run *R, int gen, const genStats *s, stFitnessRow *w) {
  memset(w, 0, sizeof *w);
  w->generation = gen;
  w->best = R->fitness[s->best], w->mean = s->mean, w->worst = s->worst;
  if (R->integrated) { /* be->ntrials is idef.trials, the layout's */
    const stIntEvaluation *be = &R->ieval[s->best];
    w->f_int = be->f_int, w->f_pred = be->f_pred, w->bonus = be->bonus;
    w->bonus_auto = be->bonus_auto, w->successes = be->successes;
    for (int t = 0; t < be->ntrials; t++) w->success[t] = be->success[t];
    return;
  }
  const stEvaluation *be = &R->eval[s->best];
  w->bonus = R->cfg->fitness_bonus * be->successes;
  st__strlcpy(w->stage, stage_label(R), sizeof w->stage);
  w->stage_generation = R->stage_gen, w->all_success = s->all, w->successes = be->successes;
  for (int p = 0; p < ST_NPRIM; p++) w->f_prim[p] = be->fp[p];
  /* each kind's (zero where it did not run: simple-prim generations, replacing ones) */
  memcpy(w->kind, be->kind, sizeof w->kind);
}

/* the generation's fitness.csv row and its best genotype, appended and synced */
static stStatus write_records(run *R, int gen, const genStats *s, char *err, size_t errsz) {
  stFitnessRow w;
  fitness_row(R, gen, s, &w);
  char row[4096];
  st_csv_row_text(&R->fcsv.schema, &w, row, sizeof row);
  stStatus st = append(R->path[P_CSV], row, err, errsz);
  if (st) return st;
  char bg[4 * ST_GENOME_MAX_GENES + 256];
  int b = snprintf(bg, sizeof bg, "# generation %d\n# stage %s\n# fitness %.17g\n", gen, stage_label(R),
                   R->fitness[s->best]);
  const stGenome *g = st_ga_genome(R->ga, s->best);
  for (int i = 0; i < g->ngenes; i++) b += snprintf(bg + b, sizeof bg - (size_t)b, "%04x", g->gene[i]);
  snprintf(bg + b, sizeof bg - (size_t)b, "\n");
  return append(R->path[P_BEST], bg, err, errsz);
}

static void progress(const run *R, int gen, const genStats *s) {
  FILE *f = R->def->progress;
  if (!f) return;
  double el = now() - R->t_start, rate = R->done_here / (el > 0 ? el : 1e-9);
  char e1[32], e2[32];
  hms(el, e1, sizeof e1);
  hms((R->limit - gen - 1) / rate, e2, sizeof e2);
  /* trials the simulation gave up on (scored as failures): rare, but a user must see them */
  char unst[48] = "";
  if (s->unstable) snprintf(unst, sizeof unst, " | %d unstable trials", s->unstable);
  if (R->integrated) {
    const stIntEvaluation *be = &R->ieval[s->best];
    fprintf(f, "gen %4d integrated best %8.3f mean %8.3f F_int %8.3f F_pred %8.3f bonus %4.0f "
            "auto %4.0f solves %2d/%d | %.2f gen/s elapsed %s left <= %s%s\n",
            gen, R->fitness[s->best], s->mean, be->f_int, be->f_pred, be->bonus, be->bonus_auto,
            be->successes, be->ntrials, rate, e1, e2, unst);
  } else {
    const stEvaluation *be = &R->eval[s->best];
    char ho[256] = ""; /* what the kinds of trials of the run's file say */
    size_t m = 0;
    for (int k = 0; k < ST_TRIAL_KIND_COUNT && m < sizeof ho; k++) {
      const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
      if (d->note && run_kind_trials(R, d->kind) > 0) {
        const int w = d->note(be, ho + m, sizeof ho - m);
        m += w > 0 ? (size_t)w : 0;
      }
    }
    fprintf(f,
            "gen %4d %-11s best %8.3f mean %8.3f bonus %3.0f solves %2d/%d%s all-solved %3d | "
            "%.2f gen/s elapsed %s left <= %s%s\n",
            gen, stage_label(R), R->fitness[s->best], s->mean, R->cfg->fitness_bonus * be->successes,
            be->successes, be->ntrials, ho, s->all, rate, e1, e2, unst);
  }
  fflush(f);
}

/* the final population, best first, with its fitness, and the last checkpoint */
static stStatus finish(run *R, int gen, int all_complete, char *err, size_t errsz) {
  const int n = st_ga_def(R->ga)->population;
  for (int r = 0; r < n; r++) {
    R->sorted[r] = *st_ga_genome(R->ga, st_ga_ranked(R->ga, r));
    R->sorted_fit[r] = R->fitness[st_ga_ranked(R->ga, r)];
  }
  stStatus st = st_genome_set_save(R->path[P_POP], R->sorted, n, R->sorted_fit, NULL, err, errsz);
  if (!st) st = write_checkpoint(R, gen + 1, 1, R->sorted, n, err, errsz);
  if (R->def->progress && !st)
    fprintf(R->def->progress, "evolve: stopped after generation %d (%s); files in %s\n", gen,
            all_complete ? "all stages complete" : "generation limit", R->def->out_dir);
  return st;
}

/* primitive stages: the evaluated population moves to the next stage unchanged (thesis 2.4),
 * to be evaluated again there as the next generation; returns 1 when there is none */
static int next_stage(run *R, int gen, int all, stStatus *st, char *err, size_t errsz) {
  const int n = st_ga_def(R->ga)->population;
  const stEvaluation *e = &R->eval[st_ga_ranked(R->ga, 0)];
  /* what completion counted (st_evaluation_completes): with fixed_chained, not the hand-over
   * and varied trials, which only train */
  if (R->def->progress && R->cfg->stage_chain_complete == ST_CHAIN_COMPLETE_FIXED_CHAINED &&
      e->kind[ST_TRIAL_CHAINED].trials > 0)
    fprintf(R->def->progress, "evolve: %s complete at generation %d (%d genotypes solve the %d "
            "fixed and %d chained trials)\n", stage_label(R), gen, all,
            e->kind[ST_TRIAL_FIXED].trials, e->kind[ST_TRIAL_CHAINED].trials);
  else if (R->def->progress)
    fprintf(R->def->progress, "evolve: %s complete at generation %d (%d genotypes solve all %d trials)\n",
            stage_label(R), gen, all, e->ntrials);
  if (R->stage_idx + 1 >= R->nstages) return 1;
  R->stage_idx++;
  R->stage_gen = 0;
  stGenome *same = R->sorted; /* scratch until finish() */
  for (int i = 0; i < n; i++) same[i] = *st_ga_genome(R->ga, i);
  *st = st_ga_restore(R->ga, gen + 1, same, n, err, errsz);
  return 0;
}

/* breeds the next generation and checkpoints it */
static stStatus breed(run *R, int stage_complete, char *err, size_t errsz) {
  const int n = st_ga_def(R->ga)->population;
  stStatus st = stage_complete ? ST_OK : st_ga_next(R->ga);
  if (st) return st;
  stGenome *pop = R->sorted; /* scratch until finish() */
  for (int i = 0; i < n; i++) pop[i] = *st_ga_genome(R->ga, i);
  return write_checkpoint(R, st_ga_generation(R->ga), 0, pop, n, err, errsz);
}

/* one generation: evaluate, record, then the next stage, the end, or the next generation;
 * sets *stop when the run is over */
static stStatus generation(run *R, int *stop, char *err, size_t errsz) {
  const int gen = st_ga_generation(R->ga);
  stStatus st = evaluate(R, gen, err, errsz);
  if (st) return st;
  st_ga_tell(R->ga, R->fitness);
  const genStats s = gen_stats(R);
  if ((st = write_records(R, gen, &s, err, errsz))) return st;
  R->done_here++;
  R->stage_gen++;
  progress(R, gen, &s);
  /* the integrated stage always runs its generations (thesis 2.4) */
  const int stage_complete = !R->integrated && s.all >= R->cfg->ga_success_genotypes;
  /* all stages complete only when the last one is: a stage completing at the generation limit
   * leaves the next one unrun */
  const int last_complete = stage_complete && next_stage(R, gen, s.all, &st, err, errsz);
  *stop = last_complete || gen + 1 >= R->limit;
  if (st) return st;
  if (*stop) return finish(R, gen, last_complete, err, errsz);
  return breed(R, stage_complete, err, errsz);
}

/* ---- the run ---- */

/* --generations N is the run's cap key (ga.integrated_generations in the integrated stage,
 * else ga.max_generations) set to N, so that config.ini records the cap the run was made under;
 * the cross-key rules see it as they see the key */
static stStatus apply_generations(stConfig *cfg, int generations, char *err, size_t errsz) {
  if (generations <= 0) return ST_OK;
  const int integrated = st_config_run_stages(cfg) == ST_CONFIG_INTEGRATED;
  *(integrated ? &cfg->ga_integrated_generations : &cfg->ga_max_generations) = generations;
  char e[1024];
  stStatus st = st_config_validate(cfg, e, sizeof e);
  if (st)
    st__errf(err, errsz, "--generations %d (the run's %s): %s", generations,
             integrated ? "ga.integrated_generations" : "ga.max_generations", e);
  return st;
}

/* which stages (every key acts in them or keeps its default), how many generations, how many
 * threads */
static stStatus plan_run(run *R, const stEvolveDef *def, char *err, size_t errsz) {
  const stConfig *cfg = R->cfg;
  const unsigned stages = st_config_run_stages(cfg);
  stStatus st = st_config_check_stages(cfg, stages, err, errsz);
  if (st) return st;
  /* the integrated stage runs alone (from the primitive stages' saved populations) */
  R->integrated = stages == ST_CONFIG_INTEGRATED;
  if (!stages || (!R->integrated && (stages & ST_CONFIG_INTEGRATED))) {
    st__errf(err, errsz, "key 'stage.stages': %s is no stage sequence this program runs (expected "
             "simple_prim, main_prim, prims or integrated)",
             st_config_enum_name("stage", "stages", cfg->stage_stages));
    return ST_ERR_ARG;
  }
  if (stages & ST_CONFIG_SIMPLE_PRIM) R->stages[R->nstages++] = ST_STAGE_SIMPLE;
  if (stages & ST_CONFIG_MAIN_PRIM) R->stages[R->nstages++] = ST_STAGE_MAIN;
  if (R->integrated) R->stages[R->nstages++] = ST_STAGE_MAIN; /* dynamic, like main-prim */
  st_integrated_def_from_config(cfg, &R->idef);
  R->limit = R->integrated ? cfg->ga_integrated_generations : cfg->ga_max_generations;
  R->threads = st_thread_count(def->threads, cfg);
  stFitnessLayout fl;
  memset(&fl, 0, sizeof fl);
  fl.integrated = R->integrated;
  fl.trials = R->integrated ? R->idef.trials : 0;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) fl.kind_trials[k] = run_kind_trials(R, (stTrialKind)k);
  st_fitness_csv(&fl, &R->fcsv);
  return ST_OK;
}

/* resuming: the checkpoint, validated against this run's configuration and files before
 * anything in the directory changes */
static stStatus read_resume(run *R, stCheckpoint *ck, char *err, size_t errsz) {
  stStatus st = same_config(R, err, errsz);
  if (st) return st;
  const stCheckpointRun cr = checkpoint_run(R);
  st = st__checkpoint_read(R->path[P_CKPT], &cr, R->path[P_CSV], R->path[P_BEST], ck, err, errsz);
  if (st) return st;
  if (ck->done && R->def->progress)
    fprintf(R->def->progress, "evolve: the run in %s is complete\n", R->def->out_dir);
  R->stage_idx = ck->stage_idx;
  R->stage_gen = ck->stage_gen;
  return ST_OK;
}

/* the GA from the checkpoint's population (resuming) or the stage's initial one */
static stStatus start_population(run *R, const stCheckpoint *ck, int have_ckpt, char *err,
                                 size_t errsz) {
  stGenomeSet init;
  memset(&init, 0, sizeof init);
  stStatus st = ST_OK;
  if (!have_ckpt)
    st = R->integrated ? assemble_initial(R, &init, err, errsz) : load_initial(R, &init, err, errsz);
  if (st) return st;
  const stGenome *pop0 = have_ckpt ? ck->pop.genome : init.count ? init.genome : NULL;
  const int npop0 = have_ckpt ? ck->pop.count : init.count;
  st = make_ga(R, pop0, npop0, err, errsz);
  if (!st && have_ckpt) st = st_ga_restore(R->ga, ck->generation, ck->pop.genome, ck->pop.count, err, errsz);
  st_genome_set_free(&init);
  return st;
}

/* resuming: fitness.csv and best.genome cut back to the checkpoint's generation (the rows of
 * the unfinished generation are redone); the last step before the first generation */
static stStatus rewind_files(run *R, const stCheckpoint *ck, char *err, size_t errsz) {
  if (R->cap_changed) { /* config.ini records the cap the run goes on under */
    stAtomicFile af;
    stStatus st = st_atomic_open(&af, R->path[P_CONFIG], err, errsz);
    if (st) return st;
    st_config_write(af.f, R->cfg);
    if ((st = st_atomic_commit(&af, err, errsz))) return st;
  }
  if (truncate(R->path[P_CSV], (off_t)ck->csv_bytes) != 0 ||
      truncate(R->path[P_BEST], (off_t)ck->best_bytes) != 0) {
    st__errf(err, errsz, "cannot resume: %s: %s", R->def->out_dir, strerror(errno));
    return ST_ERR_IO;
  }
  return ST_OK;
}

static stStatus allocate(run *R, char *err, size_t errsz) {
  const size_t n = (size_t)R->cfg->ga_population;
  R->ws = calloc((size_t)R->threads, sizeof *R->ws);
  R->eval = calloc(n, sizeof *R->eval);
  R->ieval = calloc(n, sizeof *R->ieval);
  R->fitness = calloc(n, sizeof *R->fitness);
  R->sorted = calloc(n, sizeof *R->sorted);
  R->sorted_fit = calloc(n, sizeof *R->sorted_fit);
  R->tasks = calloc(n, sizeof *R->tasks);
  R->results = calloc(n, sizeof *R->results);
  if (R->ws && R->eval && R->ieval && R->fitness && R->sorted && R->sorted_fit && R->tasks &&
      R->results)
    return ST_OK;
  st__errf(err, errsz, "evolve: out of memory");
  return ST_ERR_NOMEM;
}

static void release(run *R) {
  for (int t = 0; R->ws && t < R->threads; t++) st_workspace_free(&R->ws[t]);
  free(R->ws);
  free(R->eval);
  free(R->ieval);
  free(R->fitness);
  free(R->sorted);
  free(R->sorted_fit);
  free(R->tasks);
  free(R->results);
  st_ga_destroy(R->ga);
  st_protocol_destroy(R->proto);
}

stStatus st_evolve_run(const stEvolveDef *def, char *err, size_t errsz) {
  ST_ASSERT(def && def->cfg && def->out_dir);
  run R;
  memset(&R, 0, sizeof R);
  R.def = def;
  R.own = *def->cfg;
  R.cfg = &R.own;
  stStatus st = st_config_validate(def->cfg, err, errsz);
  if (!st) st = st_trial_kinds_check(def->cfg, NULL, err, errsz);
  if (st) return st;
  if ((st = apply_generations(&R.own, def->generations, err, errsz))) return st;
  if ((st = plan_run(&R, def, err, errsz))) return st;
  if ((st = prepare_dir(&R, err, errsz))) return st;
  stCheckpoint ck;
  memset(&ck, 0, sizeof ck);
  const int have_ckpt = def->resume && file_size(R.path[P_CKPT]) >= 0;
  /* a population and no checkpoint is a finished run whose checkpoint was removed (as the
   * committed runs under data/evolved/): starting again would overwrite its results, and
   * --resume is what scripts run over and over without looking */
  if (def->resume && !have_ckpt && file_size(R.path[P_POP]) >= 0) {
    st__errf(err, errsz, "%s: a finished run's population and no checkpoint to resume from "
             "(--resume would start the run again over its files): remove them or choose another "
             "--out to run it again", R.path[P_POP]);
    return ST_ERR_IO;
  }
  if (def->resume && !have_ckpt && def->progress)
    fprintf(def->progress, "evolve: no checkpoint in %s: starting fresh\n", def->out_dir);
  if (have_ckpt) st = read_resume(&R, &ck, err, errsz);
  const int todo = !st && !ck.done;
  if (todo) st = start_population(&R, &ck, have_ckpt, err, errsz);
  if (todo && !st) st = st_protocol_create(R.cfg, &R.proto, err, errsz);
  if (todo && !st) st = allocate(&R, err, errsz);
  if (!st) remove_stale_tmp(&R); /* accepted: what a killed run left goes */
  if (todo && !st) st = have_ckpt ? rewind_files(&R, &ck, err, errsz) : start_files(&R, err, errsz);
  st__checkpoint_free(&ck);
  R.t_start = now();
  for (int stop = !todo; !st && !stop;) st = generation(&R, &stop, err, errsz);
  release(&R);
  return st;
}
