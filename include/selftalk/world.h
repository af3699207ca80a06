/* SPDX-License-Identifier: MIT
 * libselftalk: the per-trial world - robot state, body poses, object, target and contacts.
 *
 * MuJoCo's split: the stRobot and stScene are shared and read-only; an stWorld belongs to one
 * trial on one thread, allocates everything at creation and nothing while stepping. This
 * module is the kinematic mode of thesis §2.1: joints integrate the commanded velocity
 * exactly, collisions are detected (ODE's collision library) for touch sensors and penalties
 * but have no effect, and the object never moves. */
#ifndef SELFTALK_WORLD_H
#define SELFTALK_WORLD_H

#include <stdint.h>

#include "selftalk/robot.h"
#include "selftalk/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What touches what after the last update. */
typedef struct stContacts {
  uint8_t touch[ST_NTOUCH];        /* sensor link touches the object or the table */
  uint8_t touch_object[ST_NTOUCH]; /* sensor link touches the object */
  uint8_t arm_table;               /* any arm or hand geometry touches the table */
  uint8_t robot_object;            /* any robot geometry touches the object */
  uint8_t object_table;            /* the object touches the table */
} stContacts;

typedef struct stWorld {
  const stRobot *robot;
  const stScene *scene;
  double qhat[ST_NDOF];   /* normalised DOF positions */
  double (*R)[9];         /* body rotations, world <- body (robot->nbody) */
  double (*p)[3];         /* body origins (robot->nbody) */
  double obj[3];          /* object (sphere) centre */
  double obj_start[3];    /* object centre at the start of the trial */
  double target[3];       /* target of this trial */
  stContacts contacts;
  long step;              /* control steps since reset */
  int reference_contacts; /* 1: test every geometry with ODE's narrow phase, no culling or
                             shortcuts (slow; for validation and as a benchmark baseline) */
  void *internal_;        /* the kinematic or dynamic backend's state (lib/world/world_backend.h) */
  int dynamic;            /* 1 for a world of st_world_create_dynamic (set at creation) */
} stWorld;

/* Allocates a world for a robot and scene (both must outlive it). */
ST_API stStatus st_world_create(const stRobot *robot, const stScene *scene, stWorld **world, char *err,
                         size_t errsz);

/* Nullable: world. */
ST_API void st_world_destroy(stWorld *world);

/* Starts a trial: posture, object centre, target; computes poses and contacts. */
ST_API void st_world_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]);

/* Actuation law of SPEC §3 for one DOF over one control step: joint velocity
 * alpha (y - qhat) deg/s clamped to +-vmax, integrated over dt, kept within [0, 1]. Returns
 * the new qhat. range_deg is the DOF's range in degrees. */
ST_API double st_actuate(double qhat, double y, double alpha, double vmax_deg, double dt, double range_deg);

/* One kinematic control step: moves every DOF towards the desired normalised positions
 * y[12] (the network's outputs 0-11), then updates poses and contacts. */
ST_API void st_world_step_kinematic(stWorld *w, const double *y);

/* Recomputes poses and contacts for the current qhat (after changing it directly). */
ST_API void st_world_update(stWorld *w);

/* World position of a point given in a body's frame. */
ST_API void st_world_point(const stWorld *w, int body, const double local[3], double out[3]);

/* ---- shapes: what collides, for pictures (docs/PROTOCOL.md, "Robot pictures") ------------- */

typedef enum stShapeKind {
  ST_SHAPE_ROBOT = 0, /* a collision geometry of a robot link */
  ST_SHAPE_BALL,      /* the object: its sphere, and its flattened base (a vertical cylinder) */
  ST_SHAPE_TABLE,     /* the table-top box */
  ST_SHAPE_TARGET,    /* the target: a sphere of the success radius (scene.target_radius) */
  ST_SHAPE_KIND_COUNT
} stShapeKind;

