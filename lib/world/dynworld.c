/* SPDX-License-Identifier: MIT
 * Dynamic world backend (thesis §2.1, SPEC §3; lib/world/world_backend.h): the robot, the table and
 * the object as an ODE world. See selftalk/world.h for the contract and docs/PROTOCOL.md
 * ("Dynamic mode") for the physical parameters, their reasons and the measurements behind
 * them. The geometries come from lib/world/world_geom.c, shared with the kinematic world.
 *
 * Bodies: every link moved by a revolute joint starts an ODE body; links on fixed joints
 * (massless frames, the knuckles, torso_2, l_upper_arm) are folded into the body of their
 * parent (masses and inertias summed about the common centre of mass, geometries attached
 * with offsets). The root link and its fixed children are the static world. An ODE body's
 * origin is its centre of mass and its axes are those of its first link. Hinge angles are
 * measured from the zero pose the world is built in.
 *
 * Stepping: while no robot geometry can reach the table or the object within a sub-step
 * ("free motion"), the joints follow the servo law exactly (an unsaturated velocity servo
 * reaches its target velocity within one sub-step, and without contact none saturates: see
 * PROTOCOL), the robot's bodies are disabled and ODE steps the object alone. Near contact the
 * robot's bodies join ODE's step with the velocities the servos give them, and every sub-step
 * is ODE dynamics: hinge motors with bounded torque, stops, contacts; except for the joints of
 * dynamics.kinematic_joints, exact servos at all times, whose links are kinematic bodies.
 *
 * Determinism: nothing here depends on anything but the world's own state: collisions are
 * run pair by pair in a fixed order (no ODE space, whose geom lists reorder as geoms move);
 * each world has its own ODE threading implementation (ODE's default one is one object shared
 * by the whole process); quickstep's row shuffling draws from the world's own generator state
 * (lib/world/ode_rand.c), loaded before and stored after every quickstep. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <ode/ode.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "model/model_internal.h"
#include "world/ode_lcp.h"
#include "world/ode_util.h"
#include "selftalk/rng.h"
#include "world/world_backend.h"
#include "world/world_geom.h"

#include <stdint.h>

enum { ST_DYN_MAX_CFB = 256 }; /* contact forces kept per sub-step for adaptive_joints */

/* what a robot geometry (geoms.g[i] for model geometry i) touches */
typedef struct dynGeom {
  int link;      /* model body the geometry belongs to */
  int dyn;       /* on an ODE body (0: part of the static root) */
  int is_arm;    /* counts for arm_table */
  int touch;     /* touch sensor, -1 for none */
} dynGeom;

typedef struct dynHinge {
  dJointID j;
  int link;      /* model body moved by the joint */
  int dof;
  double lo, hi; /* range used for qhat (rad); the stops are stop_margin outside */
  double lo_set, hi_set; /* stops currently set in ODE */
  int kin;       /* in dynamics.kinematic_joints: an exact servo (joint disabled, body kinematic) */
  double fmax;   /* motor torque limit, N m */
  int bounded;   /* motor_active_set: the motor row enters the LCP bounded (it saturated) */
  int free_row;  /* motor_active_set: this sub-step's motor row is unbounded (to be checked) */
  double r1[3], axis[3]; /* motor_active_set: anchor from the child's centre, axis (step start) */
  dJointFeedback fb;     /* motor_active_set: the hinge's forces on its child after a step */
} dynHinge;

typedef struct dynInternal {
  stWorldHead head;
  stDynDef def;
  int solver;               /* in use (ST_DYN_*) */
  int nsub;                 /* sub-steps per control step */
  double h;                 /* sub-step, s */
  dWorldID world;
  dThreadingImplementationID threading; /* the world's own (ODE's default one is shared by
                                           every world of the process and not thread-safe) */
  dJointGroupID cgroup;     /* contact joints */
  dSurfaceParameters surface;
  int ngroup;               /* ODE bodies of the robot */
  dBodyID *gbody;
  int *glink;               /* first (root) link of each body */
  double (*gcom)[3];        /* centre of mass of each body in its first link's frame */
  int *link_group;          /* per model body: its ODE body, -1 for the static root */
  double (*link_R)[9];      /* per model body: frame in its ODE body's first-link frame */
  double (*link_p)[3];
  int nhinge;
  dynHinge *hinge;
  int nkin;                 /* the first nkin hinges are exact servos (dynamics.kinematic_joints) */
  stRobotGeoms geoms;       /* the robot's geometries */
  dynGeom *geom;            /* (geoms.n) what each of them touches */
  dBodyID ball;
  stSceneGeoms scene;       /* the table, and the object's sphere and base on the ball body */
  dGeomID floor;
  double table_aabb[6];
  int obj_table;            /* object-table collision on */
  int robot_dyn;            /* the robot's bodies take part in ODE's step (else: free motion) */
  uint64_t seed;
  uint32_t rand_state;      /* quickstep's shuffling generator (per trial) */
  double *angle;            /* joint angle per model body (free motion: the state itself) */
  double *vel;              /* servo velocity of each hinge in the current sub-step (rad/s) */
  long dyn_substeps;        /* sub-steps with the robot in ODE since the reset */
  long dyn_hinge_substeps;  /* ... summed over them: the hinges in ODE's step */
  long points[ST_DYN_PAIR_COUNT]; /* contact joints made since the reset, by pair kind */
  dContactGeom cg[64];
  long messages;            /* ODE warnings (e.g. "LCP internal error") since the reset */
  long retries;             /* sub-steps redone after such a warning */
  long motor_redos;         /* motor_active_set: sub-steps redone because a motor saturated */
  /* dynamics.adaptive_joints: hinges nkin0 .. nkin0 + nadapt - 1 (the chain after the exact
   * servos of kinematic_joints) are exact servos while the torque they need stays within their
   * limit; the first nkin hinges are kinematic now (nkin0 <= nkin <= nkin0 + nadapt) */
  int nkin0, nadapt;
  int *want_kin;            /* per hinge: its motor needed little torque in the last sub-step */
  double (*vprev)[6];       /* per body: linear and angular velocity in the previous sub-step */
  double (*cpos)[3];        /* per body: centre of mass at the start of the step */
  dJointFeedback *cfb;      /* contacts on adaptive kinematic bodies: their forces */
  int *cfb_body, *cfb_side; /* ... on which body, as ODE's body 1 (0) or body 2 (1) */
  int ncfb;
  int kin_static_hit;       /* lowest adaptive kinematic body touching the table or the floor
                               (no contact joint can act there), or nhinge for none */
  stLcp *lcp;               /* dynamics.lcp = schur: the reduction's scratch; else NULL */
  long adapt_redos;         /* sub-steps redone because an adaptive joint needed more torque */
  double (*saved)[13];      /* body states before the current sub-step */
  int unstable;
  char reason[192];
} dynInternal;

static const stWorldBackend dyn_backend;

