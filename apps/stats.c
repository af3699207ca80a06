/* SPDX-License-Identifier: MIT
 * stats: the statistics of the post-evaluation (thesis §2.10, §3) from files, on the core's
 * selftalk/stats.h.
 *
 *   stats mwu FILE_A FILE_B [--exact-max N] [--continuity C] [--verbose]
 *   stats quartiles FILE
 *   stats table SUMMARY.csv [--test TEST] [--csv]
 *   stats describe SUMMARY.csv [--test TEST]
 *   stats selftalk TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set KEY=VALUE]
 *   stats times TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set robot.control_dt=S]
 *
 * mwu: the two-tailed Mann-Whitney U test of two files of one number per line (blank lines and
 * lines starting with '#' skipped); prints "U=... p=..." (%.17g), U = min(U_A, U_B); --verbose
 * adds a line with U_A, U_B, z, the method and the tied values. quartiles: "n=... min=... q1=...
 * median=... q3=... max=..." (definition 7).
 * table: Tables 3.1 / 3.2, the matrix of the row condition's U against each column condition
 * (the pairs in which the row's success percentage is the smaller, plus half the ties: the
 * smaller, the more likely the row is better), * for p <= 0.05 and ** for p <= 0.01, then the
 * matrix of p; --csv: one row per ordered pair instead. A condition NAME0 (the caretaker
 * variant of NAME: ST-CT0, ST0) is compared with NAME only. describe: per condition, n, median
 * and quartiles of the success percentages and of the trials the caretaker jumped "open".
 * selftalk: Fig. 3.11, for every condition NAME with a variant NAME0 in the file, per
 * individual the test of its per-repetition success percentages with self talk (NAME) against
 * the caretaker (NAME0), and the mean time to the target of its successes, as CSV. times:
 * Table 3.3, those times for the individuals significantly (p <= alpha, 0.01) better with self
 * talk; seconds = (reached_step + 1) x robot.control_dt.
 * The CSV formats are docs/PROTOCOL.md's ("Post-evaluation files"): a trials file's rows are
 * checked against the tests' trial tables (st_post_trial_layout; posteval.* keys from --config
 * / --set), an individual or trial given twice is refused; selftalk and times sort the rows once
 * (O(n log n)). Errors name FILE:LINE and
 * what was expected; exit 2. Files are read through the library's bounded reader (at most
 * 64 MiB, no NUL bytes). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/posteval.h"
#include "selftalk/stats.h"

static const char *prog = "stats";

#define USAGE                                                                                   \
  "usage: stats mwu FILE_A FILE_B [--exact-max N] [--continuity C] [--verbose]\n"              \
  "       stats quartiles FILE\n"                                                              \
  "       stats table SUMMARY.csv [--test TEST] [--csv]\n"                                     \
  "       stats describe SUMMARY.csv [--test TEST]\n"                                          \
  "       stats selftalk TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set KEY=VALUE]\n"  \
  "       stats times TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set KEY=VALUE]\n"

static void *xrealloc(void *p, size_t n, size_t size) {
  void *q = realloc(p, n * size);
  if (!q) app_die(prog, "out of memory");
  return q;
}

/* ---- text files: read whole, then line by line ---- */

typedef struct textFile {
  const char *path;
  char *buf;
  size_t len, pos;
  int lineno;
} textFile;

/* the whole file through the library's bounded reader (app_read_text: at most 64 MiB, no NUL
 * byte) */
static void text_open(textFile *t, const char *path) {
  memset(t, 0, sizeof *t);
  t->path = path;
  t->buf = app_read_text(prog, path, &t->len);
}

/* the next line without its end and surrounding white space; NULL at the end of the file */
static char *text_line(textFile *t) {
  if (t->pos >= t->len) return NULL;
  char *s = t->buf + t->pos, *nl = memchr(s, '\n', t->len - t->pos);
  const size_t n = nl ? (size_t)(nl - s) : t->len - t->pos;
  t->pos += n + 1;
  t->lineno++;
  s[n] = 0;
  size_t e = n;
  while (e > 0 && strchr(" \t\r\v\f", s[e - 1])) s[--e] = 0;
  while (*s == ' ' || *s == '\t') s++;
  return s;
}

/* the next line that is neither blank nor a # comment */
static char *text_content(textFile *t) {
  char *s;
  while ((s = text_line(t)) && (!*s || *s == '#')) {
  }
  return s;
}

/* ---- mwu, quartiles: one number per line ---- */

static double *read_numbers(const char *path, int *n) {
  textFile t;
  text_open(&t, path);
  double *x = NULL;
  int cap = 0;
  *n = 0;
  for (char *s; (s = text_content(&t));) {
    char *end;
    errno = 0;
    const double v = strtod(s, &end);
    if (end == s || *end)
      app_die(prog, "%s:%d: '%s' is not a number (expected one number per line)", path, t.lineno, s);
    if (!isfinite(v) || errno == ERANGE)
      app_die(prog, "%s:%d: '%s' is not finite (expected a finite number)", path, t.lineno, s);
    if (*n == cap) x = xrealloc(x, (size_t)(cap = 2 * cap + 64), sizeof *x);
    x[(*n)++] = v;
  }
  free(t.buf);
  if (!*n)
    app_die(prog, "%s: no numbers (expected one number per line; blank lines and # comments are "
            "skipped)", path);
  return x;
}

