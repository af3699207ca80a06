/* SPDX-License-Identifier: MIT
 * A post-evaluation run (selftalk/posteval.h): the keys it reads, its individuals, the trials
 * in parallel, the files. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/internal.h"
#include "posteval/journal.h"
#include "selftalk/evolve.h" /* st_thread_count */
#include "selftalk/fitnesscsv.h"
#include "selftalk/io.h"
#include "selftalk/postcsv.h"

/* ---- inputs ---- */

static int is_dir(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

/* the last component of path (trailing slashes ignored) into buf */
static void last_component(const char *path, char *buf, size_t n) {
  size_t end = strlen(path);
  while (end > 1 && path[end - 1] == '/') end--;
  size_t start = end;
  while (start > 0 && path[start - 1] != '/') start--;
  snprintf(buf, n, "%.*s", (int)(end - start), path + start);
}

void st_post_run_label(const char *path, char *buf, size_t n) {
  ST_ASSERT(path && buf && n > 0);
  char name[512], dir[512];
  last_component(path, name, sizeof name);
  const int run_file = !strcmp(name, "population.genome") || !strcmp(name, "checkpoint") ||
                       !strcmp(name, "best.genome");
  if (is_dir(path) || !run_file) {
    /* a directory's own name; another file's name without its extension */
    if (!is_dir(path)) name[strcspn(name, ".")] = 0;
    snprintf(buf, n, "%s", name[0] ? name : "run");
    return;
  }
  /* evolve's files: the run directory's name */
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) *slash = 0;
  else snprintf(dir, sizeof dir, ".");
  if (!strcmp(dir, ".") || !dir[0]) {
    char cwd[512];
    if (!getcwd(cwd, sizeof cwd)) snprintf(cwd, sizeof cwd, "run");
    last_component(cwd, buf, n);
  } else {
    last_component(dir, buf, n);
  }
}

static void individual_init(stPostIndividual *ind, const char *label, const char *path, int rank,
                            int generation) {
  memset(ind, 0, sizeof *ind);
  st__strlcpy(ind->run_label, label, sizeof ind->run_label);
  st__strlcpy(ind->path, path, sizeof ind->path);
  ind->rank = rank;
  ind->generation = generation;
}

stStatus st_post_load_population(const char *path, int top, int ngenes, stPostIndividual *out,
                                 char *err, size_t errsz) {
  ST_ASSERT(path && out);
  char file[ST_PATH_MAX];
  snprintf(file, sizeof file, "%s", path);
  if (is_dir(path)) {
    snprintf(file, sizeof file, "%s/population.genome", path);
    if (!exists(file)) snprintf(file, sizeof file, "%s/checkpoint", path);
    if (!exists(file))
      return st__errf(err, errsz, "%s: neither population.genome nor checkpoint (expected a "
                      "primitive run directory of evolve, or a population file)", path), ST_ERR_IO;
  }
  stGenomeSet set;
  stStatus st = st_genome_set_read(file, ngenes, &set, err, errsz);
  if (st) return st;
  if (set.count < top) {
    st__errf(err, errsz, "%s has %d genotypes (expected at least posteval.integration_top = %d)",
             file, set.count, top);
    st_genome_set_free(&set);
    return ST_ERR_ARG;
  }
  char label[128];
  st_post_run_label(file, label, sizeof label);
  for (int i = 0; i < top; i++) {
    individual_init(&out[i], label, file, i, -1);
    out[i].genome = set.genome[i];
  }
  st_genome_set_free(&set);
  return ST_OK;
}

/* the text of an ENUM or BOOL key's value */
static void choice_name(const char *section, const char *name, int v, char *buf, size_t n) {
  const stConfigKey *k = st_config_key(st_config_find(section, name));
  if (k && k->type == ST_CFG_ENUM) st__strlcpy(buf, st_config_enum_name(section, name, v), n);
  else snprintf(buf, n, "%s", v ? "true" : "false");
}

/* the run's config.ini (path, read into rc) has the condition of cfg (Table 2.1's keys) and its
 * reach starts (the post-evaluations start from the integrated stage's reach postures) */
