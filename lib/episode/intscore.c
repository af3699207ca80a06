/* SPDX-License-Identifier: MIT
 * The integrated stage's scoring: the condition table, eq. 2.14 with its penalties and
 * bonuses, and an individual's fitness over its trials (selftalk/integrated.h). Pure functions
 * of per-step quantities and trial results: no simulator. */
#include <math.h>
#include <string.h>

#include "selftalk/integrated.h"
#include "core/internal.h"

const char *st_int_fitness_name(stIntFitness f) {
  return f == ST_FIT_INTEGRATED ? "integrated" : f == ST_FIT_PREDICTION ? "prediction" : "?";
}

/* integrated.words_* choices (none|caretaker|selftalk) as word sources */
static stWordSource source_of(int choice) {
  static const stWordSource map[] = {ST_WORDS_NONE, ST_WORDS_CARETAKER, ST_WORDS_SELFTALK};
  return choice >= 0 && choice < 3 ? map[choice] : ST_WORDS_NONE;
}

void st_integrated_def_from_config(const stConfig *c, stIntegratedDef *d) {
  ST_ASSERT(c && d);
  memset(d, 0, sizeof *d);
  d->arch = (stNetArch)c->network_arch;
  d->words[0] = source_of(c->integrated_words_even);
  d->words[1] = source_of(c->integrated_words_odd);
  d->fitness[0] = c->integrated_fitness_even == ST_CFG_FIT_PREDICTION ? ST_FIT_PREDICTION : ST_FIT_INTEGRATED;
  d->fitness[1] = c->integrated_fitness_odd == ST_CFG_FIT_PREDICTION ? ST_FIT_PREDICTION : ST_FIT_INTEGRATED;
  d->first_variant = c->integrated_first_generation;
  d->first_bonus_factor = c->integrated_first_bonus_factor;
  d->trials = c->integrated_trials;
  d->steps = c->integrated_steps;
  d->hold_steps = c->integrated_hold_steps;
  d->focus_bonus_steps = c->integrated_focus_bonus_steps;
  d->fail_end = c->integrated_fail_end;
  st_pred_def_from_config(c, &d->pred);
}

void st_chain_def_from_config(const stConfig *c, stIntegratedDef *d) {
  ST_ASSERT(c && d);
  st_integrated_def_from_config(c, d);
  d->arch = ST_ARCH_BASE;
  d->words[0] = d->words[1] = ST_WORDS_CARETAKER;
  d->fitness[0] = d->fitness[1] = ST_FIT_INTEGRATED;
  d->first_variant = 0;
  d->first_bonus_factor = 1.0;
  d->trials = c->stage_chain_trials;
}

stIntPlan st_integrated_plan(const stIntegratedDef *d, int generation, int trial) {
  ST_ASSERT(d);
  ST_ASSERT(generation >= 0 && trial >= 0);
  /* the first generation's variant (thesis 2.9.4.1): the caretaker in every trial, every trial
   * scored by the integrated fitness with its bonuses multiplied */
  const int first = d->first_variant && generation == 0;
  stIntPlan p;
  p.words = first ? ST_WORDS_CARETAKER : d->words[trial % 2];
  p.fitness = first ? ST_FIT_INTEGRATED : d->fitness[trial % 2];
  p.bonus_factor = first ? d->first_bonus_factor : 1.0;
  p.autonomous = p.words != ST_WORDS_CARETAKER;
  return p;
}

/* ---- eq. 2.14 ---- */

double st_int_s(const stFitnessDef *d, const stQuantities *q, int opened) {
  ST_ASSERT(d && q);
  const double sm = st_step_s(d, ST_STAGE_MAIN, ST_PRIM_MOVE, q); /* eq. 2.12 */
  double stage;
  if (q->lifted) stage = 2.0;
  else if (opened) stage = 1.0 + st_step_s(d, ST_STAGE_MAIN, ST_PRIM_GRASP, q); /* eq. 2.11 */
  else stage = st_step_s(d, ST_STAGE_MAIN, ST_PRIM_OPEN, q);                    /* eq. 2.10 */
  return 0.5 * sm + 0.25 * stage;
}