typedef struct opts {
  const char *pos[3];
  int npos;
  const char *test;
  int csv, verbose;
  double alpha;
  stMwuDef mwu;
  appConfigArgs config;
} opts;

static void mwu_or_die(const opts *o, const double *a, int na, const double *b, int nb,
                       stMwuResult *r, const char *what) {
  char err[512];
  if (st_mwu(&o->mwu, a, na, b, nb, r, err, sizeof err)) app_die(prog, "%s: %s", what, err);
}

static int cmd_mwu(const opts *o) {
  int na, nb;
  double *a = read_numbers(o->pos[1], &na), *b = read_numbers(o->pos[2], &nb);
  stMwuResult r;
  mwu_or_die(o, a, na, b, nb, &r, "mwu");
  printf("U=%.17g p=%.17g\n", r.u, r.p);
  if (o->verbose)
    printf("U_A=%.17g U_B=%.17g z=%.17g method=%s n_A=%d n_B=%d tied_values=%d\n", r.u_a, r.u_b,
           r.z, r.method == ST_MWU_EXACT ? "exact" : "normal", na, nb, r.ties);
  free(a);
  free(b);
  return 0;
}

static int cmd_quartiles(const opts *o) {
  int n;
  double *x = read_numbers(o->pos[1], &n);
  stQuartiles q;
  char err[512];
  if (st_quartiles(x, n, &q, err, sizeof err)) app_die(prog, "%s: %s", o->pos[1], err);
  printf("n=%d min=%.17g q1=%.17g median=%.17g q3=%.17g max=%.17g\n", q.n, q.min, q.q1, q.median,
         q.q3, q.max);
  free(x);
  return 0;
}

/* ---- the post-evaluation CSVs (docs/PROTOCOL.md) ---- */

#define NAME_LEN 32
enum { WORDS_NONE, WORDS_CARETAKER, WORDS_SELFTALK };
static const char *const WORDS[] = {"none", "caretaker", "selftalk"};

typedef enum colKind { C_NAME, C_INT, C_WORDS } colKind;
typedef struct colSpec {
  const char *name;
  colKind kind;
  int lo; /* C_INT: range lo..INT_MAX */
  size_t off;
} colSpec;

typedef struct sumRow {
  char test[NAME_LEN], cond[NAME_LEN];
  int run, ind, successes, trials, excluded, open_jumped;
} sumRow;

static const colSpec SUM_COLS[] = {
    {"test", C_NAME, 0, offsetof(sumRow, test)},
    {"condition", C_NAME, 0, offsetof(sumRow, cond)},
    {"run", C_INT, 0, offsetof(sumRow, run)},
    {"individual", C_INT, 0, offsetof(sumRow, ind)},
    {"successes", C_INT, 0, offsetof(sumRow, successes)},
    {"trials", C_INT, 1, offsetof(sumRow, trials)},
    {"excluded", C_INT, 0, offsetof(sumRow, excluded)},
    {"open_jumped", C_INT, 0, offsetof(sumRow, open_jumped)}};

typedef struct trialRow {
  char test[NAME_LEN], cond[NAME_LEN];
  int run, ind, trial, type, cell, posture, rep, words, success, reached_step, open_jumped;
} trialRow;

static const colSpec TRIAL_COLS[] = {
    {"test", C_NAME, 0, offsetof(trialRow, test)},
    {"condition", C_NAME, 0, offsetof(trialRow, cond)},
    {"run", C_INT, 0, offsetof(trialRow, run)},
    {"individual", C_INT, 0, offsetof(trialRow, ind)},
    {"trial", C_INT, 0, offsetof(trialRow, trial)},
    {"type", C_INT, -1, offsetof(trialRow, type)},
    {"cell", C_INT, -1, offsetof(trialRow, cell)},
    {"posture", C_INT, 0, offsetof(trialRow, posture)},
    {"repetition", C_INT, 0, offsetof(trialRow, rep)},
    {"words", C_WORDS, 0, offsetof(trialRow, words)},
    {"success", C_INT, 0, offsetof(trialRow, success)},
    {"reached_step", C_INT, -1, offsetof(trialRow, reached_step)},
    {"open_jumped", C_INT, 0, offsetof(trialRow, open_jumped)}};

#define NCOLS(c) ((int)(sizeof(c) / sizeof(c)[0]))
#define MAX_FIELDS 256

/* splits a line at commas in place; returns the number of fields */
static int split(const textFile *t, char *s, char **field) {
  if (strchr(s, '"'))
    app_die(prog, "%s:%d: a quoted field (expected plain comma-separated values)", t->path, t->lineno);
  int n = 0;
  for (;;) {
    if (n == MAX_FIELDS) app_die(prog, "%s:%d: more than %d fields", t->path, t->lineno, MAX_FIELDS);
    field[n++] = s;
    char *c = strchr(s, ',');
    if (!c) return n;
    *c = 0;
    s = c + 1;
  }
}

