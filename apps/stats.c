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
 * The files are read, checked and compared by the library: selftalk/postcsv.h (the CSVs'
 * columns and validated readers: a trials file's rows against the tests' trial tables, whose
 * posteval.* keys come from --config / --set; an individual or trial given twice refused),
 * selftalk/poststats.h (conditions, samples, comparisons: O(n log n)), selftalk/stats.h (the
 * numbers files, the tests). This file parses the arguments and prints. Errors name FILE:LINE
 * and what was expected; exit 2. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/poststats.h"

static const char *prog = "stats";

#define USAGE                                                                                   \
  "usage: stats mwu FILE_A FILE_B [--exact-max N] [--continuity C] [--verbose]\n"              \
  "       stats quartiles FILE\n"                                                              \
  "       stats table SUMMARY.csv [--test TEST] [--csv]\n"                                     \
  "       stats describe SUMMARY.csv [--test TEST]\n"                                          \
  "       stats selftalk TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set KEY=VALUE]\n"  \
  "       stats times TRIALS.csv [--test TEST] [--alpha A] [--config FILE] [--set KEY=VALUE]\n"

typedef struct opts {
  const char *pos[3];
  int npos;
  const char *test;
  int csv, verbose;
  double alpha;
  stMwuDef mwu;
  appConfigArgs config;
} opts;

/* a library call's failure: its message, exit 2 */
static void or_die(stStatus st, const char *err) {
  if (st) app_die(prog, "%s", err);
}

static double *numbers(const char *path, int *n) {
  double *x;
  char err[2048];
  or_die(st_numbers_read(path, &x, n, err, sizeof err), err);
  return x;
}

static void mwu_or_die(const opts *o, const double *a, int na, const double *b, int nb,
                       stMwuResult *r, const char *what) {
  char err[512];
  if (st_mwu(&o->mwu, a, na, b, nb, r, err, sizeof err)) app_die(prog, "%s: %s", what, err);
}

/* ---- mwu, quartiles: one number per line ---- */

static int cmd_mwu(const opts *o) {
  int na, nb;
  double *a = numbers(o->pos[1], &na), *b = numbers(o->pos[2], &nb);
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
  double *x = numbers(o->pos[1], &n);
  stQuartiles q;
  char err[512];
  if (st_quartiles(x, n, &q, err, sizeof err)) app_die(prog, "%s: %s", o->pos[1], err);
  printf("n=%d min=%.17g q1=%.17g median=%.17g q3=%.17g max=%.17g\n", q.n, q.min, q.q1, q.median,
         q.q3, q.max);
  free(x);
  return 0;
}

/* ---- the post-evaluation files ---- */

