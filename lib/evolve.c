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

#include "internal.h"
#include "selftalk/ga.h"
#include "selftalk/io.h"
#include "selftalk/trial.h"

#define CKPT_MAGIC "selftalk-checkpoint 1"

/* the primitive stages evolve the base network; network.arch names what the integrated stage
 * grows it into (thesis 2.9.2), so a run without that stage refuses another value of it */
static const stNetArch PRIM_ARCH = ST_ARCH_BASE;

typedef struct run {
  const stEvolveDef *def;
  const stConfig *cfg;
  stProtocol *proto;
  stGa *ga;
  stStage stages[2];
  int nstages;
  int stage_idx;      /* index into stages */
  int stage_gen;      /* generations done in the current stage */
  int limit;          /* total generations allowed */
  int threads;
  stWorkspace *ws;    /* one per thread */
  stEvaluation *eval; /* per individual */
  double *fitness;
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

static long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* the out dir must exist (created) and take files, before any work */
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
  FILE *f = fopen(R->path[P_PROBE], "w");
  if (!f || fputs("probe\n", f) < 0 || fclose(f) != 0) {
    st__errf(err, errsz, "output directory '%s': not writable: %s", dir, strerror(errno));
    return ST_ERR_IO;
  }
  remove(R->path[P_PROBE]);
  return ST_OK;
}

/* ---- checkpoint ---- */

typedef struct ckpt {
  int generation, stage_idx, stage_gen, done;
  long csv_bytes, best_bytes;
  stGenomeSet pop;
} ckpt;

static stStatus write_checkpoint(run *R, int generation, int done, const stGenome *pop, int n,
                                 char *err, size_t errsz) {
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, R->path[P_CKPT], err, errsz);
  if (st) return st;
  fprintf(af.f, "# %s\n# generation %d\n# stage_idx %d\n# stage_gen %d\n# done %d\n",
          CKPT_MAGIC, generation, R->stage_idx, R->stage_gen, done);
  fprintf(af.f, "# csv_bytes %ld\n# best_bytes %ld\n", file_size(R->path[P_CSV]),
          file_size(R->path[P_BEST]));
  for (int i = 0; i < n; i++) st_genome_write(af.f, &pop[i], -1, NAN);
  return st_atomic_commit(&af, err, errsz);
}

static stStatus read_checkpoint(const char *path, ckpt *c, char *err, size_t errsz) {
  memset(c, 0, sizeof *c);
  FILE *f = fopen(path, "r");
  if (!f) {
    st__errf(err, errsz, "%s: cannot open: %s", path, strerror(errno));
    return ST_ERR_IO;
  }
  char line[256], key[64];
  long v;
  int magic = 0;
  while (fgets(line, sizeof line, f) && line[0] == '#') {
    if (strstr(line, CKPT_MAGIC)) magic = 1;
    if (sscanf(line, "# %63s %ld", key, &v) != 2) continue;
    if (!strcmp(key, "generation")) c->generation = (int)v;
    else if (!strcmp(key, "stage_idx")) c->stage_idx = (int)v;
    else if (!strcmp(key, "stage_gen")) c->stage_gen = (int)v;
    else if (!strcmp(key, "done")) c->done = (int)v;
    else if (!strcmp(key, "csv_bytes")) c->csv_bytes = v;
    else if (!strcmp(key, "best_bytes")) c->best_bytes = v;
  }
  fclose(f);
  if (!magic) {
    st__errf(err, errsz, "%s: not a selftalk checkpoint (expected '# %s')", path, CKPT_MAGIC);
    return ST_ERR_PARSE;
  }
  return st_genome_set_read(path, 0, &c->pop, err, errsz);
}

/* ---- evaluation ---- */