static void header_names(const colSpec *cols, int ncols, char *buf, size_t n) {
  buf[0] = 0;
  for (int i = 0; i < ncols; i++)
    snprintf(buf + strlen(buf), n - strlen(buf), "%s%s", i ? "," : "", cols[i].name);
}

static void check_header(const textFile *t, char *line, const colSpec *cols, int ncols) {
  char *f[MAX_FIELDS], want[512];
  const int n = line ? split(t, line, f) : 0;
  int ok = n >= ncols;
  for (int i = 0; ok && i < ncols; i++) ok = !strcmp(f[i], cols[i].name);
  if (ok) return;
  header_names(cols, ncols, want, sizeof want);
  app_die(prog, "%s:%d: %s (expected the header %s, further columns ignored)", t->path,
          t->lineno, line ? "not the header" : "no header", want);
}

static void parse_field(const textFile *t, const colSpec *c, const char *s, char *row) {
  if (c->kind == C_NAME) {
    if (!*s || strlen(s) >= NAME_LEN || strpbrk(s, " \t|"))
      app_die(prog, "%s:%d: %s '%s' (expected a name of 1..%d characters without blanks or |)",
              t->path, t->lineno, c->name, s, NAME_LEN - 1);
    strcpy(row + c->off, s);
    return;
  }
  int v = -1;
  if (c->kind == C_WORDS) {
    for (int w = 0; w < 3; w++) v = strcmp(s, WORDS[w]) ? v : w;
    if (v < 0)
      app_die(prog, "%s:%d: words '%s' (expected none, caretaker or selftalk)", t->path, t->lineno, s);
  } else {
    char *end;
    errno = 0;
    const long x = strtol(s, &end, 10);
    if (end == s || *end || errno || x < c->lo || x > INT_MAX)
      app_die(prog, "%s:%d: %s '%s' (expected an integer >= %d)", t->path, t->lineno, c->name, s, c->lo);
    v = (int)x;
  }
  memcpy(row + c->off, &v, sizeof v);
}

typedef struct rows {
  char *data;
  int n;
  size_t size;
  int *line; /* each row's line in the file */
  int *ord;  /* the rows by key (then line) */
} rows;

typedef void (*rowCheck)(const textFile *t, const void *row);
/* a row's key against another's (<0, 0, >0); and the key in words, for messages */
typedef int (*rowKey)(const void *a, const void *b);
typedef void (*rowName)(const void *row, char *buf, size_t n);

static const rows *g_rows;
static rowKey g_key;

static int cmp_order(const void *x, const void *y) {
  const int i = *(const int *)x, j = *(const int *)y;
  const int c = g_key(g_rows->data + g_rows->size * (size_t)i, g_rows->data + g_rows->size * (size_t)j);
  return c ? c : (i > j) - (i < j);
}

/* the rows' order by key, then by line (O(n log n)); a key twice is refused at its second
 * line */
static void order_rows(const char *path, rows *rs, rowKey key, rowName name) {
  rs->ord = xrealloc(NULL, (size_t)rs->n, sizeof *rs->ord);
  for (int i = 0; i < rs->n; i++) rs->ord[i] = i;
  g_rows = rs, g_key = key;
  qsort(rs->ord, (size_t)rs->n, sizeof *rs->ord, cmp_order);
  for (int i = 1; i < rs->n; i++) {
    const int a = rs->ord[i - 1], b = rs->ord[i];
    if (key(rs->data + rs->size * (size_t)a, rs->data + rs->size * (size_t)b)) continue;
    char what[160];
    name(rs->data + rs->size * (size_t)b, what, sizeof what);
    app_die(prog, "%s:%d: %s twice (first at line %d; expected each once)", path, rs->line[b],
            what, rs->line[a]);
  }
}

static void load_csv(const char *path, const colSpec *cols, int ncols, size_t size,
                     rowCheck check, rowKey key, rowName name, rows *out) {
  textFile t;
  text_open(&t, path);
  check_header(&t, text_content(&t), cols, ncols);
  int cap = 0;
  memset(out, 0, sizeof *out);
  out->size = size;
  for (char *s; (s = text_content(&t));) {
    char *f[MAX_FIELDS];
    const int n = split(&t, s, f);
    if (n < ncols) {
      char want[512];
      header_names(cols, ncols, want, sizeof want);
      app_die(prog, "%s:%d: %d fields (expected at least %d: %s)", path, t.lineno, n, ncols, want);
    }
    if (out->n == cap) {
      cap = 2 * cap + 256;
      out->data = xrealloc(out->data, (size_t)cap, size);
      out->line = xrealloc(out->line, (size_t)cap, sizeof *out->line);
    }
    out->line[out->n] = t.lineno;
    char *row = out->data + size * (size_t)out->n;
    memset(row, 0, size);
    for (int i = 0; i < ncols; i++) parse_field(&t, &cols[i], f[i], row);
    check(&t, row);
    out->n++;
  }
  free(t.buf);
  if (!out->n) app_die(prog, "%s: no rows after the header", path);
  order_rows(path, out, key, name);
}

static void rows_free(rows *rs) {
  free(rs->data);
  free(rs->line);
  free(rs->ord);
}

