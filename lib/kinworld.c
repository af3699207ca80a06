/* SPDX-License-Identifier: MIT
 * Kinematic world: exact joint integration, forward kinematics, and contact detection with
 * ODE's collision functions (no dynamics world is involved). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <ode/ode.h>
#include <stdlib.h>
#include <string.h>

#include "dynworld.h"
#include "internal.h"
#include "ode_util.h"
#include "selftalk/world.h"

typedef struct geomInfo {
  dGeomID g;
  int body;
  double radius; /* bounding sphere about the geom origin, for culling */
} geomInfo;

typedef struct kinInternal {
  int ngeom;
  geomInfo *geom;
  dGeomID table, ball, base;
  double obj_bound; /* bounding sphere of the object about the sphere centre */
  dTriMeshDataID *meshes;
} kinInternal;

double st_actuate(double qhat, double y, double alpha, double vmax_deg, double dt, double range_deg) {
  double v = alpha * (y - qhat); /* deg/s */
  if (v > vmax_deg) v = vmax_deg;
  if (v < -vmax_deg) v = -vmax_deg;
  double q = qhat + v * dt / range_deg;
  return q < 0.0 ? 0.0 : q > 1.0 ? 1.0 : q;
}

static double geom_bound(const stModel *m, int i) {
  const double *s = m->geom_size[i];
  switch (m->geom_type[i]) {
    case ST_GEOM_SPHERE: return s[0];
    case ST_GEOM_BOX: return 0.5 * sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    case ST_GEOM_CYLINDER: return sqrt(s[0] * s[0] + 0.25 * s[1] * s[1]);
    default: {
      double r2 = 0;
      for (int v = 0; v < m->geom_nvert[i]; v++) {
        const double *x = m->mesh_vert[m->geom_vert0[i] + v];
        double d = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        if (d > r2) r2 = d;
      }
      return sqrt(r2);
    }
  }
}