static stStatus same_condition(const char *path, const stConfig *cfg, const stConfig *rc,
                               char *err, size_t errsz) {
  static const char *const keys[][2] = {
      {"stage", "stages"},           {"network", "arch"},       {"integrated", "words_even"},
      {"integrated", "words_odd"},   {"integrated", "fitness_even"}, {"integrated", "fitness_odd"},
      {"integrated", "first_generation"}, {"postures", "reach_palm_down"}};
  const int have[] = {rc->stage_stages, rc->network_arch, rc->integrated_words_even,
                      rc->integrated_words_odd, rc->integrated_fitness_even,
                      rc->integrated_fitness_odd, rc->integrated_first_generation,
                      rc->postures_reach_palm_down};
  const int want[] = {ST_STAGES_INTEGRATED, cfg->network_arch, cfg->integrated_words_even,
                      cfg->integrated_words_odd, cfg->integrated_fitness_even,
                      cfg->integrated_fitness_odd, cfg->integrated_first_generation,
                      cfg->postures_reach_palm_down};
  for (int i = 0; i < (int)(sizeof have / sizeof have[0]); i++) {
    if (have[i] == want[i]) continue;
    char h[64], w[64];
    choice_name(keys[i][0], keys[i][1], have[i], h, sizeof h);
    choice_name(keys[i][0], keys[i][1], want[i], w, sizeof w);
    return st__errf(err, errsz, "%s: key '%s.%s' is %s, the config's is %s (expected an "
                    "integrated run of the config's condition)", path, keys[i][0], keys[i][1],
                    h, w), ST_ERR_ARG;
  }
  return ST_OK;
}

/* A run made with another keying of its streams or another LCP solver than the test's config is
 * still tested (a test's trials are its own, drawn from the test's keys), but a test made before
 * the shipped configs changed these keys (2026-11-28) is repeated only with the run's: say so. */
static void note_other_keys(const char *dir, const stConfig *cfg, const stConfig *rc, FILE *f) {
  if (!f) return;
  static const char *const keys[][2] = {{"run", "rng_seed"}, {"dynamics", "lcp"}};
  const int have[] = {rc->run_rng_seed, rc->dynamics_lcp};
  const int want[] = {cfg->run_rng_seed, cfg->dynamics_lcp};
  for (int i = 0; i < (int)(sizeof have / sizeof have[0]); i++) {
    if (have[i] == want[i]) continue;
    char h[64], w[64];
    choice_name(keys[i][0], keys[i][1], have[i], h, sizeof h);
    choice_name(keys[i][0], keys[i][1], want[i], w, sizeof w);
    fprintf(f, "posteval: note: %s was made with %s.%s = %s, the test runs with %s (its own "
            "trials; --set %s.%s=%s repeats a test made with the run's)\n", dir, keys[i][0],
            keys[i][1], h, w, keys[i][0], keys[i][1], h);
  }
}

/* the best of the last generation: best.genome's last record and its generation */
static stStatus last_best(const char *dir, int ngenes, stGenome *g, int *generation, char *err,
                          size_t errsz) {
  char path[ST_PATH_MAX];
  snprintf(path, sizeof path, "%s/best.genome", dir);
  stGenomeSet set;
  stStatus st = st_genome_set_read(path, ngenes, &set, err, errsz);
  if (st) return st;
  if (set.count == 0 || set.generation[set.count - 1] < 0) {
    st_genome_set_free(&set);
    return st__errf(err, errsz, "%s: no genotype with a '# generation G' line (expected "
                    "evolve's per-generation bests)", path), ST_ERR_PARSE;
  }
  *g = set.genome[set.count - 1];
  *generation = set.generation[set.count - 1];
  st_genome_set_free(&set);
  return ST_OK;
}