/* an individual: (test, condition, run, individual) */
static int ind_key(const char *ta, const char *ca, int ra, int ia, const char *tb, const char *cb,
                   int rb, int ib) {
  int c = strcmp(ta, tb);
  if (!c) c = strcmp(ca, cb);
  if (!c) c = (ra > rb) - (ra < rb);
  if (!c) c = (ia > ib) - (ia < ib);
  return c;
}

static int sum_key(const void *a, const void *b) {
  const sumRow *x = a, *y = b;
  return ind_key(x->test, x->cond, x->run, x->ind, y->test, y->cond, y->run, y->ind);
}

static void sum_name(const void *row, char *buf, size_t n) {
  const sumRow *r = row;
  snprintf(buf, n, "test %s condition %s run %d individual %d", r->test, r->cond, r->run, r->ind);
}

static int trial_ind_key(const trialRow *x, const trialRow *y) {
  return ind_key(x->test, x->cond, x->run, x->ind, y->test, y->cond, y->run, y->ind);
}

static int trial_key(const void *a, const void *b) {
  const trialRow *x = a, *y = b;
  const int c = trial_ind_key(x, y);
  return c ? c : (x->trial > y->trial) - (x->trial < y->trial);
}

static void trial_name(const void *row, char *buf, size_t n) {
  const trialRow *r = row;
  snprintf(buf, n, "test %s condition %s run %d individual %d trial %d", r->test, r->cond,
           r->run, r->ind, r->trial);
}

/* the test's name: one of posteval's (selftalk/posteval.h) */
static void check_test(const textFile *t, const char *test) {
  if (st_post_test_parse(test) < 0)
    app_die(prog, "%s:%d: test '%s' (expected integration, robustness or generalisation)",
            t->path, t->lineno, test);
}

/* the tests' trial tables (posteval.* keys of --config / --set: the defaults are the thesis's) */
#define KEYS_HINT "posteval.* keys from --config (the test's config.ini) or --set"
static stPostDef g_def[ST_POST_NTESTS];

static void check_sum(const textFile *t, const void *row) {
  const sumRow *r = row;
  check_test(t, r->test);
  if (r->successes > r->trials || r->open_jumped > r->trials || r->excluded > 1)
    app_die(prog, "%s:%d: successes %d, open_jumped %d, excluded %d (expected successes and "
            "open_jumped <= trials (%d), excluded 0 or 1)", t->path, t->lineno, r->successes,
            r->open_jumped, r->excluded, r->trials);
  if (r->excluded && r->successes)
    app_die(prog, "%s:%d: an excluded individual with %d successes (expected 0: it is not run)",
            t->path, t->lineno, r->successes);
}

static void check_trial(const textFile *t, const void *row) {
  const trialRow *r = row;
  if (r->success > 1 || r->open_jumped > 1) /* type, cell, posture: the trial table's, below */
    app_die(prog, "%s:%d: success %d, open_jumped %d (expected 0 or 1)", t->path, t->lineno,
            r->success, r->open_jumped);
  if (r->success && r->reached_step < 0)
    app_die(prog, "%s:%d: success 1 with reached_step -1 (expected the step the object reached "
            "the target)", t->path, t->lineno);
  if (!r->success && r->reached_step >= 0)
    app_die(prog, "%s:%d: success 0 with reached_step %d (expected -1: a failed trial never "
            "reached the target)", t->path, t->lineno, r->reached_step);
  check_test(t, r->test);
  const stPostDef *d = &g_def[st_post_test_parse(r->test)];
  if (r->trial >= d->trials)
    app_die(prog, "%s:%d: trial %d (expected 0..%d: the %s test has %d trials; " KEYS_HINT ")",
            t->path, t->lineno, r->trial, d->trials - 1, r->test, d->trials);
  stPostTrial l;
  st_post_trial_layout(d, r->trial, &l);
  if (r->type != l.type || r->cell != l.cell || r->posture != l.posture || r->rep != l.repetition)
    app_die(prog, "%s:%d: trial %d with type %d, cell %d, posture %d, repetition %d (expected "
            "type %d, cell %d, posture %d, repetition %d: the %s test's trial table; " KEYS_HINT
            ")", t->path,
            t->lineno, r->trial, r->type, r->cell, r->posture, r->rep, l.type, l.cell, l.posture,
            l.repetition, r->test);
}

#define ROW(rs, T, i) ((const T *)((rs)->data + (rs)->size * (size_t)(i)))

/* ---- conditions ---- */

#define MAX_CONDS 32
static const char *const KNOWN[] = {"ST-CT", "ST", "CT", "NI", "ST-CT0", "ST0"};

typedef struct conds {
  const char *name[MAX_CONDS];
  int n;
} conds;

static int cond_index(const conds *c, const char *name) {
  for (int i = 0; i < c->n; i++)
    if (!strcmp(c->name[i], name)) return i;
  return -1;
}

static void cond_add(conds *c, const char *name) {
  if (cond_index(c, name) >= 0) return;
  if (c->n == MAX_CONDS) app_die(prog, "more than %d conditions (or tests)", MAX_CONDS);
  c->name[c->n++] = name;
}