stStatus st_world_create(const stRobot *robot, const stScene *scene, stWorld **out, char *err,
                         size_t errsz) {
  *out = NULL;
  st__ode_init();
  const stModel *m = robot->model;
  stWorld *w = calloc(1, sizeof *w);
  kinInternal *k = calloc(1, sizeof *k);
  if (!w || !k) goto nomem;
  w->internal_ = k;
  w->robot = robot;
  w->scene = scene;
  w->R = calloc((size_t)robot->nbody, sizeof *w->R);
  w->p = calloc((size_t)robot->nbody, sizeof *w->p);
  k->geom = calloc((size_t)m->ngeom + 1, sizeof *k->geom);
  k->meshes = calloc((size_t)m->ngeom + 1, sizeof *k->meshes);
  if (!w->R || !w->p || !k->geom || !k->meshes) goto nomem;
  for (int i = 0; i < m->ngeom; i++) {
    const double *s = m->geom_size[i];
    dGeomID g = NULL;
    switch (m->geom_type[i]) {
      case ST_GEOM_SPHERE: g = dCreateSphere(0, s[0]); break;
      case ST_GEOM_BOX: g = dCreateBox(0, s[0], s[1], s[2]); break;
      case ST_GEOM_CYLINDER: g = dCreateCylinder(0, s[0], s[1]); break;
      case ST_GEOM_MESH: {
        dTriMeshDataID d = dGeomTriMeshDataCreate();
        dGeomTriMeshDataBuildDouble(d, m->mesh_vert[m->geom_vert0[i]], sizeof(double[3]),
                                    m->geom_nvert[i], m->mesh_tri[m->geom_tri0[i]],
                                    3 * m->geom_ntri[i], sizeof(int[3]));
        k->meshes[i] = d;
        g = dCreateTriMesh(0, d, NULL, NULL, NULL);
        break;
      }
      default: break;
    }
    if (!g) {
      st__errf(err, errsz, "geometry %d of link '%s': unsupported type", i,
               m->body_name[m->geom_body[i]]);
      st_world_destroy(w);
      return ST_ERR_MODEL;
    }
    k->geom[k->ngeom].g = g;
    k->geom[k->ngeom].body = m->geom_body[i];
    k->geom[k->ngeom].radius = geom_bound(m, i);
    k->ngeom++;
  }
  const double *lo = scene->table_lo, *hi = scene->table_hi;
  k->table = dCreateBox(0, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  dGeomSetPosition(k->table, 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
  k->ball = dCreateSphere(0, scene->obj_radius);
  k->base = scene->base_radius > 0 && scene->base_height > 0
                ? dCreateCylinder(0, scene->base_radius, scene->base_height)
                : NULL;
  /* the base's bottom rim sticks out of the sphere: bound both */
  double rim = sqrt(scene->base_radius * scene->base_radius + scene->obj_radius * scene->obj_radius);
  k->obj_bound = rim > scene->obj_radius ? rim : scene->obj_radius;
  *out = w;
  return ST_OK;
nomem:
  st_world_destroy(w);
  st__errf(err, errsz, "world: out of memory");
  return ST_ERR_NOMEM;
}

void st_world_destroy(stWorld *w) {
  if (!w) return;
  kinInternal *k = w->dynamic ? NULL : w->internal_;
  if (w->dynamic) st__dyn_destroy(w); /* a world of st_world_create_dynamic (lib/dynworld.c) */
  if (k) {
    for (int i = 0; i < k->ngeom; i++) dGeomDestroy(k->geom[i].g);
    if (k->meshes)
      for (int i = 0; i < w->robot->model->ngeom; i++)
        if (k->meshes[i]) dGeomTriMeshDataDestroy(k->meshes[i]);
    if (k->table) dGeomDestroy(k->table);
    if (k->ball) dGeomDestroy(k->ball);
    if (k->base) dGeomDestroy(k->base);
    free(k->geom);
    free(k->meshes);
    free(k);
  }
  free(w->R);
  free(w->p);
  free(w);
}

void st_world_point(const stWorld *w, int b, const double l[3], double out[3]) {
  const double *R = w->R[b], *p = w->p[b];
  for (int i = 0; i < 3; i++) out[i] = p[i] + R[3 * i] * l[0] + R[3 * i + 1] * l[1] + R[3 * i + 2] * l[2];
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

/* world rotation of a geom: body rotation times the geom's local rotation */
static void geom_rot(const stWorld *w, int gi, double *Rg) {
  const stModel *m = w->robot->model;
  const double *Rb = w->R[m->geom_body[gi]], *Rl = m->geom_rot[gi];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      Rg[3 * i + j] = Rb[3 * i] * Rl[j] + Rb[3 * i + 1] * Rl[3 + j] + Rb[3 * i + 2] * Rl[6 + j];
}

static void place_geom(const stWorld *w, int gi, const double c[3], const double *Rg) {
  kinInternal *k = w->internal_;
  dMatrix3 R = {Rg[0], Rg[1], Rg[2], 0, Rg[3], Rg[4], Rg[5], 0, Rg[6], Rg[7], Rg[8], 0};
  dGeomSetPosition(k->geom[gi].g, c[0], c[1], c[2]);
  dGeomSetRotation(k->geom[gi].g, R);
}

/* exact half extents of a primitive's world AABB about its centre; 0 for meshes (unknown) */
static int geom_half_aabb(const stModel *m, int gi, const double *Rg, double half[3]) {
  const double *s = m->geom_size[gi];
  switch (m->geom_type[gi]) {
    case ST_GEOM_SPHERE:
      half[0] = half[1] = half[2] = s[0];
      return 1;
    case ST_GEOM_BOX:
      for (int i = 0; i < 3; i++)
        half[i] = 0.5 * (fabs(Rg[3 * i]) * s[0] + fabs(Rg[3 * i + 1]) * s[1] + fabs(Rg[3 * i + 2]) * s[2]);
      return 1;
    case ST_GEOM_CYLINDER:
      for (int i = 0; i < 3; i++) {
        double u = Rg[3 * i + 2]; /* axis component */
        double rad = 1.0 - u * u;
        half[i] = 0.5 * s[1] * fabs(u) + s[0] * sqrt(rad > 0 ? rad : 0);
      }
      return 1;
    default: return 0;
  }
}

/* contact of a convex geom with the (axis-aligned) table box, deciding exactly from the geom's
 * AABB where possible: disjoint AABBs cannot touch, and a convex body whose AABB lies within
 * the table's x/y extent and overlaps its z range must cross the table (its lowest and highest
 * points bracket part of the slab). Only geoms straddling an edge need the narrow phase. */
static int table_contact(const stWorld *w, int gi, const double c[3], const double *Rg) {
  const stScene *s = w->scene;
  kinInternal *k = w->internal_;
  double half[3];
  if (geom_half_aabb(w->robot->model, gi, Rg, half)) {
    int inside_xy = 1;
    for (int i = 0; i < 3; i++) {
      if (c[i] + half[i] < s->table_lo[i] || c[i] - half[i] > s->table_hi[i]) return 0;
      if (i < 2 && (c[i] - half[i] < s->table_lo[i] || c[i] + half[i] > s->table_hi[i])) inside_xy = 0;
    }
    if (inside_xy) return 1;
  }
  place_geom(w, gi, c, Rg);
  dContactGeom cg;
  return dCollide(k->geom[gi].g, k->table, 1, &cg, sizeof cg) > 0;
}

static int touches(dGeomID a, dGeomID b) {
  dContactGeom cg;
  return b && dCollide(a, b, 1, &cg, sizeof cg) > 0;
}

static void contacts_reference(stWorld *w, stContacts *c);

static void update_contacts(stWorld *w) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  const stScene *s = w->scene;
  kinInternal *k = w->internal_;
  stContacts *c = &w->contacts;
  memset(c, 0, sizeof *c);
  dGeomSetPosition(k->ball, w->obj[0], w->obj[1], w->obj[2]);
  if (k->base) {
    /* base cylinder: axis vertical, bottom flush with the sphere's lowest point */
    dGeomSetPosition(k->base, w->obj[0], w->obj[1],
                     w->obj[2] - s->obj_radius + 0.5 * s->base_height);
  }
  if (w->reference_contacts) {
    contacts_reference(w, c);
    return;
  }
  for (int gi = 0; gi < k->ngeom; gi++) {
    const int b = k->geom[gi].body;
    const double rad = k->geom[gi].radius;
    double ctr[3];
    st_world_point(w, b, m->geom_pos[gi], ctr);
    /* cull by bounding spheres: most geoms are far from both table and object */
    int near_table = box_dist2(ctr, s->table_lo, s->table_hi) <= rad * rad;
    double dx = ctr[0] - w->obj[0], dy = ctr[1] - w->obj[1], dz = ctr[2] - w->obj[2];
    double ro = rad + k->obj_bound;
    int near_obj = dx * dx + dy * dy + dz * dz <= ro * ro;
    if (!near_table && !near_obj) continue;
    double Rg[9];
    geom_rot(w, gi, Rg);
    const int t = r->body_touch[b];
    if (near_table && r->body_is_arm[b] && table_contact(w, gi, ctr, Rg)) {
      c->arm_table = 1;
      if (t >= 0) c->touch[t] = 1;
    }
    if (near_obj) {
      place_geom(w, gi, ctr, Rg);
      if (touches(k->geom[gi].g, k->ball) || touches(k->geom[gi].g, k->base)) {
        c->robot_object = 1;
        if (t >= 0) c->touch[t] = c->touch_object[t] = 1;
      }
    }
  }
  /* the object touches the table when it rests on or sinks into it */
  c->object_table = touches(k->ball, k->table) || touches(k->base, k->table);
}

void st_world_update(stWorld *w) {
  if (w->dynamic) {
    st__dyn_update(w);
    return;
  }
  st_robot_fk(w->robot, w->qhat, w->R, w->p);
  update_contacts(w);
}

void st_world_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
  if (w->dynamic) {
    st__dyn_reset(w, qhat, obj, target);
    return;
  }
  memcpy(w->qhat, qhat, sizeof w->qhat);
  memcpy(w->obj, obj, sizeof w->obj);
  memcpy(w->obj_start, obj, sizeof w->obj_start);
  memcpy(w->target, target, sizeof w->target);
  w->step = 0;
  st_world_update(w);
}

void st_world_step_kinematic(stWorld *w, const double *y) {
  const stRobot *r = w->robot;
  const double vmax_deg = r->max_velocity / ST_DEG;
  for (int d = 0; d < ST_NDOF; d++) {
    double range_deg = (r->dof_hi[d] - r->dof_lo[d]) / ST_DEG;
    w->qhat[d] = st_actuate(w->qhat[d], y[d], r->alpha_kinematic, vmax_deg, r->dt, range_deg);
  }
  w->step++;
  st_world_update(w);
}

static void contacts_reference(stWorld *w, stContacts *c) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  kinInternal *k = w->internal_;
  memset(c, 0, sizeof *c);
  for (int gi = 0; gi < k->ngeom; gi++) {
    const int b = k->geom[gi].body, t = r->body_touch[b];
    double ctr[3], Rg[9];
    st_world_point(w, b, m->geom_pos[gi], ctr);
    geom_rot(w, gi, Rg);
    place_geom(w, gi, ctr, Rg);
    if (r->body_is_arm[b] && touches(k->geom[gi].g, k->table)) {
      c->arm_table = 1;
      if (t >= 0) c->touch[t] = 1;
    }
    if (touches(k->geom[gi].g, k->ball) || touches(k->geom[gi].g, k->base)) {
      c->robot_object = 1;
      if (t >= 0) c->touch[t] = c->touch_object[t] = 1;
    }
  }
  c->object_table = touches(k->ball, k->table) || touches(k->base, k->table);
}