static int finite3(const dReal *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* ---- the interposition check ----------------------------------------------------------- */

/* quickstep's shuffling draws of the probe world in ODE 0.16.2 (12 constraint rows, 20
 * iterations: the rows are shuffled at iterations 8 and 16, a draw per row but the last) */
enum { PROBE_QUICKSTEP_DRAWS = 22 };

static pthread_once_t g_rand_once = PTHREAD_ONCE_INIT;
static const char *g_rand_why; /* NULL: quickstep draws from the world's own generator */
static char g_rand_why_buf[512];

/* one quickstep of the probe world, drawing from the library's generator (the program's own
 * generator is not touched): ODE 0.16.2's shuffling must reach it, that many times */
static void rand_check(void) {
  if (!st__ode_rand_bound()) {
    g_rand_why = "ODE's dRandInt cannot reach the library's per-thread generator in a program "
                 "linked with the shared library, which exports only the st_ API (link the "
                 "static library, as the apps do)";
    return;
  }
  const unsigned long before = st__ode_rand_calls();
  st__ode_rand_begin(0);
  st__ode_messages_begin();
  st__ode_probe_step(1);
  st__ode_messages_end();
  st__ode_rand_end();
  const unsigned long draws = st__ode_rand_calls() - before;
  if (!draws)
    g_rand_why = "ODE's dRandInt does not reach the library's per-thread generator in this "
                 "build (ODE binds it internally)";
  else if (draws != PROBE_QUICKSTEP_DRAWS) {
    snprintf(g_rand_why_buf, sizeof g_rand_why_buf, "ODE's quickstep drew %lu numbers in the "
             "probe step where ODE 0.16.2 draws %d: the ODE loaded (%s) is not the one the "
             "per-thread generator was written for", draws, (int)PROBE_QUICKSTEP_DRAWS,
             dGetConfiguration());
    g_rand_why = g_rand_why_buf;
  }
}

/* ---- configuration ----------------------------------------------------------------------- */

void st_dyn_def_from_config(const stConfig *c, stDynDef *d) {
  ST_ASSERT(c && d);
  memset(d, 0, sizeof *d);
  d->solver = c->dynamics_solver;
  d->substep = c->dynamics_substep;
  d->iterations = c->dynamics_iterations;
  d->gravity = c->dynamics_gravity;
  d->friction = c->dynamics_friction;
  d->table_friction = c->dynamics_table_friction;
  d->erp = c->dynamics_erp;
  d->cfm = c->dynamics_cfm;
  d->contact_erp = c->dynamics_contact_erp;
  d->contact_cfm = c->dynamics_contact_cfm;
  d->surface_layer = c->dynamics_surface_layer;
  d->sor_w = c->dynamics_sor_w;
  d->max_contacts = c->dynamics_max_contacts;
  d->effort_scale = c->dynamics_effort_scale;
  d->fall_margin = c->dynamics_fall_margin;
  d->floor_z = c->dynamics_floor_z;
  d->unstable_speed = c->dynamics_unstable_speed;
  d->unstable_spin = c->dynamics_unstable_spin;
  d->limit_tolerance = c->dynamics_limit_tolerance_deg * ST_DEG;
  d->stop_margin = c->dynamics_stop_margin_deg * ST_DEG;
  d->fudge_factor = c->dynamics_fudge_factor;
  d->free_motion = c->dynamics_free_motion;
  d->contact_margin = c->dynamics_contact_margin;
  d->motor_active_set = c->dynamics_motor_active_set;
  snprintf(d->adaptive_joints, sizeof d->adaptive_joints, "%s", c->dynamics_adaptive_joints);
  d->adaptive_limit = c->dynamics_adaptive_limit;
  d->lcp = c->dynamics_lcp;
  snprintf(d->kinematic_joints, sizeof d->kinematic_joints, "%s", c->dynamics_kinematic_joints);
}

/* value checks before anything reaches ODE (its dError would end the process) */
static int check_def(const stDynDef *d, double dt, int *nsub, char *err, size_t errsz) {
#define BAD(...) return st__errf(err, errsz, __VA_ARGS__), -1
  if (d->solver < 0 || d->solver >= ST_DYN_SOLVER_COUNT)
    BAD("dynamics.solver: %d (expected quickstep or step)", d->solver);
  if (!(d->substep > 0.0 && d->substep <= dt))
    BAD("dynamics.substep: %g s (expected > 0 and <= the control step %g s)", d->substep, dt);
  double n = floor(dt / d->substep + 0.5);
  if (!(fabs(n * d->substep - dt) <= 1e-9 * dt))
    BAD("dynamics.substep: %g s does not divide the control step %g s (expected control_dt / "
        "substep to be a whole number)", d->substep, dt);
  *nsub = (int)n;
  if (d->iterations < 1) BAD("dynamics.iterations: %d (expected >= 1)", d->iterations);
  if (!(d->gravity >= 0.0 && d->gravity < 1e6))
    BAD("dynamics.gravity: %g (expected >= 0)", d->gravity);
  if (!(d->friction >= 0.0 && d->friction < 1e6))
    BAD("dynamics.friction: %g (expected >= 0)", d->friction);
  if (!(d->table_friction >= 0.0 && d->table_friction < 1e6))
    BAD("dynamics.table_friction: %g (expected >= 0)", d->table_friction);
  if (!(d->erp >= 0.0 && d->erp <= 1.0)) BAD("dynamics.erp: %g (expected 0..1)", d->erp);
  if (!(d->cfm >= 0.0 && d->cfm <= 1.0)) BAD("dynamics.cfm: %g (expected 0..1)", d->cfm);
  if (!(d->contact_erp >= 0.0 && d->contact_erp <= 1.0))
    BAD("dynamics.contact_erp: %g (expected 0..1)", d->contact_erp);
  if (!(d->contact_cfm >= 0.0 && d->contact_cfm <= 1.0))
    BAD("dynamics.contact_cfm: %g (expected 0..1)", d->contact_cfm);
  if (!(d->surface_layer >= 0.0 && d->surface_layer <= 0.1))
    BAD("dynamics.surface_layer: %g (expected 0..0.1 m)", d->surface_layer);
  if (!(d->sor_w > 0.0 && d->sor_w <= 2.0)) BAD("dynamics.sor_w: %g (expected 0..2)", d->sor_w);
  if (d->max_contacts < 1 || d->max_contacts > 64)
    BAD("dynamics.max_contacts: %d (expected 1..64)", d->max_contacts);
  if (!(d->effort_scale >= 0.0 && d->effort_scale < 1e6))
    BAD("dynamics.effort_scale: %g (expected >= 0)", d->effort_scale);
  if (!(d->fall_margin >= 0.0 && d->fall_margin < 1e6))
    BAD("dynamics.fall_margin: %g (expected >= 0)", d->fall_margin);
  if (!(d->stop_margin >= 0.0 && d->stop_margin < 0.5))
    BAD("dynamics.stop_margin_deg: %g (expected 0..28)", d->stop_margin / ST_DEG);
  if (!(d->fudge_factor >= 0.0 && d->fudge_factor <= 1.0))
    BAD("dynamics.fudge_factor: %g (expected 0..1)", d->fudge_factor);
  if (!(d->contact_margin >= 0.0 && d->contact_margin <= 1.0))
    BAD("dynamics.contact_margin: %g (expected 0..1 m)", d->contact_margin);
  if (!(d->adaptive_limit > 0.0 && d->adaptive_limit <= 1.0))
    BAD("dynamics.adaptive_limit: %g (expected > 0 and <= 1)", d->adaptive_limit);
  if (!d->adaptive_joints[0] && d->adaptive_limit != ST_DYN_ADAPTIVE_LIMIT)
    BAD("dynamics.adaptive_limit: %g with dynamics.adaptive_joints empty (expected the default "
        "%g: it acts on the adaptive joints only)", d->adaptive_limit, ST_DYN_ADAPTIVE_LIMIT);
  if (d->motor_active_set && d->solver != ST_DYN_STEP)
    BAD("dynamics.motor_active_set: on with solver quickstep (expected solver step: it acts on "
        "the direct solver's LCP only)");
  if (d->lcp < 0 || d->lcp >= ST_DYN_LCP_COUNT)
    BAD("dynamics.lcp: %d (expected dense or schur)", d->lcp);
  if (d->lcp == ST_DYN_LCP_SCHUR && d->solver != ST_DYN_STEP)
    BAD("dynamics.lcp: schur with solver quickstep (expected solver step: quickstep solves no "
        "LCP of its own)");
  if (!isfinite(d->floor_z)) BAD("dynamics.floor_z: %g (expected a finite height)", d->floor_z);
  if (!(d->unstable_speed > 0.0) || !(d->unstable_spin > 0.0) || !(d->limit_tolerance >= 0.0))
    BAD("dynamics.unstable_speed / unstable_spin / limit_tolerance_deg: %g / %g / %g (expected "
        "> 0, > 0, >= 0)", d->unstable_speed, d->unstable_spin, d->limit_tolerance / ST_DEG);
  return 0;
#undef BAD
}

/* ---- creation ---------------------------------------------------------------------------- */

/* inertia about the centre of mass must be symmetric positive definite */
static int inertia_ok(const double *I) {
  for (int i = 0; i < 9; i++)
    if (!isfinite(I[i])) return 0;
  double m1 = I[0], m2 = I[0] * I[4] - I[1] * I[3];
  double m3 = I[0] * (I[4] * I[8] - I[5] * I[7]) - I[1] * (I[3] * I[8] - I[5] * I[6]) +
              I[2] * (I[3] * I[7] - I[4] * I[6]);
  return m1 > 0 && m2 > 0 && m3 > 0;
}

/* links into bodies: a revolute joint starts one, a fixed joint folds its child into its
 * parent's (link_R, link_p: the child's frame in the first link's) */
static void group_links(dynInternal *d, const stModel *m) {
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  d->link_group[0] = -1;
  memcpy(d->link_R[0], I3, sizeof I3);
  for (int b = 1; b < m->nbody; b++) {
    const int pb = m->body_parent[b];
    if (m->jnt_type[b] == ST_JOINT_FIXED) {
      d->link_group[b] = d->link_group[pb];
      st__mat3_mul(d->link_R[pb], m->jnt_rot[b], d->link_R[b]);
      double o[3];
      st__mat3_vec(d->link_R[pb], m->jnt_pos[b], o);
      for (int i = 0; i < 3; i++) d->link_p[b][i] = d->link_p[pb][i] + o[i];
    } else {
      d->glink[d->ngroup] = b;
      d->link_group[b] = d->ngroup++;
      memcpy(d->link_R[b], I3, sizeof I3);
    }
  }
}

/* world poses (w->R, w->p) at zero joint angles: hinges measure their angle from this pose */
static void zero_pose(stWorld *w, dynInternal *d) {
  for (int b = 0; b < w->robot->model->nbody; b++) d->angle[b] = 0.0;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
}

/* mass M of body g, the sum of its links', and their common centre of mass C in the first
 * link's frame */
static stStatus body_mass(const dynInternal *d, const stModel *m, int g, double *M_out,
                          double C[3], char *err, size_t errsz) {
  double M = 0;
  C[0] = C[1] = C[2] = 0;
  for (int b = 0; b < m->nbody; b++) {
    if (d->link_group[b] != g || !(m->body_mass[b] > 0)) continue;
    double c[3];
    st__mat3_vec(d->link_R[b], m->body_com[b], c);
    for (int i = 0; i < 3; i++) C[i] += m->body_mass[b] * (c[i] + d->link_p[b][i]);
    M += m->body_mass[b];
  }
  const int gl = d->glink[g];
  if (!(M > 0 && isfinite(M))) {
    st__errf(err, errsz, "link '%s' (joint '%s'): no mass on a moving link and its fixed "
             "children (expected mass > 0)", m->body_name[gl], m->jnt_name[gl]);
    return ST_ERR_MODEL;
  }
  for (int i = 0; i < 3; i++) C[i] /= M;
  *M_out = M;
  return ST_OK;
}

/* inertia I of body g about its centre of mass C, in the first link's axes: its links'
 * inertias rotated and moved there (parallel axes) */
static stStatus body_inertia(const dynInternal *d, const stModel *m, int g, const double C[3],
                             double I[9], char *err, size_t errsz) {
  for (int i = 0; i < 9; i++) I[i] = 0;
  for (int b = 0; b < m->nbody; b++) {
    if (d->link_group[b] != g || !(m->body_mass[b] > 0)) continue;
    const double mb = m->body_mass[b];
    double c[3], T[9], RI[9], Rt[9];
    st__mat3_vec(d->link_R[b], m->body_com[b], c);
    for (int i = 0; i < 3; i++) c[i] += d->link_p[b][i] - C[i];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) Rt[3 * i + j] = d->link_R[b][3 * j + i];
    st__mat3_mul(d->link_R[b], m->body_inertia[b], RI);
    st__mat3_mul(RI, Rt, T); /* R I R^T */
    const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        I[3 * i + j] += T[3 * i + j] + mb * ((i == j ? c2 : 0.0) - c[i] * c[j]);
  }
  if (!inertia_ok(I)) {
    st__errf(err, errsz, "link '%s': inertia of the moving body is not positive definite "
             "(expected a physical inertia tensor)", m->body_name[d->glink[g]]);
    return ST_ERR_MODEL;
  }
  return ST_OK;
}

