/* SPDX-License-Identifier: MIT
 * Fuzz target: ./apps/score prediction's reader (apps/score.c, included with its main renamed:
 * the app's own code). Property: every trial of a table it accepts has outputs within
 * +-ST_PRED_OUTPUT_MAX, and a trial the prediction scores has finite F_step, F_switch, B_pred. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>

#include "app_common.h"
#include "app_shim.h"
#define main score_app_main
#include "../../apps/score.c"
#undef main

static table g_t;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  g_input = (const char *)data, g_input_len = size;
  memset(&g_t, 0, sizeof g_t);
  if (setjmp(g_die)) { /* refused */
    shim_free_all();
    return 0;
  }
  read_table("fuzz.csv", &g_t);
  const stPredDef def = st_pred_default_def();
  for (int i = 0; i < g_t.ntrials; i++) {
    for (int k = 0; k < g_t.len[i]; k++)
      for (int m = 0; m < ST_PRED_NWORDS; m++)
        if (!(fabs(g_t.o[g_t.start[i] + k][m]) <= ST_PRED_OUTPUT_MAX)) abort();
    const stPredTrial tr = {g_t.len[i], g_t.word + g_t.start[i],
                            (const double(*)[ST_PRED_NWORDS])(g_t.o + g_t.start[i])};
    stPredScore s;
    char err[256];
    if (st_pred_trial(&def, &tr, &s, err, sizeof err)) continue;
    if (!isfinite(s.f_step) || !isfinite(s.f_switch) || !isfinite(s.b_pred)) abort();
  }
  free(g_t.word), free(g_t.o), free(g_t.start), free(g_t.len);
  if (shim_live()) abort(); /* the reader left something allocated */
  return 0;
}
