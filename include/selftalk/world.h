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
  void *internal_;        /* collision geometry */
} stWorld;

/* Allocates a world for a robot and scene (both must outlive it). */
stStatus st_world_create(const stRobot *robot, const stScene *scene, stWorld **world, char *err,
                         size_t errsz);

/* Nullable: world. */
void st_world_destroy(stWorld *world);

/* Starts a trial: posture, object centre, target; computes poses and contacts. */
void st_world_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]);

/* Actuation law of SPEC §3 for one DOF over one control step: joint velocity
 * alpha (y - qhat) deg/s clamped to +-vmax, integrated over dt, kept within [0, 1]. Returns
 * the new qhat. range_deg is the DOF's range in degrees. */
double st_actuate(double qhat, double y, double alpha, double vmax_deg, double dt, double range_deg);

/* One kinematic control step: moves every DOF towards the desired normalised positions
 * y[12] (the network's outputs 0-11), then updates poses and contacts. */
void st_world_step_kinematic(stWorld *w, const double *y);

/* Recomputes poses and contacts for the current qhat (after changing it directly). */
void st_world_update(stWorld *w);

/* World position of a point given in a body's frame. */
void st_world_point(const stWorld *w, int body, const double local[3], double out[3]);

#ifdef __cplusplus
}
#endif

#endif
