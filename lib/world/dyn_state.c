/* SPDX-License-Identifier: MIT
 * The dynamic world's state and its reset (lib/world/dynworld.c has the map of its files):
 * whether it diverged, where its bodies are placed, the robot between free motion and ODE's
 * step, the state read into the stWorld fields, a trial's start. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "selftalk/rng.h"
#include "world/dynworld.h"
#include "world/ode_util.h"

static int finite3(const dReal *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

void st__dyn_set_unstable(stWorld *w, const char *fmt, ...) {
  dynInternal *d = w->internal_;
  if (d->unstable) return;
  d->unstable = 1;
  int n = snprintf(d->reason, sizeof d->reason, "step %ld: ", w->step);
  va_list ap;
  va_start(ap, fmt);
  if (n > 0 && (size_t)n < sizeof d->reason)
    vsnprintf(d->reason + n, sizeof d->reason - (size_t)n, fmt, ap);
  va_end(ap);
}

/* NaN / runaway check of one body; 1 when fine */
static int body_ok(stWorld *w, dBodyID b, const char *name) {
  const dynInternal *d = w->internal_;
  const dReal *x = dBodyGetPosition(b), *v = dBodyGetLinearVel(b), *o = dBodyGetAngularVel(b);
  const dReal *q = dBodyGetQuaternion(b);
  if (!finite3(x) || !finite3(v) || !finite3(o) || !isfinite(q[0]) || !finite3(q + 1)) {
    st__dyn_set_unstable(w, "body '%s' has a non-finite position, orientation or velocity",
                         name);
    return 0;
  }
  const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double o2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  if (v2 > d->def.unstable_speed * d->def.unstable_speed) {
    st__dyn_set_unstable(w, "body '%s' moves at %.3g m/s (unstable_speed %g)", name, sqrt(v2),
                         d->def.unstable_speed);
    return 0;
  }
  if (o2 > d->def.unstable_spin * d->def.unstable_spin) {
    st__dyn_set_unstable(w, "body '%s' spins at %.3g rad/s (unstable_spin %g)", name, sqrt(o2),
                         d->def.unstable_spin);
    return 0;
  }
  return 1;
}

/* after a sub-step: the object, and the robot's bodies when they took part; 1 when fine */
int st__dyn_bodies_ok(stWorld *w) {
  dynInternal *d = w->internal_;
  if (d->robot_dyn)
    for (int g = 0; g < d->ngroup; g++)
      if (!body_ok(w, d->gbody[g], w->robot->model->body_name[d->glink[g]])) return 0;
  return body_ok(w, d->ball, "object");
}

/* body g where forward kinematics (w->R, w->p) puts its first link */
void st__dyn_place_body(stWorld *w, int g) {
  dynInternal *d = w->internal_;
  const int gl = d->glink[g];
  double c[3];
  st__mat3_vec(w->R[gl], d->gcom[g], c);
  dBodyID b = d->gbody[g];
  dBodySetPosition(b, w->p[gl][0] + c[0], w->p[gl][1] + c[1], w->p[gl][2] + c[2]);
  dMatrix3 Ro;
  st__mat3_to_ode(w->R[gl], Ro);
  dBodySetRotation(b, Ro);
}

/* places every robot body where forward kinematics of d->angle puts it (FK into w->R / w->p) */
static void place_bodies(stWorld *w) {
  dynInternal *d = w->internal_;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  for (int g = 0; g < d->ngroup; g++) st__dyn_place_body(w, g);
}

/* sets every robot body's velocity (only_kin: every kinematic body's) to what the joint
 * velocities d->vel give (hinge i moves body i; parents come first) */
static void prescribe_velocities(stWorld *w, int only_kin) {
  dynInternal *d = w->internal_;
  const stModel *m = w->robot->model;
  for (int g = 0; g < (only_kin ? d->nkin : d->ngroup); g++) { /* the kinematic ones come first */
    const int pg = d->link_group[m->body_parent[d->glink[g]]];
    dVector3 a, anc;
    dJointGetHingeAxis(d->hinge[g].j, a);
    dJointGetHingeAnchor(d->hinge[g].j, anc);
    const dReal *x = dBodyGetPosition(d->gbody[g]);
    double wp[3] = {0, 0, 0}, vp[3] = {0, 0, 0}, rp[3] = {0, 0, 0};
    if (pg >= 0) {
      const dReal *o = dBodyGetAngularVel(d->gbody[pg]), *v = dBodyGetLinearVel(d->gbody[pg]);
      const dReal *xp = dBodyGetPosition(d->gbody[pg]);
      for (int k = 0; k < 3; k++) {
        wp[k] = o[k];
        vp[k] = v[k];
        rp[k] = anc[k] - xp[k];
      }
    }
    double wc[3], rc[3];
    for (int k = 0; k < 3; k++) {
      wc[k] = wp[k] + a[k] * d->vel[g];
      rc[k] = anc[k] - x[k];
    }
    /* the anchor moves alike as a point of the parent and of the child */
    const double v0 = vp[0] + (wp[1] * rp[2] - wp[2] * rp[1]) - (wc[1] * rc[2] - wc[2] * rc[1]);
    const double v1 = vp[1] + (wp[2] * rp[0] - wp[0] * rp[2]) - (wc[2] * rc[0] - wc[0] * rc[2]);
    const double v2 = vp[2] + (wp[0] * rp[1] - wp[1] * rp[0]) - (wc[0] * rc[1] - wc[1] * rc[0]);
    dBodySetAngularVel(d->gbody[g], wc[0], wc[1], wc[2]);
    dBodySetLinearVel(d->gbody[g], v0, v1, v2);
    dBodySetForce(d->gbody[g], 0, 0, 0);
    dBodySetTorque(d->gbody[g], 0, 0, 0);
  }
}

