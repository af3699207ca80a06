/* SPDX-License-Identifier: MIT
 * The statistics of the post-evaluation files (selftalk/poststats.h): conditions, the samples
 * of a summary, the self talk against caretaker comparisons of a trials file. */
#include "selftalk/poststats.h"

#include <stdlib.h>
#include <string.h>

#include "core/internal.h"

/* ---- names ---- */

static const char *const KNOWN[] = {"ST-CT", "ST", "CT", "NI", "ST-CT0", "ST0"};

int st_post_names_index(const stPostNames *c, const char *name) {
  ST_ASSERT(c && name);
  for (int i = 0; i < c->n; i++)
    if (!strcmp(c->name[i], name)) return i;
  return -1;
}

/* row i's name (its test or its condition, what) into c; the first one too many names the file
 * and the row's line */
static stStatus names_add(stPostNames *c, const stCsvRows *rs, int i, const char *name,
                          const char *what, const char *where, char *err, size_t errsz) {
  if (st_post_names_index(c, name) >= 0) return ST_OK;
  if (c->n == ST_POST_MAX_NAMES)
    return st__errf(err, errsz, "%s:%d: %s '%s': more than %d %ss %s (expected at most %d)",
                    rs->name ? rs->name : "(rows)", rs->line ? rs->line[i] : i + 1, what, name,
                    ST_POST_MAX_NAMES, what, where, ST_POST_MAX_NAMES),
           ST_ERR_RANGE;
  c->name[c->n++] = name;
  return ST_OK;
}

/* the thesis's order first, then the others as they come */
static void names_order(stPostNames *c) {
  stPostNames o = {{0}, 0};
  for (int k = 0; k < (int)(sizeof KNOWN / sizeof KNOWN[0]); k++) {
    const int i = st_post_names_index(c, KNOWN[k]);
    if (i >= 0) o.name[o.n++] = c->name[i];
  }
  for (int i = 0; i < c->n; i++)
    if (st_post_names_index(&o, c->name[i]) < 0) o.name[o.n++] = c->name[i];
  *c = o;
}

/* the rows' test and condition: both files' first two columns */
static const char *test_of(const stCsvRows *rs, int i) {
  return (const char *)st_csv_row(rs, i) + rs->schema->col[0].offset;
}
static const char *cond_of(const stCsvRows *rs, int i) {
  return (const char *)st_csv_row(rs, i) + rs->schema->col[1].offset;
}

stStatus st_post_tests(const stCsvRows *rs, stPostNames *tests, char *err, size_t errsz) {
  ST_ASSERT(rs && tests);
  memset(tests, 0, sizeof *tests);
  stStatus st = ST_OK;
  for (int i = 0; i < rs->n && !st; i++)
    st = names_add(tests, rs, i, test_of(rs, i), "test", "in the file", err, errsz);
  return st;
}

/* the conditions of a test's rows, in order */
static stStatus conditions(const stCsvRows *rs, const char *test, stPostNames *c, char *err,
                           size_t errsz) {
  memset(c, 0, sizeof *c);
  stStatus st = ST_OK;
  for (int i = 0; i < rs->n && !st; i++)
    if (!strcmp(test_of(rs, i), test))
      st = names_add(c, rs, i, cond_of(rs, i), "condition", "in the test", err, errsz);
  if (!st) names_order(c);
  return st;
}

const char *st_post_pick_test(const stPostNames *tests, const char *want) {
  ST_ASSERT(tests);
  if (want && st_post_names_index(tests, want) >= 0) return want;
  if (!want && tests->n == 1) return tests->name[0];
  return NULL;
}

/* x is y's caretaker variant: y followed by "0" */
static int variant_of(const char *x, const char *y) {
  const size_t n = strlen(y);
  return strlen(x) == n + 1 && !strncmp(x, y, n) && x[n] == '0';
}

static int is_variant(const stPostNames *c, int i) {
  for (int j = 0; j < c->n; j++)
    if (variant_of(c->name[i], c->name[j])) return 1;
  return 0;
}

int st_post_compared(const stPostNames *c, int i, int j) {
  ST_ASSERT(c && i >= 0 && i < c->n && j >= 0 && j < c->n);
  if (i == j) return 0;
  if (variant_of(c->name[i], c->name[j]) || variant_of(c->name[j], c->name[i])) return 1;
  return !is_variant(c, i) && !is_variant(c, j);
}

/* ---- summary ---- */

