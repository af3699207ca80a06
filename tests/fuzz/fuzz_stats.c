/* SPDX-License-Identifier: MIT
 * Fuzz target: ./apps/stats's readers, the library's (selftalk/csv.h, selftalk/postcsv.h,
 * selftalk/stats.h: the in-memory entry points of lib/core/readers.h, which the file readers
 * call). The first byte picks the reader: one number per line (mwu, quartiles), a summary.csv
 * (table, describe) or a trials.csv (selftalk, times), the rest is the file. Properties: the
 * quartiles of accepted numbers are finite and ordered; accepted rows are unique by key and
 * sorted; a summary's samples hold its test's rows; a trials file's individuals partition its
 * rows, each found again by binary search, and its comparisons (when it has a NAME0) have p in
 * (0, 1]. Leaks fail as crashes (libFuzzer's leak check). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/readers.h"
#include "selftalk/poststats.h"

static stPostDef g_def[ST_POST_NTESTS];

static void check_order(const stCsvRows *rs) {
  for (int i = 1; i < rs->n; i++)
    if (st_csv_compare(rs->schema, rs->schema->nkey, st_csv_sorted(rs, i - 1), st_csv_sorted(rs, i)) >= 0)
      abort();
}

static void numbers(const char *text, size_t len) {
  double *x;
  int n;
  if (st__numbers_parse("fuzz.txt", text, len, &x, &n, NULL, 0)) return;
  stQuartiles q;
  if (n < 1 || st_quartiles(x, n, &q, NULL, 0)) abort();
  if (!(isfinite(q.q1) && isfinite(q.median) && isfinite(q.q3)) || !(q.min <= q.q1) ||
      !(q.q1 <= q.median) || !(q.median <= q.q3) || !(q.q3 <= q.max))
    abort();
  free(x);
}

/* the test the app would pick without --test, or the first */
static const char *some_test(const stCsvRows *rs) {
  stPostNames tests;
  if (st_post_tests(rs, &tests, NULL, 0)) return NULL;
  const char *t = st_post_pick_test(&tests, NULL);
  return t ? t : tests.n ? tests.name[0] : NULL;
}

static void summary(const char *text, size_t len) {
  stCsvRows rs;
  if (st__csv_parse("fuzz.csv", text, len, st_post_summary_schema(), NULL, &rs, NULL, 0)) return;
  check_order(&rs);
  const char *test = some_test(&rs);
  stPostSamples s;
  if (test && !st_post_samples(&rs, test, &s, NULL, 0)) {
    int n = 0, want = 0;
    for (int k = 0; k < s.conds.n; k++) n += s.n[k];
    for (int i = 0; i < rs.n; i++) want += !strcmp(((const stPostSummaryRow *)st_csv_row(&rs, i))->test, test);
    if (n != want) abort();
    st_post_samples_free(&s);
  }
  st_csv_rows_free(&rs);
}

static void trials(const char *text, size_t len) {
  stCsvRows rs;
  if (st__csv_parse("fuzz.csv", text, len, st_post_trials_schema(), g_def, &rs, NULL, 0)) return;
  check_order(&rs);
  stCsvGroup *g;
  int ng, covered = 0;
  if (st_csv_groups(&rs, ST_POST_INDIVIDUAL_KEY, &g, &ng, NULL, 0)) abort();
  for (int i = 0; i < ng; i++) {
    covered += g[i].end - g[i].start;
    if (st_csv_group_find(&rs, ST_POST_INDIVIDUAL_KEY, g, ng, st_csv_sorted(&rs, g[i].start)) != &g[i])
      abort();
  }
  if (covered != rs.n) abort();
  free(g);
  const char *test = some_test(&rs);
  stPostComparisons cs;
  const stMwuDef def = st_mwu_default_def();
  if (test && !st_post_compare(&rs, "fuzz.csv", test, &def, 0.01, &cs, NULL, 0)) {
    for (int i = 0; i < cs.n; i++)
      if (!(cs.c[i].mwu.p > 0.0 && cs.c[i].mwu.p <= 1.0)) abort();
    st_post_comparisons_free(&cs);
  }
  st_csv_rows_free(&rs);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (!size) return 0;
  static int init;
  if (!init) { /* the tests' trial tables of the default keys, as stats without --config */
    stConfig cfg;
    st_config_default(&cfg);
    for (int t = 0; t < ST_POST_NTESTS; t++) st_post_def_from_config(&cfg, (stPostTest)t, &g_def[t]);
    init = 1;
  }
  const char *text = (const char *)data + 1;
  switch (data[0] % 3) {
    case 0: numbers(text, size - 1); break;
    case 1: summary(text, size - 1); break;
    default: trials(text, size - 1);
  }
  return 0;
}
