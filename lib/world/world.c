/* SPDX-License-Identifier: MIT
 * The public st_world_* functions: allocation of an stWorld and dispatch to its backend,
 * kinematic (lib/world/kinworld.c) or dynamic (lib/world/dynworld.c), through the operations its state
 * carries (lib/world/world_backend.h). */
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "world/world_backend.h"
#include "world/world_geom.h"

static const stWorldBackend *backend(const stWorld *w) {
  return ((const stWorldHead *)w->internal_)->backend;
}

/* the stWorld and its pose arrays; NULL when out of memory */
static stWorld *world_new(const stRobot *robot, const stScene *scene) {
  stWorld *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->robot = robot;
  w->scene = scene;
  w->R = calloc((size_t)robot->nbody, sizeof *w->R);
  w->p = calloc((size_t)robot->nbody, sizeof *w->p);
  if (!w->R || !w->p) {
    st_world_destroy(w);
    return NULL;
  }
  return w;
}

/* hands the created world out, or destroys it after a failed backend creation */
static stStatus world_finish(stWorld *w, stStatus st, stWorld **out) {
  if (st) {
    st_world_destroy(w);
    return st;
  }
  *out = w;
  return ST_OK;
}

stStatus st_world_create(const stRobot *robot, const stScene *scene, stWorld **out, char *err,
                         size_t errsz) {
  *out = NULL;
  stWorld *w = world_new(robot, scene);
  if (!w) return st__errf(err, errsz, "world: out of memory"), ST_ERR_NOMEM;
  return world_finish(w, st__kin_create(w, err, errsz), out);
}

stStatus st_world_create_dynamic(const stRobot *robot, const stScene *scene, const stDynDef *def,
                                 stWorld **out, char *err, size_t errsz) {
  *out = NULL;
  stWorld *w = world_new(robot, scene);
  if (!w) return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  w->dynamic = 1;
  return world_finish(w, st__dyn_create(w, def, err, errsz), out);
}

void st_world_destroy(stWorld *w) {
  if (!w) return;
  if (w->internal_) backend(w)->destroy(w);
  free(w->R);
  free(w->p);
  free(w);
}

void st_world_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
  backend(w)->reset(w, qhat, obj, target);
}

void st_world_update(stWorld *w) { backend(w)->update(w); }

double st_actuate(double qhat, double y, double alpha, double vmax_deg, double dt,
                  double range_deg) {
  double v = alpha * (y - qhat); /* deg/s */
  if (v > vmax_deg) v = vmax_deg;
  if (v < -vmax_deg) v = -vmax_deg;
  double q = qhat + v * dt / range_deg;
  return q < 0.0 ? 0.0 : q > 1.0 ? 1.0 : q;
}

/* the kinematic mode's step: the actuation law on qhat, then the backend's poses and contacts */
void st_world_step_kinematic(stWorld *w, const double *y) {
  const stRobot *r = w->robot;
  const double vmax_deg = r->max_velocity / ST_DEG;
  for (int d = 0; d < ST_NDOF; d++) {
    double range_deg = (r->dof_hi[d] - r->dof_lo[d]) / ST_DEG;
    w->qhat[d] = st_actuate(w->qhat[d], y[d], r->alpha_kinematic, vmax_deg, r->dt, range_deg);
  }
  w->step++;
  backend(w)->update(w);
}

void st_world_step_dynamic(stWorld *w, const double *y) {
  if (backend(w)->step) backend(w)->step(w, y);
  else st_world_step_kinematic(w, y);
}

void st_world_step(stWorld *w, const double *y) { st_world_step_dynamic(w, y); }

void st_world_point(const stWorld *w, int b, const double l[3], double out[3]) {
  st__frame_point(w->R[b], w->p[b], l, out);
}

void st_world_joint_angles(const stWorld *w, double *angle) { backend(w)->joint_angles(w, angle); }

/* ---- dynamics: the answers of a world without them where the backend has none ------------- */

void st_world_set_seed(stWorld *w, uint64_t key) {
  if (backend(w)->set_seed) backend(w)->set_seed(w, key);
}

void st_world_set_object_table_collision(stWorld *w, int on) {
  if (backend(w)->set_object_table_collision) backend(w)->set_object_table_collision(w, on);
}

int st_world_object_fell(const stWorld *w) {
  return backend(w)->object_fell ? backend(w)->object_fell(w) : 0;
}

int st_world_unstable(const stWorld *w) {
  return backend(w)->unstable ? backend(w)->unstable(w) : 0;
}

const char *st_world_unstable_reason(const stWorld *w) {
  return backend(w)->unstable_reason ? backend(w)->unstable_reason(w) : "";
}

void st_world_dynamic_info(const stWorld *w, stDynInfo *info) {
  memset(info, 0, sizeof *info);
  if (backend(w)->info) backend(w)->info(w, info);
}
