/* SPDX-License-Identifier: MIT
 * The public st_world_* functions: allocation of an stWorld and dispatch to its backend,
 * kinematic (lib/world/kinworld.c) or dynamic (lib/world/dynworld.c), through the operations its state
 * carries (lib/world/world_backend.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "world/world_backend.h"
#include "world/world_geom.h"

static const stWorldBackend *backend(const stWorld *w) {
  ST_ASSERT(w && w->internal_); /* every public function's world: created, not destroyed */
  return ((const stWorldHead *)w->internal_)->backend;
}

/* the stWorld and its pose arrays; NULL when out of memory */
static stWorld *world_new(const stRobot *robot, const stScene *scene) {
  stWorld *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->robot = robot;
  w->scene = scene;
  w->R = calloc((size_t)robot->nbody, sizeof *w->R);
  w->p = calloc((size_t)robot->nbody, sizeof *w->p);
  if (!w->R || !w->p) {
    st_world_destroy(w);
    return NULL;
  }
  return w;
}

/* hands the created world out, or destroys it after a failed backend creation */
static stStatus world_finish(stWorld *w, stStatus st, stWorld **out) {
  if (st) {
    st_world_destroy(w);
    return st;
  }
  *out = w;
  return ST_OK;
}

stStatus st_world_create(const stRobot *robot, const stScene *scene, stWorld **out, char *err,
                         size_t errsz) {
  ST_ASSERT(robot && scene && out);
  *out = NULL;
  stWorld *w = world_new(robot, scene);
  if (!w) return st__errf(err, errsz, "world: out of memory"), ST_ERR_NOMEM;
  return world_finish(w, st__kin_create(w, err, errsz), out);
}

stStatus st_world_create_dynamic(const stRobot *robot, const stScene *scene, const stDynDef *def,
                                 stWorld **out, char *err, size_t errsz) {
  ST_ASSERT(robot && scene && def && out);
  *out = NULL;
  stWorld *w = world_new(robot, scene);
  if (!w) return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  w->dynamic = 1;
  return world_finish(w, st__dyn_create(w, def, err, errsz), out);
}

void st_world_destroy(stWorld *w) {
  if (!w) return;
  if (w->internal_) backend(w)->destroy(w);
  free(w->R);
  free(w->p);
  free(w);
}

void st_world_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]) {
  ST_ASSERT(w && qhat && obj && target);
  backend(w)->reset(w, qhat, obj, target);
}

void st_world_update(stWorld *w) { backend(w)->update(w); }

double st_actuate(double qhat, double y, double alpha, double vmax_deg, double dt,
                  double range_deg) {
  double v = alpha * (y - qhat); /* deg/s */
  if (v > vmax_deg) v = vmax_deg;
  if (v < -vmax_deg) v = -vmax_deg;
  double q = qhat + v * dt / range_deg;
  return q < 0.0 ? 0.0 : q > 1.0 ? 1.0 : q;
}

/* the kinematic mode's step: the actuation law on qhat, then the backend's poses and contacts */
void st_world_step_kinematic(stWorld *w, const double *y) {
  ST_ASSERT(w && y);
  const stRobot *r = w->robot;
  const double vmax_deg = r->max_velocity / ST_DEG;
  for (int d = 0; d < ST_NDOF; d++) {
    double range_deg = (r->dof_hi[d] - r->dof_lo[d]) / ST_DEG;
    w->qhat[d] = st_actuate(w->qhat[d], y[d], r->alpha_kinematic, vmax_deg, r->dt, range_deg);
  }
  w->step++;
  backend(w)->update(w);
}

void st_world_step_dynamic(stWorld *w, const double *y) {
  ST_ASSERT(w && y);
  if (backend(w)->step) backend(w)->step(w, y);
  else st_world_step_kinematic(w, y);
}

void st_world_step(stWorld *w, const double *y) { st_world_step_dynamic(w, y); }

void st_world_point(const stWorld *w, int b, const double l[3], double out[3]) {
  ST_ASSERT(w && l && out);
  ST_ASSERT(b >= 0 && b < w->robot->nbody);
  st__frame_point(w->R[b], w->p[b], l, out);
}

void st_world_joint_angles(const stWorld *w, double *angle) {
  ST_ASSERT(angle);
  backend(w)->joint_angles(w, angle);
}

/* ---- dynamics: the answers of a world without them where the backend has none ------------- */

void st_world_set_seed(stWorld *w, uint64_t key) {
  if (backend(w)->set_seed) backend(w)->set_seed(w, key);
}

void st_world_set_object_table_collision(stWorld *w, int on) {
  ST_ASSERT(w);
  if (backend(w)->set_object_table_collision) backend(w)->set_object_table_collision(w, on);
}

int st_world_object_fell(const stWorld *w) {
  return backend(w)->object_fell ? backend(w)->object_fell(w) : 0;
}

double st_world_object_ceiling(const stWorld *w) {
  ST_ASSERT(w);
  return backend(w)->object_ceiling ? backend(w)->object_ceiling(w) : INFINITY;
}

int st_world_unstable(const stWorld *w) {
  return backend(w)->unstable ? backend(w)->unstable(w) : 0;
}

const char *st_world_unstable_reason(const stWorld *w) {
  return backend(w)->unstable_reason ? backend(w)->unstable_reason(w) : "";
}