stStatus st_post_samples(const stCsvRows *rs, const char *test, stPostSamples *s, char *err,
                         size_t errsz) {
  ST_ASSERT(rs && rs->schema == st_post_summary_schema() && test && s);
  memset(s, 0, sizeof *s);
  s->test = test;
  stStatus st = conditions(rs, test, &s->conds, err, errsz);
  if (st) return st;
  for (int k = 0; k < s->conds.n; k++) {
    s->pct[k] = malloc((size_t)rs->n * sizeof(double));
    s->jumped[k] = malloc((size_t)rs->n * sizeof(double));
    if (!s->pct[k] || !s->jumped[k]) {
      st_post_samples_free(s);
      return st__errf(err, errsz, "out of memory"), ST_ERR_NOMEM;
    }
  }
  for (int i = 0; i < rs->n; i++) {
    const stPostSummaryRow *r = st_csv_row(rs, i);
    const int k = st_post_names_index(&s->conds, r->condition);
    if (strcmp(r->test, test) || k < 0) continue;
    s->jumped[k][s->n[k]] = r->open_jumped;
    s->pct[k][s->n[k]++] = 100.0 * r->successes / r->trials;
  }
  return ST_OK;
}

void st_post_samples_free(stPostSamples *s) {
  if (!s) return;
  for (int k = 0; k < ST_POST_MAX_NAMES; k++) free(s->pct[k]), free(s->jumped[k]);
  memset(s, 0, sizeof *s);
}

/* ---- trials: self talk against the caretaker ---- */

/* one individual under one condition: per-repetition counts and the successes' steps */
typedef struct tally {
  int trials[ST_POST_MAX_REPS], successes[ST_POST_MAX_REPS];
  int nrep, total, succ;
  double steps; /* sum of reached_step + 1 over the successes */
} tally;

/* what one comparison works in: the two tallies and their samples */
typedef struct scratch {
  tally t[2];
  double x[2][ST_POST_MAX_REPS];
} scratch;

/* the comparison's inputs */
typedef struct comparer {
  const stCsvRows *rs;
  const char *name, *test;
  const stMwuDef *mwu;
  double alpha;
  stCsvGroup *g;
  int ng;
  scratch *w;
} comparer;

static const stPostTrialRow *group_row(const stCsvRows *rs, const stCsvGroup *g, int k) {
  return st_csv_sorted(rs, g->start + k);
}

/* an individual's rows (NULL: none, excluded) */
static stStatus tally_of(const stCsvRows *rs, const stCsvGroup *g, tally *t, char *err,
                         size_t errsz) {
  memset(t, 0, sizeof *t);
  for (int k = 0; g && k < g->end - g->start; k++) {
    const stPostTrialRow *r = group_row(rs, g, k);
    if (r->repetition >= ST_POST_MAX_REPS)
      return st__errf(err, errsz, "repetition %d (expected < %d)", r->repetition,
                      ST_POST_MAX_REPS), ST_ERR_RANGE;
    t->trials[r->repetition]++;
    t->successes[r->repetition] += r->success;
    t->nrep = r->repetition + 1 > t->nrep ? r->repetition + 1 : t->nrep;
    t->total++;
    t->succ += r->success;
    t->steps += r->success ? r->reached_step + 1.0 : 0.0;
  }
  return ST_OK;
}

/* the success percentage of each repetition that has trials in `like` (an excluded
 * individual, with no trials, scores 0 in each) */
static int rep_pcts(const tally *t, const tally *like, double *x) {
  int n = 0;
  for (int k = 0; k < like->nrep; k++)
    if (like->trials[k]) x[n++] = t->trials[k] ? 100.0 * t->successes[k] / t->trials[k] : 0.0;
  return n;
}

/* self: the individual's rows in NAME (NULL: none); care: in NAME0 */
static stStatus compare(const comparer *C, const stCsvGroup *self, const stCsvGroup *care,
                        stPostComparison *c, char *err, size_t errsz) {
  tally *t = C->w->t;
  stStatus st = tally_of(C->rs, self, &t[0], err, errsz);
  if (!st) st = tally_of(C->rs, care, &t[1], err, errsz);
  if (st) return st;
  c->excluded = t[0].total == 0;
  const int na = rep_pcts(&t[0], c->excluded ? &t[1] : &t[0], C->w->x[0]);
  const int nb = rep_pcts(&t[1], &t[1], C->w->x[1]);
  for (int k = 0; k < 2; k++)
    c->trials[k] = t[k].total, c->successes[k] = t[k].succ, c->steps[k] = t[k].steps;
  char e[512];
  if (st_mwu(C->mwu, C->w->x[0], na, C->w->x[1], nb, &c->mwu, e, sizeof e))
    return st__errf(err, errsz, "%s: %s against %s, run %d individual %d: %s", C->name,
                    c->condition, c->variant, c->run, c->individual, e), ST_ERR_ARG;
  c->better = c->mwu.p > C->alpha || c->mwu.u_a == c->mwu.u_b ? "none"
              : c->mwu.u_a > c->mwu.u_b                      ? "selftalk"
                                                              : "caretaker";
  return ST_OK;
}