/* the thesis's order first, then the others as they come; names point into the rows */
static void cond_order(conds *c) {
  conds o = {{0}, 0};
  for (int k = 0; k < (int)(sizeof KNOWN / sizeof KNOWN[0]); k++)
    if (cond_index(c, KNOWN[k]) >= 0) o.name[o.n++] = c->name[cond_index(c, KNOWN[k])];
  for (int i = 0; i < c->n; i++) cond_add(&o, c->name[i]);
  *c = o;
}

/* x is y's caretaker variant: y followed by "0" */
static int variant_of(const char *x, const char *y) {
  const size_t n = strlen(y);
  return strlen(x) == n + 1 && !strncmp(x, y, n) && x[n] == '0';
}

static int is_variant(const conds *c, int i) {
  for (int j = 0; j < c->n; j++)
    if (variant_of(c->name[i], c->name[j])) return 1;
  return 0;
}

/* Table 3.2's pairs: among the conditions, and each variant with its own condition only */
static int compared(const conds *c, int i, int j) {
  if (i == j) return 0;
  if (variant_of(c->name[i], c->name[j]) || variant_of(c->name[j], c->name[i])) return 1;
  return !is_variant(c, i) && !is_variant(c, j);
}

/* ---- summary: table, describe ---- */

/* the test the rows are filtered to: --test, or the file's only one */
static const char *pick_test(const char *path, const char *want, const conds *tests) {
  if (want && cond_index(tests, want) >= 0) return want;
  if (!want && tests->n == 1) return tests->name[0];
  char list[512] = "";
  for (int i = 0; i < tests->n; i++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", tests->name[i]);
  app_die(prog, "%s: %s (tests in the file: %s)", path,
          want ? "no rows of this --test" : "several tests: choose one with --test", list);
}

typedef struct samples {
  rows rs; /* the names in c point into it */
  const char *test;
  conds c;
  double *x[MAX_CONDS];
  double *jumped[MAX_CONDS];
  int n[MAX_CONDS];
} samples;

/* the success percentages (and open_jumped) of each condition of the test */
static void summary_samples(const opts *o, samples *s) {
  memset(s, 0, sizeof *s);
  rows *rs = &s->rs;
  load_csv(o->pos[1], SUM_COLS, NCOLS(SUM_COLS), sizeof(sumRow), check_sum, sum_key, sum_name, rs);
  conds tests = {{0}, 0};
  for (int i = 0; i < rs->n; i++) cond_add(&tests, ROW(rs, sumRow, i)->test);
  s->test = pick_test(o->pos[1], o->test, &tests);
  for (int i = 0; i < rs->n; i++)
    if (!strcmp(ROW(rs, sumRow, i)->test, s->test)) cond_add(&s->c, ROW(rs, sumRow, i)->cond);
  cond_order(&s->c);
  for (int k = 0; k < s->c.n; k++) {
    s->x[k] = xrealloc(NULL, (size_t)rs->n, sizeof(double));
    s->jumped[k] = xrealloc(NULL, (size_t)rs->n, sizeof(double));
  }
  for (int i = 0; i < rs->n; i++) {
    const sumRow *r = ROW(rs, sumRow, i);
    const int k = cond_index(&s->c, r->cond);
    if (strcmp(r->test, s->test) || k < 0) continue;
    s->jumped[k][s->n[k]] = r->open_jumped;
    s->x[k][s->n[k]++] = 100.0 * r->successes / r->trials;
  }
}

static void samples_free(samples *s) {
  for (int k = 0; k < s->c.n; k++) free(s->x[k]), free(s->jumped[k]);
  rows_free(&s->rs);
}

static const char *stars(double p) { return p <= 0.01 ? "**" : p <= 0.05 ? "*" : ""; }

static void matrix(const opts *o, const samples *s, int want_p) {
  printf("\n| %s |", want_p ? "p" : "U");
  for (int j = 0; j < s->c.n; j++) printf(" %s |", s->c.name[j]);
  printf("\n|---|");
  for (int j = 0; j < s->c.n; j++) printf("---|");
  for (int i = 0; i < s->c.n; i++) {
    printf("\n| %s |", s->c.name[i]);
    for (int j = 0; j < s->c.n; j++) {
      stMwuResult r;
      if (!compared(&s->c, i, j)) {
        printf(" - |");
        continue;
      }
      mwu_or_die(o, s->x[i], s->n[i], s->x[j], s->n[j], &r, o->pos[1]);
      if (want_p) printf(" %.3g |", r.p);
      else printf(" %g%s |", r.u_b, stars(r.p));
    }
  }
  printf("\n");
}

static void pairs_csv(const opts *o, const samples *s) {
  printf("test,row,column,n_row,n_column,U,p,method,stars\n");
  for (int i = 0; i < s->c.n; i++)
    for (int j = 0; j < s->c.n; j++) {
      stMwuResult r;
      if (!compared(&s->c, i, j)) continue;
      mwu_or_die(o, s->x[i], s->n[i], s->x[j], s->n[j], &r, o->pos[1]);
      printf("%s,%s,%s,%d,%d,%.17g,%.17g,%s,%s\n", s->test, s->c.name[i], s->c.name[j], s->n[i], s->n[j],
             r.u_b, r.p, r.method == ST_MWU_EXACT ? "exact" : "normal", stars(r.p));
    }
}

static int cmd_table(const opts *o) {
  samples s;
  summary_samples(o, &s);
  if (o->csv) {
    pairs_csv(o, &s);
    samples_free(&s);
    return 0;
  }
  printf("# %s: %s\n# two-tailed Mann-Whitney U of the individuals' success percentages; row's U: the pairs "
         "in which the row's value is the smaller, plus half the ties (the smaller, the more "
         "likely the row is better than the column); * p <= 0.05, ** p <= 0.01\n", o->pos[1], s.test);
  matrix(o, &s, 0);
  matrix(o, &s, 1);
  samples_free(&s);
  return 0;
}

static void describe_line(const char *cond, const char *what, const double *x, int n) {
  stQuartiles q;
  char err[256];
  if (st_quartiles(x, n, &q, err, sizeof err)) app_die(prog, "%s: %s", cond, err);
  printf("| %s | %s | %d | %g | %g | %g | %g | %g |\n", cond, what, n, q.median, q.q1, q.q3,
         q.min, q.max);
}

static int cmd_describe(const opts *o) {
  samples s;
  summary_samples(o, &s);
  printf("# %s: %s\n\n| condition | quantity | n | median | lower quartile | upper quartile | min | max |\n"
         "|---|---|---|---|---|---|---|---|\n", o->pos[1], s.test);
  for (int k = 0; k < s.c.n; k++) {
    describe_line(s.c.name[k], "success %", s.x[k], s.n[k]);
    describe_line(s.c.name[k], "open jumped", s.jumped[k], s.n[k]);
  }
  samples_free(&s);
  return 0;
}

/* ---- trials: selftalk (Fig. 3.11), times (Table 3.3) ---- */

#define MAX_REPS 1000

/* one individual under one condition: per-repetition counts and the successes' steps */
typedef struct tallyT {
  int trials[MAX_REPS], successes[MAX_REPS];
  int nrep, total, succ;
  double steps; /* sum of reached_step + 1 over the successes */
} tallyT;

/* an individual's rows: rs->ord[start..end), in trial order; first: its first line's row */
typedef struct group {
  int start, end, first;
} group;

#define TROW(rs, g, k) ROW(rs, trialRow, (rs)->ord[(g)->start + (k)])

static void tally(const rows *rs, const group *g, tallyT *t) {
  memset(t, 0, sizeof *t);
  if (!g) return;
  for (int k = 0; k < g->end - g->start; k++) {
    const trialRow *r = TROW(rs, g, k);
    if (r->rep >= MAX_REPS) app_die(prog, "repetition %d (expected < %d)", r->rep, MAX_REPS);
    t->trials[r->rep]++;
    t->successes[r->rep] += r->success;
    t->nrep = r->rep + 1 > t->nrep ? r->rep + 1 : t->nrep;
    t->total++;
    t->succ += r->success;
    t->steps += r->success ? r->reached_step + 1.0 : 0.0;
  }
}

/* the success percentage of each repetition that has trials in `like` (an excluded
 * individual, with no trials, scores 0 in each) */
static int rep_pcts(const tallyT *t, const tallyT *like, double *x) {
  int n = 0;
  for (int k = 0; k < like->nrep; k++)
    if (like->trials[k]) x[n++] = t->trials[k] ? 100.0 * t->successes[k] / t->trials[k] : 0.0;
  return n;
}

/* one individual with self talk (cond) and with the caretaker's words (variant) */
typedef struct comparison {
  char cond[NAME_LEN]; /* NAME of the variant NAME0: need not be in the file */
  const char *variant;
  int run, ind, excluded;
  int total[2], succ[2]; /* [0] self talk, [1] caretaker */
  double steps[2];
  stMwuResult r;
  const char *better;
} comparison;

/* self: the individual's rows in NAME (NULL: none, excluded); care: in NAME0 */
static void compare(const opts *o, const rows *rs, const group *self, const group *care,
                    comparison *c) {
  static tallyT t[2];
  static double x[2][MAX_REPS];
  tally(rs, self, &t[0]);
  tally(rs, care, &t[1]);
  c->excluded = t[0].total == 0;
  const int na = rep_pcts(&t[0], c->excluded ? &t[1] : &t[0], x[0]), nb = rep_pcts(&t[1], &t[1], x[1]);
  for (int k = 0; k < 2; k++) c->total[k] = t[k].total, c->succ[k] = t[k].succ, c->steps[k] = t[k].steps;
  char what[160];
  snprintf(what, sizeof what, "%s: %s against %s, run %d individual %d", o->pos[1], c->cond,
           c->variant, c->run, c->ind);
  mwu_or_die(o, x[0], na, x[1], nb, &c->r, what);
  c->better = c->r.p > o->alpha || c->r.u_a == c->r.u_b ? "none"
              : c->r.u_a > c->r.u_b                    ? "selftalk"
                                                       : "caretaker";
}

typedef struct comparisons {
  comparison *c;
  int n;
} comparisons;

/* the individuals of the file, each a group of rows, in key order (O(n)) */
static group *groups_of(const rows *rs, int *ng) {
  group *g = xrealloc(NULL, (size_t)rs->n, sizeof *g);
  *ng = 0;
  for (int i = 0; i < rs->n;) {
    group *x = &g[(*ng)++];
    x->start = i, x->first = rs->ord[i];
    const trialRow *r0 = ROW(rs, trialRow, rs->ord[i]);
    while (i < rs->n && !trial_ind_key(ROW(rs, trialRow, rs->ord[i]), r0)) {
      x->first = rs->ord[i] < x->first ? rs->ord[i] : x->first;
      i++;
    }
    x->end = i;
  }
  return g;
}

/* the group of an individual, by binary search (O(log n)); NULL when it has no rows */
static const group *find_group(const rows *rs, const group *g, int ng, const trialRow *want) {
  int lo = 0, hi = ng;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    const int c = trial_ind_key(TROW(rs, &g[mid], 0), want);
    if (!c) return &g[mid];
    if (c < 0) lo = mid + 1;
    else hi = mid;
  }
  return NULL;
}

