/* SPDX-License-Identifier: MIT
 * libselftalk: the dynamic world backend's own state and its files' functions (lib/world/dyn*.c;
 * the map of the files: lib/world/dynworld.c). Not installed. */
#ifndef SELFTALK_DYNWORLD_H
#define SELFTALK_DYNWORLD_H

#include <ode/ode.h>
#include <stdint.h>

#include "core/internal.h"
#include "world/ode_lcp.h"
#include "world/world_backend.h"
#include "world/world_geom.h"

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
  double stop_margin;       /* def's in radians: the stops' margin outside the qhat range, */
  double limit_tolerance;   /* and how far beyond its range a joint makes the world unstable */
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
  stLcp *lcp;               /* dynamics.lcp other than dense: the reduction's scratch; else NULL */
  long adapt_redos;         /* sub-steps redone because an adaptive joint needed more torque */
  double (*saved)[13];      /* body states before the current sub-step */
  int unstable;
  char reason[192];
} dynInternal;

/* the operations of the dynamic world (lib/world/dynworld.c) */
extern const stWorldBackend st__dyn_backend;

/* ---- the [dynamics] keys (dynworld.c) ---- */

/* def's keys within the key table's ranges, then together (a control step dt that is a whole
 * number *nsub of sub-steps, ...): ST_OK, or ST_ERR_RANGE naming the key */
stStatus st__dyn_check_def(const stDynDef *def, double dt, int *nsub, char *err, size_t errsz);

/* ---- creation (dyn_create.c) ---- */

void st__dyn_destroy(stWorld *w);
/* 1 when quickstep's shuffling uses the per-world generator (checked once per process) */
int st__dyn_rand_interposed(void);

/* ---- contacts (dyn_contact.c) ---- */

/* every pair that can collide, in a fixed order: robot-table, robot-object, then the object's
 * own pairs; with make, contact joints for ODE's next step. ORs what touches what into c. The
 * robot's geometries must be where its ODE bodies are (robot in ODE, or poses just set). */
void st__dyn_collide_all(stWorld *w, int make, stContacts *c);
/* the object's pairs alone: with the table (when on) and the floor */
void st__dyn_collide_object(stWorld *w, int make, stContacts *c);
void st__dyn_contacts_or(stContacts *acc, const stContacts *c);
/* 1 when some robot geometry comes within margin of the table or the object */
int st__dyn_robot_near(const stWorld *w, double margin);

/* ---- state and reset (dyn_state.c) ---- */

/* marks the world unstable (the first reason is kept) */
void st__dyn_set_unstable(stWorld *w, const char *fmt, ...) ST_PRINTF(2, 3);
/* after a sub-step: the object, and the robot's bodies when they took part; 1 when fine */
int st__dyn_bodies_ok(stWorld *w);
/* body g where forward kinematics (w->R, w->p) puts its first link */
void st__dyn_place_body(stWorld *w, int g);
/* the kinematic bodies where forward kinematics of the angles puts them, moving at the servo
 * velocities */
void st__dyn_place_kinematic(stWorld *w);
/* free motion -> ODE, and back (read: the measured angles become the state) */
void st__dyn_robot_to_ode(stWorld *w);
void st__dyn_robot_to_free(stWorld *w, int read);
/* joint angles -> qhat; poses (FK); object centre */
void st__dyn_read_state(stWorld *w);
/* dynamics.adaptive_joints: hinge i an exact servo (on) or a bounded motor again */
void st__dyn_set_kin(dynInternal *d, int i, int on, int read);
/* the stops of a hinge at lo, hi */
void st__dyn_set_stops(dynHinge *hg, double lo, double hi);
void st__dyn_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]);
void st__dyn_update(stWorld *w);

/* ---- stepping (dyn_step.c) and its redo strategies (dyn_redo.c) ---- */

void st__dyn_step(stWorld *w, const double *y);

/* the state of every body taking part in the step, saved before a sub-step and restored to
 * take it again */
void st__dyn_save_bodies(dynInternal *d, double (*st)[13]);
void st__dyn_restore_bodies(dynInternal *d, double (*st)[13]);
/* before a sub-step with the robot in ODE: dynamics.motor_active_set's unbounded motor rows,
 * dynamics.adaptive_joints' frames; at its start, the adaptive hinges that become exact servos */
void st__dyn_motors_prepare(dynInternal *d);
void st__dyn_adaptive_prepare(dynInternal *d);
void st__dyn_adaptive_update(dynInternal *d);
/* The redo strategies of a sub-step with the robot in ODE: each looks at the step just taken
 * and, when it must be taken again from the saved state, changes what it must and returns 1;
 * *tries counts its own redos of this sub-step. Softer: ODE's direct solver failed on a
 * degenerate set of contacts ("LCP internal error", `messages` of them): contact and joint CFM
 * x10, up to 3 times. Adaptive: an exact servo needed more torque than its motor has. Motors:
 * an unbounded motor row exceeded its limit, bounded again. */
int st__dyn_redo_softer(dynInternal *d, unsigned long messages, int *tries);
int st__dyn_redo_adaptive(const stWorld *w, dynInternal *d, int *tries);
int st__dyn_redo_motors(dynInternal *d, int *tries);

#endif