static void place_body(stWorld *w, int g);

/* an ODE body per group of links, with its mass, where the zero pose puts it */
static stStatus create_bodies(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  for (int g = 0; g < d->ngroup; g++) {
    double M, C[3], I[9];
    stStatus st = body_mass(d, w->robot->model, g, &M, C, err, errsz);
    if (!st) st = body_inertia(d, w->robot->model, g, C, I, err, errsz);
    if (st) return st;
    memcpy(d->gcom[g], C, sizeof C);
    d->gbody[g] = dBodyCreate(d->world);
    dMass ms;
    dMassSetZero(&ms);
    dMassSetParameters(&ms, M, 0, 0, 0, I[0], I[4], I[8], I[1], I[2], I[5]);
    dBodySetMass(d->gbody[g], &ms);
    place_body(w, g);
  }
  return ST_OK;
}

/* the hinge of link b: anchored at the joint origin, axis from the model, stops stop_margin
 * outside the qhat range, a velocity motor of torque up to the URDF effort times effort_scale */
static stStatus create_hinge(stWorld *w, dynInternal *d, int b, char *err, size_t errsz) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  const double lo = r->body_range[b][0], hi = r->body_range[b][1];
  const double effort = m->jnt_effort[b] * d->def.effort_scale;
  const double *a = m->jnt_axis[b];
  const double an = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(isfinite(lo) && isfinite(hi) && lo < hi && hi - lo < 2 * ST_PI) ||
      !(effort >= 0 && isfinite(effort)) || !(an > 1e-9 && isfinite(an))) {
    st__errf(err, errsz, "joint '%s': range %g..%g rad, effort %g N m, axis norm %g (expected "
             "a finite range narrower than 360 degrees, a finite effort >= 0 and an axis)",
             m->jnt_name[b], lo, hi, effort, an);
    return ST_ERR_MODEL;
  }
  const int pg = d->link_group[m->body_parent[b]];
  dJointID j = dJointCreateHinge(d->world, 0);
  dJointAttach(j, d->gbody[d->link_group[b]], pg >= 0 ? d->gbody[pg] : 0);
  dJointSetHingeAnchor(j, w->p[b][0], w->p[b][1], w->p[b][2]);
  double ax[3];
  st__mat3_vec(w->R[b], a, ax);
  dJointSetHingeAxis(j, ax[0], ax[1], ax[2]);
  dJointSetHingeParam(j, dParamLoStop, lo - d->def.stop_margin);
  dJointSetHingeParam(j, dParamHiStop, hi + d->def.stop_margin);
  dJointSetHingeParam(j, dParamFudgeFactor, d->def.fudge_factor);
  dJointSetHingeParam(j, dParamStopERP, d->def.erp);
  dJointSetHingeParam(j, dParamStopCFM, d->def.cfm);
  dJointSetHingeParam(j, dParamCFM, d->def.cfm);
  dJointSetHingeParam(j, dParamVel, 0.0);
  dJointSetHingeParam(j, dParamFMax, effort);
  dynHinge *hg = &d->hinge[d->nhinge++];
  hg->fmax = effort;
  if (d->def.motor_active_set) dJointSetFeedback(j, &hg->fb);
  hg->j = j;
  hg->link = b;
  hg->dof = r->body_dof[b];
  hg->lo = lo;
  hg->hi = hi;
  hg->lo_set = lo - d->def.stop_margin;
  hg->hi_set = hi + d->def.stop_margin;
  return ST_OK;
}

