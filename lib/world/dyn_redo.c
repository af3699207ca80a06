/* SPDX-License-Identifier: MIT
 * The redo strategies of a sub-step with the robot in ODE's step (lib/world/dynworld.c has the
 * map of its files; the sub-step: lib/world/dyn_step.c). The bodies' states are saved before
 * it; after ODE's step each strategy looks at what the step did and may ask for it again from
 * the saved state, having changed what it must:
 *   softer    ODE's direct solver fails on a degenerate set of contacts ("LCP internal error",
 *             reported through dMessage) and returns garbage: contact and joint CFM x10, up to
 *             3 times;
 *   adaptive  dynamics.adaptive_joints: an exact servo needed more torque than its motor has
 *             (or touched the table): it and the adaptive hinges after it become motors;
 *   motors    dynamics.motor_active_set: an unbounded motor row needed more than its limit:
 *             bounded. */
#include <math.h>
#include <string.h>

#include "world/dynworld.h"

/* saves / restores the state of every body taking part in the step */
void st__dyn_save_bodies(dynInternal *d, double (*st)[13]) {
  for (int g = 0; g <= d->ngroup; g++) {
    dBodyID b = g < d->ngroup ? d->gbody[g] : d->ball;
    memcpy(st[g], dBodyGetPosition(b), 3 * sizeof(double));
    memcpy(st[g] + 3, dBodyGetQuaternion(b), 4 * sizeof(double));
    memcpy(st[g] + 7, dBodyGetLinearVel(b), 3 * sizeof(double));
    memcpy(st[g] + 10, dBodyGetAngularVel(b), 3 * sizeof(double));
  }
}

void st__dyn_restore_bodies(dynInternal *d, double (*st)[13]) {
  for (int g = 0; g <= d->ngroup; g++) {
    dBodyID b = g < d->ngroup ? d->gbody[g] : d->ball;
    dBodySetPosition(b, st[g][0], st[g][1], st[g][2]);
    dBodySetQuaternion(b, st[g] + 3);
    dBodySetLinearVel(b, st[g][7], st[g][8], st[g][9]);
    dBodySetAngularVel(b, st[g][10], st[g][11], st[g][12]);
    dBodySetForce(b, 0, 0, 0);
    dBodySetTorque(b, 0, 0, 0);
  }
}

/* hinge hg's anchor seen from its child's centre x, and its axis, at the start of a step: where
 * the torque checks after the step take moments (motor_torque, adaptive_torque) */
static void hinge_frame(dynHinge *hg, const dReal *x) {
  dVector3 anc, ax;
  dJointGetHingeAnchor(hg->j, anc);
  dJointGetHingeAxis(hg->j, ax);
  for (int k = 0; k < 3; k++) {
    hg->r1[k] = anc[k] - x[k];
    hg->axis[k] = ax[k];
  }
}

/* dynamics.motor_active_set, before a step: a hinge motor that did not saturate in the previous
 * sub-step (and whose joint is off its stops, where ODE replaces the motor row by the stop's)
 * gets an unbounded row, which ODE's Dantzig solver factors in one block with the joints' rows
 * instead of pivoting it alone; its child's anchor and axis are kept for the check. */
void st__dyn_motors_prepare(dynInternal *d) {
  for (int i = 0; i < d->nhinge; i++) {
    dynHinge *hg = &d->hinge[i];
    if (hg->kin) continue;
    const double a = dJointGetHingeAngle(hg->j);
    /* ODE's own test of an active stop (testRotationalLimit), on the same angle */
    const int stop = a <= hg->lo_set || a >= hg->hi_set;
    const int free_row = !hg->bounded && !stop && hg->fmax > 0.0;
    if (free_row != hg->free_row)
      dJointSetHingeParam(hg->j, dParamFMax, free_row ? dInfinity : hg->fmax);
    hg->free_row = free_row;
    if (!free_row && !hg->bounded) continue;
    hinge_frame(hg, dBodyGetPosition(dJointGetBody(hg->j, 0)));
  }
}

/* the motor torque of hinge hg in the step just taken: its forces on the child, less the
 * moment of the linear rows at the anchor, along the axis (the angular rows act across it) */
static double motor_torque(const dynHinge *hg) {
  const dReal *t = hg->fb.t1;
  const double f[3] = {hg->fb.f1[0], hg->fb.f1[1], hg->fb.f1[2]};
  double rf[3];
  st__cross3(hg->r1, f, rf);
  return (t[0] - rf[0]) * hg->axis[0] + (t[1] - rf[1]) * hg->axis[1] +
         (t[2] - rf[2]) * hg->axis[2];
}