double st_int_step_fitness(const stFitnessDef *d, const stQuantities *q, int opened,
                           double y_focus, double threshold) {
  ST_ASSERT(d && q);
  const int right_target = q->lifted; /* the target while lifted, the object otherwise */
  const double ff = right_target ? y_focus : 1.0 - y_focus;
  const int correct = (y_focus >= threshold) == right_target;
  return d->focus_weight * ff + (correct ? (1.0 - d->focus_weight) * st_int_s(d, q, opened) : 0.0);
}

double st_int_penalty(const stQuantities *q, double pen_table, double pen_moving) {
  ST_ASSERT(q);
  return pen_table + (q->lifted ? 0.0 : pen_moving);
}

/* ---- one trial ---- */

void st_int_score_begin(stIntScore *sc, const stFitnessDef *fd, double focus_threshold,
                        const stIntegratedDef *def) {
  ST_ASSERT(sc && fd);
  memset(sc, 0, sizeof *sc);
  sc->fd = fd;
  sc->focus_threshold = focus_threshold;
  sc->steps = def->steps;
  sc->hold_steps = def->hold_steps;
  sc->focus_bonus_steps = def->focus_bonus_steps;
  sc->fail_end = def->fail_end;
  sc->keep = ST_INT_KEEP_POINTS;
  sc->fill_p = fd->fail_penalty;
  sc->r.reached_step = -1;
  sc->r.furthest_word = -1;
}

/* the bookkeeping of one step: opened, in the target, the focus bonus */
static void track(stIntScore *sc, int step, const stQuantities *q, double y_focus) {
  stIntTrialResult *r = &sc->r;
  r->opened |= st_success_now(sc->fd, ST_STAGE_MAIN, ST_PRIM_OPEN, q);
  sc->lifted = q->lifted;
  const int in_target = q->d_m < sc->fd->target_radius;
  sc->was_in_target |= in_target;
  if (in_target && q->lifted && r->reached_step < 0) r->reached_step = step;
  sc->focus_run = q->lifted && y_focus >= sc->focus_threshold ? sc->focus_run + 1 : 0;
  if (sc->focus_run >= sc->focus_bonus_steps) r->focus_bonus = 1;
}

int st_int_score_step(stIntScore *sc, int step, const stQuantities *q, double y_focus,
                      double pen_table, double pen_moving, int fell, int unstable, double *S_out,
                      double *P_out) {
  ST_ASSERT(sc && q); /* S_out, P_out nullable */
  stIntTrialResult *r = &sc->r;
  track(sc, step, q, y_focus);
  const double S = st_int_step_fitness(sc->fd, q, r->opened, y_focus, sc->focus_threshold);
  const double P = st_int_penalty(q, pen_table, pen_moving);
  r->sum_s += S;
  r->sum_p += P;
  r->steps_run++;
  if (S_out) *S_out = S;
  if (P_out) *P_out = P;
  int event = -1;
  /* a diverged world is frozen (st_world_unstable): it has no rest to run out, so every mode
   * ends it by the penalty rule; a fall ends the trial only by that rule */
  if (unstable || (fell && sc->fail_end == ST_FAIL_END_PENALTY)) {
    r->unstable = unstable;
    event = ST_END_FAILURE;
  } else if (r->reached_step >= 0 && step - r->reached_step > sc->hold_steps && q->lifted) {
    event = ST_END_SUCCESS; /* moved to the target "more than 20 steps ago" and still held */
  }
  if (event >= 0) r->end = (stTrialEnd)event;
  return event;
}