static stStatus create_hinges(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  const stModel *m = w->robot->model;
  for (int b = 1; b < m->nbody; b++) {
    if (m->jnt_type[b] != ST_JOINT_REVOLUTE) continue;
    stStatus st = create_hinge(w, d, b, err, errsz);
    if (st) return st;
  }
  return ST_OK;
}

/* geometry i on its body, with the offset of its link and of the body's centre of mass (on
 * the static root: placed in the world, whose frame the root's is) */
static void attach_geom(stWorld *w, dynInternal *d, int i) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  const int l = m->geom_body[i], g = d->link_group[l];
  dGeomID geom = d->geoms.g[i];
  double gp[3], gR[9];
  st__mat3_vec(d->link_R[l], m->geom_pos[i], gp);
  for (int k = 0; k < 3; k++) gp[k] += d->link_p[l][k];
  st__mat3_mul(d->link_R[l], m->geom_rot[i], gR);
  dMatrix3 Ro;
  st__mat3_to_ode(gR, Ro);
  if (g >= 0) {
    dGeomSetBody(geom, d->gbody[g]);
    dGeomSetOffsetRotation(geom, Ro);
    dGeomSetOffsetPosition(geom, gp[0] - d->gcom[g][0], gp[1] - d->gcom[g][1],
                           gp[2] - d->gcom[g][2]);
  } else {
    dGeomSetRotation(geom, Ro);
    dGeomSetPosition(geom, gp[0], gp[1], gp[2]);
  }
  dynGeom *dg = &d->geom[i];
  dg->link = l;
  dg->dyn = g >= 0;
  dg->is_arm = r->body_is_arm[l];
  dg->touch = r->body_touch[l];
}

/* the robot's geometries (lib/world/world_geom.c), each attached */
static stStatus create_geoms(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  stStatus st = st__robot_geoms_create(w->robot->model, 1, &d->geoms, err, errsz);
  if (st) return st;
  for (int i = 0; i < d->geoms.n; i++) attach_geom(w, d, i);
  return ST_OK;
}

/* scene: table, floor, and the object (sphere + flattened base, one body) */
static stStatus create_scene(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  const stScene *sc = w->scene;
  if (!(sc->obj_radius > 0 && sc->obj_mass > 0 && sc->base_radius >= 0 && sc->base_height >= 0 &&
        sc->base_height <= 2 * sc->obj_radius)) {
    st__errf(err, errsz, "scene: object radius %g, mass %g, base %g x %g (expected positive "
             "radius and mass, a base inside the sphere's height)", sc->obj_radius, sc->obj_mass,
             sc->base_radius, sc->base_height);
    return ST_ERR_RANGE;
  }
  const double *lo = sc->table_lo, *hi = sc->table_hi;
  if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2])) {
    st__errf(err, errsz, "scene: empty table box (expected min < max on every axis)");
    return ST_ERR_RANGE;
  }
  st__scene_geoms_create(sc, &d->scene);
  dGeomGetAABB(d->scene.table, d->table_aabb);
  d->floor = dCreatePlane(0, 0, 0, 1, d->def.floor_z);
  d->ball = dBodyCreate(d->world);
  dMass ms;
  dMassSetSphereTotal(&ms, sc->obj_mass, sc->obj_radius);
  dBodySetMass(d->ball, &ms);
  dGeomSetBody(d->scene.ball, d->ball);
  if (d->scene.base) {
    dGeomSetBody(d->scene.base, d->ball);
    dGeomSetOffsetPosition(d->scene.base, 0, 0, -sc->obj_radius + 0.5 * sc->base_height);
  }
  return ST_OK;
}

/* dynamics.kinematic_joints: those hinges become exact servos (joint disabled, body kinematic).
 * They must be the chain's first hinges (hinges are in model order, parents first), so that
 * every kinematic body's parent is the static root or kinematic itself. */
static stStatus mark_kinematic(dynInternal *d, const stModel *m, char *err, size_t errsz) {
  enum { MAX_KIN = 64 };
  char names[MAX_KIN][ST_NAME_MAX];
  const int n = st__split_names(d->def.kinematic_joints, names, MAX_KIN);
  if (n < 0 || n > d->nhinge || n > MAX_KIN) {
    st__errf(err, errsz, "dynamics.kinematic_joints: '%s' (expected at most the model's %d hinge "
             "names, each shorter than %d characters)", d->def.kinematic_joints, d->nhinge,
             ST_NAME_MAX);
    return ST_ERR_RANGE;
  }
  for (int k = 0; k < n; k++) {
    const char *need = m->jnt_name[d->hinge[k].link];
    int listed = 0;
    for (int j = 0; j < n; j++) listed |= !strcmp(names[j], need);
    if (!listed) {
      st__errf(err, errsz, "dynamics.kinematic_joints: '%s' names %d joints but not '%s' "
               "(expected the chain's first %d hinges, each once)", d->def.kinematic_joints, n,
               need, n);
      return ST_ERR_RANGE;
    }
  }
  for (int k = 0; k < n; k++) {
    d->hinge[k].kin = 1;
    dJointDisable(d->hinge[k].j);
    dBodySetKinematic(d->gbody[k]);
  }
  d->nkin = n;
  return ST_OK;
}

/* dynamics.adaptive_joints: hinges after those of kinematic_joints, in chain order, that are
 * exact servos while the torque they need stays within their limit (set_kin switches them) */
static stStatus mark_adaptive(dynInternal *d, const stModel *m, char *err, size_t errsz) {
  enum { MAX_AD = 16 };
  char names[MAX_AD][ST_NAME_MAX];
  const int n = st__split_names(d->def.adaptive_joints, names, MAX_AD);
  d->nkin0 = d->nkin;
  if (n < 0 || n > MAX_AD || d->nkin + n > d->nhinge) {
    st__errf(err, errsz, "dynamics.adaptive_joints: '%s' (expected at most %d hinge names, each "
             "shorter than %d characters)", d->def.adaptive_joints, MAX_AD, ST_NAME_MAX);
    return ST_ERR_RANGE;
  }
  for (int k = 0; k < n; k++) {
    const int i = d->nkin + k;
    const char *need = m->jnt_name[d->hinge[i].link];
    const int pg = d->link_group[m->body_parent[d->hinge[i].link]];
    if (strcmp(names[k], need) || pg != i - 1 || d->hinge[i].fmax <= 0.0) {
      st__errf(err, errsz, "dynamics.adaptive_joints: '%s': joint %d is '%s' (expected the %d "
               "powered hinges that follow dynamics.kinematic_joints along the chain, in order: "
               "'%s' here)", d->def.adaptive_joints, k + 1, names[k], n, need);
      return ST_ERR_RANGE;
    }
  }
  d->nadapt = n;
  if (n && d->solver != ST_DYN_STEP) {
    st__errf(err, errsz, "dynamics.adaptive_joints: '%s' with solver quickstep (expected solver "
             "step)", d->def.adaptive_joints);
    return ST_ERR_RANGE;
  }
  for (int g = 0; g < d->ngroup; g++) dBodySetData(d->gbody[g], (void *)(intptr_t)(g + 1));
  if (n)
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) dJointSetFeedback(d->hinge[i].j, &d->hinge[i].fb);
  return ST_OK;
}

