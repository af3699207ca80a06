/* SPDX-License-Identifier: MIT
 * fitness.csv (selftalk/fitnesscsv.h): its one column table, a layout's columns, and the
 * reader of a generation's trials. */
#include "selftalk/fitnesscsv.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/io.h"
#include "run/fitnesscsv_parse.h"

#define R stFitnessRow
#define P ST_FITNESS_PRIMITIVE
#define I ST_FITNESS_INTEGRATED
#define BOTH (ST_FITNESS_PRIMITIVE | ST_FITNESS_INTEGRATED)
/* the integrated and the primitive columns interleaved so that each keeps its order; the
 * primitive stages' trials are the kinds' columns, after these */
static const stFitnessColumn g_cols[] = {
    {ST_CSV_COL_INT(R, generation, "generation", 0), BOTH, 0},
    {ST_CSV_COL_REAL(R, best, "best"), BOTH, 0},
    {ST_CSV_COL_REAL(R, mean, "mean"), BOTH, 0},
    {ST_CSV_COL_REAL(R, worst, "worst"), BOTH, 0},
    {ST_CSV_COL_REAL(R, f_int, "best_F_int"), I, 0},
    {ST_CSV_COL_REAL(R, f_pred, "best_F_pred"), I, 0},
    {ST_CSV_COL_REAL(R, bonus, "best_bonus"), BOTH, 0},
    {ST_CSV_COL_REAL(R, bonus_auto, "best_bonus_auto"), I, 0},
    {ST_CSV_COL_NAME(R, stage, "stage"), P, 0},
    {ST_CSV_COL_INT(R, stage_generation, "stage_generation", 0), P, 0},
    {ST_CSV_COL_INT(R, all_success, "all_success", 0), P, 0},
    {ST_CSV_COL_INT(R, successes, "best_successes", 0), BOTH, 0},
    {ST_CSV_COL_REAL(R, f_prim[ST_PRIM_REACH], "best_F_reach"), P, 0},
    {ST_CSV_COL_REAL(R, f_prim[ST_PRIM_OPEN], "best_F_open"), P, 0},
    {ST_CSV_COL_REAL(R, f_prim[ST_PRIM_GRASP], "best_F_grasp"), P, 0},
    {ST_CSV_COL_REAL(R, f_prim[ST_PRIM_MOVE], "best_F_move"), P, 0},
    {ST_CSV_COL_INT(R, success[0], ST_TRIAL_COLUMN, 0), I, 1},
};
#undef R
#undef P
#undef I
#undef BOTH
#define NCOLS ((int)(sizeof g_cols / sizeof g_cols[0]))
#define GENERATION (&g_cols[0].col) /* the first column: checkpoint.c finds rows by it */

const stFitnessColumn *st_fitness_columns(int *n) {
  ST_ASSERT(n);
  *n = NCOLS;
  return g_cols;
}

/* column k of the schema: col, named name (with trial t when it is a format), moved by offset */
static void put(stFitnessCsv *c, int k, const stCsvColumn *col, const char *name, int t,
                size_t offset) {
  c->col[k] = *col;
  c->col[k].offset += offset;
  if (t < 0) return;
  snprintf(c->name[k], sizeof c->name[k], name, t);
  c->col[k].name = c->name[k];
}

/* the kinds' columns: a kind's own (over its stKindEvaluation), then one per trial */
static int kind_columns(const stFitnessLayout *l, stFitnessCsv *c, int k) {
  for (int i = 0; i < ST_TRIAL_KIND_COUNT; i++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)i);
    const int n = l->kind_trials[i];
    if (n <= 0) continue;
    const size_t at = offsetof(stFitnessRow, kind) + (size_t)i * sizeof(stKindEvaluation);
    if (d->column.name) put(c, k++, &d->column, NULL, -1, at);
    const stCsvColumn trial = ST_CSV_COL_INT(stKindEvaluation, success[0], d->trial_column, 0);
    for (int t = 0; t < n; t++, k++) put(c, k, &trial, d->trial_column, t, at + (size_t)t * sizeof(int));
  }
  return k;
}

void st_fitness_csv(const stFitnessLayout *l, stFitnessCsv *c) {
  ST_ASSERT(l && c && l->trials >= 0 && l->trials <= ST_INT_MAX_TRIALS);
  memset(c, 0, sizeof *c);
  const unsigned stage = l->integrated ? ST_FITNESS_INTEGRATED : ST_FITNESS_PRIMITIVE;
  int k = 0;
  for (int i = 0; i < NCOLS; i++) {
    const stFitnessColumn *f = &g_cols[i];
    if (!(f->stages & stage)) continue;
    if (!f->per_trial) put(c, k++, &f->col, NULL, -1, 0);
    for (int t = 0; f->per_trial && t < l->trials; t++, k++)
      put(c, k, &f->col, f->col.name, t, (size_t)t * sizeof(int));
  }
  if (!l->integrated) {
    for (int i = 0; i < ST_TRIAL_KIND_COUNT; i++)
      ST_ASSERT(l->kind_trials[i] >= 0 && l->kind_trials[i] <= st_trial_kind_def((stTrialKind)i)->max);
    k = kind_columns(l, c, k);
  }
  const stCsvSchema s = {"fitness.csv", c->col, k, 0, 0, sizeof(stFitnessRow), NULL};
  c->schema = s;
}

/* ---- reading a generation's trials ---- */

/* splits a CSV line in place; returns the number of fields (at most max; max + 1 when there
 * are more) */
static int split_csv(char *line, char **field, int max) {
  int n = 0;
  line[strcspn(line, "\r\n")] = 0;
  for (char *p = line; n <= max;) {
    if (n == max) return max + 1;
    field[n++] = p;
    p = strchr(p, ',');
    if (!p) break;
    *p++ = 0;
  }
  return n;
}

