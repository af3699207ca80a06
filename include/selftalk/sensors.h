/* SPDX-License-Identifier: MIT
 * libselftalk: what the robot senses (the network's inputs, SPEC §4) and the quantities the
 * fitness functions are built from (SPEC §6, thesis §2.7.1.2, §2.8.1.1). Pure functions of a
 * world's state. */
#ifndef SELFTALK_SENSORS_H
#define SELFTALK_SENSORS_H

#include "selftalk/world.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Protocol numbers used here (config keys network.* and fitness.*). */
typedef struct stSensorDef {
  double focus_scale;     /* focus vector = (focus - palm) * this; 20 */
  double focus_threshold; /* focus output < this: object; 0.5 */
  double reach_height;    /* d_r point above the object centre; 0.095 m */
  double penalty_table;   /* 1 */
  double penalty_object;  /* 1 */
  double move_free;       /* 0.02 m */
  double move_scale;      /* 0.1 m */
  double move_max;        /* 2 */
} stSensorDef;

ST_API void st_sensor_def_from_config(const stConfig *cfg, stSensorDef *def);

/* The fitness quantities of one step. */
typedef struct stQuantities {
  double palm[3];      /* centre of the palm's inner surface */
  double normal[3];    /* unit palm normal, out of the inner surface */
  double tip[ST_NTIP][3];
  double d_r;          /* palm centre to the point reach_height above the object centre */
  double d_g;          /* object centre to the centroid of thumb tip, little tip, palm centre */
  double d_m;          /* object centre to target */
  double d_mhat;       /* palm centre to target */
  double h;            /* openness: 1 - mean(qhat thumb flexion, qhat finger flexion) */
  double p;            /* palm facing the table: (1 - n_z) / 2 */
  int touching;        /* a fingertip or palm sensor touches the object */
  int lifted;          /* the object touches the robot and not the table */
} stQuantities;

ST_API void st_quantities(const stWorld *w, const stSensorDef *def, stQuantities *q);

/* Focus output y read as a choice: 1 target, 0 object. */
ST_API int st_focus_is_target(const stSensorDef *def, double y_focus);

/* Focus correctness f_f: 1 - y when the right focus is the object, y when it is the target. */
ST_API double st_focus_correctness(double y_focus, int right_is_target);

/* Network inputs (SPEC §4 order) for this step: qhat, touch, focus vector (zero when
 * first_step), linguistic input ling[4] and, when n == 26, the secondary input. focus_target
 * selects the focus point (the target, else the object's current centre). */
ST_API void st_sensor_inputs(const stWorld *w, const stSensorDef *def, const stQuantities *q,
                      int focus_target, int first_step, const double *ling, double secondary,
                      double *in, int n);

/* Per-step penalties (SPEC §6). */
ST_API double st_penalty_table(const stWorld *w, const stSensorDef *def);
ST_API double st_penalty_object(const stWorld *w, const stSensorDef *def);
/* min(move_max, d / move_scale) for the object's displacement d from its start; 0 when
 * d < move_free. */
ST_API double st_penalty_moving(const stWorld *w, const stSensorDef *def);

#ifdef __cplusplus
}
#endif

#endif
