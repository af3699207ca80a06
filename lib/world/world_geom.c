/* SPDX-License-Identifier: MIT
 * ODE geometry shared by the kinematic and the dynamic world (see world_geom.h). */
#include "world/world_geom.h"

#include <math.h>
#include <stdlib.h>

#include "core/internal.h"

/* ---- the robot's collision shapes -------------------------------------------------------- */

static int finite3(const double *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* a shape ODE can be given: positive finite sizes, a mesh with a triangle */
static int size_ok(const stModel *m, int i) {
  const double *s = m->geom_size[i];
  switch (m->geom_type[i]) {
    case ST_GEOM_SPHERE: return s[0] > 0 && isfinite(s[0]);
    case ST_GEOM_BOX: return s[0] > 0 && s[1] > 0 && s[2] > 0 && finite3(s);
    case ST_GEOM_CYLINDER: return s[0] > 0 && s[1] > 0 && isfinite(s[0]) && isfinite(s[1]);
    case ST_GEOM_MESH: return m->geom_nvert[i] >= 3 && m->geom_ntri[i] >= 1;
    default: return 0;
  }
}

static dGeomID make_geom(const stModel *m, int i, dTriMeshDataID *mesh) {
  const double *s = m->geom_size[i];
  *mesh = NULL;
  switch (m->geom_type[i]) {
    case ST_GEOM_SPHERE: return dCreateSphere(0, s[0]);
    case ST_GEOM_BOX: return dCreateBox(0, s[0], s[1], s[2]);
    case ST_GEOM_CYLINDER: return dCreateCylinder(0, s[0], s[1]);
    case ST_GEOM_MESH: {
      dTriMeshDataID d = dGeomTriMeshDataCreate();
      dGeomTriMeshDataBuildDouble(d, m->mesh_vert[m->geom_vert0[i]], sizeof(double[3]),
                                  m->geom_nvert[i], m->mesh_tri[m->geom_tri0[i]],
                                  3 * m->geom_ntri[i], sizeof(int[3]));
      *mesh = d;
      return dCreateTriMesh(0, d, NULL, NULL, NULL);
    }
    default: return NULL;
  }
}

/* radius of the sphere about the geometry's origin that holds it */
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

stStatus st__robot_geoms_create(const stModel *m, int check_sizes, stRobotGeoms *gs, char *err,
                                size_t errsz) {
  gs->g = calloc((size_t)m->ngeom + 1, sizeof *gs->g);
  gs->mesh = calloc((size_t)m->ngeom + 1, sizeof *gs->mesh);
  gs->bound = calloc((size_t)m->ngeom + 1, sizeof *gs->bound);
  if (!gs->g || !gs->mesh || !gs->bound) {
    st__errf(err, errsz, "world: out of memory");
    return ST_ERR_NOMEM;
  }
  for (int i = 0; i < m->ngeom; i++) {
    dGeomID g = check_sizes && !size_ok(m, i) ? NULL : make_geom(m, i, &gs->mesh[i]);
    if (!g) {
      st__errf(err, errsz, "geometry %d of link '%s': unsupported type or bad size", i,
               m->body_name[m->geom_body[i]]);
      return ST_ERR_MODEL;
    }
    gs->g[gs->n++] = g;
    gs->bound[i] = geom_bound(m, i);
  }
  return ST_OK;
}

void st__robot_geoms_destroy(const stModel *m, stRobotGeoms *gs) {
  if (gs->g)
    for (int i = 0; i < gs->n; i++) dGeomDestroy(gs->g[i]);
  if (gs->mesh)
    for (int i = 0; i < m->ngeom; i++)
      if (gs->mesh[i]) dGeomTriMeshDataDestroy(gs->mesh[i]);
  free(gs->g);
  free(gs->mesh);
  free(gs->bound);
  gs->g = NULL;
  gs->mesh = NULL;
  gs->bound = NULL;
  gs->n = 0;
}

int st__geom_half_aabb(const stModel *m, int gi, const double *Rg, double half[3]) {
  const double *s = m->geom_size[gi];
  switch (m->geom_type[gi]) {
    case ST_GEOM_SPHERE:
      half[0] = half[1] = half[2] = s[0];
      return 1;
    case ST_GEOM_BOX:
      for (int i = 0; i < 3; i++)
        half[i] = 0.5 * (fabs(Rg[3 * i]) * s[0] + fabs(Rg[3 * i + 1]) * s[1] +
                         fabs(Rg[3 * i + 2]) * s[2]);
      return 1;
    case ST_GEOM_CYLINDER:
      for (int i = 0; i < 3; i++) {
        const double u = Rg[3 * i + 2], r2 = 1.0 - u * u; /* u: the axis's component */
        half[i] = 0.5 * s[1] * fabs(u) + s[0] * sqrt(r2 > 0 ? r2 : 0);
      }
      return 1;
    default: return 0;
  }
}

/* ---- the scene ----------------------------------------------------------------------------- */

void st__scene_geoms_create(const stScene *s, stSceneGeoms *sg) {
  const double *lo = s->table_lo, *hi = s->table_hi;
  sg->table = dCreateBox(0, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  dGeomSetPosition(sg->table, 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
  sg->ball = dCreateSphere(0, s->obj_radius);
  sg->base = s->base_radius > 0 && s->base_height > 0
                 ? dCreateCylinder(0, s->base_radius, s->base_height)
                 : NULL;
}

void st__scene_geoms_destroy(stSceneGeoms *sg) {
  if (sg->table) dGeomDestroy(sg->table);
  if (sg->ball) dGeomDestroy(sg->ball);
  if (sg->base) dGeomDestroy(sg->base);
  sg->table = sg->ball = sg->base = NULL;
}