#define MAX_FIELDS 256

/* the generation column and the trials' columns (at most max) of a header; -1 with the name
 * of a column given twice */
static int trial_columns(char *header, int *nf, int *gcol, int *tcol, int max, const char **twice) {
  char *fld[MAX_FIELDS];
  *nf = split_csv(header, fld, MAX_FIELDS);
  int nt = 0;
  *gcol = -1;
  for (int i = 0; i < *nf && i < MAX_FIELDS; i++) {
    for (int j = 0; j < i; j++)
      if (!strcmp(fld[i], fld[j])) return *twice = fld[i], -1;
    char want[32];
    snprintf(want, sizeof want, ST_TRIAL_COLUMN, nt);
    if (!strcmp(fld[i], GENERATION->name)) *gcol = i;
    if (!strcmp(fld[i], want) && nt < max) tcol[nt++] = i;
  }
  return nt;
}

/* issue 48: strict. Every row as long as the header, its generation an integer above the
 * previous row's (a duplicated or unordered generation is refused, not the first taken), every
 * trial's column 0 or 1 (an empty or 'x' value was read as a success) */
/* an integer >= 0 as "%d" prints it: no sign, space or leading zero */
static int canonical_int(const char *v) {
  if (!v[0] || (v[0] == '0' && v[1])) return 0;
  for (const char *c = v; *c; c++)
    if (*c < '0' || *c > '9') return 0;
  return 1;
}

typedef struct successesAsk {
  int generation, max;
  uint8_t *success;
  int *n;
} successesAsk;

static stStatus parse_successes(const char *path, char *text, size_t len, void *ctx, char *err,
                                size_t errsz) {
  const successesAsk *a = ctx;
  const int generation = a->generation, max = a->max;
  uint8_t *success = a->success;
  int *n = a->n;
  stStatus st = ST_OK;
  int gcol = -1, tcol[ST_INT_MAX_TRIALS], nf_head = 0, lineno = 0, found = 0, prev = -1;
  char first[32];
  snprintf(first, sizeof first, ST_TRIAL_COLUMN, 0);
  *n = 0;
  const char *rest = text, *at;
  size_t n_at;
  while (!st && st__text_line(&rest, text + len, &at, &n_at, NULL)) {
    char *line = text + (at - text);
    line[n_at] = 0; /* our copy: each line a C string (the last one's byte is the final NUL) */
    if (++lineno == 1) {
      const char *twice = NULL;
      *n = trial_columns(line, &nf_head, &gcol, tcol, max, &twice);
      if (twice) {
        st = ST_ERR_PARSE;
        st__errf(err, errsz, "%s:1: column '%s' twice (expected each column once)", path, twice);
      } else if (nf_head > MAX_FIELDS || gcol < 0 || *n == 0) {
        st = ST_ERR_PARSE;
        st__errf(err, errsz, "%s:1: no %s and %s columns (expected the fitness.csv of an "
                 "integrated run)", path, GENERATION->name, first);
      }
      continue;
    }
    char *fld[MAX_FIELDS];
    const int nf = split_csv(line, fld, MAX_FIELDS);
    int g;
    if (nf != nf_head) {
      st = ST_ERR_PARSE;
      st__errf(err, errsz, "%s:%d: %d fields (expected %d, as the header)", path, lineno, nf,
               nf_head);
      break;
    }
    if (!canonical_int(fld[gcol]) || st__parse_int(fld[gcol], &g)) {
      st = ST_ERR_PARSE;
      st__errf(err, errsz, "%s:%d: %s '%s' (expected an integer >= 0 as evolve writes it)",
               path, lineno, GENERATION->name, fld[gcol]);
      break;
    }
    if (g <= prev) {
      st = ST_ERR_PARSE;
      st__errf(err, errsz, "%s:%d: %s %d after %d (expected one row per generation, in "
               "increasing order)", path, lineno, GENERATION->name, g, prev);
      break;
    }
    prev = g;
    for (int i = 0; i < *n && !st; i++) {
      const char *v = fld[tcol[i]];
      if (strcmp(v, "0") && strcmp(v, "1")) {
        char name[32];
        snprintf(name, sizeof name, ST_TRIAL_COLUMN, i);
        st = ST_ERR_PARSE;
        st__errf(err, errsz, "%s:%d: %s '%s' (expected 0 or 1: the trial failed or succeeded)",
                 path, lineno, name, v);
      }
      if (g == generation) success[i] = (uint8_t)(v[0] == '1');
    }
    found |= g == generation;
  }
  if (!st && !found) {
    st = ST_ERR_PARSE;
    st__errf(err, errsz, "%s: no row for generation %d, the last of best.genome (expected the "
             "run's own fitness.csv)", path, generation);
  }
  return st;
}

stStatus st_fitness_csv_successes(const char *path, int generation, uint8_t *success, int max,
                                  int *n, char *err, size_t errsz) {
  ST_ASSERT(path && success && n && max >= 0 && max <= ST_INT_MAX_TRIALS);
  successesAsk a = {generation, max, success, n};
  return st__text_read_parse(path, parse_successes, &a, err, errsz);
}

stStatus st__fitness_csv_successes_parse(const char *name, const char *text, size_t len,
                                         int generation, uint8_t *success, int max, int *n,
                                         char *err, size_t errsz) {
  ST_ASSERT(name && (text || !len) && success && n && max >= 0 && max <= ST_INT_MAX_TRIALS);
  successesAsk a = {generation, max, success, n};
  *n = 0;
  return st__text_parse(name, text, len, parse_successes, &a, err, errsz);
}
