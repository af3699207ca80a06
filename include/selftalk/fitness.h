/* SPDX-License-Identifier: MIT
 * libselftalk: the fitness functions of the primitive stages (thesis §2.6-§2.8, SPEC §6-§7):
 * step fitness S_p(t) (eq. 2.4 with 2.5-2.12), penalties P_p(t), success conditions, the
 * primitive fitness F_p (eq. 2.3) and their harmonic mean (eq. 2.2 read as SPEC §7 says).
 * Pure functions of the fitness quantities of one step: no simulator state, no allocation. */
#ifndef SELFTALK_FITNESS_H
#define SELFTALK_FITNESS_H

#include "selftalk/config.h"
#include "selftalk/sensors.h"
#include "selftalk/study.h" /* the primitives and stages */

#ifdef __cplusplus
extern "C" {
#endif

/* Protocol numbers of the fitness (keys fitness.*; defaults are the thesis's). */
typedef struct stFitnessDef {
  double focus_weight;   /* 0.2 */
  double decay;          /* 10 */
  double open_h;         /* 0.7 */
  double grasp_h;        /* 0.4 */
  double success_dist;   /* 0.03 */
  double palm_down;      /* 0.9 */
  double target_radius;  /* 0.06 (scene.target_radius) */
  double bonus;          /* 10 */
  double scale;          /* 100 */
  double fp_min;         /* 0.001 */
  double fail_penalty;   /* 4 */
  int reach_hold_steps;  /* 20 */
  double move_touch, move_lift, move_lift_dist; /* 0.1, 0.1, 0.8 */
} stFitnessDef;

ST_API void st_fitness_def_from_config(const stConfig *cfg, stFitnessDef *def);

/* 1 when the right focus of a primitive is the target (move), 0 for the object. */
ST_API int st_primitive_focus_target(int primitive);

/* The primitive-specific part s_p(t) (eq. 2.5-2.8 simple-prim, 2.9-2.12 main-prim). In
 * simple-prim, move uses d_mhat (palm to target: SPEC §7, eq. 2.8's typo). */
ST_API double st_step_s(const stFitnessDef *def, stStage stage, int primitive, const stQuantities *q);

/* Step fitness S_p(t) (eq. 2.4) for a focus output y: w f_f + (focus correct ? (1-w) s_p : 0). */
ST_API double st_step_fitness(const stFitnessDef *def, stStage stage, int primitive,
                       const stQuantities *q, double y_focus, double focus_threshold);

/* The "at any time during the trial" success conditions: simple-prim all four, main-prim
 * reach and open (eq. 2.5-2.10 success lines); main-prim move's "within target_radius" part.
 * Main-prim grasp has no per-step condition (it is judged at the end): returns 0. */
ST_API int st_success_now(const stFitnessDef *def, stStage stage, int primitive, const stQuantities *q);

/* Which penalties apply (thesis 2.7.2, 2.8.1.2): bit 0 table, bit 1 object, bit 2 moving.
 * step is the control step (main-prim grasp's moving penalty stops after table_off_step). */
enum { ST_PEN_TABLE = 1, ST_PEN_OBJECT = 2, ST_PEN_MOVING = 4 };
ST_API int st_penalty_mask(stStage stage, int primitive, int step, int grasp_table_off_step);

/* F_p = bonus + scale / n_steps * sum_sp where sum_sp = sum over the primitive's steps of
 * S - P (eq. 2.3). n_steps 0 gives the bonus alone. */
ST_API double st_primitive_fitness(const stFitnessDef *def, double bonus, double sum_sp, long n_steps);

/* F = n / sum(1 / max(F_p, fp_min)) over n primitives (eq. 2.2 with SPEC §7's factor). */
ST_API double st_harmonic_fitness(const stFitnessDef *def, const double *fp, int n);

#ifdef __cplusplus
}
#endif

#endif
