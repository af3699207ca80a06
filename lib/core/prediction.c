/* SPDX-License-Identifier: MIT
 * The prediction fitness, eq. 2.15-2.24 as SPEC §10 reads it (selftalk/prediction.h). */
#include "selftalk/prediction.h"

#include <math.h>
#include <string.h>

#include "core/internal.h"

stPredDef st_pred_default_def(void) {
  stPredDef d = {20, 5, 10.0, 100.0};
  return d;
}

void st_pred_def_from_config(const stConfig *c, stPredDef *d) {
  ST_ASSERT(c && d);
  d->window = c->prediction_window;
  d->bonus_window = c->prediction_bonus_window;
  d->bonus = c->fitness_bonus;
  d->scale = c->fitness_scale;
}

/* argmax (ties: lowest index), h1 and h2 of one step's outputs */
static int top_two(const double o[ST_PRED_NWORDS], double *h1, double *h2) {
  int best = 0;
  for (int p = 1; p < ST_PRED_NWORDS; p++)
    if (o[p] > o[best]) best = p;
  double second = -INFINITY;
  for (int p = 0; p < ST_PRED_NWORDS; p++)
    if (p != best && o[p] > second) second = o[p];
  *h1 = o[best];
  *h2 = second;
  return best;
}

static int argmax(const double o[ST_PRED_NWORDS]) {
  double h1, h2;
  return top_two(o, &h1, &h2);
}

double st_pred_d1(const double o[ST_PRED_NWORDS], int p) {
  ST_ASSERT(o);
  ST_ASSERT(p >= 0 && p < ST_PRED_NWORDS);
  double h1, h2;
  top_two(o, &h1, &h2);
  return 1.0 - (h1 - o[p]);
}

/* eq. 2.15: the prediction at t of the word heard at t + 1 */
static double f_step(const double o[ST_PRED_NWORDS], int pc) {
  double h1, h2;
  if (top_two(o, &h1, &h2) == pc) return 0.75 + fmin(0.25, o[pc] - h2);
  return 0.25 * st_pred_d1(o, pc);
}

/* eq. 2.17: the first word, predicted at step 0 */
static double first_word(const stPredTrial *t, int p1, stPredScore *s, const stPredDef *d) {
  const int c0 = argmax(t->o[0]) == p1;
  s->b_pred += c0 ? d->bonus : 0.0;
  return c0 ? 1.0 : 0.5 * st_pred_d1(t->o[0], p1);
}

/* the step just before the word first changes to p (from step 1 on), -1 if it never does */
static int switch_step(const stPredTrial *t, int p) {
  for (int k = 1; k + 1 < t->n; k++)
    if (t->word[k] != p && t->word[k + 1] == p) return k;
  return -1;
}

/* eq. 2.18-2.21 for a word the caretaker switches to after the step before ts */
static double switch_word(const stPredTrial *t, int p, int ts, stPredScore *s,
                          const stPredDef *d) {
  const double d1 = st_pred_d1(t->o[ts], p);
  const double before = st_pred_d1(t->o[ts - d->window > 0 ? ts - d->window : 0], p);
  /* the sign that rewards the upcoming word getting closer to the top (SPEC §10) */
  const double fi = 1.0 / (1.0 + exp(-(d1 - before)));
  const int c = argmax(t->o[ts]) == p;
  int tpr = ts;
  while (c && tpr > 0 && argmax(t->o[tpr - 1]) == p) tpr--;
  const double fii = c ? 1.0 : d1;
  const double fiii = c ? fmax(0.0, 1.0 - (double)(ts - tpr) / d->window) : 0.0;
  s->t_pr[p] = c ? tpr : -1;
  s->b_pred += c && ts - tpr < d->bonus_window ? d->bonus : 0.0;
  return 0.5 * fi + 0.1 * fii + 0.4 * fiii;
}

static stStatus check_trial(const stPredTrial *t, char *err, size_t errsz) {
  if (t->n < 2)
    return st__errf(err, errsz, "prediction: a trial of %d steps (expected at least 2)", t->n),
           ST_ERR_ARG;
  for (int k = 0; k < t->n; k++) {
    if (t->word[k] < -1 || t->word[k] >= ST_PRED_NWORDS)
      return st__errf(err, errsz, "prediction: step %d: word %d (expected -1..3)", k,
                      t->word[k]), ST_ERR_ARG;
    if (k > 0 && t->word[k] < 0)
      return st__errf(err, errsz, "prediction: step %d: no word (expected the caretaker to "
                      "speak at every step after the first)", k), ST_ERR_ARG;
    if (k > 0 && t->word[k] < t->word[k - 1])
      return st__errf(err, errsz, "prediction: step %d: word %d after %d (expected the "
                      "caretaker's words in order, never back)", k, t->word[k], t->word[k - 1]),
             ST_ERR_ARG;
    for (int p = 0; p < ST_PRED_NWORDS; p++)
      if (!(fabs(t->o[k][p]) <= ST_PRED_OUTPUT_MAX))
        return st__errf(err, errsz, "prediction: step %d: output %d is %g (expected a finite "
                        "number within +-%g)", k, p, t->o[k][p], ST_PRED_OUTPUT_MAX), ST_ERR_ARG;
  }
  return ST_OK;
}

stStatus st_pred_trial(const stPredDef *d, const stPredTrial *t, stPredScore *s, char *err,
                       size_t errsz) {
  ST_ASSERT(d && t && s);
  memset(s, 0, sizeof *s);
  for (int p = 0; p < ST_PRED_NWORDS; p++) s->t_s[p] = s->t_pr[p] = -1;
  stStatus st = check_trial(t, err, errsz);
  if (st) return st;
  /* step prediction (eq. 2.15-2.16) */
  double sum = 0.0;
  for (int k = 0; k + 1 < t->n; k++) {
    sum += f_step(t->o[k], t->word[k + 1]);
    s->correct += argmax(t->o[k]) == t->word[k + 1];
  }
  s->f_step = d->scale / (double)(t->n - 1) * sum;
  /* switch prediction (eq. 2.17-2.22) and its bonus (eq. 2.23) */
  const int p1 = t->word[1];
  double total = 0.0;
  for (int p = 0; p < ST_PRED_NWORDS; p++) {
    const int ts = p == p1 ? -1 : switch_step(t, p);
    s->t_s[p] = ts;
    if (p == p1) s->fsw[p] = first_word(t, p1, s, d);
    else if (ts >= 0) s->fsw[p] = switch_word(t, p, ts, s, d);
    else s->fsw[p] = 1.0, s->b_pred += d->bonus; /* jumped (or never given) */
    total += s->fsw[p];
  }
  s->f_switch = d->scale / ST_PRED_NWORDS * total;
  return ST_OK;
}

double st_pred_fitness(const stPredScore *s, const int *counts, int n, double *b_sum) {
  ST_ASSERT(n >= 0 && (n == 0 || (s && counts)));
  double b = 0.0, parts = 0.0;
  for (int i = 0; i < n; i++) {
    if (!counts[i]) continue;
    b += s[i].b_pred;
    parts += s[i].f_step / 3.0 + 2.0 * s[i].f_switch / 3.0;
  }
  if (b_sum) *b_sum = b;
  return n > 0 ? b + parts / (double)n : 0.0;
}