/* the kinematic bodies where forward kinematics of d->angle puts them, moving at d->vel */
void st__dyn_place_kinematic(stWorld *w) {
  dynInternal *d = w->internal_;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  for (int g = 0; g < d->ngroup && d->hinge[g].kin; g++) st__dyn_place_body(w, g);
  prescribe_velocities(w, 1);
}


/* free motion -> ODE: bodies at the kinematic pose, moving at the servo velocities */
void st__dyn_robot_to_ode(stWorld *w) {
  dynInternal *d = w->internal_;
  place_bodies(w);
  prescribe_velocities(w, 0);
  for (int g = 0; g < d->ngroup; g++) dBodyEnable(d->gbody[g]);
  d->robot_dyn = 1;
  for (int g = d->nkin0; g < d->nkin0 + d->nadapt; g++) { /* adaptive_joints: no jump */
    const dReal *v = dBodyGetLinearVel(d->gbody[g]), *om = dBodyGetAngularVel(d->gbody[g]);
    for (int k = 0; k < 3; k++) {
      d->vprev[g][k] = v[k];
      d->vprev[g][3 + k] = om[k];
    }
  }
}

/* ODE -> free motion: the measured angles become the state (with read; else d->angle already
 * is); the bodies leave the step */
void st__dyn_robot_to_free(stWorld *w, int read) {
  dynInternal *d = w->internal_;
  if (read)
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) d->angle[d->hinge[i].link] = dJointGetHingeAngle(d->hinge[i].j);
  for (int g = 0; g < d->ngroup; g++) dBodyDisable(d->gbody[g]);
  d->robot_dyn = 0;
}

/* joint angles -> qhat; poses (FK); object centre */
void st__dyn_read_state(stWorld *w) {
  dynInternal *d = w->internal_;
  double sum[ST_NDOF] = {0};
  int cnt[ST_NDOF] = {0};
  for (int i = 0; i < d->nhinge; i++) {
    const dynHinge *hg = &d->hinge[i];
    if (d->robot_dyn && !hg->kin) d->angle[hg->link] = dJointGetHingeAngle(hg->j);
    const double q = (d->angle[hg->link] - hg->lo) / (hg->hi - hg->lo);
    sum[hg->dof] += q < 0.0 ? 0.0 : q > 1.0 ? 1.0 : q;
    cnt[hg->dof]++;
  }
  for (int k = 0; k < ST_NDOF; k++) w->qhat[k] = cnt[k] ? sum[k] / cnt[k] : 0.0;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  const dReal *o = dBodyGetPosition(d->ball);
  for (int i = 0; i < 3; i++) w->obj[i] = o[i];
}

/* ---- reset ------------------------------------------------------------------------------- */

/* dynamics.adaptive_joints: hinge i (an adaptive one) becomes an exact servo (on: joint disabled,
 * body kinematic, its angle from now on d->angle: the measured one with read) or a bounded
 * motor again; d->nkin counts the kinematic prefix (the caller keeps it a prefix) */
void st__dyn_set_kin(dynInternal *d, int i, int on, int read) {
  dynHinge *hg = &d->hinge[i];
  if (on == hg->kin) return;
  if (on) {
    if (read) d->angle[hg->link] = dJointGetHingeAngle(hg->j);
    dJointDisable(hg->j);
    dBodySetKinematic(d->gbody[i]);
    d->nkin = i + 1;
  } else {
    dJointEnable(hg->j);
    dBodySetDynamic(d->gbody[i]);
    dJointSetHingeParam(hg->j, dParamVel, d->vel[i]);
    d->nkin = i;
  }
  hg->kin = on;
}

/* the stops of a hinge at lo, hi; ODE ignores a low stop above the high one (and vice versa):
 * they are set in a safe order */