/* the whole ODE world, phase by phase */
static stStatus build(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  group_links(d, w->robot->model);
  zero_pose(w, d);
  stStatus st = create_bodies(w, d, err, errsz);
  if (!st) st = create_hinges(w, d, err, errsz);
  if (!st) st = create_geoms(w, d, err, errsz);
  if (!st) st = create_scene(w, d, err, errsz);
  if (!st) st = mark_kinematic(d, w->robot->model, err, errsz);
  if (!st) st = mark_adaptive(d, w->robot->model, err, errsz);
  return st;
}

/* the per-body and per-geometry arrays; 0 when out of memory */
static int alloc_arrays(dynInternal *d, const stModel *m) {
  const size_t nb = (size_t)m->nbody;
  d->gbody = calloc(nb, sizeof *d->gbody);
  d->glink = calloc(nb, sizeof *d->glink);
  d->gcom = calloc(nb, sizeof *d->gcom);
  d->link_group = calloc(nb, sizeof *d->link_group);
  d->link_R = calloc(nb, sizeof *d->link_R);
  d->link_p = calloc(nb, sizeof *d->link_p);
  d->hinge = calloc(nb, sizeof *d->hinge);
  d->angle = calloc(nb, sizeof *d->angle);
  d->vel = calloc(nb, sizeof *d->vel);
  d->saved = calloc(nb + 1, sizeof *d->saved);
  d->geom = calloc((size_t)m->ngeom + 1, sizeof *d->geom);
  d->want_kin = calloc(nb, sizeof *d->want_kin);
  d->vprev = calloc(nb, sizeof *d->vprev);
  d->cpos = calloc(nb, sizeof *d->cpos);
  d->cfb = calloc(ST_DYN_MAX_CFB, sizeof *d->cfb);
  d->cfb_body = calloc(ST_DYN_MAX_CFB, sizeof *d->cfb_body);
  d->cfb_side = calloc(ST_DYN_MAX_CFB, sizeof *d->cfb_side);
  return d->gbody && d->glink && d->gcom && d->link_group && d->link_R && d->link_p && d->hinge &&
         d->angle && d->vel && d->saved && d->geom && d->want_kin && d->vprev && d->cpos &&
         d->cfb && d->cfb_body && d->cfb_side;
}

/* the ODE world with its own threading implementation, its contact group and the parameters of
 * the [dynamics] keys; 0 when out of memory */
static int create_ode_world(dynInternal *d) {
  const stDynDef *def = &d->def;
  d->world = dWorldCreate();
  d->threading = dThreadingAllocateSelfThreadedImplementation();
  if (!d->threading) return 0;
  dWorldSetStepThreadingImplementation(d->world, dThreadingImplementationGetFunctions(d->threading),
                                       d->threading);
  d->cgroup = dJointGroupCreate(0);
  dWorldSetGravity(d->world, 0, 0, -def->gravity);
  dWorldSetERP(d->world, def->erp);
  dWorldSetCFM(d->world, def->cfm);
  dWorldSetQuickStepNumIterations(d->world, def->iterations);
  dWorldSetQuickStepW(d->world, def->sor_w);
  dWorldSetContactSurfaceLayer(d->world, def->surface_layer);
  d->surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
  d->surface.mu = def->friction;
  d->surface.soft_erp = def->contact_erp;
  d->surface.soft_cfm = def->contact_cfm;
  return 1;
}

stStatus st__dyn_create(stWorld *w, const stDynDef *def, char *err, size_t errsz) {
  int nsub = 0;
  if (check_def(def, w->robot->dt, &nsub, err, errsz)) return ST_ERR_RANGE;
  st__ode_init();
  st__ode_messages_install();
  const char *why = st__ode_layout_precision();
  if (why) return st__errf(err, errsz, "dynamic world: %s", why), ST_ERR_RANGE;
  if (def->solver == ST_DYN_QUICKSTEP) {
    pthread_once(&g_rand_once, rand_check);
    if (g_rand_why)
      return st__errf(err, errsz, "dynamics.solver: quickstep, but %s (expected step)", g_rand_why),
             ST_ERR_RANGE;
  }
  if (def->lcp == ST_DYN_LCP_SCHUR && (why = st__lcp_unavailable()))
    return st__errf(err, errsz, "dynamics.lcp: schur, but %s (expected dense)", why), ST_ERR_RANGE;
  dynInternal *d = calloc(1, sizeof *d);
  if (!d) return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  d->head.backend = &dyn_backend;
  w->internal_ = d;
  d->def = *def;
  d->nsub = nsub;
  d->h = w->robot->dt / nsub;
  d->solver = def->solver;
  if (!alloc_arrays(d, w->robot->model) || !create_ode_world(d))
    return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  if (def->lcp == ST_DYN_LCP_SCHUR) {
    if (!(d->lcp = st__lcp_create()))
      return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
    /* room in ODE's step arena for the check mode's second solve (lib/world/ode_lcp.h): the
     * steps' own need is far below 1 MB */
    const dWorldStepReserveInfo reserve = {sizeof reserve, 2.0f, 1u << 20};
    dWorldSetStepMemoryReservationPolicy(d->world, &reserve);
  }
  stStatus st = build(w, d, err, errsz);
  if (st) return st;
  d->obj_table = 1;
  return ST_OK;
}

static void dyn_destroy(stWorld *w) {
  dynInternal *d = w->internal_;
  st__robot_geoms_destroy(w->robot->model, &d->geoms);
  st__scene_geoms_destroy(&d->scene);
  if (d->floor) dGeomDestroy(d->floor);
  if (d->cgroup) dJointGroupDestroy(d->cgroup);
  if (d->world) dWorldDestroy(d->world); /* its bodies and hinges too */
  if (d->threading) dThreadingFreeImplementation(d->threading);
  free(d->gbody);
  free(d->glink);
  free(d->gcom);
  free(d->link_group);
  free(d->link_R);
  free(d->link_p);
  free(d->hinge);
  free(d->angle);
  free(d->vel);
  free(d->saved);
  free(d->geom);
  free(d->want_kin);
  free(d->vprev);
  free(d->cpos);
  free(d->cfb);
  free(d->cfb_body);
  free(d->cfb_side);
  st__lcp_destroy(d->lcp);
  free(d);
  w->internal_ = NULL;
}

/* ---- contacts ---------------------------------------------------------------------------- */

/* the group of body b when it is an adaptive joint's body, kinematic now; else -1 */
static int adaptive_kin_body(const dynInternal *d, dBodyID b) {
  if (!b || !d->nadapt) return -1;
  const int g = (int)(intptr_t)dBodyGetData(b) - 1;
  return g >= d->nkin0 && g < d->nkin ? g : -1;
}