/* after a step: 1 when an unbounded motor needed more than its limit (it becomes bounded and the
 * sub-step must be redone); else a bounded motor that stayed inside its limit is unbounded again
 * from the next sub-step. With every motor inside its limit the unbounded rows give the solution
 * the bounded ones would (the LCP's matrix is positive definite: its solution is unique). */
static int motors_check(dynInternal *d) {
  int redo = 0;
  for (int i = 0; i < d->nhinge; i++) {
    dynHinge *hg = &d->hinge[i];
    if (hg->free_row && fabs(motor_torque(hg)) > hg->fmax) {
      hg->bounded = 1;
      redo = 1;
    }
  }
  if (redo) return 1;
  for (int i = 0; i < d->nhinge; i++) {
    dynHinge *hg = &d->hinge[i];
    if (hg->bounded && !hg->free_row && fabs(motor_torque(hg)) < hg->fmax * (1.0 - 1e-6))
      hg->bounded = 0;
  }
  return 0;
}

/* dynamics.adaptive_joints, before a step: every adaptive hinge's anchor and axis, and the
 * centre of mass of its body (the forces ODE reports act about it); the contact forces to come */
void st__dyn_adaptive_prepare(dynInternal *d) {
  for (int i = d->nkin0; i < d->nkin0 + d->nadapt; i++) {
    const dReal *x = dBodyGetPosition(d->gbody[i]);
    hinge_frame(&d->hinge[i], x);
    for (int k = 0; k < 3; k++) d->cpos[i][k] = x[k];
  }
}

/* moment about point a of force f at point p plus torque t, added to m */
static void add_moment(double *m, const double *a, const double *p, const dReal *f,
                       const dReal *t) {
  const double r[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]}, ff[3] = {f[0], f[1], f[2]};
  double rf[3];
  st__cross3(r, ff, rf);
  for (int k = 0; k < 3; k++) m[k] += rf[k] + (t ? t[k] : 0.0);
}

/* the torque the motor of kinematic adaptive hinge j needed in the step just taken: Newton-Euler
 * of the kinematic bodies it carries (bodies j .. nkin - 1, the chain), about its anchor along its
 * axis, given their motion (velocity change since the previous sub-step), gravity, the forces of
 * the hinges of their dynamic children and of their contacts (ODE's feedback) */
static double adaptive_torque(const stWorld *w, const dynInternal *d, int j) {
  const dynHinge *hj = &d->hinge[j];
  double a[3], need[3] = {0, 0, 0}, ext[3] = {0, 0, 0};
  for (int k = 0; k < 3; k++) a[k] = d->cpos[j][k] + hj->r1[k];
  const double gz = -d->def.gravity;
  for (int b = j; b < d->nkin; b++) {
    dMass ms;
    dBodyGetMass(d->gbody[b], &ms);
    const dReal *v = dBodyGetLinearVel(d->gbody[b]), *om = dBodyGetAngularVel(d->gbody[b]);
    const dReal *R = dBodyGetRotation(d->gbody[b]);
    /* m (acc - g) at the centre; I alpha + om x I om, I in world axes: R I R^T */
    const dReal f[3] = {ms.mass * (v[0] - d->vprev[b][0]) / d->h,
                        ms.mass * (v[1] - d->vprev[b][1]) / d->h,
                        ms.mass * ((v[2] - d->vprev[b][2]) / d->h - gz)};
    double al[3], Iw[3], Io[3], tmp[3], tmp2[3];
    for (int k = 0; k < 3; k++) al[k] = (om[k] - d->vprev[b][3 + k]) / d->h;
    /* body-frame vectors: x_b = R^T x */
    double alb[3], omb[3];
    for (int r = 0; r < 3; r++) {
      alb[r] = R[0 * 4 + r] * al[0] + R[1 * 4 + r] * al[1] + R[2 * 4 + r] * al[2];
      omb[r] = R[0 * 4 + r] * om[0] + R[1 * 4 + r] * om[1] + R[2 * 4 + r] * om[2];
    }
    for (int r = 0; r < 3; r++) {
      tmp[r] = ms.I[r * 4 + 0] * alb[0] + ms.I[r * 4 + 1] * alb[1] + ms.I[r * 4 + 2] * alb[2];
      tmp2[r] = ms.I[r * 4 + 0] * omb[0] + ms.I[r * 4 + 1] * omb[1] + ms.I[r * 4 + 2] * omb[2];
    }
    for (int r = 0; r < 3; r++) {
      Iw[r] = R[r * 4 + 0] * tmp[0] + R[r * 4 + 1] * tmp[1] + R[r * 4 + 2] * tmp[2];
      Io[r] = R[r * 4 + 0] * tmp2[0] + R[r * 4 + 1] * tmp2[1] + R[r * 4 + 2] * tmp2[2];
    }
    const double omd[3] = {om[0], om[1], om[2]};
    double gyro[3];
    st__cross3(omd, Io, gyro);
    const dReal t[3] = {Iw[0] + gyro[0], Iw[1] + gyro[1], Iw[2] + gyro[2]};
    add_moment(need, a, d->cpos[b], f, t);
  }
  /* the dynamic children's hinges on these bodies (ODE's body 2 is the parent) */
  const stModel *m = w->robot->model;
  for (int i = d->nkin; i < d->nhinge; i++) {
    const int pg = d->link_group[m->body_parent[d->hinge[i].link]];
    if (pg >= j && pg < d->nkin)
      add_moment(ext, a, d->cpos[pg], d->hinge[i].fb.f2, d->hinge[i].fb.t2);
  }
  for (int c = 0; c < d->ncfb; c++) {
    const int b = d->cfb_body[c];
    if (b < j) continue;
    const dJointFeedback *fb = &d->cfb[c];
    const int two = d->cfb_side[c];
    add_moment(ext, a, d->cpos[b], two ? fb->f2 : fb->f1, two ? fb->t2 : fb->t1);
  }
  return (need[0] - ext[0]) * hj->axis[0] + (need[1] - ext[1]) * hj->axis[1] +
         (need[2] - ext[2]) * hj->axis[2];
}