void st__dyn_set_stops(dynHinge *hg, double lo, double hi) {
  if (lo > hg->hi_set) {
    dJointSetHingeParam(hg->j, dParamHiStop, hi);
    dJointSetHingeParam(hg->j, dParamLoStop, lo);
  } else {
    dJointSetHingeParam(hg->j, dParamLoStop, lo);
    dJointSetHingeParam(hg->j, dParamHiStop, hi);
  }
  hg->lo_set = lo;
  hg->hi_set = hi;
}


/* the robot's bodies at rest in the posture qhat (clamped to [0, 1], NaN -> 0) */
static void reset_pose(stWorld *w, const double *qhat) {
  dynInternal *d = w->internal_;
  double q[ST_NDOF];
  for (int k = 0; k < ST_NDOF; k++)
    q[k] = !(qhat[k] >= 0.0) ? 0.0 : qhat[k] > 1.0 ? 1.0 : qhat[k]; /* NaN -> 0 */
  st_robot_angles(w->robot, q, d->angle);
  for (int i = 0; i < d->nhinge; i++) d->vel[i] = 0.0;
  place_bodies(w);
  prescribe_velocities(w, 0); /* at rest */
}

/* the object at rest at obj (at the origin when obj is not finite); 1 when it is finite */
static int reset_object(dynInternal *d, const double obj[3]) {
  const int ok = isfinite(obj[0]) && isfinite(obj[1]) && isfinite(obj[2]);
  dBodySetPosition(d->ball, ok ? obj[0] : 0, ok ? obj[1] : 0, ok ? obj[2] : 0);
  static const dMatrix3 I = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  dBodySetRotation(d->ball, I);
  dBodySetLinearVel(d->ball, 0, 0, 0);
  dBodySetAngularVel(d->ball, 0, 0, 0);
  dBodySetForce(d->ball, 0, 0, 0);
  dBodySetTorque(d->ball, 0, 0, 0);
  dBodyEnable(d->ball);
  return ok;
}

/* motors at rest, the stops as built (speculative_stops may have moved them), the robot's
 * bodies in ODE's step */
static void reset_joints(dynInternal *d) {
  for (int i = 0; i < d->nhinge; i++) {
    dynHinge *hg = &d->hinge[i];
    dJointSetHingeParam(hg->j, dParamVel, 0.0);
    hg->bounded = hg->free_row = 0;
    if (d->def.motor_active_set) dJointSetHingeParam(hg->j, dParamFMax, hg->fmax);
    st__dyn_set_stops(hg, hg->lo - d->stop_margin, hg->hi + d->stop_margin);
  }
  for (int g = 0; g < d->ngroup; g++) dBodyEnable(d->gbody[g]);
  d->robot_dyn = 1;
  for (int i = d->nkin0 + d->nadapt - 1; i >= d->nkin0; i--) st__dyn_set_kin(d, i, 0, 0);
  for (int i = d->nkin0; i < d->nkin0 + d->nadapt; i++) st__dyn_set_kin(d, i, 1, 0);
  for (int g = 0; g < d->ngroup; g++) {
    d->want_kin[g] = 0;
    for (int k = 0; k < 6; k++) d->vprev[g][k] = 0.0;
  }
}

/* the per-trial counters, flags and quickstep's generator */
static void reset_counters(dynInternal *d) {
  d->obj_table = 1;
  d->messages = 0;
  d->retries = 0;
  d->motor_redos = 0;
  d->adapt_redos = 0;
  d->dyn_substeps = 0;
  d->dyn_hinge_substeps = 0;
  memset(d->points, 0, sizeof d->points);
  if (d->lcp) st__lcp_reset(d->lcp);
  d->unstable = 0;
  d->reason[0] = 0;
  d->rand_state = (uint32_t)(st_rng_mix64(d->seed ^ 0x6f64655f72616e64ull) >> 32);
}

void st__dyn_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
  dynInternal *d = w->internal_;
  st__ode_init();
  reset_pose(w, qhat);
  const int ok = reset_object(d, obj);
  reset_joints(d);
  reset_counters(d);
  w->step = 0;
  memcpy(w->obj_start, obj, sizeof w->obj_start);
  memcpy(w->target, target, sizeof w->target);
  dJointGroupEmpty(d->cgroup);
  memset(&w->contacts, 0, sizeof w->contacts);
  st__dyn_collide_all(w, 0, &w->contacts);
  if (d->def.free_motion && !st__dyn_robot_near(w, d->def.contact_margin))
    st__dyn_robot_to_free(w, 0);
  st__dyn_read_state(w);
  if (!ok) st__dyn_set_unstable(w, "object position is not finite");
}

void st__dyn_update(stWorld *w) {
  if (!((dynInternal *)w->internal_)->unstable) st__dyn_read_state(w);
}