/* One shape in the world frame. Every type fits the box of full extents size[0..2] along its
 * own axes (the columns of R), centred at pos: a sphere has 2r, 2r, 2r; a cylinder 2r, 2r and
 * its length along its own z axis; a mesh (ST_GEOM_MESH) is given as the bounding box of its
 * vertices in its own frame, pos that box's centre. */
typedef struct stShape {
  stShapeKind kind;
  stGeomType type;
  int body;           /* ST_SHAPE_ROBOT: the model body (link) it belongs to; else -1 */
  int geom;           /* ST_SHAPE_ROBOT: the model geometry index; else -1 */
  const char *owner;  /* the link's name, or "ball", "table", "target" (static or the model's) */
  double size[3];     /* full extents along the shape's axes, m */
  double pos[3];      /* centre, world frame */
  double R[9];        /* world <- shape, row-major */
} stShape;

/* The shapes of the world's current state: every collision geometry of the robot's model (at
 * the poses R, p of the world: forward kinematics of the joint readings), then the ball's
 * sphere and base (at obj, turned as the object is: in dynamic mode the object body's
 * rotation), the table and the target. Fills out[0 .. min(n, max) - 1] and returns n, the
 * number of shapes (constant for a world); nullable out when max is 0. Reads the state only:
 * calling it never changes a simulation. */
ST_API int st_world_shapes(const stWorld *w, stShape *out, int max);

/* "robot", "ball", "table", "target"; "?" for another value. */
ST_API const char *st_shape_kind_name(int kind);

/* ---- dynamic mode (thesis §2.1, SPEC §3; lib/world/dynworld.c, docs/PROTOCOL.md "Dynamic mode") --
 * An ODE world per stWorld: the robot's links as rigid bodies (massless frames and fixed-joint
 * children folded into their parent body; the root fixed to the world), hinge joints with
 * stops and velocity motors of bounded torque, the table (static box), the object (sphere with
 * its flattened base, one body), a floor under the table, gravity and friction contacts. There
 * are no robot-robot collisions (as in iCub_SIM by default). While no robot part can reach
 * the table or the object within a sub-step, the robot moves kinematically by the servo law
 * (exactly what unsaturated servos do) and ODE steps only the object. The joints listed in
 * dynamics.kinematic_joints (the chain's first ones) follow the servo law exactly at all times:
 * their links are kinematic bodies, their torque unbounded.
 *
 * After every control step the same stWorld fields as in kinematic mode are filled: qhat
 * (joint readings clamped to [0, 1]; a coupled DOF reports the mean of its joints), R / p
 * (forward kinematics of the joint angles), obj (the object body's centre) and contacts (what
 * touched what in the state after any sub-step of the control step). st_world_reset,
 * st_world_update and st_world_destroy work on both kinds of world. A world belongs to one
 * thread at a time; worlds share no state, and a trial's trajectory depends only on its
 * posture, object, target, seed and commands, bit for bit. */

enum { ST_DYN_QUICKSTEP = 0, ST_DYN_STEP, ST_DYN_SOLVER_COUNT }; /* dynamics.solver */
enum { ST_DYN_LCP_DENSE = 0, ST_DYN_LCP_SCHUR, ST_DYN_LCP_BLOCK, ST_DYN_LCP_WARM,
       ST_DYN_LCP_COUNT }; /* dynamics.lcp */

/* The [dynamics] keys (selftalk/config.h, ST_CONFIG_DYNAMICS_KEYS: their meaning, defaults and
 * ranges), one field each named as its key: solver (ST_DYN_*), substep (s; the control step
 * must be a whole number of sub-steps), limit_tolerance_deg and stop_margin_deg (degrees),
 * kinematic_joints and adaptive_joints (comma-separated joint names), lcp (ST_DYN_LCP_*), ... The
 * world checks them where it consumes them, against the key table's ranges
 * (st_config_check_number). */