int st_int_score_settle(stIntScore *sc, int out_of_reach, double pen_moving_floor,
                        int words_fixed) {
  ST_ASSERT(sc && pen_moving_floor >= 0.0);
  stIntTrialResult *r = &sc->r;
  const long rem = sc->steps - r->steps_run;
  if (sc->fail_end != ST_FAIL_END_EXACT || !out_of_reach || rem <= 0) return -1;
  if ((sc->keep & ST_INT_KEEP_RECORD) && r->reached_step >= 0) return -1;
  if ((sc->keep & ST_INT_KEEP_WORDS) && !words_fixed) return -1;
  if (sc->keep & ST_INT_KEEP_POINTS) {
    /* never touched again, S = w f_f + (correct ? (1 - w) s_i : 0) with f_f = 1 - y <= 1 and
     * s_i = s_m / 2 + stage / 4 <= 0 + 2 / 4 (s_m: no touch, no lift; s_o, s_g <= 1), and P >=
     * the moving penalty's floor (the table's >= 0); should the world diverge at a later step,
     * the rest pays fail_penalty. The sum over the rest is linear in the step it diverges at,
     * so both ends bound it. The margin is far above the rounding of the two sums (< N^2 x 200
     * x 2^-52 for N <= 1e5 steps). */
    const double w = sc->fd->focus_weight, smax = w + 0.5 * (1.0 - w);
    const double cur = r->sum_s - r->sum_p, margin = 1e-6 * (double)sc->steps;
    if (!(cur + (double)rem * (smax - pen_moving_floor) <= -margin &&
          cur - (double)rem * sc->fd->fail_penalty <= -margin))
      return -1;
  }
  r->end = ST_END_FAILURE;
  sc->fill_p = pen_moving_floor; /* what every remaining step is certain to pay */
  return ST_END_FAILURE;
}

void st_int_score_end(stIntScore *sc, stIntTrialResult *out) {
  ST_ASSERT(sc && out);
  stIntTrialResult *r = &sc->r;
  const long remaining = sc->steps - r->steps_run;
  if (r->end == ST_END_SUCCESS) r->sum_s += (double)remaining;
  if (r->end == ST_END_FAILURE) r->sum_p += sc->fill_p * (double)remaining;
  r->steps = sc->steps;
  r->success = r->end != ST_END_FAILURE && sc->was_in_target && sc->lifted;
  *out = *r;
}

double st_int_trial_bonus(const stIntTrialResult *r, double bonus, double factor) {
  ST_ASSERT(r);
  return (double)(r->focus_bonus + r->success) * bonus * factor;
}

double st_int_trial_points(const stIntTrialResult *r) {
  ST_ASSERT(r);
  return fmax(0.0, r->sum_s - r->sum_p);
}

/* ---- an individual ---- */

/* the integrated part: F_int = B + scale / N sum max(0, sum S - sum P) over its trials */
static void combine_integrated(double bonus, double scale, const stIntPlan *plan,
                               const stIntTrialResult *r, int n, stIntEvaluation *e) {
  double b = 0.0, points = 0.0;
  long steps = 0;
  for (int i = 0; i < n; i++) {
    if (plan[i].fitness != ST_FIT_INTEGRATED) continue;
    const double bi = st_int_trial_bonus(&r[i], bonus, plan[i].bonus_factor);
    b += bi;
    if (plan[i].autonomous) e->bonus_auto += bi;
    points += st_int_trial_points(&r[i]);
    steps += r[i].steps;
  }
  e->f_int = b + (steps > 0 ? scale / (double)steps * points : 0.0);
  e->bonus += b;
}

/* the prediction part over its trials; a trial counts when its object reached the target */
static void combine_prediction(const stIntPlan *plan, const stIntTrialResult *r,
                               const stPredScore *pred, int n, stIntEvaluation *e) {
  stPredScore s[ST_INT_MAX_TRIALS];
  int counts[ST_INT_MAX_TRIALS], t = 0;
  for (int i = 0; i < n && pred; i++) {
    if (plan[i].fitness != ST_FIT_PREDICTION) continue;
    s[t] = pred[i];
    counts[t++] = r[i].reached_step >= 0;
  }
  double b = 0.0;
  e->f_pred = st_pred_fitness(s, counts, t, &b);
  e->bonus += b;
}

void st_int_combine(double bonus, double scale, const stIntPlan *plan,
                    const stIntTrialResult *r, const stPredScore *pred, int n,
                    stIntEvaluation *e) {
  ST_ASSERT(n >= 0 && n <= ST_INT_MAX_TRIALS);
  ST_ASSERT(e && (n == 0 || (plan && r)));
  memset(e, 0, sizeof *e);
  e->ntrials = n;
  combine_integrated(bonus, scale, plan, r, n, e);
  combine_prediction(plan, r, pred, n, e);
  e->fitness = e->f_int + e->f_pred;
  for (int i = 0; i < n; i++) {
    e->success[i] = (uint8_t)r[i].success;
    e->successes += r[i].success;
    e->unstable += r[i].unstable;
    e->progress += (r[i].furthest_word > 0 ? r[i].furthest_word : 0) / (double)n;
  }
}
