/* SPDX-License-Identifier: MIT
 * libselftalk: the robot - the model bound to the experiment: the 12 actuated DOF of SPEC §3
 * (in SPEC order) with their coupled joints, the normalised positions, the touch-sensor links,
 * the fingertip and palm frames, and forward kinematics.
 *
 * stRobot is immutable after st_robot_create and shared read-only by every thread. It owns its
 * stModel. Normalised position qhat in [0, 1] maps a joint's range linearly (min -> 0); a
 * coupled joint follows its DOF at the same normalised position within its own range. */
#ifndef SELFTALK_ROBOT_H
#define SELFTALK_ROBOT_H

#include <stdint.h>

#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_NDOF 12  /* actuated DOF, SPEC §3 order */
#define ST_NTOUCH 6 /* touch sensors: thumb, index, middle, ring, little fingertip, palm */
#define ST_NTIP 5   /* fingertips: thumb, index, middle, ring, little */

enum {
  ST_DOF_TORSO_YAW = 0,
  ST_DOF_TORSO_PITCH,
  ST_DOF_SHOULDER_PITCH,
  ST_DOF_SHOULDER_ROLL,
  ST_DOF_SHOULDER_YAW,
  ST_DOF_ELBOW,
  ST_DOF_WRIST_PROSUP,
  ST_DOF_WRIST_PITCH,
  ST_DOF_WRIST_YAW,
  ST_DOF_THUMB_OPPOSE,
  ST_DOF_THUMB_FLEX,
  ST_DOF_FINGER_FLEX
};
enum { ST_TOUCH_THUMB = 0, ST_TOUCH_INDEX, ST_TOUCH_MIDDLE, ST_TOUCH_RING, ST_TOUCH_LITTLE, ST_TOUCH_PALM };

/* The bound robot (read-only once created). Per-body arrays have model->nbody entries. */
typedef struct stRobot {
  stModel *model;               /* owned */
  int nbody;
  char dof_name[ST_NDOF][ST_NAME_MAX];
  int dof_body[ST_NDOF];        /* body whose parent joint is the DOF's master joint */
  double dof_lo[ST_NDOF], dof_hi[ST_NDOF]; /* master joint range used for qhat (rad) */
  int dof_ncoupled[ST_NDOF];    /* joints driven by the DOF, master included */
  int *body_dof;                /* DOF driving the body's joint, -1 for fixed joints */
  double (*body_range)[2];      /* range of the body's joint used for qhat (rad) */
  int revolute_z;               /* every revolute axis is +z: FK takes a fast path */
  int touch_body[ST_NTOUCH];    /* link of each touch sensor */
  int tip_body[ST_NTIP];        /* fingertip frames */
  int palm_body;                /* palm centre frame, +z = palm normal */
  int ee_body;                  /* iKin end-effector frame "l_ee" if present, else -1 */
  uint8_t *body_is_arm;         /* 1 for the arm and hand (descendants of robot.arm_first_link) */
  int *body_touch;              /* touch sensor a body's contacts report to, -1 for none */
  double alpha_kinematic, alpha_dynamic; /* deg/s per unit of qhat error */
  double max_velocity;          /* rad/s */
  double dt;                    /* control step, s */
  void *buffer_;
} stRobot;

/* Loads cfg->robot_urdf and binds it (see st_robot_bind). */
ST_API stStatus st_robot_create(const stConfig *cfg, stRobot **robot, char *err, size_t errsz);

/* Binds a model (ownership passes to the robot, also on failure) using the [robot] keys.
 * A joint or link the config names that the model lacks is an error naming the key. */
ST_API stStatus st_robot_bind(stModel *model, const stConfig *cfg, const char *source, stRobot **robot,
                       char *err, size_t errsz);

/* Nullable: robot. Frees the model too. */
ST_API void st_robot_destroy(stRobot *robot);

/* Angle (rad) of a DOF's master joint at normalised position qhat, and back. */
ST_API double st_robot_dof_angle(const stRobot *r, int dof, double qhat);
ST_API double st_robot_dof_qhat(const stRobot *r, int dof, double angle);

/* Forward kinematics: world pose of every body for normalised DOF positions qhat[12] (coupled
 * joints at the same normalised position). R: nbody row-major rotations (world <- body);
 * p: nbody origins. Pure; no allocation. */
ST_API void st_robot_fk(const stRobot *r, const double *qhat, double (*R)[9], double (*p)[3]);

/* Forward kinematics from one angle per body joint (rad; entries of fixed joints ignored):
 * for dynamic-mode readings and tests where coupled joints differ. */
ST_API void st_robot_fk_angles(const stRobot *r, const double *angle, double (*R)[9], double (*p)[3]);

/* A world point in the frame of a body at pose (R, p) from st_robot_fk: R^T (world - p). */
ST_API void st_robot_point_local(const double R[9], const double p[3], const double world[3],
                          double local[3]);

/* A lower bound on the height (world z) that any collision geometry of the robot (*geom_z)
 * and its palm frame's origin (*palm_z) can reach with every revolute joint within its range
 * (as qhat maps it) widened by tol rad on each side, whatever the joints do: the first
 * revolute joints of the chain (up to three) on a grid with the Lipschitz bound of its cells,
 * the rest by the triangle inequality over the joint offsets (so not the minimum, a bound).
 * Static geometry counts too: a resting object touching it would be "touched by the robot".
 * Takes some 10-100 ms: computed once per protocol, where an exact early end needs it. */
ST_API void st_robot_lowest_z(const stRobot *r, double tol, double *geom_z, double *palm_z);

/* Joint angle of every body (rad, 0 for fixed joints) for normalised DOF positions. */
ST_API void st_robot_angles(const stRobot *r, const double *qhat, double *angle);

#ifdef __cplusplus
}
#endif

#endif