/* narrow phase of one pair; with make, one contact joint per point. Returns 1 on contact.
 * ODE's colliders return at most the requested number of points, the first ones they find:
 * for the object's flat base on the table that is one side of the rim, and the object creeps.
 * So up to 16 are asked for and max_contacts of them kept, evenly spread over the list. */
static int collide(dynInternal *d, dGeomID a, dGeomID b, int make, double mu, int kind) {
  if (!a || !b) return 0;
  enum { ASK = 16 };
  const int n = dCollide(a, b, ASK, d->cg, sizeof d->cg[0]);
  const int keep = n < d->def.max_contacts ? n : d->def.max_contacts;
  if (make)
    for (int k = 0; k < keep; k++) {
      const int i = keep == n ? k : (int)((long)k * n / keep);
      dContact c;
      memset(&c, 0, sizeof c);
      c.surface = d->surface;
      c.surface.mu = mu;
      c.geom = d->cg[i];
      dBodyID b1 = dGeomGetBody(d->cg[i].g1), b2 = dGeomGetBody(d->cg[i].g2);
      const int a1 = adaptive_kin_body(d, b1), a2 = adaptive_kin_body(d, b2);
      if ((!b1 || dBodyIsKinematic(b1)) && (!b2 || dBodyIsKinematic(b2))) { /* no effect */
        /* an adaptive exact servo's body on the table: no force can tell its torque */
        if (a1 >= 0 && a1 < d->kin_static_hit) d->kin_static_hit = a1;
        if (a2 >= 0 && a2 < d->kin_static_hit) d->kin_static_hit = a2;
        continue;
      }
      dJointID j = dJointCreateContact(d->world, d->cgroup, &c);
      dJointAttach(j, b1, b2);
      if (a1 >= 0 || a2 >= 0) {
        if (d->ncfb < ST_DYN_MAX_CFB) {
          dJointSetFeedback(j, &d->cfb[d->ncfb]);
          d->cfb_body[d->ncfb] = a1 >= 0 ? a1 : a2;
          d->cfb_side[d->ncfb] = a1 >= 0 ? 0 : 1;
          d->ncfb++;
        } else if ((a1 >= 0 ? a1 : a2) < d->kin_static_hit) {
          d->kin_static_hit = a1 >= 0 ? a1 : a2; /* cannot be checked: make it dynamic */
        }
      }
      d->points[kind]++;
    }
  return n > 0;
}

/* world AABB of the object (sphere and base) */
static void object_aabb(const dynInternal *d, dReal oa[6]) {
  dReal t[6];
  dGeomGetAABB(d->scene.ball, oa);
  if (d->scene.base) {
    dGeomGetAABB(d->scene.base, t);
    for (int i = 0; i < 3; i++) {
      if (t[2 * i] < oa[2 * i]) oa[2 * i] = t[2 * i];
      if (t[2 * i + 1] > oa[2 * i + 1]) oa[2 * i + 1] = t[2 * i + 1];
    }
  }
}

/* the object's pairs: with the table (when on) and the floor; ORs object_table into c */
static void collide_object(stWorld *w, int make, stContacts *c) {
  dynInternal *d = w->internal_;
  dReal oa[6];
  object_aabb(d, oa);
  if (d->obj_table && st__aabb_overlap(oa, d->table_aabb)) {
    const double mu = d->def.table_friction;
    int hit = collide(d, d->scene.ball, d->scene.table, make, mu, ST_DYN_PAIR_OBJECT_TABLE);
    hit |= collide(d, d->scene.base, d->scene.table, make, mu, ST_DYN_PAIR_OBJECT_TABLE);
    if (hit) c->object_table = 1;
  }
  if (oa[4] <= d->def.floor_z) {
    collide(d, d->scene.ball, d->floor, make, d->def.table_friction, ST_DYN_PAIR_OBJECT_FLOOR);
    collide(d, d->scene.base, d->floor, make, d->def.table_friction, ST_DYN_PAIR_OBJECT_FLOOR);
  }
}

/* every pair that can collide, in a fixed order: robot-table, robot-object, then the object's
 * own pairs. No robot-robot pairs. ORs what touches what into c. The robot's geometries must
 * be where its ODE bodies are (robot in ODE, or poses just set). */
static void collide_all(stWorld *w, int make, stContacts *c) {
  dynInternal *d = w->internal_;
  dReal oa[6];
  object_aabb(d, oa);
  for (int i = 0; i < d->geoms.n; i++) {
    const dynGeom *g = &d->geom[i];
    dGeomID gi = d->geoms.g[i];
    dReal a[6];
    dGeomGetAABB(gi, a);
    if (g->dyn && st__aabb_overlap(a, d->table_aabb) &&
        collide(d, gi, d->scene.table, make, d->def.friction, ST_DYN_PAIR_ROBOT_TABLE)) {
      if (g->is_arm) c->arm_table = 1;
      if (g->touch >= 0) c->touch[g->touch] = 1;
    }
    if (st__aabb_overlap(a, oa)) {
      int hit = collide(d, gi, d->scene.ball, make, d->def.friction, ST_DYN_PAIR_ROBOT_BALL);
      hit |= collide(d, gi, d->scene.base, make, d->def.friction, ST_DYN_PAIR_ROBOT_BASE);
      if (hit) {
        c->robot_object = 1;
        if (g->touch >= 0) c->touch[g->touch] = c->touch_object[g->touch] = 1;
      }
    }
  }
  collide_object(w, make, c);
}

static void contacts_or(stContacts *acc, const stContacts *c) {
  for (int i = 0; i < ST_NTOUCH; i++) {
    acc->touch[i] |= c->touch[i];
    acc->touch_object[i] |= c->touch_object[i];
  }
  acc->arm_table |= c->arm_table;
  acc->robot_object |= c->robot_object;
  acc->object_table |= c->object_table;
}

/* 1 when some robot geometry comes within margin of the table or the object: judged on
 * exact world AABBs of the primitives computed from the link poses w->R / w->p (no ODE call),
 * the object's AABB grown by its own motion over one sub-step */
static int robot_near(const stWorld *w, double margin) {
  const dynInternal *d = w->internal_;
  const stModel *m = w->robot->model;
  dReal oa[6];
  object_aabb(d, oa);
  const dReal *ov = dBodyGetLinearVel(d->ball);
  for (int k = 0; k < 3; k++) {
    const double grow = fabs(ov[k]) * d->h;
    oa[2 * k] -= grow;
    oa[2 * k + 1] += grow;
  }
  for (int i = 0; i < d->geoms.n; i++) {
    const dynGeom *g = &d->geom[i];
    if (!g->dyn) continue; /* the static root does not move */
    const int l = g->link;
    const double *Rl = w->R[l];
    double Rg[9], c[3], half[3];
    st__mat3_mul(Rl, m->geom_rot[i], Rg);
    st__mat3_vec(Rl, m->geom_pos[i], c);
    for (int k = 0; k < 3; k++) c[k] += w->p[l][k];
    if (!st__geom_half_aabb(m, i, Rg, half)) half[0] = half[1] = half[2] = d->geoms.bound[i];
    dReal a[6];
    for (int k = 0; k < 3; k++) {
      a[2 * k] = c[k] - half[k] - margin;
      a[2 * k + 1] = c[k] + half[k] + margin;
    }
    if (st__aabb_overlap(a, d->table_aabb) || st__aabb_overlap(a, oa)) return 1;
  }
  return 0;
}

/* ---- state ------------------------------------------------------------------------------- */

static void set_unstable(stWorld *w, const char *fmt, ...) ST_PRINTF(2, 3);