static int by_first(const void *x, const void *y) {
  const int a = (*(const stCsvGroup *const *)x)->first, b = (*(const stCsvGroup *const *)y)->first;
  return (a > b) - (a < b);
}

/* the individuals of condition v in file order (of their first rows), each against its rows
 * in cond */
static stStatus compare_condition(const comparer *C, const char *cond, const char *v,
                                  stPostComparisons *out, char *err, size_t errsz) {
  const stCsvGroup **mine = malloc(((size_t)C->ng + 1) * sizeof *mine);
  stPostComparison *grown = mine ? realloc(out->c, ((size_t)out->n + (size_t)C->ng + 1) * sizeof *out->c) : NULL;
  if (grown) out->c = grown;
  if (!mine || !grown) {
    free(mine);
    return st__errf(err, errsz, "out of memory"), ST_ERR_NOMEM;
  }
  int n = 0;
  for (int i = 0; i < C->ng; i++) {
    const stPostTrialRow *r = group_row(C->rs, &C->g[i], 0);
    if (!strcmp(r->condition, v) && !strcmp(r->test, C->test)) mine[n++] = &C->g[i];
  }
  qsort(mine, (size_t)n, sizeof *mine, by_first);
  stStatus st = ST_OK;
  for (int i = 0; i < n && !st; i++) {
    stPostTrialRow want = *group_row(C->rs, mine[i], 0);
    st__strlcpy(want.condition, cond, sizeof want.condition);
    stPostComparison *c = &out->c[out->n++];
    memset(c, 0, sizeof *c);
    st__strlcpy(c->condition, cond, sizeof c->condition);
    c->variant = v, c->run = want.run, c->individual = want.individual;
    const stCsvGroup *self = st_csv_group_find(C->rs, ST_POST_INDIVIDUAL_KEY, C->g, C->ng, &want);
    st = compare(C, self, mine[i], c, err, errsz);
  }
  free(mine);
  return st;
}

/* NAME of a condition NAME0 (a caretaker variant) into base; 0 for other names */
static int base_of(const char *v, char base[ST_CSV_NAME_LEN]) {
  const size_t n = strlen(v);
  if (n < 2 || n > ST_CSV_NAME_LEN || v[n - 1] != '0') return 0;
  memcpy(base, v, n - 1);
  base[n - 1] = 0;
  return 1;
}

stStatus st_post_compare(const stCsvRows *rs, const char *name, const char *test,
                         const stMwuDef *mwu, double alpha, stPostComparisons *out, char *err,
                         size_t errsz) {
  ST_ASSERT(rs && rs->schema == st_post_trials_schema() && name && test && out);
  memset(out, 0, sizeof *out);
  comparer C = {rs, name, test, mwu, alpha, NULL, 0, malloc(sizeof(scratch))};
  stPostNames c = {{0}, 0};
  stStatus st = C.w ? conditions(rs, test, &c, err, errsz)
                    : (st__errf(err, errsz, "out of memory"), ST_ERR_NOMEM);
  if (!st) st = st_csv_groups(rs, ST_POST_INDIVIDUAL_KEY, &C.g, &C.ng, err, errsz);
  for (int v = 0; v < c.n && !st; v++) {
    char base[ST_CSV_NAME_LEN];
    if (base_of(c.name[v], base)) st = compare_condition(&C, base, c.name[v], out, err, errsz);
  }
  free(C.g);
  free(C.w);
  if (!st && !out->n)
    st = (st__errf(err, errsz, "%s: no condition NAME0 in test %s (expected the caretaker "
                   "variant of a self talk condition, e.g. ST-CT0 beside ST-CT)", name, test),
          ST_ERR_ARG);
  if (st) st_post_comparisons_free(out);
  return st;
}

void st_post_comparisons_free(stPostComparisons *c) {
  if (!c) return;
  free(c->c);
  c->c = NULL;
  c->n = 0;
}
