/* SPDX-License-Identifier: MIT
 * Fuzz target: the post-evaluation journal's reader (st__post_journal_parse,
 * lib/posteval/journal.h: what posteval --resume reads) for 80 units of trials of 60 steps and
 * fingerprint 00000000000000ab (the seed, tests/fuzz/seeds/journal/, is such a journal).
 * Property: every accepted line is one a trial gives: success exactly with end success and
 * its step the last one run, at most the trial's steps, not unstable with end full,
 * open_jumped by the scorer's rule; *ndone the units marked done. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "posteval/journal.h"

#define UNITS 80
#define STEPS 60

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static uint8_t done[UNITS];
  static stPostResult res[UNITS];
  long ndone;
  char err[1024];
  if (st__post_journal_parse("fuzz.journal", (const char *)data, size, 0xab, UNITS, STEPS, done,
                             res, &ndone, err, sizeof err))
    return 0;
  long n = 0;
  for (int u = 0; u < UNITS; u++) {
    if (!done[u]) continue;
    n++;
    const stPostResult *r = &res[u];
    if (r->success != (r->end == ST_END_SUCCESS) || r->success != (r->reached_step >= 0)) abort();
    if (r->success && r->reached_step != r->steps_run - 1) abort();
    if (r->steps_run < 1 || r->steps_run > STEPS) abort();
    if (r->end == ST_END_FULL && (r->steps_run != STEPS || r->unstable)) abort();
    if (r->end == ST_END_QUIET || r->open_jumped != st__post_open_jumped(r->heard)) abort();
  }
  if (n != ndone) abort();
  return 0;
}