static stStatus evaluate(run *R, int generation, char *err, size_t errsz) {
  const stGaDef *gd = st_ga_def(R->ga);
  const stStage stage = R->stages[R->stage_idx];
  int failed = -1;
  stStatus first = ST_OK;
  char msg[512] = "";
#pragma omp parallel num_threads(R->threads)
  {
    stWorkspace *ws = &R->ws[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
    for (int i = 0; i < gd->population; i++) {
      stNetParams np;
      char e[512];
      stStatus st = st_net_decode(&R->proto->net, PRIM_ARCH, st_ga_genome(R->ga, i), &np, e, sizeof e);
      if (!st) st = st_stage_evaluate(R->proto, ws, stage, generation, i, &np, &R->eval[i], e, sizeof e);
      R->fitness[i] = st ? NAN : R->eval[i].fitness;
      if (st) {
#pragma omp critical
        if (failed < 0 || i < failed) {
          failed = i;
          first = st;
          st__strlcpy(msg, e, sizeof msg);
        }
      }
    }
  }
  if (failed >= 0) st__errf(err, errsz, "evaluating genotype %d: %s", failed, msg);
  return first;
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

static void csv_header(char *buf, size_t n) {
  int k = snprintf(buf, n,
                   "generation,best,mean,worst,best_bonus,stage,stage_generation,all_success,"
                   "best_successes,best_F_reach,best_F_open,best_F_grasp,best_F_move");
  for (int t = 0; t < ST_PRIM_TRIALS && k < (int)n; t++) k += snprintf(buf + k, n - (size_t)k, ",best_t%d", t);
  if (k < (int)n) snprintf(buf + k, n - (size_t)k, "\n");
}

static stStatus start_files(run *R, char *err, size_t errsz) {
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, R->path[P_CONFIG], err, errsz);
  if (st) return st;
  st_config_write(af.f, R->cfg);
  if ((st = st_atomic_commit(&af, err, errsz))) return st;
  char hdr[1024];
  csv_header(hdr, sizeof hdr);
  FILE *f = fopen(R->path[P_CSV], "w");
  if (!f || fputs(hdr, f) < 0 || fclose(f) != 0) {
    st__errf(err, errsz, "%s: cannot write: %s", R->path[P_CSV], strerror(errno));
    return ST_ERR_IO;
  }
  f = fopen(R->path[P_BEST], "w");
  if (!f || fclose(f) != 0) {
    st__errf(err, errsz, "%s: cannot write: %s", R->path[P_BEST], strerror(errno));
    return ST_ERR_IO;
  }
  remove(R->path[P_POP]);
  return ST_OK;
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
  if (memcmp(&old, &cur, sizeof old)) {
    st__errf(err, errsz, "cannot resume: %s differs from this run's configuration (resume needs "
             "the same config and --set options)", R->path[P_CONFIG]);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

static stStatus load_initial(run *R, stGenomeSet *set, char *err, size_t errsz) {
  const char *path = R->cfg->stage_init_population;
  memset(set, 0, sizeof *set);
  if (!path[0]) return ST_OK;
  stStatus st = st_genome_set_read(path, st_arch_ngenes(PRIM_ARCH), set, err, errsz);
  if (st) return st;
  if (set->count < R->cfg->ga_population) {
    st__errf(err, errsz, "stage.init_population: %s has %d genotypes (expected at least %d)", path,
             set->count, R->cfg->ga_population);
    st_genome_set_free(set);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

stStatus st_evolve_run(const stEvolveDef *def, char *err, size_t errsz) {
  run R;
  memset(&R, 0, sizeof R);
  R.def = def;
  R.cfg = def->cfg;
  const stConfig *cfg = def->cfg;
  stStatus st = st_config_validate(cfg, err, errsz);
  if (st) return st;
  /* every key acts in this run or keeps its default */
  const unsigned stages = st_config_run_stages(cfg);
  if ((st = st_config_check_stages(cfg, stages, err, errsz))) return st;
  if (stages & ST_CONFIG_SIMPLE_PRIM) R.stages[R.nstages++] = ST_STAGE_SIMPLE;
  if (stages & ST_CONFIG_MAIN_PRIM) R.stages[R.nstages++] = ST_STAGE_MAIN;
  if (!R.nstages) {
    st__errf(err, errsz, "key 'stage.stages': %s has no stage this program runs (expected "
             "simple_prim, main_prim or prims)", st_config_enum_name("stage", "stages", cfg->stage_stages));
    return ST_ERR_ARG;
  }
  R.limit = def->generations > 0 ? def->generations : cfg->ga_max_generations;
  R.threads = def->threads > 0 ? def->threads : cfg->run_threads > 0 ? cfg->run_threads : omp_get_num_procs();
  if ((st = prepare_dir(&R, err, errsz))) return st;

  ckpt ck;
  memset(&ck, 0, sizeof ck);
  int have_ckpt = def->resume && file_size(R.path[P_CKPT]) >= 0;
  if (def->resume && !have_ckpt && def->progress)
    fprintf(def->progress, "evolve: no checkpoint in %s: starting fresh\n", def->out_dir);
  stGenomeSet init;
  memset(&init, 0, sizeof init);
  if (have_ckpt) {
    if ((st = same_config(&R, err, errsz))) return st;
    if ((st = read_checkpoint(R.path[P_CKPT], &ck, err, errsz))) return st;
    if (ck.done) {
      if (def->progress) fprintf(def->progress, "evolve: the run in %s is complete\n", def->out_dir);
      st_genome_set_free(&ck.pop);
      return ST_OK;
    }
    /* cut the appended files back to the checkpoint's generation */
    if (truncate(R.path[P_CSV], ck.csv_bytes) != 0 || truncate(R.path[P_BEST], ck.best_bytes) != 0) {
      st__errf(err, errsz, "cannot resume: %s: %s", def->out_dir, strerror(errno));
      st_genome_set_free(&ck.pop);
      return ST_ERR_IO;
    }
    R.stage_idx = ck.stage_idx;
    R.stage_gen = ck.stage_gen;
  } else if ((st = load_initial(&R, &init, err, errsz))) {
    return st;
  }

  stGaDef gd = st_ga_def_from_config(cfg);
  gd.ngenes = st_arch_ngenes(PRIM_ARCH);
  const stGenome *pop0 = have_ckpt ? ck.pop.genome : init.count ? init.genome : NULL;
  int npop0 = have_ckpt ? ck.pop.count : init.count;
  st = st_ga_create(&gd, pop0, npop0, NULL, &R.ga, err, errsz);
  if (!st && have_ckpt) st = st_ga_restore(R.ga, ck.generation, ck.pop.genome, ck.pop.count, err, errsz);
  st_genome_set_free(&ck.pop);
  st_genome_set_free(&init);
  if (st) return st;

  if (!st) st = st_protocol_create(cfg, &R.proto, err, errsz);
  if (!st && !have_ckpt) st = start_files(&R, err, errsz);
  R.ws = calloc((size_t)R.threads, sizeof *R.ws);
  R.eval = calloc((size_t)gd.population, sizeof *R.eval);
  R.fitness = calloc((size_t)gd.population, sizeof *R.fitness);
  stGenome *sorted = calloc((size_t)gd.population, sizeof *sorted);
  double *sorted_fit = calloc((size_t)gd.population, sizeof *sorted_fit);
  if (!st && (!R.ws || !R.eval || !R.fitness || !sorted || !sorted_fit)) {
    st__errf(err, errsz, "evolve: out of memory");
    st = ST_ERR_NOMEM;
  }

  const double t_start = now();
  int done_here = 0;
  while (!st) {
    const int gen = st_ga_generation(R.ga);
    const stStage stage = R.stages[R.stage_idx];
    if ((st = evaluate(&R, gen, err, errsz))) break;
    st_ga_tell(R.ga, R.fitness);
    const int best = st_ga_ranked(R.ga, 0);
    double mean = 0, worst = INFINITY;
    int all = 0, unstable = 0;
    for (int i = 0; i < gd.population; i++) {
      unstable += R.eval[i].unstable;
      mean += R.fitness[i] / gd.population;
      if (R.fitness[i] < worst) worst = R.fitness[i];
      all += R.eval[i].successes == R.eval[i].ntrials; /* every trial it is evaluated on */
    }
    const stEvaluation *be = &R.eval[best];
    char row[2048];
    int k = snprintf(row, sizeof row, "%d,%.17g,%.17g,%.17g,%.17g,%s,%d,%d,%d,%.17g,%.17g,%.17g,%.17g",
                     gen, R.fitness[best], mean, worst, cfg->fitness_bonus * be->successes,
                     st_stage_name(stage), R.stage_gen, all, be->successes, be->fp[0], be->fp[1],
                     be->fp[2], be->fp[3]);
    for (int t = 0; t < ST_PRIM_TRIALS; t++) k += snprintf(row + k, sizeof row - (size_t)k, ",%d", be->success[t]);
    snprintf(row + k, sizeof row - (size_t)k, "\n");
    if ((st = append(R.path[P_CSV], row, err, errsz))) break;
    char bg[4 * ST_GENOME_MAX_GENES + 256];
    int b = snprintf(bg, sizeof bg, "# generation %d\n# stage %s\n# fitness %.17g\n", gen, st_stage_name(stage),
                     R.fitness[best]);
    const stGenome *g = st_ga_genome(R.ga, best);
    for (int i = 0; i < g->ngenes; i++) b += snprintf(bg + b, sizeof bg - (size_t)b, "%04x", g->gene[i]);
    snprintf(bg + b, sizeof bg - (size_t)b, "\n");
    if ((st = append(R.path[P_BEST], bg, err, errsz))) break;

    done_here++;
    R.stage_gen++;
    int stop = 0;
    const int stage_complete = all >= cfg->ga_success_genotypes;
    if (def->progress) {
      double el = now() - t_start, rate = done_here / (el > 0 ? el : 1e-9);
      char e1[32], e2[32];
      hms(el, e1, sizeof e1);
      hms((R.limit - gen - 1) / rate, e2, sizeof e2);
      /* trials the simulation gave up on (scored as failures): rare, but a user must see them */
      char unst[48] = "";
      if (unstable) snprintf(unst, sizeof unst, " | %d unstable trials", unstable);
      fprintf(def->progress,
              "gen %4d %-11s best %8.3f mean %8.3f bonus %3.0f solves %2d/%d all-solved %3d | "
              "%.2f gen/s elapsed %s left <= %s%s\n",
              gen, st_stage_name(stage), R.fitness[best], mean, cfg->fitness_bonus * be->successes,
              be->successes, be->ntrials, all, rate, e1, e2, unst);
      fflush(def->progress);
    }
    if (stage_complete) {
      if (def->progress)
        fprintf(def->progress, "evolve: %s complete at generation %d (%d genotypes solve all 16 trials)\n",
                st_stage_name(stage), gen, all);
      if (R.stage_idx + 1 < R.nstages) {
        /* the population moves on unchanged (thesis 2.4): evaluated again under the next stage */
        R.stage_idx++;
        R.stage_gen = 0;
        stGenome *same = malloc(sizeof *same * (size_t)gd.population);
        for (int i = 0; i < gd.population; i++) same[i] = *st_ga_genome(R.ga, i);
        st = st_ga_restore(R.ga, gen + 1, same, gd.population, err, errsz);
        free(same);
      } else {
        stop = 1;
      }
    }
    if (gen + 1 >= R.limit) stop = 1;
    if (stop) {
      /* the final population, best first, with its fitness */
      for (int r = 0; r < gd.population; r++) {
        sorted[r] = *st_ga_genome(R.ga, st_ga_ranked(R.ga, r));
        sorted_fit[r] = R.fitness[st_ga_ranked(R.ga, r)];
      }
      if (!st) st = st_genome_set_save(R.path[P_POP], sorted, gd.population, sorted_fit, NULL, err, errsz);
      if (!st) st = write_checkpoint(&R, gen + 1, 1, sorted, gd.population, err, errsz);
      if (def->progress && !st)
        fprintf(def->progress, "evolve: stopped after generation %d (%s); files in %s\n", gen,
                stage_complete ? "all stages complete" : "generation limit", def->out_dir);
      break;
    }
    if (!stage_complete && !st) st = st_ga_next(R.ga);
    if (!st) {
      stGenome *pop = malloc(sizeof *pop * (size_t)gd.population);
      for (int i = 0; i < gd.population; i++) pop[i] = *st_ga_genome(R.ga, i);
      st = write_checkpoint(&R, st_ga_generation(R.ga), 0, pop, gd.population, err, errsz);
      free(pop);
    }
  }

  for (int t = 0; R.ws && t < R.threads; t++) st_workspace_free(&R.ws[t]);
  free(R.ws);
  free(R.eval);
  free(R.fitness);
  free(sorted);
  free(sorted_fit);
  st_ga_destroy(R.ga);
  st_protocol_destroy(R.proto);
  return st;
}
