/* SPDX-License-Identifier: MIT
 * The dynamic world's stepping (lib/world/dynworld.c has the map of its files): a control step
 * is sub-steps, each the servo law of every joint, then free motion while nothing can touch the
 * robot within it (the servos exact, the robot moved kinematically, ODE stepping the object
 * alone), else the robot in ODE's step with its redo strategies (lib/world/dyn_redo.c). */
#include <math.h>
#include <string.h>

#include "world/dynworld.h"
#include "world/ode_util.h"

/* the servo law of SPEC §3 for every joint, from its current angle: d->vel (rad/s) */
static void servo(stWorld *w, const double *y) {
  dynInternal *d = w->internal_;
  const stRobot *r = w->robot;
  const double alpha = r->alpha_dynamic * ST_DEG; /* rad/s per unit of qhat error */
  const double vmax = r->max_velocity;
  for (int i = 0; i < d->nhinge; i++) {
    const dynHinge *hg = &d->hinge[i];
    double yd = y[hg->dof];
    yd = yd < 0.0 ? 0.0 : yd > 1.0 ? 1.0 : yd;
    const double a = d->robot_dyn && !hg->kin ? dJointGetHingeAngle(hg->j) : d->angle[hg->link];
    double v = alpha * (yd - (a - hg->lo) / (hg->hi - hg->lo));
    d->vel[i] = v > vmax ? vmax : v < -vmax ? -vmax : v;
  }
}

/* ODE activates a stop only when a joint starts a sub-step at or beyond it, so a joint hit
 * hard overshoots by up to one sub-step of travel. A fast joint that would cross its stop
 * within this sub-step at its current rate gets the stop at its current angle instead: it
 * stops a little early rather than late. */
static void speculative_stops(dynInternal *d, double vmax) {
  for (int i = 0; i < d->nhinge; i++) {
    dynHinge *hg = &d->hinge[i];
    if (hg->kin) continue;
    const double rate = dJointGetHingeAngleRate(hg->j);
    double lo = hg->lo - d->stop_margin, hi = hg->hi + d->stop_margin;
    /* only joints thrown faster than any servo moves them: a joint resting on a stop gets
     * ODE's explicit motor kick (fudge_factor) when powered away from it */
    if (fabs(rate) > 1.5 * vmax) {
      const double a = dJointGetHingeAngle(hg->j), r = rate * d->h;
      if (a + r < lo && a > lo) lo = a;
      if (a + r > hi && a < hi) hi = a;
    }
    if (lo != hg->lo_set || hi != hg->hi_set) st__dyn_set_stops(hg, lo, hi);
  }
}

/* ODE's step of the world: quickstep with the world's own generator, or step (with the LCP
 * reduction of dynamics.lcp = schur); the contact joints emptied after it. *messages: ODE's
 * warnings during it. Returns 0 when ODE ran out of memory. */
static int ode_step(dynInternal *d, unsigned long *messages) {
  int ok;
  st__ode_messages_begin(); /* ODE's warnings of this world's step are counted, not printed */
  const unsigned long msg0 = st__ode_messages();
  if (d->solver == ST_DYN_QUICKSTEP) {
    st__ode_rand_begin(d->rand_state);
    ok = dWorldQuickStep(d->world, d->h);
    d->rand_state = st__ode_rand_end();
  } else {
    if (d->lcp) st__lcp_begin(d->lcp);
    ok = dWorldStep(d->world, d->h);
    if (d->lcp) st__lcp_end();
  }
  *messages = st__ode_messages() - msg0;
  st__ode_messages_end();
  dJointGroupEmpty(d->cgroup);
  d->messages += (long)*messages;
  return ok;
}

/* free motion: the object alone in ODE's step, its contacts ORed into c */
static int free_substep(stWorld *w, stContacts *c) {
  dynInternal *d = w->internal_;
  d->ncfb = 0;
  d->kin_static_hit = d->nhinge;
  st__dyn_collide_object(w, 1, c);
  unsigned long messages;
  return ode_step(d, &messages);
}

/* the robot in ODE's step: contacts (ORed into c), then the stepper, taken again from the saved
 * state while one of the redo strategies asks (lib/world/dyn_redo.c, in that order: softer
 * constraints after a solver failure, an adaptive joint's torque, a saturated motor row); then
 * the constraints as they were */
