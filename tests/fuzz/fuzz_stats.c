/* SPDX-License-Identifier: MIT
 * Fuzz target: ./apps/stats's readers (apps/stats.c, included with its main renamed: the app's
 * own code). The first byte picks the reader: one number per line (mwu, quartiles), a
 * summary.csv (table, describe) or a trials.csv (selftalk, times), the rest is the file.
 * Properties: the quartiles of accepted numbers are finite and ordered; accepted rows are
 * unique by key and sorted; a trials file's individuals partition its rows, each found again
 * by binary search; the app frees what it allocated. */
#define _POSIX_C_SOURCE 200809L
#include "app_common.h"
#include "app_shim.h"
#define main stats_app_main
#include "../../apps/stats.c"
#undef main

static rows g_rs;

static void check_order(const rows *rs, rowKey key) {
  for (int i = 1; i < rs->n; i++)
    if (key(rs->data + rs->size * (size_t)rs->ord[i - 1], rs->data + rs->size * (size_t)rs->ord[i]) >= 0)
      abort();
}

static void numbers(void) {
  int n;
  double *x = read_numbers("fuzz.txt", &n);
  stQuartiles q;
  if (st_quartiles(x, n, &q, NULL, 0)) abort();
  if (!(isfinite(q.q1) && isfinite(q.median) && isfinite(q.q3)) || !(q.min <= q.q1) ||
      !(q.q1 <= q.median) || !(q.median <= q.q3) || !(q.q3 <= q.max))
    abort();
  free(x);
}

static void summary(void) {
  load_csv("fuzz.csv", SUM_COLS, NCOLS(SUM_COLS), sizeof(sumRow), check_sum, sum_key, sum_name, &g_rs);
  check_order(&g_rs, sum_key);
  rows_free(&g_rs);
}

static void trials(void) {
  load_csv("fuzz.csv", TRIAL_COLS, NCOLS(TRIAL_COLS), sizeof(trialRow), check_trial, trial_key,
           trial_name, &g_rs);
  check_order(&g_rs, trial_key);
  int ng, covered = 0;
  group *g = groups_of(&g_rs, &ng);
  for (int i = 0; i < ng; i++) {
    covered += g[i].end - g[i].start;
    if (find_group(&g_rs, g, ng, TROW(&g_rs, &g[i], 0)) != &g[i]) abort();
  }
  if (covered != g_rs.n) abort();
  free(g);
  rows_free(&g_rs);
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
  g_input = (const char *)data + 1, g_input_len = size - 1;
  memset(&g_rs, 0, sizeof g_rs);
  if (setjmp(g_die)) { /* refused */
    shim_free_all();
    return 0;
  }
  switch (data[0] % 3) {
    case 0: numbers(); break;
    case 1: summary(); break;
    default: trials();
  }
  if (shim_live()) abort(); /* the reader left something allocated */
  return 0;
}
