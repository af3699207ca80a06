/* SPDX-License-Identifier: MIT
 * Fuzz target: the URDF importer (st__model_parse_urdf, lib/model/model_internal.h; meshes are
 * looked for in a directory that does not exist). Property: a model it accepts holds only what
 * the world can simulate (docs/PROTOCOL.md, "Robot model": the limits checked at load). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "model/model_internal.h"

static void require(int ok, const char *what, int i) {
  if (ok) return;
  fprintf(stderr, "an accepted model breaks its limits: %s %d\n", what, i);
  abort();
}

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static void check_model(const stModel *m) {
  require(m->nbody >= 1, "nbody", m->nbody);
  for (int b = 0; b < m->nbody; b++) {
    require(b == 0 ? m->body_parent[b] == -1 : m->body_parent[b] >= 0 && m->body_parent[b] < b,
            "parent of body", b);
    require(m->body_mass[b] == 0 || (m->body_mass[b] >= 1e-6 && m->body_mass[b] <= 1e3), "mass of body", b);
    require(norm3(m->body_com[b]) <= 10 && norm3(m->jnt_pos[b]) <= 10, "origins of body", b);
    for (int k = 0; k < 9; k++) require(isfinite(m->body_inertia[b][k]) && isfinite(m->jnt_rot[b][k]), "matrices of body", b);
    if (m->jnt_type[b] == ST_JOINT_REVOLUTE) require(fabs(norm3(m->jnt_axis[b]) - 1) < 1e-9, "axis of joint", b);
  }
  for (int g = 0; g < m->ngeom; g++) {
    require(m->geom_body[g] >= 0 && m->geom_body[g] < m->nbody, "body of geom", g);
    require(norm3(m->geom_pos[g]) <= 10, "origin of geom", g);
    const int n = m->geom_type[g] == ST_GEOM_SPHERE ? 1 : m->geom_type[g] == ST_GEOM_CYLINDER ? 2
                : m->geom_type[g] == ST_GEOM_BOX ? 3 : 0;
    for (int k = 0; k < n; k++) require(m->geom_size[g][k] >= 1e-6 && m->geom_size[g][k] <= 10, "size of geom", g);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  stModel *m = NULL;
  char err[2048];
  if (st__model_parse_urdf("fuzz.urdf", "/nonexistent-fuzz-meshes", (const char *)data, size, &m,
                           err, sizeof err))
    return 0;
  check_model(m);
  st_model_destroy(m);
  return 0;
}