/* st_post_load_run, its notes (nullable) on `note` */
static stStatus load_run(const char *dir, const stConfig *cfg, int exclusion, FILE *note,
                         stPostIndividual *out, char *err, size_t errsz) {
  if (!is_dir(dir))
    return st__errf(err, errsz, "%s: not a directory (expected an integrated run directory of "
                    "evolve: config.ini, fitness.csv, best.genome)", dir), ST_ERR_IO;
  char path[ST_PATH_MAX];
  snprintf(path, sizeof path, "%s/config.ini", dir);
  stConfig run;
  st_config_default(&run);
  char e[1024];
  if (st_config_load(path, &run, e, sizeof e))
    return st__errf(err, errsz, "integrated run %s: %s", dir, e), ST_ERR_IO;
  stStatus st = same_condition(path, cfg, &run, err, errsz);
  if (!st) note_other_keys(dir, cfg, &run, note);
  stGenome g;
  int generation = -1;
  if (!st) st = last_best(dir, st_arch_ngenes((stNetArch)cfg->network_arch), &g, &generation, err, errsz);
  uint8_t success[ST_INT_MAX_TRIALS];
  int n = 0;
  snprintf(path, sizeof path, "%s/fitness.csv", dir);
  if (!st) st = st_fitness_csv_successes(path, generation, success, ST_INT_MAX_TRIALS, &n, err, errsz);
  if (st) return st;
  char label[128];
  st_post_run_label(dir, label, sizeof label);
  snprintf(path, sizeof path, "%s/best.genome", dir);
  individual_init(out, label, path, 0, generation);
  out->genome = g;
  if (exclusion) {
    stIntegratedDef idef;
    st_integrated_def_from_config(cfg, &idef);
    out->excluded = st_post_excluded(&idef, generation, success, n);
  }
  return ST_OK;
}

stStatus st_post_load_run(const char *dir, const stConfig *cfg, int exclusion,
                          stPostIndividual *out, char *err, size_t errsz) {
  ST_ASSERT(dir && cfg && out);
  return load_run(dir, cfg, exclusion, NULL, out, err, errsz);
}

/* ---- the run ---- */

typedef struct postRun {
  const stPostRunDef *def;
  const stConfig *cfg;
  stPostDef pd;
  stIntegratedDef idef;
  stPostLabels labels;
  char condition[64];
  stWordSource words;
  stPostIndividual *ind;
  int nind;
  stPostTrial *trials;
  stNetParams *net;
  stPostResult *res;
  uint8_t *unit_done;      /* per unit: its result is in res (run here or read from the journal) */
  stProtocol *proto;
  stWorkspace *ws;
  int threads;
  long total, done, resumed;
  double t0, last_print, last_journal, journal_every;
  uint64_t fingerprint;
  char journal[ST_PATH_MAX];
} postRun;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* keys: the config file's against the default (read by the run's own stages or by the test),
 * the --set options' against the file (read by the test) */
static stStatus check_keys(const postRun *R, char *err, size_t errsz) {
  stConfig d;
  st_config_default(&d);
  const stConfig *file = R->def->file_cfg ? R->def->file_cfg : &d;
  const unsigned reader = st_post_test_reader(R->def->test);
  stStatus st = st_config_check_changes(file, &d, "the default",
                                        st_config_run_stages(file) | reader, err, errsz);
  if (!st) st = st_config_check_changes(R->cfg, file, "the config file's value", reader, err, errsz);
  return st;
}

static stStatus load_individuals(postRun *R, char *err, size_t errsz) {
  const stPostRunDef *d = R->def;
  const stPostTestInfo *info = st_post_test_info(d->test);
  const int populations = info->populations;
  const int per = populations ? R->cfg->posteval_integration_top : 1;
  if (d->ninputs < 1)
    return st__errf(err, errsz, "no inputs (expected %s)", populations
                    ? "population files or primitive run directories"
                    : "integrated run directories"), ST_ERR_ARG;
  R->nind = d->ninputs * per;
  R->ind = calloc((size_t)R->nind, sizeof *R->ind);
  if (!R->ind) return st__errf(err, errsz, "posteval: out of memory"), ST_ERR_NOMEM;
  const int ngenes = st_arch_ngenes((stNetArch)R->cfg->network_arch);
  const int exclusion = info->excludes && d->variant == ST_POST_OWN_WORDS;
  for (int i = 0; i < d->ninputs; i++) {
    stStatus st = populations
                      ? st_post_load_population(d->inputs[i], per, ngenes, &R->ind[i * per], err, errsz)
                      : load_run(d->inputs[i], R->cfg, exclusion, d->progress, &R->ind[i], err, errsz);
    if (st) return st;
    for (int k = 0; k < per; k++) R->ind[i * per + k].run = i; /* the input's position */
    for (int j = 0; j < i * per; j++)
      if (!strcmp(R->ind[j].run_label, R->ind[i * per].run_label))
        return st__errf(err, errsz, "%s and %s have the same run label '%s' (expected runs in "
                        "directories of different names)", R->ind[j].path, R->ind[i * per].path,
                        R->ind[j].run_label), ST_ERR_ARG;
  }
  return ST_OK;
}