static void set_unstable(stWorld *w, const char *fmt, ...) {
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
    set_unstable(w, "body '%s' has a non-finite position, orientation or velocity", name);
    return 0;
  }
  const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double o2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  if (v2 > d->def.unstable_speed * d->def.unstable_speed) {
    set_unstable(w, "body '%s' moves at %.3g m/s (unstable_speed %g)", name, sqrt(v2),
                 d->def.unstable_speed);
    return 0;
  }
  if (o2 > d->def.unstable_spin * d->def.unstable_spin) {
    set_unstable(w, "body '%s' spins at %.3g rad/s (unstable_spin %g)", name, sqrt(o2),
                 d->def.unstable_spin);
    return 0;
  }
  return 1;
}

/* after a sub-step: the object, and the robot's bodies when they took part; 1 when fine */
static int bodies_ok(stWorld *w) {
  dynInternal *d = w->internal_;
  if (d->robot_dyn)
    for (int g = 0; g < d->ngroup; g++)
      if (!body_ok(w, d->gbody[g], w->robot->model->body_name[d->glink[g]])) return 0;
  return body_ok(w, d->ball, "object");
}

/* body g where forward kinematics (w->R, w->p) puts its first link */
static void place_body(stWorld *w, int g) {
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
  for (int g = 0; g < d->ngroup; g++) place_body(w, g);
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
static void place_kinematic(stWorld *w) {
  dynInternal *d = w->internal_;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  for (int g = 0; g < d->ngroup && d->hinge[g].kin; g++) place_body(w, g);
  prescribe_velocities(w, 1);
}


/* free motion -> ODE: bodies at the kinematic pose, moving at the servo velocities */
static void robot_to_ode(stWorld *w) {
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
static void robot_to_free(stWorld *w, int read) {
  dynInternal *d = w->internal_;
  if (read)
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) d->angle[d->hinge[i].link] = dJointGetHingeAngle(d->hinge[i].j);
  for (int g = 0; g < d->ngroup; g++) dBodyDisable(d->gbody[g]);
  d->robot_dyn = 0;
}

/* joint angles -> qhat; poses (FK); object centre */
static void read_state(stWorld *w) {
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
static void set_kin(dynInternal *d, int i, int on, int read) {
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
static void set_stops(dynHinge *hg, double lo, double hi) {
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

static void dyn_set_seed(stWorld *w, uint64_t key) { ((dynInternal *)w->internal_)->seed = key; }

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
    set_stops(hg, hg->lo - d->def.stop_margin, hg->hi + d->def.stop_margin);
  }
  for (int g = 0; g < d->ngroup; g++) dBodyEnable(d->gbody[g]);
  d->robot_dyn = 1;
  for (int i = d->nkin0 + d->nadapt - 1; i >= d->nkin0; i--) set_kin(d, i, 0, 0);
  for (int i = d->nkin0; i < d->nkin0 + d->nadapt; i++) set_kin(d, i, 1, 0);
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
  if (d->lcp) st__lcp_stats_reset(d->lcp);
  d->unstable = 0;
  d->reason[0] = 0;
  d->rand_state = (uint32_t)(st_rng_mix64(d->seed ^ 0x6f64655f72616e64ull) >> 32);
}

static void dyn_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
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
  collide_all(w, 0, &w->contacts);
  if (d->def.free_motion && !robot_near(w, d->def.contact_margin)) robot_to_free(w, 0);
  read_state(w);
  if (!ok) set_unstable(w, "object position is not finite");
}

static void dyn_update(stWorld *w) {
  if (!((dynInternal *)w->internal_)->unstable) read_state(w);
}

/* ---- stepping ---------------------------------------------------------------------------- */

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
    double lo = hg->lo - d->def.stop_margin, hi = hg->hi + d->def.stop_margin;
    /* only joints thrown faster than any servo moves them: a joint resting on a stop gets
     * ODE's explicit motor kick (fudge_factor) when powered away from it */
    if (fabs(rate) > 1.5 * vmax) {
      const double a = dJointGetHingeAngle(hg->j), r = rate * d->h;
      if (a + r < lo && a > lo) lo = a;
      if (a + r > hi && a < hi) hi = a;
    }
    if (lo != hg->lo_set || hi != hg->hi_set) set_stops(hg, lo, hi);
  }
}

/* saves / restores the state of every body taking part in the step */
static void save_bodies(dynInternal *d, double (*st)[13]) {
  for (int g = 0; g <= d->ngroup; g++) {
    dBodyID b = g < d->ngroup ? d->gbody[g] : d->ball;
    memcpy(st[g], dBodyGetPosition(b), 3 * sizeof(double));
    memcpy(st[g] + 3, dBodyGetQuaternion(b), 4 * sizeof(double));
    memcpy(st[g] + 7, dBodyGetLinearVel(b), 3 * sizeof(double));
    memcpy(st[g] + 10, dBodyGetAngularVel(b), 3 * sizeof(double));
  }
}

