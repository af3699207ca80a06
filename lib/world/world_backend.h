/* SPDX-License-Identifier: MIT
 * libselftalk: the interface between lib/world/world.c, which owns the public st_world_* functions,
 * and the two backends it dispatches to: kinematic (lib/world/kinworld.c) and dynamic
 * (lib/world/dynworld.c). The backends never call each other nor the public st_world_* functions;
 * what they share is in lib/world/world_geom.h. Not installed. */
#ifndef SELFTALK_WORLD_BACKEND_H
#define SELFTALK_WORLD_BACKEND_H

#include <stdint.h>

#include "selftalk/world.h"

/* The operations of one kind of world. Those of the first block are required. A NULL in the
 * second block means the backend has no dynamics, and lib/world/world.c answers as world.h says a
 * kinematic world does: step is then st_world_step_kinematic (the actuation law on qhat, then
 * update), the others have no effect, return 0 or "", or leave info zeroed. */
typedef struct stWorldBackend {
  /* frees the backend's state (w->internal_), also one left by a failed creation; lib/world/world.c
   * frees the stWorld and its pose arrays */
  void (*destroy)(stWorld *w);
  /* sets qhat (or the state it is read from), obj, obj_start, target and step = 0, then does
   * what update does */
  void (*reset)(stWorld *w, const double *qhat, const double obj[3], const double target[3]);
  /* fills R, p and contacts (and, in dynamic mode, qhat and obj) from the state */
  void (*update)(stWorld *w);
  void (*joint_angles)(const stWorld *w, double *angle);

  void (*step)(stWorld *w, const double *y); /* one control step, step incremented */
  void (*set_seed)(stWorld *w, uint64_t key);
  void (*set_object_table_collision)(stWorld *w, int on);
  int (*object_fell)(const stWorld *w);
  double (*object_ceiling)(const stWorld *w);
  int (*unstable)(const stWorld *w);
  const char *(*unstable_reason)(const stWorld *w);
  void (*info)(const stWorld *w, stDynInfo *info);
  /* the object's rotation (world <- object, row-major; read only): NULL for an object that
   * never turns (identity) */
  void (*object_rotation)(const stWorld *w, double R[9]);
} stWorldBackend;

/* Every backend's state, which stWorld.internal_ points to, starts with this head: the
 * backend's operations, set at creation. */
typedef struct stWorldHead {
  const stWorldBackend *backend;
} stWorldHead;

/* Creation of a backend's state into a world that lib/world/world.c has allocated (robot, scene,
 * R and p set, everything else zero). On failure the backend may leave partial state in
 * w->internal_ (its head set): lib/world/world.c then destroys the world through it. */
stStatus st__kin_create(stWorld *w, char *err, size_t errsz);
stStatus st__dyn_create(stWorld *w, const stDynDef *def, char *err, size_t errsz);

#endif