/* the test the rows are filtered to: --test, or the file's only one */
static const char *pick_test(const opts *o, const stCsvRows *rows) {
  stPostNames tests;
  char err[512];
  or_die(st_post_tests(rows, &tests, err, sizeof err), err);
  const char *test = st_post_pick_test(&tests, o->test);
  if (test) return test;
  char list[512] = "";
  for (int i = 0; i < tests.n; i++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", tests.name[i]);
  app_die(prog, "%s: %s (tests in the file: %s)", o->pos[1],
          o->test ? "no rows of this --test" : "several tests: choose one with --test", list);
}

/* the success percentages (and open_jumped) of each condition of the test */
static void summary_samples(const opts *o, stCsvRows *rows, stPostSamples *s) {
  char err[2048];
  or_die(st_post_read_summary(o->pos[1], rows, err, sizeof err), err);
  or_die(st_post_samples(rows, pick_test(o, rows), s, err, sizeof err), err);
}

static void samples_free(stCsvRows *rows, stPostSamples *s) {
  st_post_samples_free(s);
  st_csv_rows_free(rows);
}

static const char *stars(double p) { return p <= 0.01 ? "**" : p <= 0.05 ? "*" : ""; }

static void matrix(const opts *o, const stPostSamples *s, int want_p) {
  const stPostNames *c = &s->conds;
  printf("\n| %s |", want_p ? "p" : "U");
  for (int j = 0; j < c->n; j++) printf(" %s |", c->name[j]);
  printf("\n|---|");
  for (int j = 0; j < c->n; j++) printf("---|");
  for (int i = 0; i < c->n; i++) {
    printf("\n| %s |", c->name[i]);
    for (int j = 0; j < c->n; j++) {
      stMwuResult r;
      if (!st_post_compared(c, i, j)) {
        printf(" - |");
        continue;
      }
      mwu_or_die(o, s->pct[i], s->n[i], s->pct[j], s->n[j], &r, o->pos[1]);
      if (want_p) printf(" %.3g |", r.p);
      else printf(" %g%s |", r.u_b, stars(r.p));
    }
  }
  printf("\n");
}

static void pairs_csv(const opts *o, const stPostSamples *s) {
  const stPostNames *c = &s->conds;
  printf("test,row,column,n_row,n_column,U,p,method,stars\n");
  for (int i = 0; i < c->n; i++)
    for (int j = 0; j < c->n; j++) {
      stMwuResult r;
      if (!st_post_compared(c, i, j)) continue;
      mwu_or_die(o, s->pct[i], s->n[i], s->pct[j], s->n[j], &r, o->pos[1]);
      printf("%s,%s,%s,%d,%d,%.17g,%.17g,%s,%s\n", s->test, c->name[i], c->name[j], s->n[i],
             s->n[j], r.u_b, r.p, r.method == ST_MWU_EXACT ? "exact" : "normal", stars(r.p));
    }
}

static int cmd_table(const opts *o) {
  stCsvRows rows;
  stPostSamples s;
  summary_samples(o, &rows, &s);
  if (o->csv) {
    pairs_csv(o, &s);
    samples_free(&rows, &s);
    return 0;
  }
  printf("# %s: %s\n# two-tailed Mann-Whitney U of the individuals' success percentages; row's U: the pairs "
         "in which the row's value is the smaller, plus half the ties (the smaller, the more "
         "likely the row is better than the column); * p <= 0.05, ** p <= 0.01\n", o->pos[1], s.test);
  matrix(o, &s, 0);
  matrix(o, &s, 1);
  samples_free(&rows, &s);
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
  stCsvRows rows;
  stPostSamples s;
  summary_samples(o, &rows, &s);
  printf("# %s: %s\n\n| condition | quantity | n | median | lower quartile | upper quartile | min | max |\n"
         "|---|---|---|---|---|---|---|---|\n", o->pos[1], s.test);
  for (int k = 0; k < s.conds.n; k++) {
    describe_line(s.conds.name[k], "success %", s.pct[k], s.n[k]);
    describe_line(s.conds.name[k], "open jumped", s.jumped[k], s.n[k]);
  }
  samples_free(&rows, &s);
  return 0;
}

/* ---- trials: selftalk (Fig. 3.11), times (Table 3.3) ---- */

/* every individual of every NAME0 in the file against NAME (the tests' trial tables from the
 * configuration: --config, --set); cfg: the configuration */
static stPostComparisons compare_all(const opts *o, stConfig *cfg, stCsvRows *rows) {
  app_config_resolve(&o->config, cfg, prog);
  stPostDef defs[ST_POST_NTESTS];
  for (int t = 0; t < ST_POST_NTESTS; t++) st_post_def_from_config(cfg, (stPostTest)t, &defs[t]);
  char err[2048];
  or_die(st_post_read_trials(o->pos[1], defs, rows, err, sizeof err), err);
  stPostComparisons cs;
  or_die(st_post_compare(rows, o->pos[1], pick_test(o, rows), &o->mwu, o->alpha, &cs, err,
                         sizeof err), err);
  return cs;
}

/* mean seconds to the target over the successes; empty when there are none */
static void seconds(char *buf, size_t n, double steps, int succ, double dt) {
  if (succ) snprintf(buf, n, "%.17g", steps / succ * dt);
  else buf[0] = 0;
}

static int cmd_selftalk(const opts *o) {
  stCsvRows rows;
  stConfig cfg;
  stPostComparisons cs = compare_all(o, &cfg, &rows);
  const double dt = cfg.robot_control_dt;
  printf("condition,caretaker_condition,run,individual,excluded,selftalk_pct,caretaker_pct,U,p,"
         "method,better,selftalk_seconds,caretaker_seconds\n");
  for (int i = 0; i < cs.n; i++) {
    const stPostComparison *c = &cs.c[i];
    char s0[40], s1[40];
    seconds(s0, sizeof s0, c->steps[0], c->successes[0], dt);
    seconds(s1, sizeof s1, c->steps[1], c->successes[1], dt);
    printf("%s,%s,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%s,%s,%s,%s\n", c->condition, c->variant,
           c->run, c->individual, c->excluded,
           c->trials[0] ? 100.0 * c->successes[0] / c->trials[0] : 0.0,
           c->trials[1] ? 100.0 * c->successes[1] / c->trials[1] : 0.0, c->mwu.u, c->mwu.p,
           c->mwu.method == ST_MWU_EXACT ? "exact" : "normal", c->better, s0, s1);
  }
  st_post_comparisons_free(&cs);
  st_csv_rows_free(&rows);
  return 0;
}

/* Table 3.3's two rows over the n individuals better with self talk */
static void times_rows(const stPostComparisons *cs, int n, double dt) {
  printf("\n|---|");
  for (int i = 0; i < n; i++) printf("---|");
  for (int k = 0; k < 2; k++) {
    printf("\n| %s |", k ? "Caretaker" : "Self talk");
    for (int i = 0; i < cs->n; i++) {
      const stPostComparison *c = &cs->c[i];
      if (strcmp(c->better, "selftalk")) continue;
      if (c->successes[k]) printf(" %.2f |", c->steps[k] / c->successes[k] * dt);
      else printf(" - |");
    }
  }
  printf("\n");
}

static int cmd_times(const opts *o) {
  stCsvRows rows;
  stConfig cfg;
  stPostComparisons cs = compare_all(o, &cfg, &rows);
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
      if (!strcmp(cs.c[i].better, "selftalk"))
        printf(" %s run %d |", cs.c[i].condition, cs.c[i].run);
    times_rows(&cs, n, dt);
  }
  st_post_comparisons_free(&cs);
  st_csv_rows_free(&rows);
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
