/* SPDX-License-Identifier: MIT */
#include "selftalk/caretaker.h"

#include <string.h>

#include "core/internal.h"

void st_caretaker_init(stCaretaker *c, const stConfig *cfg) {
  ST_ASSERT(c && cfg);
  memset(c, 0, sizeof *c);
  c->label = -1;
  c->first_step = cfg->caretaker_first_step;
  c->grasp_touches = cfg->caretaker_grasp_touches;
  for (int p = 0; p < ST_NPRIM; p++) c->switch_step[p] = -1;
}

int st_caretaker_done(const stCaretaker *c, const stFitnessDef *d, int p, const stQuantities *q,
                      const stContacts *k) {
  ST_ASSERT(c && d && q && k);
  switch (p) {
    case ST_PRIM_REACH:
    case ST_PRIM_OPEN: return st_success_now(d, ST_STAGE_MAIN, p, q);
    case ST_PRIM_GRASP: {
      /* the main-prim grasp condition needs the table removed; here: enough touches */
      int n = 0;
      for (int i = 0; i < ST_NTOUCH; i++) n += k->touch_object[i];
      return n >= c->grasp_touches;
    }
    default: return 0; /* move is the last word */
  }
}

int st_caretaker_word(stCaretaker *c, const stFitnessDef *d, int step, const stQuantities *q,
                      const stContacts *k) {
  ST_ASSERT(c && d && q && k);
  ST_ASSERT(step >= 0);
  if (step < c->first_step) return -1;
  if (c->label < 0) c->label = ST_PRIM_REACH;
  /* switch on success; a word already satisfied when first due is jumped */
  while (c->label < ST_PRIM_MOVE && st_caretaker_done(c, d, c->label, q, k)) c->label++;
  if (c->switch_step[c->label] < 0) c->switch_step[c->label] = step;
  c->given[c->label]++;
  return c->label;
}
