/* SPDX-License-Identifier: MIT
 * Kinematic world backend (lib/world/world_backend.h): forward kinematics of qhat, and contact
 * detection with ODE's collision functions (no dynamics world is involved). Its step is the
 * kinematic actuation law, which lib/world/world.c applies to qhat before calling update. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <ode/ode.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "world/ode_util.h"
#include "world/world_backend.h"
#include "world/world_geom.h"

typedef struct kinInternal {
  stWorldHead head;
  stRobotGeoms geoms;  /* model geometry i is geoms.g[i]; bound culls it */
  stSceneGeoms scene;  /* table, object sphere and base, placed by hand */
  double obj_bound;    /* bounding sphere of the object about the sphere centre */
} kinInternal;

static const stWorldBackend kin_backend;

stStatus st__kin_create(stWorld *w, char *err, size_t errsz) {
  st__ode_init();
  const stScene *scene = w->scene;
  kinInternal *k = calloc(1, sizeof *k);
  if (!k) return st__errf(err, errsz, "world: out of memory"), ST_ERR_NOMEM;
  k->head.backend = &kin_backend;
  w->internal_ = k;
  stStatus st = st__robot_geoms_create(w->robot->model, 0, &k->geoms, err, errsz);
  if (st) return st;
  st__scene_geoms_create(scene, &k->scene);
  /* the base's bottom rim sticks out of the sphere: bound both */
  const double rim =
      sqrt(scene->base_radius * scene->base_radius + scene->obj_radius * scene->obj_radius);
  k->obj_bound = rim > scene->obj_radius ? rim : scene->obj_radius;
  return ST_OK;
}

static void kin_destroy(stWorld *w) {
  kinInternal *k = w->internal_;
  st__robot_geoms_destroy(w->robot->model, &k->geoms);
  st__scene_geoms_destroy(&k->scene);
  free(k);
  w->internal_ = NULL;
}

/* squared distance from a point to an axis-aligned box */
static double box_dist2(const double *c, const double *lo, const double *hi) {
  double d2 = 0;
  for (int i = 0; i < 3; i++) {
    double d = c[i] < lo[i] ? lo[i] - c[i] : c[i] > hi[i] ? c[i] - hi[i] : 0.0;
    d2 += d * d;
  }
  return d2;
}

/* world centre of a geom on body b */
static inline void geom_centre(const stWorld *w, int gi, int b, double c[3]) {
  st__frame_point(w->R[b], w->p[b], w->robot->model->geom_pos[gi], c);
}

/* world rotation of a geom: body rotation times the geom's local rotation */
static void geom_rot(const stWorld *w, int gi, double *Rg) {
  const stModel *m = w->robot->model;
  st__mat3_mul(w->R[m->geom_body[gi]], m->geom_rot[gi], Rg);
}

static void place_geom(const stWorld *w, int gi, const double c[3], const double *Rg) {
  kinInternal *k = w->internal_;
  dMatrix3 R;
  st__mat3_to_ode(Rg, R);
  dGeomSetPosition(k->geoms.g[gi], c[0], c[1], c[2]);
  dGeomSetRotation(k->geoms.g[gi], R);
}

/* contact of a convex geom with the (axis-aligned) table box, deciding exactly from the geom's
 * AABB where possible: disjoint AABBs cannot touch, and a convex body whose AABB lies within
 * the table's x/y extent and overlaps its z range must cross the table (its lowest and highest
 * points bracket part of the slab). Only geoms straddling an edge need the narrow phase. */
static int table_contact(const stWorld *w, int gi, const double c[3], const double *Rg) {
  const stScene *s = w->scene;
  kinInternal *k = w->internal_;
  double half[3];
  if (st__geom_half_aabb(w->robot->model, gi, Rg, half)) {
    int inside_xy = 1;
    for (int i = 0; i < 3; i++) {
      if (c[i] + half[i] < s->table_lo[i] || c[i] - half[i] > s->table_hi[i]) return 0;
      if (i < 2 && (c[i] - half[i] < s->table_lo[i] || c[i] + half[i] > s->table_hi[i]))
        inside_xy = 0;
    }
    if (inside_xy) return 1;
  }
  place_geom(w, gi, c, Rg);
  dContactGeom cg;
  return dCollide(k->geoms.g[gi], k->scene.table, 1, &cg, sizeof cg) > 0;
}

static int touches(dGeomID a, dGeomID b) {
  dContactGeom cg;
  return b && dCollide(a, b, 1, &cg, sizeof cg) > 0;
}