#define ST__DYN_NUM(s, k, d, lo, hi, h) double k;
#define ST__DYN_INT(s, k, d, lo, hi, h) int k;
#define ST__DYN_FLAG(s, k, d, h) int k;
#define ST__DYN_ENUM(s, k, d, ch, h) int k;
#define ST__DYN_STR(s, k, d, h) char k[ST_CONFIG_STR_MAX];
typedef struct stDynDef {
  ST_CONFIG_DYNAMICS_KEYS(ST__DYN_INT, ST__DYN_NUM, ST__DYN_FLAG, ST__DYN_ENUM, ST__DYN_STR)
} stDynDef;
#undef ST__DYN_NUM
#undef ST__DYN_INT
#undef ST__DYN_FLAG
#undef ST__DYN_ENUM
#undef ST__DYN_STR

/* Fills def from the [dynamics] keys. */
ST_API void st_dyn_def_from_config(const stConfig *cfg, stDynDef *def);

/* Allocates a dynamic world (robot, scene and def are read at creation; robot and scene must
 * outlive the world). Fails with ST_ERR_RANGE on a bad def (e.g. a control step that is not a
 * whole number of sub-steps) and ST_ERR_MODEL when the model cannot be simulated (a moving
 * link without mass, a bad inertia, an unsupported geometry); err names the cause. The world
 * must be reset (st_world_reset) before it is stepped. ST_ERR_RANGE, saying why, for an ODE
 * that is not double precision, for solver quickstep where ODE's random generator cannot be the
 * library's per-world one, and for lcp schur where ODE's LCP cannot reach the library's (both:
 * in a program linked with the shared library, or with another ODE than 0.16.2: checked once
 * per process with a probe step; docs/PROTOCOL.md, "Dynamic mode"). */
ST_API stStatus st_world_create_dynamic(const stRobot *robot, const stScene *scene, const stDynDef *def,
                                 stWorld **world, char *err, size_t errsz);

/* Key of the per-trial random stream of quickstep's constraint shuffling, used by the next
 * st_world_reset (0 until set). Give each trial its own key (e.g. from st_rng_keyed); equal
 * keys and inputs give bit-identical trials. Solver step draws no random numbers; no effect
 * on a kinematic world. */
ST_API void st_world_set_seed(stWorld *w, uint64_t key);

/* One dynamic control step (robot->dt): every joint's motor runs at alpha_dynamic (y - qhat)
 * degrees/s (qhat of that joint, y of its DOF clamped to [0, 1]; the velocity clamped to
 * +-robot->max_velocity; re-evaluated every sub-step) with torque up to URDF effort times
 * effort_scale; coupled joints each follow their own qhat error, so the object can block them
 * one by one. Then the stWorld fields are filled and step is incremented. Does nothing once
 * the world is unstable; a non-finite y makes it unstable. On a kinematic world it is
 * st_world_step_kinematic. */
ST_API void st_world_step_dynamic(stWorld *w, const double *y);

/* One control step in the world's own mode (kinematic or dynamic). */
ST_API void st_world_step(stWorld *w, const double *y);

/* Switches the object-table collision (on after every reset). Grasp trials switch it off after
 * 40 steps, move trials after 10 (thesis §2.8.1.2): the object then falls through the table
 * unless the hand holds it. The contacts of the next sub-step follow the new setting. */
ST_API void st_world_set_object_table_collision(stWorld *w, int on);

/* 1 when the object has fallen: its centre is more than fall_margin below the table top, or
 * it is outside the table's x/y extent and below the table top. 0 in kinematic mode. */
ST_API int st_world_object_fell(const stWorld *w);

/* An upper bound on the height of the object's centre from now on for as long as no robot part
 * touches it: its height plus its kinetic energy (linear and rotational) over m g. Gravity,
 * the floor and the table cannot lift it higher (no restitution: contacts do not bounce;
 * ODE's contact correction can add a little, which the caller's margin must cover).
 * +inf in kinematic mode or without gravity. */
ST_API double st_world_object_ceiling(const stWorld *w);

/* 1 when the simulation diverged (NaN or infinite values, a body faster than unstable_speed or
 * unstable_spin, a joint beyond its range by more than limit_tolerance, a non-finite
 * command): the caller must end the trial as a failure (the world stays frozen until the next
 * reset). 0 for a kinematic world. */