static void restore_bodies(dynInternal *d, double (*st)[13]) {
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
static void motors_prepare(dynInternal *d) {
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
static void adaptive_prepare(dynInternal *d) {
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
    for (int i = d->nkin - 1; i >= first; i--) set_kin(d, i, 0, 1);
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
static void adaptive_update(dynInternal *d) {
  while (d->nkin < d->nkin0 + d->nadapt && d->want_kin[d->nkin]) {
    d->want_kin[d->nkin] = 0;
    set_kin(d, d->nkin, 1, 1);
  }
}

/* one ODE sub-step: contacts (flags ORed into c), then the stepper. ODE's direct solver can
 * fail on a degenerate set of contacts ("LCP internal error", reported through dMessage) and
 * then returns garbage: the sub-step is redone from the saved state with softer constraints
 * (contact and joint CFM x10, up to 3 times). With motor_active_set, a sub-step in which an
 * unbounded motor row exceeded its limit is redone with it bounded. Returns 0 when ODE ran out
 * of memory. */
static int ode_substep(stWorld *w, stContacts *c) {
  dynInternal *d = w->internal_;
  const int robot = d->robot_dyn;
  const int mas = robot && d->def.motor_active_set && d->solver == ST_DYN_STEP;
  if (robot) save_bodies(d, d->saved);
  dSurfaceParameters surface = d->surface;
  const int adapt = robot && d->nadapt;
  st__ode_messages_begin(); /* ODE's warnings of this world's sub-step are counted, not printed */
  for (int attempt = 0, redo = 0, aredo = 0;;) {
    d->ncfb = 0;
    d->kin_static_hit = d->nhinge;
    if (robot) collide_all(w, 1, c);
    else collide_object(w, 1, c);
    if (mas) motors_prepare(d);
    if (adapt) adaptive_prepare(d);
    int ok;
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
    const unsigned long msgs = st__ode_messages() - msg0;
    dJointGroupEmpty(d->cgroup);
    d->messages += (long)msgs;
    if (ok && msgs && robot && attempt < 3) { /* degenerate: softer */
      restore_bodies(d, d->saved);
      d->surface.soft_cfm *= 10.0;
      dWorldSetCFM(d->world, d->def.cfm * pow(10.0, attempt + 1));
      d->retries++;
      attempt++;
      continue;
    }
    if (ok && adapt && aredo <= d->nadapt && adaptive_check(w, d)) { /* a servo needed more */
      restore_bodies(d, d->saved);
      d->adapt_redos++;
      aredo++;
      continue;
    }
    if (ok && mas && redo <= d->nhinge && motors_check(d)) { /* a motor saturated: bounded */
      restore_bodies(d, d->saved);
      d->motor_redos++;
      redo++;
      continue;
    }
    d->surface = surface;
    dWorldSetCFM(d->world, d->def.cfm);
    st__ode_messages_end();
    return ok;
  }
}

/* 1 when every command is finite; else the world becomes unstable */
static int commands_ok(stWorld *w, const double *y) {
  for (int k = 0; k < ST_NDOF; k++)
    if (!isfinite(y[k])) {
      set_unstable(w, "command y[%d] = %g is not finite", k, y[k]);
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
  if (!d->robot_dyn && robot_near(w, d->def.contact_margin)) robot_to_ode(w);
  if (d->robot_dyn) {
    if (d->nadapt) adaptive_update(d);
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) dJointSetHingeParam(d->hinge[i].j, dParamVel, d->vel[i]);
    if (d->nkin) place_kinematic(w);
    speculative_stops(d, w->robot->max_velocity);
    d->dyn_substeps++;
    d->dyn_hinge_substeps += d->nhinge - d->nkin;
  } else {
    for (int i = 0; i < d->nhinge; i++) d->angle[d->hinge[i].link] += d->vel[i] * d->h;
    st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
  }
  const int ok = ode_substep(w, c);
  if (d->robot_dyn) /* the exact servos advance as in free motion */
    for (int i = 0; i < d->nkin; i++) d->angle[d->hinge[i].link] += d->vel[i] * d->h;
  if (!ok) {
    set_unstable(w, "ODE could not allocate its step memory");
    return 0;
  }
  return bodies_ok(w);
}

/* 1 when every joint is within its range by limit_tolerance; else the world becomes unstable */
static int joints_in_range(stWorld *w) {
  dynInternal *d = w->internal_;
  for (int i = 0; i < d->nhinge; i++) {
    const dynHinge *hg = &d->hinge[i];
    const double a = d->angle[hg->link];
    const double tol = d->def.limit_tolerance;
    if (!isfinite(a) || a < hg->lo - tol || a > hg->hi + tol) {
      set_unstable(w, "joint '%s' at %.2f deg, beyond its range %.2f..%.2f deg by more than "
                   "limit_tolerance_deg %.2f", w->robot->model->jnt_name[hg->link], a / ST_DEG,
                   hg->lo / ST_DEG, hg->hi / ST_DEG, d->def.limit_tolerance / ST_DEG);
      return 0;
    }
  }
  return 1;
}

static void dyn_step(stWorld *w, const double *y) {
  dynInternal *d = w->internal_;
  if (d->unstable || !commands_ok(w, y)) return;
  st__ode_init();
  stContacts acc;
  memset(&acc, 0, sizeof acc);
  for (int s = 0; s < d->nsub; s++) {
    stContacts c;
    memset(&c, 0, sizeof c);
    const int fine = substep(w, y, &c);
    if (s > 0) contacts_or(&acc, &c); /* the state after this control step's previous sub-step */
    if (!fine) break;
  }
  w->step++;
  if (d->unstable) return;
  /* contacts of the final state (no joints: the next sub-step finds its own) */
  stContacts c;
  memset(&c, 0, sizeof c);
  if (d->robot_dyn) collide_all(w, 0, &c);
  else collide_object(w, 0, &c);
  contacts_or(&acc, &c);
  w->contacts = acc;
  read_state(w);
  if (!joints_in_range(w)) return;
  /* back to free motion once the robot is clear of the table and the object */
  if (d->robot_dyn && d->def.free_motion && !robot_near(w, d->def.contact_margin))
    robot_to_free(w, 1);
}

/* ---- queries ------------------------------------------------------------------------------- */

static void dyn_set_object_table_collision(stWorld *w, int on) {
  ((dynInternal *)w->internal_)->obj_table = !!on;
}

static int dyn_object_fell(const stWorld *w) {
  const dynInternal *d = w->internal_;
  const stScene *s = w->scene;
  const double *o = w->obj;
  if (o[2] < s->table_top_z - d->def.fall_margin) return 1;
  const int off = o[0] < s->table_lo[0] || o[0] > s->table_hi[0] || o[1] < s->table_lo[1] ||
                  o[1] > s->table_hi[1];
  return off && o[2] < s->table_top_z;
}

static double dyn_object_ceiling(const stWorld *w) {
  const dynInternal *d = w->internal_;
  if (!(d->def.gravity > 0.0) || d->unstable) return INFINITY;
  dMass ms;
  dBodyGetMass(d->ball, &ms);
  const dReal *v = dBodyGetLinearVel(d->ball), *o = dBodyGetAngularVel(d->ball);
  dVector3 ob; /* the spin in the body frame, where the inertia is */
  dBodyVectorFromWorld(d->ball, o[0], o[1], o[2], ob);
  double rot = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) rot += ob[i] * ms.I[4 * i + j] * ob[j];
  const double ke = 0.5 * ms.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * rot;
  return w->obj[2] + ke / (ms.mass * d->def.gravity);
}

static int dyn_unstable(const stWorld *w) { return ((const dynInternal *)w->internal_)->unstable; }

static const char *dyn_unstable_reason(const stWorld *w) {
  return ((const dynInternal *)w->internal_)->reason;
}

static void dyn_info(const stWorld *w, stDynInfo *info) {
  const dynInternal *d = w->internal_;
  info->bodies = d->ngroup;
  info->hinges = d->nhinge;
  info->kinematic_hinges = d->nkin;
  info->geoms = d->geoms.n;
  info->substeps = d->nsub;
  info->solver = d->solver;
  pthread_once(&g_rand_once, rand_check);
  info->rand_interposed = g_rand_why == NULL;
  info->solver_warnings = d->messages;
  info->solver_retries = d->retries;
  info->motor_redos = d->motor_redos;
  info->adaptive_redos = d->adapt_redos;
  info->adaptive_kinematic = d->nkin - d->nkin0;
  info->dyn_substeps = d->dyn_substeps;
  info->dyn_hinge_substeps = d->dyn_hinge_substeps;
  info->robot_in_ode = d->robot_dyn;
  stLcpStats ls;
  memset(&ls, 0, sizeof ls);
  if (d->lcp) st__lcp_stats(d->lcp, &ls);
  info->lcp_solves = ls.calls;
  info->lcp_reduced = ls.reduced;
  info->lcp_reduced_rows = ls.rows;
  info->lcp_unbounded_rows = ls.unbounded;
  info->lcp_orderings = ls.orderings;
  memcpy(info->contact_points, d->points, sizeof d->points);
}

static void dyn_joint_angles(const stWorld *w, double *angle) {
  const dynInternal *d = w->internal_;
  memcpy(angle, d->angle, sizeof(double) * (size_t)w->robot->nbody);
}

/* the object body's rotation, from ODE's 3x4 layout */
static void dyn_object_rotation(const stWorld *w, double R[9]) {
  const dReal *o = dBodyGetRotation(((const dynInternal *)w->internal_)->ball);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = o[4 * i + j];
}

static const stWorldBackend dyn_backend = {
    .destroy = dyn_destroy,
    .reset = dyn_reset,
    .update = dyn_update,
    .joint_angles = dyn_joint_angles,
    .step = dyn_step,
    .set_seed = dyn_set_seed,
    .set_object_table_collision = dyn_set_object_table_collision,
    .object_fell = dyn_object_fell,
    .object_ceiling = dyn_object_ceiling,
    .unstable = dyn_unstable,
    .unstable_reason = dyn_unstable_reason,
    .info = dyn_info,
    .object_rotation = dyn_object_rotation,
};
