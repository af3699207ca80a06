/* SPDX-License-Identifier: MIT
 * libselftalk: the robot model's storage (one allocation) and look-ups. The URDF importer is
 * lib/model/model_urdf.cpp. */
#include "selftalk/model.h"

#include "core/internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "model/model_internal.h"

/* every array starts on this boundary (enough for double and int) */
#define ST_MODEL_ALIGN 16

/* adds an array of count elements of size elem to the layout; returns its offset or
 * SIZE_MAX on overflow */
static size_t layout_add(size_t *total, size_t count, size_t elem) {
  size_t off = (*total + (ST_MODEL_ALIGN - 1)) & ~(size_t)(ST_MODEL_ALIGN - 1);
  if (off < *total || (count && elem > (SIZE_MAX - off) / count)) return SIZE_MAX;
  *total = off + count * elem;
  return off;
}

/* The arrays of stModel in layout order: X(field, count). One list drives both the size
 * computation and the pointer assignment, so they cannot disagree. */
#define ST_MODEL_ARRAYS(X)                                                                  \
  X(body_name, nb) X(body_parent, nb) X(body_mass, nb) X(body_com, nb) X(body_inertia, nb)  \
  X(jnt_name, nb) X(jnt_type, nb) X(jnt_pos, nb) X(jnt_rot, nb) X(jnt_axis, nb)             \
  X(jnt_range, nb) X(jnt_effort, nb) X(jnt_velocity, nb) X(jnt_mimic, nb)                   \
  X(jnt_mimic_mult, nb) X(jnt_mimic_offset, nb)                                             \
  X(geom_body, ng) X(geom_type, ng) X(geom_size, ng) X(geom_pos, ng) X(geom_rot, ng)        \
  X(geom_vert0, ng) X(geom_nvert, ng) X(geom_tri0, ng) X(geom_ntri, ng)                     \
  X(mesh_vert, nv) X(mesh_tri, nt)

static void set_identity(double *m) {
  memset(m, 0, 9 * sizeof *m);
  m[0] = m[4] = m[8] = 1.0;
}

stModel *st__model_alloc(int nbody, int ngeom, int nvert, int ntri) {
  if (nbody < 1 || ngeom < 0 || nvert < 0 || ntri < 0) return NULL;
  size_t nb = (size_t)nbody, ng = (size_t)ngeom, nv = (size_t)nvert, nt = (size_t)ntri;
  stModel tmp; /* only for sizeof of the element types */
  size_t total = 0;
  if (layout_add(&total, 1, sizeof tmp) == SIZE_MAX) return NULL;
#define X(field, n)                                                    \
  size_t off_##field = layout_add(&total, n, sizeof *tmp.field);       \
  if (off_##field == SIZE_MAX) return NULL;
  ST_MODEL_ARRAYS(X)
#undef X
  char *buf = calloc(1, total);
  if (!buf) return NULL;
  stModel *m = (stModel *)buf;
  m->nbody = nbody;
  m->ngeom = ngeom;
  m->nvert = nvert;
  m->ntri = ntri;
  m->buffer_ = buf;
#define X(field, n) m->field = (void *)(buf + off_##field);
  ST_MODEL_ARRAYS(X)
#undef X
  for (int b = 0; b < nbody; b++) {
    m->body_parent[b] = -1;
    m->jnt_type[b] = ST_JOINT_FIXED;
    set_identity(m->jnt_rot[b]);
    m->jnt_mimic[b] = -1;
    m->jnt_mimic_mult[b] = 1.0;
  }
  for (int g = 0; g < ngeom; g++) set_identity(m->geom_rot[g]);
  return m;
}

void st_model_destroy(stModel *model) {
  if (model) free(model->buffer_); /* the struct itself lives in buffer_ */
}

int st_model_body(const stModel *model, const char *link_name) {
  ST_ASSERT(model && link_name);
  if (!model || !link_name) return -1;
  for (int b = 0; b < model->nbody; b++)
    if (!strncmp(model->body_name[b], link_name, ST_NAME_MAX)) return b;
  return -1;
}

int st_model_joint(const stModel *model, const char *joint_name) {
  ST_ASSERT(model && joint_name);
  if (!model || !joint_name) return -1;
  for (int b = 1; b < model->nbody; b++) /* entry 0 (the root) has no joint */
    if (!strncmp(model->jnt_name[b], joint_name, ST_NAME_MAX)) return b;
  return -1;
}

const char *st_geom_type_name(int type) {
  static const char *const names[ST_GEOM_TYPE_COUNT] = {"sphere", "box", "cylinder", "mesh"};
  return type >= 0 && type < ST_GEOM_TYPE_COUNT ? names[type] : "?";
}