/* the object's geoms at w->obj: the base cylinder's axis vertical, its bottom flush with the
 * sphere's lowest point */
static void place_object(stWorld *w) {
  kinInternal *k = w->internal_;
  const stScene *s = w->scene;
  dGeomSetPosition(k->scene.ball, w->obj[0], w->obj[1], w->obj[2]);
  if (k->scene.base)
    dGeomSetPosition(k->scene.base, w->obj[0], w->obj[1],
                     w->obj[2] - s->obj_radius + 0.5 * s->base_height);
}

/* the flags of one robot geom touching the table (arm geoms only) or the object */
static void geom_touches(stWorld *w, int gi, int table, int object, stContacts *c) {
  const stRobot *r = w->robot;
  kinInternal *k = w->internal_;
  const int b = r->model->geom_body[gi], t = r->body_touch[b];
  if (table) {
    c->arm_table = 1;
    if (t >= 0) c->touch[t] = 1;
  }
  const dGeomID g = k->geoms.g[gi];
  if (object && (touches(g, k->scene.ball) || touches(g, k->scene.base))) {
    c->robot_object = 1;
    if (t >= 0) c->touch[t] = c->touch_object[t] = 1;
  }
}

/* the object touches the table when it rests on or sinks into it */
static int object_on_table(const kinInternal *k) {
  return touches(k->scene.ball, k->scene.table) || touches(k->scene.base, k->scene.table);
}

/* every geometry with ODE's narrow phase (stWorld.reference_contacts) */
static void contacts_reference(stWorld *w, stContacts *c) {
  const stRobot *r = w->robot;
  kinInternal *k = w->internal_;
  for (int gi = 0; gi < k->geoms.n; gi++) {
    const int b = r->model->geom_body[gi];
    double ctr[3], Rg[9];
    geom_centre(w, gi, b, ctr);
    geom_rot(w, gi, Rg);
    place_geom(w, gi, ctr, Rg);
    const int arm = r->body_is_arm[b];
    geom_touches(w, gi, arm && touches(k->geoms.g[gi], k->scene.table), 1, c);
  }
  c->object_table = object_on_table(k);
}

/* the same answer as contacts_reference, with the geoms far from the table and the object
 * culled by bounding spheres and the table decided from AABBs where possible */
static void contacts_culled(stWorld *w, stContacts *c) {
  const stRobot *r = w->robot;
  const stScene *s = w->scene;
  kinInternal *k = w->internal_;
  for (int gi = 0; gi < k->geoms.n; gi++) {
    const int b = r->model->geom_body[gi];
    const double rad = k->geoms.bound[gi];
    double ctr[3];
    geom_centre(w, gi, b, ctr);
    int near_table = box_dist2(ctr, s->table_lo, s->table_hi) <= rad * rad;
    double dx = ctr[0] - w->obj[0], dy = ctr[1] - w->obj[1], dz = ctr[2] - w->obj[2];
    double ro = rad + k->obj_bound;
    int near_obj = dx * dx + dy * dy + dz * dz <= ro * ro;
    if (!near_table && !near_obj) continue;
    double Rg[9];
    geom_rot(w, gi, Rg);
    const int table = near_table && r->body_is_arm[b] && table_contact(w, gi, ctr, Rg);
    if (near_obj) place_geom(w, gi, ctr, Rg);
    geom_touches(w, gi, table, near_obj, c);
  }
  c->object_table = object_on_table(k);
}

static void kin_update(stWorld *w) {
  st_robot_fk(w->robot, w->qhat, w->R, w->p);
  memset(&w->contacts, 0, sizeof w->contacts);
  place_object(w);
  if (w->reference_contacts) contacts_reference(w, &w->contacts);
  else contacts_culled(w, &w->contacts);
}

static void kin_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
  memcpy(w->qhat, qhat, sizeof w->qhat);
  memcpy(w->obj, obj, sizeof w->obj);
  memcpy(w->obj_start, obj, sizeof w->obj_start);
  memcpy(w->target, target, sizeof w->target);
  w->step = 0;
  kin_update(w);
}

static void kin_joint_angles(const stWorld *w, double *angle) {
  st_robot_angles(w->robot, w->qhat, angle);
}

/* no dynamics: the step is the actuation law (lib/world/world.c), the dynamic queries have their
 * defaults */
static const stWorldBackend kin_backend = {
    .destroy = kin_destroy,
    .reset = kin_reset,
    .update = kin_update,
    .joint_angles = kin_joint_angles,
};
