/* SPDX-License-Identifier: MIT
 * libselftalk: the robot model - an immutable description of a kinematic tree (links, joints,
 * inertia, collision geometry), imported from a URDF.
 *
 * The model holds plain numbers only (no simulator handles): it is built once, then read by
 * every thread through a const pointer. All arrays live in one allocation owned by the model
 * (st_model_destroy frees it); reading never allocates. Frames: each body's frame is its
 * parent joint's frame, as in URDF. Angles in radians, lengths in metres. */
#ifndef SELFTALK_MODEL_H
#define SELFTALK_MODEL_H

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_NAME_MAX 64

typedef enum stJointType {
  ST_JOINT_FIXED = 0,
  ST_JOINT_REVOLUTE, /* URDF revolute, or continuous (range -inf..inf) */
  ST_JOINT_TYPE_COUNT
} stJointType;

typedef enum stGeomType {
  ST_GEOM_SPHERE = 0, /* size[0] = radius */
  ST_GEOM_BOX,        /* size = full extents x, y, z */
  ST_GEOM_CYLINDER,   /* size[0] = radius, size[1] = length along the geom's z axis */
  ST_GEOM_MESH,       /* triangles mesh_tri[3*tri0 ..], vertices already scaled, geom frame */
  ST_GEOM_TYPE_COUNT
} stGeomType;

/* A kinematic tree. Body 0 is the root; every other body b has one parent joint connecting
 * it to body_parent[b] < b (parents come before children). */
typedef struct stModel {
  int nbody;
  int ngeom;
  int nvert; /* mesh vertices, all meshes */
  int ntri;  /* mesh triangles, all meshes */

  /* bodies (nbody) */
  char (*body_name)[ST_NAME_MAX];
  int *body_parent;          /* -1 for the root */
  double *body_mass;         /* kg; 0 for a massless frame */
  double (*body_com)[3];     /* centre of mass in the body frame */
  double (*body_inertia)[9]; /* inertia about the COM, body axes, row-major 3x3 */

  /* joint from body_parent[b] to b (entry 0 unused) */
  char (*jnt_name)[ST_NAME_MAX];
  int *jnt_type;           /* stJointType */
  double (*jnt_pos)[3];    /* joint origin in the parent body's frame */
  double (*jnt_rot)[9];    /* joint origin rotation (row-major): parent <- joint frame */
  double (*jnt_axis)[3];   /* unit axis in the joint (= child body) frame */
  double (*jnt_range)[2];  /* lower, upper (rad); -inf, inf when unlimited */
  double *jnt_effort;      /* N m; 0 when the URDF gives none */
  double *jnt_velocity;    /* rad/s; 0 when the URDF gives none */
  int *jnt_mimic;          /* body whose joint this one mimics, or -1 */
  double *jnt_mimic_mult;  /* q = mult * q_master + offset */
  double *jnt_mimic_offset;

  /* collision geometry (ngeom) */
  int *geom_body;
  int *geom_type;          /* stGeomType */
  double (*geom_size)[3];
  double (*geom_pos)[3];   /* in the body frame */
  double (*geom_rot)[9];   /* body <- geom, row-major */
  int *geom_vert0, *geom_nvert; /* ST_GEOM_MESH: vertex range in mesh_vert */
  int *geom_tri0, *geom_ntri;   /* ST_GEOM_MESH: triangle range in mesh_tri */

  double (*mesh_vert)[3];  /* nvert vertices, geom frame, scaled */
  int (*mesh_tri)[3];      /* ntri triangles, indices relative to the geom's geom_vert0 */

  void *buffer_;           /* the one allocation */
} stModel;

/* Imports a URDF (urdfdom; meshes through assimp, relative to the URDF's directory). Refuses
 * what the world cannot simulate (docs/PROTOCOL.md, "Input files and faults"): shape sizes
 * outside [1e-6, 10] m, origins farther than 10 m, masses outside [1e-6, 1e3] kg, inertias not
 * positive definite, above 1e3 kg m^2 or breaking the triangle inequality, joint limits beyond
 * +-2 pi, loops of joints, meshes that are not regular files of at most ST_FILE_MAX bytes or
 * reach beyond 100 m. Errors name the file and the element: "FILE: link 'l_hand': collision
 * mesh 'x.stl': cannot read (...)". On success *model is owned by the caller
 * (st_model_destroy). */
ST_API stStatus st_model_load_urdf(const char *path, stModel **model, char *err, size_t errsz);

/* Nullable: model. */
ST_API void st_model_destroy(stModel *model);

/* Body index of a link name, or -1. */
ST_API int st_model_body(const stModel *model, const char *link_name);

/* Body index whose parent joint has this name, or -1. */
ST_API int st_model_joint(const stModel *model, const char *joint_name);

/* "sphere", "box", "cylinder", "mesh" (stGeomType); "?" for another value. */
ST_API const char *st_geom_type_name(int type);

#ifdef __cplusplus
}
#endif

#endif
