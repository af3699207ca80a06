/* SPDX-License-Identifier: MIT
 * libselftalk: the caretaker of thesis §2.9.3 - gives the words reach, open, grasp, move in
 * sequence, switching to the next as soon as the main-prim success condition of the current
 * primitive holds (grasp: enough touch sensors on the object), and jumping a word whose
 * condition already holds when it would first be given. Silent at the first step. A plain
 * value per trial; no allocation. */
#ifndef SELFTALK_CARETAKER_H
#define SELFTALK_CARETAKER_H

#include "selftalk/fitness.h"
#include "selftalk/world.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stCaretaker {
  int label;                   /* word being given, -1 before the first */
  int first_step;              /* caretaker.first_step (1) */
  int grasp_touches;           /* caretaker.grasp_touches (3) */
  int given[ST_NPRIM];         /* steps each word was given */
  int switch_step[ST_NPRIM];   /* step a word was first given, -1 if never (jumped) */
} stCaretaker;

ST_API void st_caretaker_init(stCaretaker *c, const stConfig *cfg);

/* 1 when the caretaker's condition for leaving `primitive` holds in this state. */
ST_API int st_caretaker_done(const stCaretaker *c, const stFitnessDef *def, int primitive,
                      const stQuantities *q, const stContacts *contacts);

/* The word to give at control step `step` (sensing the state q / contacts before acting):
 * ST_PRIM_* or -1 for none. Call once per step, in order. */
ST_API int st_caretaker_word(stCaretaker *c, const stFitnessDef *def, int step, const stQuantities *q,
                      const stContacts *contacts);

#ifdef __cplusplus
}
#endif

#endif