static int cmp_first(const void *x, const void *y) {
  const int a = (*(const group *const *)x)->first, b = (*(const group *const *)y)->first;
  return (a > b) - (a < b);
}

/* the individuals of condition v in file order (of their first rows), each against its rows
 * in cond: O(n log n) */
static void compare_condition(const opts *o, const rows *rs, const group *g, int ng,
                              const char *test, const char *cond, const char *v,
                              comparisons *out) {
  const group **mine = xrealloc(NULL, (size_t)ng, sizeof *mine);
  int n = 0;
  for (int i = 0; i < ng; i++) {
    const trialRow *r = TROW(rs, &g[i], 0);
    if (!strcmp(r->cond, v) && !strcmp(r->test, test)) mine[n++] = &g[i];
  }
  qsort(mine, (size_t)n, sizeof *mine, cmp_first);
  out->c = xrealloc(out->c, (size_t)out->n + (size_t)n, sizeof *out->c);
  for (int i = 0; i < n; i++) {
    trialRow want = *TROW(rs, mine[i], 0);
    strcpy(want.cond, cond);
    comparison *c = &out->c[out->n++];
    memset(c, 0, sizeof *c);
    strcpy(c->cond, cond);
    c->variant = v, c->run = want.run, c->ind = want.ind;
    compare(o, rs, find_group(rs, g, ng, &want), mine[i], c);
  }
  free(mine);
}