/* the out dir exists (created) and takes files, before any work */
static stStatus prepare_dir(const char *dir, char *err, size_t errsz) {
  char tmp[ST_PATH_MAX];
  if (!dir[0] || strlen(dir) + 32 >= sizeof tmp)
    return st__errf(err, errsz, "output directory '%s': bad path", dir), ST_ERR_IO;
  snprintf(tmp, sizeof tmp, "%s", dir);
  for (char *p = tmp + 1; *p; p++)
    if (*p == '/') {
      *p = 0;
      mkdir(tmp, 0777);
      *p = '/';
    }
  if (mkdir(tmp, 0777) != 0 && errno != EEXIST)
    return st__errf(err, errsz, "output directory '%s': cannot create: %s", dir, strerror(errno)),
           ST_ERR_IO;
  snprintf(tmp, sizeof tmp, "%s/.write_probe", dir);
  FILE *f = fopen(tmp, "w");
  if (!f || fputs("probe\n", f) < 0 || fclose(f) != 0)
    return st__errf(err, errsz, "output directory '%s': not writable: %s", dir, strerror(errno)),
           ST_ERR_IO;
  remove(tmp);
  return ST_OK;
}

/* what the run's rows say: test, condition, words; the trial table */
static stStatus plan(postRun *R, char *err, size_t errsz) {
  const stPostRunDef *d = R->def;
  st_post_def_from_config(R->cfg, d->test, &R->pd);
  st_integrated_def_from_config(R->cfg, &R->idef);
  stStatus st = st_post_words(&R->idef, d->test, d->variant, &R->words, err, errsz);
  if (st) return st;
  if (d->condition) snprintf(R->condition, sizeof R->condition, "%s", d->condition);
  else st_post_condition(R->cfg, d->test, d->variant, R->condition, sizeof R->condition);
  if (!R->condition[0] || strpbrk(R->condition, ",\"| \t\r\n"))
    return st__errf(err, errsz, "condition '%s': not a plain label (expected a name without "
                    "commas, quotes, '|' or blanks)", R->condition), ST_ERR_ARG;
  R->labels.test = st_post_test_name(d->test);
  R->labels.condition = R->condition;
  R->labels.words = R->words;
  R->threads = st_thread_count(d->threads, R->cfg);
  return ST_OK;
}

static stStatus allocate(postRun *R, char *err, size_t errsz) {
  const size_t nt = (size_t)R->pd.trials;
  R->trials = calloc(nt, sizeof *R->trials);
  R->net = calloc((size_t)R->nind, sizeof *R->net);
  R->res = calloc((size_t)R->nind * nt, sizeof *R->res);
  R->unit_done = calloc((size_t)R->nind * nt, 1);
  R->ws = calloc((size_t)R->threads, sizeof *R->ws);
  if (R->trials && R->net && R->res && R->unit_done && R->ws) return ST_OK;
  return st__errf(err, errsz, "posteval: out of memory"), ST_ERR_NOMEM;
}

/* the table and the networks */
static stStatus prepare(postRun *R, char *err, size_t errsz) {
  for (int t = 0; t < R->pd.trials; t++) st_post_trial(&R->pd, &R->proto->scene, t, &R->trials[t]);
  for (int i = 0; i < R->nind; i++) {
    char e[512];
    stStatus st = st_net_decode(&R->proto->net, (stNetArch)R->cfg->network_arch,
                                &R->ind[i].genome, &R->net[i], e, sizeof e);
    if (st) return st__errf(err, errsz, "%s, genotype %d: %s", R->ind[i].path, R->ind[i].rank, e), st;
  }
  R->total = 0;
  for (int i = 0; i < R->nind; i++) R->total += R->ind[i].excluded ? 0 : R->pd.trials;
  return ST_OK;
}

/* DIR's files: the three written at the end (write_files), then the journal; the CSVs' names
 * are their schemas' (selftalk/postcsv.h) */
static const char *const g_out_names[] = {"config.ini", "trials.csv", "summary.csv",
                                          ST_POST_JOURNAL};
#define N_RESULT_FILES 3

/* the temporary files of DIR's files that a test killed mid-write left */
static void remove_stale_tmp(const postRun *R) {
  char path[ST_PATH_MAX + 32];
  for (size_t i = 0; i < sizeof g_out_names / sizeof g_out_names[0]; i++) {
    snprintf(path, sizeof path, "%s/%s", R->def->out_dir, g_out_names[i]);
    st_atomic_clean(path);
  }
}

