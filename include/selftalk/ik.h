/* SPDX-License-Identifier: MIT
 * libselftalk: inverse kinematics on the stRobot - deterministic damped least squares
 * (Levenberg-Marquardt) in normalised joint units.
 *
 * Task: place one point of a body frame (e.g. the palm centre, robot->palm_body) at a world
 * position and, optionally, turn up to ST_IK_NAXIS of its body-fixed unit vectors (e.g. the
 * palm normal, the frame's +z) towards world directions, each with a weight. The unknowns are
 * the normalised positions qhat of the DOF with a non-zero mobility weight (by default the 9
 * torso and arm DOF); the hand DOF are never moved by default. Every iteration clamps qhat to
 * [0, 1] and freezes, for that iteration, a DOF at a limit whose step points out of range.
 *
 * The Jacobian is analytic (every DOF is a rotation about its joint's axis; coupled joints add
 * their columns, scaled by their own ranges). The damping adapts (Levenberg-Marquardt: a step
 * that does not lower the cost is rejected and the damping raised, an accepted one lowers it),
 * so the solver is robust to poor conditioning. It is a local method: from a start far from
 * any solution it can stop in a local minimum against the joint limits (ST_ERR_RANGE); start
 * near the intended posture (st_posture does, from fixed start postures). No randomness: the
 * same robot, definition, target and start give a bit-identical answer.
 *
 * Ownership: st_ik_solve allocates one work buffer (body poses, 2 x nbody) per call, before
 * iterating, and frees it before returning; the iterations allocate nothing. The robot,
 * definition and target are only read. Thread-safe on distinct qhat / result buffers. */
#ifndef SELFTALK_IK_H
#define SELFTALK_IK_H

#include "selftalk/robot.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_IK_NAXIS 2 /* body axes that can be aligned at once */

/* Solver settings (st_ik_default_def gives the defaults quoted below). */
typedef struct stIkDef {
  int max_iter;               /* FK evaluations (accepted or rejected steps); 500 */
  double damping;             /* initial damping lambda; 1e-2 */
  double damping_min;         /* lower bound of the adaptive damping; 1e-6 */
  double damping_max;         /* the solver gives up (stalled) when lambda exceeds this; 1e3 */
  double max_step;            /* largest change of one DOF's qhat per iteration; 0.1 */
  double tol_pos;             /* converged when the position error is below this, m; 1e-5 */
  double tol_dir;             /* ... and every aligned axis is within this angle, rad; 1e-4 */
  double dof_weight[ST_NDOF]; /* mobility of each DOF (SPEC order): 0 = fixed; a larger weight
                                 lets the DOF take a larger share of each step (damping of DOF
                                 i is lambda^2 / weight i). Default 1 for DOF 0-8, 0 for the
                                 hand DOF 9-11 */
} stIkDef;

/* What to reach. Cost = pos_weight |x - pos|^2 + sum_k dir_weight[k] |R axis[k] - dir[k]|^2,
 * where x is the world position of `point` (body frame) and R the body's rotation; for small
 * angles |R a - d|^2 is the angle squared, so dir_weight = 0.01 trades 1 rad for 0.1 m. */
typedef struct stIkTarget {
  int body;                        /* body (frame) to place, e.g. robot->palm_body */
  double point[3];                 /* point in that body's frame; usually 0 (the origin) */
  double pos[3];                   /* world target of the point, m */
  double pos_weight;               /* > 0, or 0 to align axes only; 1 */
  double axis[ST_IK_NAXIS][3];     /* unit vectors in the body frame (e.g. 0,0,1: palm normal) */
  double dir[ST_IK_NAXIS][3];      /* unit world directions they should point to */
  double dir_weight[ST_IK_NAXIS];  /* 0: axis unused */
} stIkTarget;

/* What was achieved. */
typedef struct stIkResult {
  double pos_err;                  /* |x - pos|, m */
  double dir_err[ST_IK_NAXIS];     /* angle between R axis[k] and dir[k], rad (0 when unused) */
  double cost;                     /* the weighted cost above */
  int iterations;                  /* FK evaluations used */
  int converged;                   /* 1 when within tol_pos and tol_dir */
} stIkResult;

ST_API stIkDef st_ik_default_def(void);

/* A target for a body's origin at pos, weight 1, no axis alignment. */
ST_API stIkTarget st_ik_target(int body, const double pos[3]);

/* Adds (or replaces) axis alignment k: body-frame axis -> world direction dir, weighted.
 * Both vectors are normalised here. */
ST_API void st_ik_target_align(stIkTarget *t, int k, const double axis[3], const double dir[3],
                        double weight);

/* Solves from qhat[12] (in: start; out: the best posture found, clamped to [0, 1]; DOF of zero
 * mobility untouched). Nullable: result. Returns ST_OK when converged, ST_ERR_RANGE when the
 * target was not reached within tolerances (qhat then holds the lowest-cost posture visited,
 * result says how far it is), ST_ERR_ARG on a bad body, weights or settings, ST_ERR_NOMEM. */
ST_API stStatus st_ik_solve(const stRobot *r, const stIkDef *def, const stIkTarget *target,
                     double qhat[ST_NDOF], stIkResult *result);

/* Errors and cost of a posture for a target, without solving (allocates like st_ik_solve). */
ST_API stStatus st_ik_evaluate(const stRobot *r, const stIkTarget *target, const double qhat[ST_NDOF],
                        stIkResult *result);

#ifdef __cplusplus
}
#endif

#endif