/* NAME of a condition NAME0 (a caretaker variant) into base; 0 for other names. NAME need not
 * be in the file (all of its individuals excluded). */
static int base_of(const char *v, char base[NAME_LEN]) {
  const size_t n = strlen(v);
  if (n < 2 || v[n - 1] != '0') return 0;
  memcpy(base, v, n - 1);
  base[n - 1] = 0;
  return 1;
}

/* the tests' trial tables from the configuration (--config, --set) */
static void trial_tables(const opts *o, stConfig *cfg) {
  app_config_resolve(&o->config, cfg, prog);
  for (int t = 0; t < ST_POST_NTESTS; t++) st_post_def_from_config(cfg, (stPostTest)t, &g_def[t]);
}

/* every individual of every NAME0 in the file against NAME, in the thesis's order */
static comparisons compare_all(const opts *o, rows *rs) {
  load_csv(o->pos[1], TRIAL_COLS, NCOLS(TRIAL_COLS), sizeof(trialRow), check_trial, trial_key,
           trial_name, rs);
  conds tests = {{0}, 0};
  for (int i = 0; i < rs->n; i++) cond_add(&tests, ROW(rs, trialRow, i)->test);
  const char *test = pick_test(o->pos[1], o->test, &tests);
  conds c = {{0}, 0};
  for (int i = 0; i < rs->n; i++)
    if (!strcmp(ROW(rs, trialRow, i)->test, test)) cond_add(&c, ROW(rs, trialRow, i)->cond);
  cond_order(&c);
  int ng;
  group *g = groups_of(rs, &ng);
  comparisons out = {NULL, 0};
  for (int v = 0; v < c.n; v++) {
    char base[NAME_LEN];
    if (base_of(c.name[v], base)) compare_condition(o, rs, g, ng, test, base, c.name[v], &out);
  }
  free(g);
  if (!out.n)
    app_die(prog, "%s: no condition NAME0 in test %s (expected the caretaker variant of a self "
            "talk condition, e.g. ST-CT0 beside ST-CT)", o->pos[1], test);
  return out;
}

/* mean seconds to the target over the successes; empty when there are none */
static void seconds(char *buf, size_t n, double steps, int succ, double dt) {
  if (succ) snprintf(buf, n, "%.17g", steps / succ * dt);
  else buf[0] = 0;
}

static int cmd_selftalk(const opts *o) {
  rows rs;
  stConfig cfg;
  trial_tables(o, &cfg);
  const comparisons cs = compare_all(o, &rs);
  const double dt = cfg.robot_control_dt;
  printf("condition,caretaker_condition,run,individual,excluded,selftalk_pct,caretaker_pct,U,p,"
         "method,better,selftalk_seconds,caretaker_seconds\n");
  for (int i = 0; i < cs.n; i++) {
    const comparison *c = &cs.c[i];
    char s0[40], s1[40];
    seconds(s0, sizeof s0, c->steps[0], c->succ[0], dt);
    seconds(s1, sizeof s1, c->steps[1], c->succ[1], dt);
    printf("%s,%s,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%s,%s,%s,%s\n", c->cond, c->variant, c->run,
           c->ind, c->excluded, c->total[0] ? 100.0 * c->succ[0] / c->total[0] : 0.0,
           c->total[1] ? 100.0 * c->succ[1] / c->total[1] : 0.0, c->r.u, c->r.p,
           c->r.method == ST_MWU_EXACT ? "exact" : "normal", c->better, s0, s1);
  }
  free(cs.c);
  rows_free(&rs);
  return 0;
}