/* DIR/posteval.journal: a test killed before its end continues with --resume; one already
 * there without --resume is refused (nothing is overwritten); a complete journal re-writes the
 * same files */
static stStatus open_journal(postRun *R, char *err, size_t errsz) {
  const stPostRunDef *d = R->def;
  snprintf(R->journal, sizeof R->journal, "%s/%s", d->out_dir, ST_POST_JOURNAL);
  R->fingerprint = st__post_fingerprint(R->cfg, R->proto->robot->model, d->test, d->variant,
                                        R->condition, R->ind, R->nind);
  R->journal_every = d->journal_seconds > 0 ? d->journal_seconds
                     : d->journal_seconds < 0 ? 0.0 : ST_POST_JOURNAL_SECONDS;
  if (access(R->journal, F_OK) != 0) {
    if (errno == ENOENT) return ST_OK;
    return st__errf(err, errsz, "%s: %s", R->journal, strerror(errno)), ST_ERR_IO;
  }
  if (!d->resume)
    return st__errf(err, errsz, "%s holds a post-evaluation (%s): give --resume to continue it "
                    "(or re-write its files), or choose another --out", d->out_dir, R->journal),
           ST_ERR_ARG;
  const long units = (long)R->nind * R->pd.trials;
  stStatus st = st__post_journal_read(R->journal, R->fingerprint, units, R->pd.steps,
                                      R->unit_done, R->res, &R->resumed, err, errsz);
  for (long u = 0; !st && u < units; u++)
    if (R->unit_done[u] && R->ind[u / R->pd.trials].excluded)
      st = (st__errf(err, errsz, "%s: unit %ld is of an excluded individual", R->journal, u),
            ST_ERR_PARSE);
  return st;
}

static stStatus write_journal(const postRun *R, char *err, size_t errsz) {
  return st__post_journal_write(R->journal, R->fingerprint, (long)R->nind * R->pd.trials,
                                R->unit_done, R->res, err, errsz);
}

static void hms(double s, char *buf, size_t n) {
  const long t = (long)(s + 0.5);
  snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
}

/* unit u done: the journal every journal_every seconds; a progress line every 10 s and at the
 * end (called in a critical section) */
static stStatus progress(postRun *R, long u, char *err, size_t errsz) {
  R->unit_done[u] = 1;
  R->done++;
  FILE *f = R->def->progress;
  const double t = now();
  if (t - R->last_journal >= R->journal_every) {
    R->last_journal = t;
    stStatus st = write_journal(R, err, errsz);
    if (st) return st;
  }
  if (!f || (t - R->last_print < 10.0 && R->done < R->total)) return ST_OK;
  R->last_print = t;
  const double el = t - R->t0, rate = (R->done - R->resumed) / (el > 0 ? el : 1e-9);
  char e1[32], e2[32];
  hms(el, e1, sizeof e1);
  hms((double)(R->total - R->done) / rate, e2, sizeof e2);
  fprintf(f, "posteval %s %s: %ld/%ld trials (%.1f%%) | %.2f trials/s elapsed %s left %s\n",
          R->labels.test, R->condition, R->done, R->total, 100.0 * R->done / R->total, rate, e1, e2);
  fflush(f);
  return ST_OK;
}

/* every trial of every individual not excluded and not in the journal; unit u = individual
 * u / trials, trial u % trials; results by index, so the files do not depend on the threads.
 * A trial that fails is reported (the first by index); one that cannot write the journal
 * stops the test. */