static int robot_substep(stWorld *w, stContacts *c) {
  dynInternal *d = w->internal_;
  const int motors = d->def.motor_active_set && d->solver == ST_DYN_STEP, adapt = d->nadapt > 0;
  const dSurfaceParameters surface = d->surface;
  int softer_tries = 0, adaptive_tries = 0, motor_tries = 0, ok;
  st__dyn_save_bodies(d, d->saved);
  for (;;) {
    d->ncfb = 0;
    d->kin_static_hit = d->nhinge;
    st__dyn_collide_all(w, 1, c);
    if (motors) st__dyn_motors_prepare(d);
    if (adapt) st__dyn_adaptive_prepare(d);
    unsigned long messages;
    ok = ode_step(d, &messages);
    if (!ok || !(st__dyn_redo_softer(d, messages, &softer_tries) ||
                 (adapt && st__dyn_redo_adaptive(w, d, &adaptive_tries)) ||
                 (motors && st__dyn_redo_motors(d, &motor_tries))))
      break;
    st__dyn_restore_bodies(d, d->saved);
  }
  d->surface = surface;
  dWorldSetCFM(d->world, d->def.cfm);
  return ok;
}

/* 1 when every command is finite; else the world becomes unstable */
static int commands_ok(stWorld *w, const double *y) {
  for (int k = 0; k < ST_NDOF; k++)
    if (!isfinite(y[k])) {
      st__dyn_set_unstable(w, "command y[%d] = %g is not finite", k, y[k]);
      return 0;
    }
  return 1;
}

/* one sub-step: the servo velocities, then free motion while nothing can touch within it (the
 * servos are exact: they never saturate without contact; the robot moves kinematically and
 * ODE steps the object alone), else the robot in ODE's step. Contacts are ORed into c. Returns
 * 0 when the world became unstable. */
static int substep(stWorld *w, const double *y, stContacts *c) {
  dynInternal *d = w->internal_;
  servo(w, y);
  if (!d->robot_dyn && st__dyn_robot_near(w, d->def.contact_margin)) st__dyn_robot_to_ode(w);
  if (d->robot_dyn) {
    if (d->nadapt) st__dyn_adaptive_update(d);
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) dJointSetHingeParam(d->hinge[i].j, dParamVel, d->vel[i]);
    if (d->nkin) st__dyn_place_kinematic(w);
    speculative_stops(d, w->robot->max_velocity);
    d->dyn_substeps++;
    d->dyn_hinge_substeps += d->nhinge - d->nkin;
  } else {
    for (int i = 0; i < d->nhinge; i++) d->angle[d->hinge[i].link] += d->vel[i] * d->h;
    st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  }
  const int ok = d->robot_dyn ? robot_substep(w, c) : free_substep(w, c);
  if (d->robot_dyn) /* the exact servos advance as in free motion */
    for (int i = 0; i < d->nkin; i++) d->angle[d->hinge[i].link] += d->vel[i] * d->h;
  if (!ok) {
    st__dyn_set_unstable(w, "ODE could not allocate its step memory");
    return 0;
  }
  return st__dyn_bodies_ok(w);
}

/* 1 when every joint is within its range by limit_tolerance; else the world becomes unstable */
static int joints_in_range(stWorld *w) {
  dynInternal *d = w->internal_;
  for (int i = 0; i < d->nhinge; i++) {
    const dynHinge *hg = &d->hinge[i];
    const double a = d->angle[hg->link];
    const double tol = d->limit_tolerance;
    if (!isfinite(a) || a < hg->lo - tol || a > hg->hi + tol) {
      st__dyn_set_unstable(w, "joint '%s' at %.2f deg, beyond its range %.2f..%.2f deg by more "
                           "than limit_tolerance_deg %.2f", w->robot->model->jnt_name[hg->link],
                           a / ST_DEG, hg->lo / ST_DEG, hg->hi / ST_DEG,
                           d->def.limit_tolerance_deg);
      return 0;
    }
  }
  return 1;
}

void st__dyn_step(stWorld *w, const double *y) {
  dynInternal *d = w->internal_;
  if (d->unstable || !commands_ok(w, y)) return;
  st__ode_init();
  stContacts acc;
  memset(&acc, 0, sizeof acc);
  for (int s = 0; s < d->nsub; s++) {
    stContacts c;
    memset(&c, 0, sizeof c);
    const int fine = substep(w, y, &c);
    /* the state after this control step's previous sub-step */
    if (s > 0) st__dyn_contacts_or(&acc, &c);
    if (!fine) break;
  }
  w->step++;
  if (d->unstable) return;
  /* contacts of the final state (no joints: the next sub-step finds its own) */
  stContacts c;
  memset(&c, 0, sizeof c);
  if (d->robot_dyn) st__dyn_collide_all(w, 0, &c);
  else st__dyn_collide_object(w, 0, &c);
  st__dyn_contacts_or(&acc, &c);
  w->contacts = acc;
  st__dyn_read_state(w);
  if (!joints_in_range(w)) return;
  /* back to free motion once the robot is clear of the table and the object */
  if (d->robot_dyn && d->def.free_motion && !st__dyn_robot_near(w, d->def.contact_margin))
    st__dyn_robot_to_free(w, 1);
}
