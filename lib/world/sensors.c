/* SPDX-License-Identifier: MIT */
#include "selftalk/sensors.h"

#include <math.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/genome.h"

void st_sensor_def_from_config(const stConfig *c, stSensorDef *d) {
  ST_ASSERT(c && d);
  d->focus_scale = c->network_focus_scale;
  d->focus_threshold = c->network_focus_threshold;
  d->reach_height = c->fitness_reach_height;
  d->penalty_table = c->fitness_penalty_table;
  d->penalty_object = c->fitness_penalty_object;
  d->move_free = c->fitness_move_free;
  d->move_scale = c->fitness_move_scale;
  d->move_max = c->fitness_move_max;
}

static double dist(const double *a, const double *b) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

void st_quantities(const stWorld *w, const stSensorDef *def, stQuantities *q) {
  ST_ASSERT(w && def && q);
  const stRobot *r = w->robot;
  memcpy(q->palm, w->p[r->palm_body], sizeof q->palm);
  const double *R = w->R[r->palm_body];
  q->normal[0] = R[2]; /* the frame's z axis: third column */
  q->normal[1] = R[5];
  q->normal[2] = R[8];
  for (int i = 0; i < ST_NTIP; i++) memcpy(q->tip[i], w->p[r->tip_body[i]], sizeof q->tip[i]);
  double above[3] = {w->obj[0], w->obj[1], w->obj[2] + def->reach_height};
  q->d_r = dist(q->palm, above);
  double cg[3];
  for (int i = 0; i < 3; i++) cg[i] = (q->tip[0][i] + q->tip[ST_NTIP - 1][i] + q->palm[i]) / 3.0;
  q->d_g = dist(w->obj, cg);
  q->d_m = dist(w->obj, w->target);
  q->d_mhat = dist(q->palm, w->target);
  q->h = 1.0 - 0.5 * (w->qhat[ST_DOF_THUMB_FLEX] + w->qhat[ST_DOF_FINGER_FLEX]);
  q->p = 0.5 * (1.0 - q->normal[2]);
  q->touching = 0;
  for (int i = 0; i < ST_NTOUCH; i++) q->touching |= w->contacts.touch_object[i];
  q->lifted = w->contacts.robot_object && !w->contacts.object_table;
}

int st_focus_is_target(const stSensorDef *def, double y) {
  ST_ASSERT(def);
  return y >= def->focus_threshold;
}

double st_focus_correctness(double y, int right_is_target) { return right_is_target ? y : 1.0 - y; }

void st_sensor_inputs(const stWorld *w, const stSensorDef *def, const stQuantities *q,
                      int focus_target, int first_step, const double *ling, double secondary,
                      double *in, int n) {
  ST_ASSERT(w && def && q && in);
  for (int d = 0; d < ST_NDOF; d++) in[d] = w->qhat[d];
  for (int i = 0; i < ST_NTOUCH; i++) in[ST_NET_IN_TOUCH + i] = w->contacts.touch[i];
  const double *f = focus_target ? w->target : w->obj;
  for (int i = 0; i < 3; i++)
    in[ST_NET_IN_FOCUS + i] = first_step ? 0.0 : (f[i] - q->palm[i]) * def->focus_scale;
  for (int m = 0; m < ST_NET_NLING; m++) in[ST_NET_IN_LING + m] = ling ? ling[m] : 0.0;
  if (n > ST_NET_IN_SECONDARY) in[ST_NET_IN_SECONDARY] = secondary;
}

double st_penalty_table(const stWorld *w, const stSensorDef *def) {
  ST_ASSERT(w && def);
  return w->contacts.arm_table ? def->penalty_table : 0.0;
}

double st_penalty_object(const stWorld *w, const stSensorDef *def) {
  ST_ASSERT(w && def);
  return w->contacts.robot_object ? def->penalty_object : 0.0;
}

double st_penalty_moving(const stWorld *w, const stSensorDef *def) {
  ST_ASSERT(w && def);
  double d = dist(w->obj, w->obj_start);
  if (d < def->move_free) return 0.0;
  double p = d / def->move_scale;
  return p < def->move_max ? p : def->move_max;
}