ST_API int st_world_unstable(const stWorld *w);

/* Why the world is unstable, e.g. "step 12: body 'l_hand' moves at 73.2 m/s (unstable_speed
 * 50)"; "" when stable. Owned by the world, valid until its next reset. */
ST_API const char *st_world_unstable_reason(const stWorld *w);

/* Joint angle of every body (rad, robot->nbody entries, 0 for fixed joints): in dynamic mode
 * the simulated joints' angles, which may lie slightly outside their range (qhat is clamped
 * to [0, 1]); in kinematic mode those of qhat. */
ST_API void st_world_joint_angles(const stWorld *w, double *angle);

/* The kinds of colliding pairs (stDynInfo.contact_points): a robot geometry with the table, with
 * the object's sphere, with the object's base; the object (sphere or base) with the table, with
 * the floor. */
enum {
  ST_DYN_PAIR_ROBOT_TABLE = 0,
  ST_DYN_PAIR_ROBOT_BALL,
  ST_DYN_PAIR_ROBOT_BASE,
  ST_DYN_PAIR_OBJECT_TABLE,
  ST_DYN_PAIR_OBJECT_FLOOR,
  ST_DYN_PAIR_COUNT
};

/* Facts about a dynamic world (for benchmarks and logs). */
typedef struct stDynInfo {
  int bodies;          /* ODE bodies of the robot (the object not included) */
  int hinges;          /* hinge joints */
  int kinematic_hinges; /* of which exact servos (dynamics.kinematic_joints): not in ODE's step */
  int geoms;           /* robot collision geometries */
  int substeps;        /* sub-steps per control step */
  int solver;          /* solver in use (ST_DYN_*) */
  int rand_interposed; /* 1 when quickstep's shuffling can use the per-world generator (else
                          dynamics.solver = quickstep is refused: the shared library, another
                          ODE) */
  long solver_warnings; /* ODE warnings since the last reset (e.g. "LCP internal error": a
                           degenerate set of contacts) */
  long solver_retries;  /* sub-steps redone with softer constraints after such a warning */
  long motor_redos;     /* dynamics.motor_active_set: sub-steps redone because an unbounded
                           motor row needed more than its torque limit */
  long adaptive_redos;  /* dynamics.adaptive_joints: sub-steps redone because an exact servo
                           needed more torque than its motor has (or touched the table) */
  int adaptive_kinematic; /* dynamics.adaptive_joints: how many are exact servos now */
  long dyn_substeps;    /* sub-steps since the last reset with the robot in ODE's step (the
                           others were free motion) */
  long dyn_hinge_substeps; /* the hinges in ODE's step (not exact servos), summed over those
                              sub-steps: 6 LCP rows each */
  int robot_in_ode;     /* the robot is in ODE's step now (near the table or the object) */
  long lcp_solves;      /* dynamics.lcp = schur: the LCPs of ODE's steps since the last reset */
  long lcp_reduced;     /* ... of which solved by the reduction (the rest had < 2 unbounded rows) */
  long lcp_reduced_rows; /* the rows of the reduced ones ... */
  long lcp_unbounded_rows; /* ... and of those, the unbounded rows the reduction eliminated */
  long lcp_orderings;   /* ... and how many of them computed a fill-reducing order (the others
                           found theirs among the last few patterns') */
  long contact_points[ST_DYN_PAIR_COUNT]; /* contact joints made since the last reset, by pair
                                             (ST_DYN_PAIR_*): each is 3 rows of ODE's LCP (1
                                             with zero friction), beside 6 per hinge in ODE */
  long lcp_direct;      /* dynamics.lcp = warm: reduced LCPs solved directly, guess checked ... */
  long lcp_fallbacks;   /* ... and those left to ODE's Dantzig */
} stDynInfo;

/* Fills info (all zero for a kinematic world). */
ST_API void st_world_dynamic_info(const stWorld *w, stDynInfo *info);

#ifdef __cplusplus
}
#endif

#endif
