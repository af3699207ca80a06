/* SPDX-License-Identifier: MIT
 * libselftalk: ODE geometry shared by the two world backends (lib/world/kinworld.c, lib/world/dynworld.c):
 * the robot's collision shapes, the scene's table and object, bounding volumes and the 3x3
 * arithmetic they need; not installed. Matrices are row-major 3x3 (world <- local). */
#ifndef SELFTALK_WORLD_GEOM_H
#define SELFTALK_WORLD_GEOM_H

#include <ode/ode.h>

#include "selftalk/model.h"
#include "selftalk/scene.h"

/* C = A B */
static inline void st__mat3_mul(const double *A, const double *B, double *C) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

/* y = A x */
static inline void st__mat3_vec(const double *A, const double *x, double *y) {
  for (int i = 0; i < 3; i++) y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}

/* out = p + R l: a point given in the frame R, p, in the world (summed in this order; the
 * dynamic world's st__mat3_vec then + p rounds differently, and each keeps its own) */
static inline void st__frame_point(const double R[9], const double p[3], const double l[3],
                                   double out[3]) {
  for (int i = 0; i < 3; i++)
    out[i] = p[i] + R[3 * i] * l[0] + R[3 * i + 1] * l[1] + R[3 * i + 2] * l[2];
}

/* R in ODE's layout (3x4, rows padded) */
static inline void st__mat3_to_ode(const double *R, dMatrix3 out) {
  for (int i = 0; i < 3; i++) {
    out[4 * i] = R[3 * i];
    out[4 * i + 1] = R[3 * i + 1];
    out[4 * i + 2] = R[3 * i + 2];
    out[4 * i + 3] = 0;
  }
}

/* 1 when two ODE AABBs (min x, max x, min y, ...) overlap or touch */
static inline int st__aabb_overlap(const dReal *a, const dReal *b) {
  return a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3] && a[4] <= b[5] &&
         b[4] <= a[5];
}

/* The ODE geometry of every collision shape of a model, unplaced and on no body: g[i] is
 * model geometry i. */
typedef struct stRobotGeoms {
  int n;                  /* geometries created so far (all of them after creation) */
  dGeomID *g;             /* (ngeom) */
  dTriMeshDataID *mesh;   /* (ngeom) trimesh data of a mesh geometry, NULL otherwise */
  double *bound;          /* (ngeom) bounding-sphere radius about the geometry's origin */
} stRobotGeoms;

/* Creates every geometry of m into gs (zeroed by the caller). With check_sizes, a shape without
 * a positive finite size (a mesh without a triangle) is refused like an unknown type, with
 * ST_ERR_MODEL and err naming it; ST_ERR_NOMEM when out of memory. gs must be freed with
 * st__robot_geoms_destroy, also after a failure. */
stStatus st__robot_geoms_create(const stModel *m, int check_sizes, stRobotGeoms *gs, char *err,
                                size_t errsz);

/* Frees what st__robot_geoms_create made (nullable contents). */
void st__robot_geoms_destroy(const stModel *m, stRobotGeoms *gs);

/* Exact half extents of a primitive geometry's world AABB about its centre, for its world
 * rotation Rg; returns 0 (half unset) for a mesh, whose extent needs its vertices. */
int st__geom_half_aabb(const stModel *m, int gi, const double *Rg, double half[3]);

/* The scene's geometries, on no body: the table box placed at its box, the object's sphere
 * and (when the scene has one) its flattened base, a vertical cylinder (NULL otherwise). */
typedef struct stSceneGeoms {
  dGeomID table, ball, base;
} stSceneGeoms;

void st__scene_geoms_create(const stScene *s, stSceneGeoms *sg);

/* Frees the scene's geometries (nullable members). */
void st__scene_geoms_destroy(stSceneGeoms *sg);

#endif
