/* SPDX-License-Identifier: MIT */
#include "selftalk/fitness.h"

#include "core/internal.h"

#include <math.h>

void st_fitness_def_from_config(const stConfig *c, stFitnessDef *d) {
  ST_ASSERT(c && d);
  d->focus_weight = c->fitness_focus_weight;
  d->decay = c->fitness_decay;
  d->open_h = c->fitness_open_h;
  d->grasp_h = c->fitness_grasp_h;
  d->success_dist = c->fitness_success_dist;
  d->palm_down = c->fitness_palm_down;
  d->target_radius = c->scene_target_radius;
  d->bonus = c->fitness_bonus;
  d->scale = c->fitness_scale;
  d->fp_min = c->fitness_fp_min;
  d->fail_penalty = c->fitness_fail_penalty;
  d->reach_hold_steps = c->fitness_reach_hold_steps;
  d->move_touch = c->fitness_move_touch;
  d->move_lift = c->fitness_move_lift;
  d->move_lift_dist = c->fitness_move_lift_dist;
}

int st_primitive_focus_target(int p) { return p == ST_PRIM_MOVE; }

double st_step_s(const stFitnessDef *d, stStage stage, int p, const stQuantities *q) {
  ST_ASSERT(d && q);
  const double k = d->decay;
  switch (p) {
    case ST_PRIM_REACH: return exp(-k * q->d_r); /* eq. 2.5 */
    case ST_PRIM_OPEN:                            /* eq. 2.6 */
      return 0.5 * ((1.0 - fabs(q->h - d->open_h) / d->open_h) + q->p) * exp(-k * q->d_r);
    case ST_PRIM_GRASP: /* eq. 2.7 */
      return 0.5 * ((1.0 - fabs(q->h - d->grasp_h) / (1.0 - d->grasp_h)) + q->p) * exp(-k * q->d_g);
    case ST_PRIM_MOVE:
      if (stage == ST_STAGE_SIMPLE) return exp(-k * q->d_mhat); /* eq. 2.8 as SPEC §7 reads it */
      /* eq. 2.12 */
      return (q->touching ? d->move_touch : 0.0) +
             (q->lifted ? d->move_lift + d->move_lift_dist * exp(-k * q->d_m) : 0.0);
    default: return 0.0;
  }
}

double st_step_fitness(const stFitnessDef *d, stStage stage, int p, const stQuantities *q,
                       double y_focus, double threshold) {
  ST_ASSERT(d && q);
  const int right_target = st_primitive_focus_target(p);
  const double ff = right_target ? y_focus : 1.0 - y_focus;
  const int correct = (y_focus >= threshold) == right_target;
  return d->focus_weight * ff + (correct ? (1.0 - d->focus_weight) * st_step_s(d, stage, p, q) : 0.0);
}

int st_success_now(const stFitnessDef *d, stStage stage, int p, const stQuantities *q) {
  ST_ASSERT(d && q);
  switch (p) {
    case ST_PRIM_REACH: return q->d_r < d->success_dist;
    case ST_PRIM_OPEN: return q->d_r < d->success_dist && q->h > d->open_h && q->p > d->palm_down;
    case ST_PRIM_GRASP:
      return stage == ST_STAGE_SIMPLE &&
             (q->d_g < d->success_dist && q->h < d->grasp_h && q->p > d->palm_down);
    case ST_PRIM_MOVE:
      return stage == ST_STAGE_SIMPLE ? q->d_mhat < d->success_dist : q->d_m < d->target_radius;
    default: return 0;
  }
}

int st_penalty_mask(stStage stage, int p, int step, int grasp_table_off_step) {
  if (stage == ST_STAGE_SIMPLE)
    return p == ST_PRIM_REACH || p == ST_PRIM_OPEN ? ST_PEN_TABLE | ST_PEN_OBJECT : ST_PEN_TABLE;
  switch (p) {
    case ST_PRIM_REACH:
    case ST_PRIM_OPEN: return ST_PEN_TABLE | ST_PEN_OBJECT | ST_PEN_MOVING;
    case ST_PRIM_GRASP: return ST_PEN_TABLE | (step < grasp_table_off_step ? ST_PEN_MOVING : 0);
    default: return ST_PEN_TABLE;
  }
}

double st_primitive_fitness(const stFitnessDef *d, double bonus, double sum_sp, long n) {
  ST_ASSERT(d);
  return bonus + (n > 0 ? d->scale / (double)n * sum_sp : 0.0);
}

double st_harmonic_fitness(const stFitnessDef *d, const double *fp, int n) {
  ST_ASSERT(d && fp && n > 0);
  double inv = 0.0;
  for (int i = 0; i < n; i++) inv += 1.0 / (fp[i] > d->fp_min ? fp[i] : d->fp_min);
  return (double)n / inv;
}