void st_world_dynamic_info(const stWorld *w, stDynInfo *info) {
  ST_ASSERT(info);
  memset(info, 0, sizeof *info);
  if (backend(w)->info) backend(w)->info(w, info);
}

/* ---- shapes (selftalk/world.h) ------------------------------------------------------------ */

const char *st_shape_kind_name(int kind) {
  static const char *const names[ST_SHAPE_KIND_COUNT] = {"robot", "ball", "table", "target"};
  return kind >= 0 && kind < ST_SHAPE_KIND_COUNT ? names[kind] : "?";
}

static const double IDENTITY[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/* a shape of the scene: axes R (identity when NULL), full extents ex, ey, ez */
static stShape scene_shape(stShapeKind kind, stGeomType type, const double *R, double ex,
                           double ey, double ez) {
  stShape s = {kind, type, -1, -1, st_shape_kind_name(kind), {ex, ey, ez}, {0, 0, 0}, {0}};
  memcpy(s.R, R ? R : IDENTITY, sizeof s.R);
  return s;
}

/* a mesh's vertices' bounding box in its own frame: centre c, full extents ext */
static void mesh_box(const stModel *m, int gi, double c[3], double ext[3]) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int v = 0; v < m->geom_nvert[gi]; v++)
    for (int k = 0; k < 3; k++) {
      const double x = m->mesh_vert[m->geom_vert0[gi] + v][k];
      lo[k] = fmin(lo[k], x);
      hi[k] = fmax(hi[k], x);
    }
  for (int k = 0; k < 3; k++) {
    const int empty = !(hi[k] >= lo[k]);
    c[k] = empty ? 0.0 : 0.5 * (lo[k] + hi[k]);
    ext[k] = empty ? 0.0 : hi[k] - lo[k];
  }
}

/* model geometry gi at the world's poses */
static stShape robot_shape(const stWorld *w, int gi) {
  const stModel *m = w->robot->model;
  const int b = m->geom_body[gi];
  const double *sz = m->geom_size[gi];
  stShape s = {ST_SHAPE_ROBOT, (stGeomType)m->geom_type[gi], b, gi, m->body_name[b],
               {0, 0, 0}, {0, 0, 0}, {0}};
  double c[3] = {0, 0, 0}, local[3];
  switch (s.type) {
    case ST_GEOM_SPHERE: s.size[0] = s.size[1] = s.size[2] = 2.0 * sz[0]; break;
    case ST_GEOM_BOX: memcpy(s.size, sz, sizeof s.size); break;
    case ST_GEOM_CYLINDER:
      s.size[0] = s.size[1] = 2.0 * sz[0];
      s.size[2] = sz[1];
      break;
    default: mesh_box(m, gi, c, s.size); break;
  }
  st__mat3_vec(m->geom_rot[gi], c, local); /* the centre in the body frame */
  for (int k = 0; k < 3; k++) local[k] += m->geom_pos[gi][k];
  st__frame_point(w->R[b], w->p[b], local, s.pos);
  st__mat3_mul(w->R[b], m->geom_rot[gi], s.R);
  return s;
}

/* the scene's shapes in order: ball sphere, ball base (when the scene has one), table,
 * target; returns their count */
static int scene_shapes(const stWorld *w, stShape out[4]) {
  const stScene *sc = w->scene;
  double Ro[9];
  if (backend(w)->object_rotation) backend(w)->object_rotation(w, Ro);
  else memcpy(Ro, IDENTITY, sizeof Ro);
  const double d = 2.0 * sc->obj_radius;
  int n = 0;
  out[n] = scene_shape(ST_SHAPE_BALL, ST_GEOM_SPHERE, Ro, d, d, d);
  memcpy(out[n++].pos, w->obj, sizeof w->obj);
  if (sc->base_radius > 0 && sc->base_height > 0) { /* as lib/world/world_geom.c makes it */
    const double db = 2.0 * sc->base_radius;
    const double off[3] = {0, 0, -sc->obj_radius + 0.5 * sc->base_height};
    out[n] = scene_shape(ST_SHAPE_BALL, ST_GEOM_CYLINDER, Ro, db, db, sc->base_height);
    st__frame_point(Ro, w->obj, off, out[n++].pos);
  }
  const double *lo = sc->table_lo, *hi = sc->table_hi;
  out[n] = scene_shape(ST_SHAPE_TABLE, ST_GEOM_BOX, NULL, hi[0] - lo[0], hi[1] - lo[1],
                       hi[2] - lo[2]);
  for (int k = 0; k < 3; k++) out[n].pos[k] = 0.5 * (lo[k] + hi[k]);
  n++;
  const double dt = 2.0 * sc->target_radius;
  out[n] = scene_shape(ST_SHAPE_TARGET, ST_GEOM_SPHERE, NULL, dt, dt, dt);
  memcpy(out[n++].pos, w->target, sizeof w->target);
  return n;
}

int st_world_shapes(const stWorld *w, stShape *out, int max) {
  ST_ASSERT(w && max >= 0 && (out || max == 0));
  const int ngeom = w->robot->model->ngeom;
  stShape scene[4];
  const int nscene = scene_shapes(w, scene);
  for (int i = 0; i < ngeom && i < max; i++) out[i] = robot_shape(w, i);
  for (int i = 0; i < nscene && ngeom + i < max; i++) out[ngeom + i] = scene[i];
  return ngeom + nscene;
}