/* after a step: the first kinematic adaptive hinge that touched the table or needed more than
 * adaptive_limit times its motor's limit becomes a bounded motor with every adaptive hinge after
 * it (returns 1: the sub-step must be redone); else every dynamic adaptive hinge whose motor
 * needed less than half that (and is off its stops) may become an exact servo at the next
 * sub-step, and the velocities are kept for the next check */
static int adaptive_check(const stWorld *w, dynInternal *d) {
  int first = d->kin_static_hit < d->nhinge ? d->kin_static_hit : -1;
  for (int j = d->nkin0; first < 0 && j < d->nkin; j++)
    if (fabs(adaptive_torque(w, d, j)) > d->def.adaptive_limit * d->hinge[j].fmax) first = j;
  if (first >= 0) {
    for (int i = d->nkin - 1; i >= first; i--) st__dyn_set_kin(d, i, 0, 1);
    return 1;
  }
  for (int i = d->nkin; i < d->nkin0 + d->nadapt; i++) {
    const dynHinge *hg = &d->hinge[i];
    const double a = dJointGetHingeAngle(hg->j);
    d->want_kin[i] = fabs(motor_torque(hg)) < 0.5 * d->def.adaptive_limit * hg->fmax &&
                     a > hg->lo_set && a < hg->hi_set;
  }
  for (int g = d->nkin0; g < d->nkin0 + d->nadapt; g++) {
    const dReal *v = dBodyGetLinearVel(d->gbody[g]), *om = dBodyGetAngularVel(d->gbody[g]);
    for (int k = 0; k < 3; k++) {
      d->vprev[g][k] = v[k];
      d->vprev[g][3 + k] = om[k];
    }
  }
  return 0;
}

/* dynamics.adaptive_joints, at the start of a sub-step with the robot in ODE: the dynamic
 * adaptive hinges that needed little torque (want_kin), in chain order, become exact servos */
void st__dyn_adaptive_update(dynInternal *d) {
  while (d->nkin < d->nkin0 + d->nadapt && d->want_kin[d->nkin]) {
    d->want_kin[d->nkin] = 0;
    st__dyn_set_kin(d, d->nkin, 1, 1);
  }
}

/* ---- the strategies ---- */

int st__dyn_redo_softer(dynInternal *d, unsigned long messages, int *tries) {
  if (!messages || *tries >= 3) return 0;
  d->surface.soft_cfm *= 10.0;
  dWorldSetCFM(d->world, d->def.cfm * pow(10.0, *tries + 1));
  d->retries++;
  ++*tries;
  return 1;
}

int st__dyn_redo_adaptive(const stWorld *w, dynInternal *d, int *tries) {
  if (*tries > d->nadapt || !adaptive_check(w, d)) return 0;
  d->adapt_redos++;
  ++*tries;
  return 1;
}

int st__dyn_redo_motors(dynInternal *d, int *tries) {
  if (*tries > d->nhinge || !motors_check(d)) return 0;
  d->motor_redos++;
  ++*tries;
  return 1;
}