static stStatus run_trials(postRun *R, char *err, size_t errsz) {
  const long nt = R->pd.trials, units = (long)R->nind * nt;
  long failed = -1;
  int stop = 0;
  stStatus first = ST_OK;
  char msg[1200] = "";
  R->done = R->resumed;
  R->t0 = R->last_print = R->last_journal = now();
#pragma omp parallel num_threads(R->threads)
  {
    stWorkspace *ws = &R->ws[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
    for (long u = 0; u < units; u++) {
      const int i = (int)(u / nt), t = (int)(u % nt);
      int stopped;
#pragma omp atomic read
      stopped = stop;
      if (stopped || R->ind[i].excluded || R->unit_done[u]) continue;
      char e[512];
      stNetController nc;
      const stController ctl = st_net_controller(&nc, &R->net[i], NULL, 0);
      stStatus st = st_post_run_trial(R->proto, &R->idef, ws, &R->trials[t], &ctl, R->words,
                                      &R->res[u], NULL, NULL, e, sizeof e);
#pragma omp critical
      {
        if (st && (failed < 0 || u < failed)) {
          failed = u;
          first = st;
          snprintf(msg, sizeof msg, "%s, genotype %d, trial %d: %s", R->ind[i].path,
                   R->ind[i].rank, t, e);
        }
        if (!st && !stop && (st = progress(R, u, e, sizeof e)) != ST_OK) {
          failed = 0; /* before every trial's own failure */
          first = st;
          snprintf(msg, sizeof msg, "%s", e);
#pragma omp atomic write
          stop = 1;
        }
      }
    }
  }
  if (failed >= 0) return st__errf(err, errsz, "%s", msg), first;
  return write_journal(R, err, errsz); /* complete: every unit */
}

static stStatus write_file(const char *dir, const char *name, const postRun *R, char *err,
                           size_t errsz) {
  char path[ST_PATH_MAX];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, path, err, errsz);
  if (st) return st;
  int rc;
  if (!strcmp(name, "config.ini")) rc = st_config_write(af.f, R->cfg);
  else if (!strcmp(name, st_post_trials_schema()->file))
    rc = st_post_write_trials(af.f, &R->labels, R->ind, R->nind, R->trials, R->pd.trials, R->res);
  else rc = st_post_write_summary(af.f, &R->labels, R->ind, R->nind, R->pd.trials, R->res);
  if (rc) {
    st_atomic_abort(&af);
    return st__errf(err, errsz, "%s: cannot write", path), ST_ERR_IO;
  }
  return st_atomic_commit(&af, err, errsz);
}

static stStatus write_files(const postRun *R, char *err, size_t errsz) {
  for (int i = 0; i < N_RESULT_FILES; i++) {
    stStatus st = write_file(R->def->out_dir, g_out_names[i], R, err, errsz);
    if (st) return st;
  }
  return ST_OK;
}

static void finish_line(const postRun *R) {
  FILE *f = R->def->progress;
  if (!f) return;
  int excluded = 0;
  for (int i = 0; i < R->nind; i++) excluded += R->ind[i].excluded;
  char e[32];
  hms(now() - R->t0, e, sizeof e);
  fprintf(f, "posteval %s %s: %d individuals (%d excluded), %ld trials (%ld from the journal) "
          "in %s on %d threads; files in %s\n", R->labels.test, R->condition, R->nind, excluded,
          R->total, R->resumed, e, R->threads, R->def->out_dir);
}

static void release(postRun *R) {
  for (int t = 0; R->ws && t < R->threads; t++) st_workspace_free(&R->ws[t]);
  free(R->ws);
  free(R->ind);
  free(R->trials);
  free(R->net);
  free(R->res);
  free(R->unit_done);
  st_protocol_destroy(R->proto);
}

stStatus st_post_run(const stPostRunDef *def, char *err, size_t errsz) {
  ST_ASSERT(def);
  postRun R;
  memset(&R, 0, sizeof R);
  R.def = def;
  R.cfg = def->cfg;
  if ((int)def->test < 0 || def->test >= ST_POST_NTESTS)
    return st__errf(err, errsz, "test %d (expected integration, robustness or generalisation)",
                    (int)def->test), ST_ERR_ARG;
  stStatus st = st_config_validate(def->cfg, err, errsz);
  if (!st) st = check_keys(&R, err, errsz);
  if (!st) st = plan(&R, err, errsz);
  if (!st) st = load_individuals(&R, err, errsz);
  if (!st) st = prepare_dir(def->out_dir, err, errsz);
  if (!st) st = allocate(&R, err, errsz);
  if (!st) st = st_protocol_create(R.cfg, &R.proto, err, errsz);
  if (!st) st = prepare(&R, err, errsz);
  if (!st) st = open_journal(&R, err, errsz);
  if (!st) remove_stale_tmp(&R); /* accepted: what a killed test left goes, nothing else */
  if (!st) st = run_trials(&R, err, errsz);
  if (!st) st = write_files(&R, err, errsz);
  if (!st) finish_line(&R);
  release(&R);
  return st;
}