/* Table 3.3's two rows over the n individuals better with self talk */
static void times_rows(const comparisons *cs, int n, double dt) {
  printf("\n|---|");
  for (int i = 0; i < n; i++) printf("---|");
  for (int k = 0; k < 2; k++) {
    printf("\n| %s |", k ? "Caretaker" : "Self talk");
    for (int i = 0; i < cs->n; i++) {
      const comparison *c = &cs->c[i];
      if (strcmp(c->better, "selftalk")) continue;
      if (c->succ[k]) printf(" %.2f |", c->steps[k] / c->succ[k] * dt);
      else printf(" - |");
    }
  }
  printf("\n");
}

static int cmd_times(const opts *o) {
  rows rs;
  stConfig cfg;
  trial_tables(o, &cfg);
  const comparisons cs = compare_all(o, &rs);
  const double dt = cfg.robot_control_dt;
  printf("# %s: mean seconds to the target over the successful trials ((reached_step + 1) x %g s), "
         "the individuals significantly better with self talk (p <= %g)\n\n", o->pos[1], dt,
         o->alpha);
  int n = 0;
  for (int i = 0; i < cs.n; i++) n += !strcmp(cs.c[i].better, "selftalk");
  if (!n) printf("no individual is significantly better with self talk\n");
  else {
    printf("| |"); /* the table: one column per such individual */
    for (int i = 0; i < cs.n; i++)
      if (!strcmp(cs.c[i].better, "selftalk")) printf(" %s run %d |", cs.c[i].cond, cs.c[i].run);
    times_rows(&cs, n, dt);
  }
  free(cs.c);
  rows_free(&rs);
  return 0;
}

/* ---- command line ---- */

static double real_arg(const char *opt, const char *v, double lo, double hi) {
  char *end;
  const double x = strtod(v, &end);
  if (end == v || *end || !(x >= lo && x <= hi))
    app_die(prog, "%s '%s': expected a number in %g..%g", opt, v, lo, hi);
  return x;
}

static void parse(int argc, char **argv, opts *o) {
  memset(o, 0, sizeof *o);
  o->alpha = 0.01;
  o->mwu = st_mwu_default_def();
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    const int has = v != NULL;
    if (app_config_arg(&o->config, argc, argv, &i, prog)) continue;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) printf(USAGE), exit(0);
    else if (!strcmp(a, "--csv")) o->csv = 1;
    else if (!strcmp(a, "--verbose")) o->verbose = 1;
    else if (!strcmp(a, "--test") && has) o->test = v, i++;
    else if (!strcmp(a, "--alpha") && has) o->alpha = real_arg(a, v, 0.0, 1.0), i++;
    else if (!strcmp(a, "--continuity") && has) o->mwu.continuity = real_arg(a, v, 0.0, 0.5), i++;
    else if (!strcmp(a, "--exact-max") && has) {
      o->mwu.exact_max_n = app_int_arg(prog, a, v, 0), i++;
      if (o->mwu.exact_max_n > ST_MWU_EXACT_LIMIT)
        app_die(prog, "--exact-max %s: expected 0..%d", v, ST_MWU_EXACT_LIMIT);
    } else if (a[0] == '-' && a[1]) app_die(prog, "option '%s' unknown or without its value", a);
    else if (o->npos < 3) o->pos[o->npos++] = a;
    else app_die(prog, "unexpected argument '%s'\n%s", a, USAGE);
  }
}

typedef struct command {
  const char *name;
  int nfiles;
  int (*run)(const opts *o);
} command;

static const command COMMANDS[] = {{"mwu", 2, cmd_mwu},           {"quartiles", 1, cmd_quartiles},
                                   {"table", 1, cmd_table},       {"describe", 1, cmd_describe},
                                   {"selftalk", 1, cmd_selftalk}, {"times", 1, cmd_times}};

int main(int argc, char **argv) {
  opts o;
  parse(argc, argv, &o);
  if (!o.npos) app_die(prog, "no command\n%s", USAGE);
  for (int i = 0; i < (int)(sizeof COMMANDS / sizeof COMMANDS[0]); i++) {
    if (strcmp(o.pos[0], COMMANDS[i].name)) continue;
    if (o.npos != 1 + COMMANDS[i].nfiles)
      app_die(prog, "%s needs %d file%s\n%s", o.pos[0], COMMANDS[i].nfiles,
              COMMANDS[i].nfiles > 1 ? "s" : "", USAGE);
    return COMMANDS[i].run(&o);
  }
  app_die(prog, "'%s': unknown command (expected mwu, quartiles, table, describe, selftalk or "
          "times)\n%s", o.pos[0], USAGE);
}
