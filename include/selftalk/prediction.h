/* SPDX-License-Identifier: MIT
 * libselftalk: the prediction fitness of the integrated stage (thesis §2.9.4.2, eq. 2.15-2.24,
 * as SPEC §10 reads it). A pure function of the caretaker's words and the four linguistic
 * outputs of each step: no simulator, no allocation (part of libselftalk-core).
 *
 * A caretaker trial has steps t = 0..N-1, the word w(t) heard at t (-1 at t = 0: the
 * caretaker is silent) and the outputs o(p, t), p = reach, open, grasp, move. The prediction
 * made at t is the argmax at t (ties: lowest index), judged against the next word:
 * c(t) = [argmax(t) = w(t + 1)], t = 0..N-2. Per trial:
 *   F_step   = 100 / (N - 1) sum_t f_step(t)                                  (eq. 2.15-2.16)
 *   F_switch = 25 sum_p f_switch(p): the first word by eq. 2.17, every later word the
 *              caretaker switches to by eq. 2.18-2.21, a word never switched to 1 (jumped)
 *   B_pred   = bonus (c(0) + later words switched to in time + words jumped)       (eq. 2.23)
 * and over the T caretaker trials, those whose object never reached the target lifted
 * counting 0 (eq. 2.24):
 *   F_pred = sum B_pred + (1 / T) sum (F_step / 3 + 2 F_switch / 3). */
#ifndef SELFTALK_PREDICTION_H
#define SELFTALK_PREDICTION_H

#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/study.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PRED_NWORDS ST_NPRIM /* the words: one a primitive */

/* The largest |output| a trial may have: the network's linguistic outputs are sigmoids in
 * [0, 1] (emitted with a gain of at most 1000), and below this every difference and sum of
 * eq. 2.15-2.24 stays finite (finite values near the largest double gave -inf). */
#define ST_PRED_OUTPUT_MAX 1e6

/* The protocol numbers of eq. 2.15-2.24 (keys prediction.* and fitness.bonus / scale). */
typedef struct stPredDef {
  int window;       /* eq. 2.18, 2.20: steps looked back before a switch; 20 */
  int bonus_window; /* eq. 2.23: a switch predicted fewer than this many steps early; 5 */
  double bonus;     /* eq. 2.23: per correct first word, switch or jumped word; 10 */
  double scale;     /* F_step and F_switch range 0..scale; 100 */
} stPredDef;

/* The thesis's values. */
ST_API stPredDef st_pred_default_def(void);
ST_API void st_pred_def_from_config(const stConfig *cfg, stPredDef *def);

/* One caretaker trial. */
typedef struct stPredTrial {
  int n;                               /* steps, >= 2 */
  const int *word;                     /* w(t), n values: -1 none, else 0..3 */
  const double (*o)[ST_PRED_NWORDS];   /* o(p, t), n rows */
} stPredTrial;

/* How a trial scored. */
typedef struct stPredScore {
  double f_step;                    /* F_step, 0..scale */
  double f_switch;                  /* F_switch, 0..scale */
  double b_pred;                    /* B_pred */
  double fsw[ST_PRED_NWORDS];       /* f_switch of each word's slot (reach: the first word) */
  int t_s[ST_PRED_NWORDS];          /* t_s(p) of a word switched to; -1 */
  int t_pr[ST_PRED_NWORDS];         /* t_pr(p) when c(t_s(p)); -1 */
  int correct;                      /* steps with c(t) */
} stPredScore;

/* Scores one trial. ST_ERR_ARG (naming the step) for n < 2, a word outside -1..3, no word
 * at a step t >= 1 (every step after the first must hear one: caretaker.first_step = 1), a
 * word before the previous one (the caretaker never goes back), or an output that is not
 * finite or beyond +-ST_PRED_OUTPUT_MAX. */
ST_API stStatus st_pred_trial(const stPredDef *def, const stPredTrial *t, stPredScore *s, char *err,
                       size_t errsz);

/* d1(p, t) = 1 - (h1(t) - o(p, t)) for one step's outputs (eq. 2.15). */
ST_API double st_pred_d1(const double o[ST_PRED_NWORDS], int p);

/* F_pred over ntrials caretaker trials (eq. 2.24): counts[i] = 0 for a trial whose object
 * never reached the target lifted (it adds nothing but still counts in T = ntrials). Writes
 * the summed B_pred (nullable). 0 when ntrials is 0. */
ST_API double st_pred_fitness(const stPredScore *s, const int *counts, int ntrials, double *b_sum);

#ifdef __cplusplus
}
#endif

#endif
