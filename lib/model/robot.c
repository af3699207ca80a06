/* SPDX-License-Identifier: MIT */
#include "selftalk/robot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "model/model_internal.h"

int st__split_names(const char *list, char names[][ST_NAME_MAX], int max) {
  const int n = st__list_count(list);
  for (int i = 0; i < n; i++) {
    const char *item;
    size_t len;
    st__list_item(list, i, &item, &len);
    if (!len || len >= ST_NAME_MAX) return -1; /* the config refuses empty items */
    if (i < max) {
      memcpy(names[i], item, len);
      names[i][len] = 0;
    }
  }
  return n;
}

/* body index for a link name listed in a config key, or an error naming the key */
static int need_link(const stModel *m, const char *name, const char *key, const char *source,
                     char *err, size_t errsz) {
  int b = st_model_body(m, name);
  if (b < 0)
    st__errf(err, errsz, "robot.%s: link '%s' is not in %s (expected a link of the model)", key,
             name, source);
  return b;
}

/* the body indices of the `want` link names listed in a config key (robot.KEY); -1 with an
 * error naming the key when the count is not `want` or a link is not in the model */
static int need_links(const stModel *m, const char *list, const char *key, int want, int *body,
                      const char *source, char *err, size_t errsz) {
  char links[ST_NTOUCH + 1][ST_NAME_MAX]; /* the longest list, and one more to see an extra */
  ST_ASSERT(want > 0 && want <= ST_NTOUCH);
  const int n = st__split_names(list, links, want + 1);
  if (n != want) {
    st__errf(err, errsz, "robot.%s: %d names (expected %d)", key, n, want);
    return -1;
  }
  for (int i = 0; i < want; i++)
    if ((body[i] = need_link(m, links[i], key, source, err, errsz)) < 0) return -1;
  return 0;
}

static int master_of(const stModel *m, int b) {
  for (int guard = 0; guard < m->nbody && m->jnt_mimic[b] >= 0; guard++) b = m->jnt_mimic[b];
  return b;
}

stStatus st_robot_bind(stModel *m, const stConfig *cfg, const char *source, stRobot **out,
                       char *err, size_t errsz) {
  ST_ASSERT(m && cfg && out);
  *out = NULL;
  stRobot *r = calloc(1, sizeof *r);
  size_t nb = (size_t)m->nbody;
  void *buf = calloc(1, nb * (sizeof(int) * 2 + sizeof(double[2]) + sizeof(uint8_t)) + 64);
  if (!r || !buf) {
    free(r);
    free(buf);
    st_model_destroy(m);
    st__errf(err, errsz, "%s: out of memory", source);
    return ST_ERR_NOMEM;
  }
  r->buffer_ = buf;
  r->model = m;
  r->nbody = m->nbody;
  char *c = buf;
  r->body_range = (double(*)[2])c;
  c += nb * sizeof(double[2]);
  r->body_dof = (int *)c;
  c += nb * sizeof(int);
  r->body_touch = (int *)c;
  c += nb * sizeof(int);
  r->body_is_arm = (uint8_t *)c;

  char names[ST_NDOF + 1][ST_NAME_MAX];
  int n = st__split_names(cfg->robot_dof_joints, names, ST_NDOF + 1);
  if (n != ST_NDOF) {
    st__errf(err, errsz, "robot.dof_joints: %d names (expected %d comma-separated joint names)", n,
             ST_NDOF);
    goto fail;
  }
  for (int b = 0; b < m->nbody; b++) {
    r->body_dof[b] = -1;
    r->body_touch[b] = -1;
    r->body_range[b][0] = m->jnt_range[b][0];
    r->body_range[b][1] = m->jnt_range[b][1];
  }
  const double torso_lo = cfg->robot_torso_min_deg * ST_DEG;
  const double torso_hi = cfg->robot_torso_max_deg * ST_DEG;
  for (int d = 0; d < ST_NDOF; d++) {
    int b = st_model_joint(m, names[d]);
    if (b < 0 || m->jnt_type[b] != ST_JOINT_REVOLUTE) {
      st__errf(err, errsz, "robot.dof_joints: joint '%s' %s %s (expected a revolute joint)",
               names[d], b < 0 ? "is not in" : "is not revolute in", source);
      goto fail;
    }
    if (m->jnt_mimic[b] >= 0) {
      st__errf(err, errsz, "robot.dof_joints: joint '%s' mimics another joint in %s (expected "
               "the master joint of the DOF)", names[d], source);
      goto fail;
    }
    if (!isfinite(m->jnt_range[b][0]) || !isfinite(m->jnt_range[b][1]) ||
        m->jnt_range[b][0] >= m->jnt_range[b][1]) {
      st__errf(err, errsz, "robot.dof_joints: joint '%s' in %s has no finite range (expected "
               "lower < upper limits)", names[d], source);
      goto fail;
    }
    st__strlcpy(r->dof_name[d], names[d], ST_NAME_MAX);
    r->dof_body[d] = b;
    r->dof_lo[d] = m->jnt_range[b][0];
    r->dof_hi[d] = m->jnt_range[b][1];
    if (d == ST_DOF_TORSO_YAW || d == ST_DOF_TORSO_PITCH) {
      /* thesis 2.2: the torso is narrowed to [-10, 40] deg within the robot's range */
      if (torso_lo > r->dof_lo[d]) r->dof_lo[d] = torso_lo;
      if (torso_hi < r->dof_hi[d]) r->dof_hi[d] = torso_hi;
    }
    r->body_range[b][0] = r->dof_lo[d];
    r->body_range[b][1] = r->dof_hi[d];
  }
  /* every revolute joint belongs to one DOF, directly or through a mimic chain */
  r->revolute_z = 1;
  for (int b = 1; b < m->nbody; b++) {
    if (m->jnt_type[b] != ST_JOINT_REVOLUTE) continue;
    int mb = master_of(m, b);
    for (int d = 0; d < ST_NDOF; d++)
      if (r->dof_body[d] == mb) r->body_dof[b] = d;
    if (r->body_dof[b] < 0) {
      st__errf(err, errsz, "%s: joint '%s' is neither a DOF of robot.dof_joints nor mimics one "
               "(expected every revolute joint to be driven)", source, m->jnt_name[b]);
      goto fail;
    }
    r->dof_ncoupled[r->body_dof[b]]++;
    if (b != mb && !(isfinite(r->body_range[b][0]) && r->body_range[b][0] < r->body_range[b][1])) {
      st__errf(err, errsz, "%s: coupled joint '%s' has no finite range (expected lower < upper)",
               source, m->jnt_name[b]);
      goto fail;
    }
    const double *a = m->jnt_axis[b];
    if (!(a[0] == 0.0 && a[1] == 0.0 && a[2] == 1.0)) r->revolute_z = 0;
  }

  if (need_links(m, cfg->robot_touch_links, "touch_links", ST_NTOUCH, r->touch_body, source, err,
                 errsz) ||
      need_links(m, cfg->robot_tip_frames, "tip_frames", ST_NTIP, r->tip_body, source, err, errsz))
    goto fail;
  if ((r->palm_body = need_link(m, cfg->robot_palm_frame, "palm_frame", source, err, errsz)) < 0)
    goto fail;
  int arm0 = need_link(m, cfg->robot_arm_first_link, "arm_first_link", source, err, errsz);
  if (arm0 < 0) goto fail;
  r->ee_body = st_model_body(m, "l_ee");
  for (int b = 0; b < m->nbody; b++) {
    int a = b;
    while (a > 0 && a != arm0) a = m->body_parent[a];
    r->body_is_arm[b] = (uint8_t)(a == arm0);
  }
  /* a touch sensor reports the contacts of its link's own geometry */
  for (int i = 0; i < ST_NTOUCH; i++) r->body_touch[r->touch_body[i]] = i;

  r->alpha_kinematic = cfg->robot_alpha_kinematic;
  r->alpha_dynamic = cfg->robot_alpha_dynamic;
  r->max_velocity = cfg->robot_max_velocity_deg * ST_DEG;
  r->dt = cfg->robot_control_dt;
  *out = r;
  return ST_OK;
fail:
  st_robot_destroy(r);
  return ST_ERR_MODEL;
}

stStatus st_robot_create(const stConfig *cfg, stRobot **robot, char *err, size_t errsz) {
  ST_ASSERT(cfg && robot);
  stModel *m = NULL;
  stStatus st = st_model_load_urdf(cfg->robot_urdf, &m, err, errsz);
  if (st) {
    st__err_key(err, errsz, "robot.urdf");
    return st;
  }
  return st_robot_bind(m, cfg, cfg->robot_urdf, robot, err, errsz);
}

void st_robot_destroy(stRobot *r) {
  if (!r) return;
  st_model_destroy(r->model);
  free(r->buffer_);
  free(r);
}

double st_robot_dof_angle(const stRobot *r, int dof, double qhat) {
  ST_ASSERT(r && dof >= 0 && dof < ST_NDOF);
  return r->dof_lo[dof] + qhat * (r->dof_hi[dof] - r->dof_lo[dof]);
}

double st_robot_dof_qhat(const stRobot *r, int dof, double angle) {
  ST_ASSERT(r && dof >= 0 && dof < ST_NDOF);
  return (angle - r->dof_lo[dof]) / (r->dof_hi[dof] - r->dof_lo[dof]);
}

void st_robot_angles(const stRobot *r, const double *qhat, double *angle) {
  ST_ASSERT(r && qhat && angle);
  for (int b = 0; b < r->nbody; b++) {
    int d = r->body_dof[b];
    angle[b] = d < 0 ? 0.0
                     : r->body_range[b][0] + qhat[d] * (r->body_range[b][1] - r->body_range[b][0]);
  }
}

/* rotation by angle q about unit axis a (Rodrigues) */
static void axis_rot(const double *a, double q, double *R) {
  double c = cos(q), s = sin(q), t = 1.0 - c;
  R[0] = t * a[0] * a[0] + c;
  R[1] = t * a[0] * a[1] - s * a[2];
  R[2] = t * a[0] * a[2] + s * a[1];
  R[3] = t * a[0] * a[1] + s * a[2];
  R[4] = t * a[1] * a[1] + c;
  R[5] = t * a[1] * a[2] - s * a[0];
  R[6] = t * a[0] * a[2] - s * a[1];
  R[7] = t * a[1] * a[2] + s * a[0];
  R[8] = t * a[2] * a[2] + c;
}

/* the hot loop of every kinematic step: written out so the compiler keeps it in registers */
void st_robot_fk_angles(const stRobot *r, const double *restrict angle, double (*restrict R)[9],
                        double (*restrict p)[3]) {
  const stModel *m = r->model;
  static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  memcpy(R[0], I, sizeof I);
  p[0][0] = p[0][1] = p[0][2] = 0.0;
  double last_q = 0.0, c = 1.0, s = 0.0; /* coupled joints repeat an angle: reuse its sincos */
  for (int b = 1; b < m->nbody; b++) {
    const int pb = m->body_parent[b];
    const double *restrict Rp = R[pb];
    const double *restrict o = m->jnt_pos[b];
    const double *restrict Ro = m->jnt_rot[b];
    const double r0 = Rp[0], r1 = Rp[1], r2 = Rp[2], r3 = Rp[3], r4 = Rp[4], r5 = Rp[5],
                 r6 = Rp[6], r7 = Rp[7], r8 = Rp[8];
    p[b][0] = p[pb][0] + r0 * o[0] + r1 * o[1] + r2 * o[2];
    p[b][1] = p[pb][1] + r3 * o[0] + r4 * o[1] + r5 * o[2];
    p[b][2] = p[pb][2] + r6 * o[0] + r7 * o[1] + r8 * o[2];
    double M[9];
    if (m->jnt_type[b] != ST_JOINT_REVOLUTE) {
      memcpy(M, Ro, sizeof M);
    } else if (r->revolute_z) {
      if (angle[b] != last_q) {
        last_q = angle[b];
        c = cos(last_q);
        s = sin(last_q);
      }
      /* Ro Rz(q): column 0 = c x + s y, column 1 = -s x + c y, column 2 = z */
      for (int i = 0; i < 3; i++) {
        M[3 * i] = c * Ro[3 * i] + s * Ro[3 * i + 1];
        M[3 * i + 1] = c * Ro[3 * i + 1] - s * Ro[3 * i];
        M[3 * i + 2] = Ro[3 * i + 2];
      }
    } else {
      double Ra[9];
      axis_rot(m->jnt_axis[b], angle[b], Ra);
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          M[3 * i + j] = Ro[3 * i] * Ra[j] + Ro[3 * i + 1] * Ra[3 + j] + Ro[3 * i + 2] * Ra[6 + j];
    }
    double *restrict Rb = R[b];
    Rb[0] = r0 * M[0] + r1 * M[3] + r2 * M[6];
    Rb[1] = r0 * M[1] + r1 * M[4] + r2 * M[7];
    Rb[2] = r0 * M[2] + r1 * M[5] + r2 * M[8];
    Rb[3] = r3 * M[0] + r4 * M[3] + r5 * M[6];
    Rb[4] = r3 * M[1] + r4 * M[4] + r5 * M[7];
    Rb[5] = r3 * M[2] + r4 * M[5] + r5 * M[8];
    Rb[6] = r6 * M[0] + r7 * M[3] + r8 * M[6];
    Rb[7] = r6 * M[1] + r7 * M[4] + r8 * M[7];
    Rb[8] = r6 * M[2] + r7 * M[5] + r8 * M[8];
  }
}

void st_robot_point_local(const double R[9], const double p[3], const double world[3],
                          double local[3]) {
  const double d[3] = {world[0] - p[0], world[1] - p[1], world[2] - p[2]};
  for (int i = 0; i < 3; i++) local[i] = R[i] * d[0] + R[3 + i] * d[1] + R[6 + i] * d[2];
}

void st_robot_fk(const stRobot *r, const double *qhat, double (*R)[9], double (*p)[3]) {
  ST_ASSERT(r && qhat && R && p);
  double angle[256];
  double *a = r->nbody <= 256 ? angle : malloc(sizeof(double) * (size_t)r->nbody);
  st_robot_angles(r, qhat, a);
  st_robot_fk_angles(r, a, R, p);
  if (a != angle) free(a);
}

/* ---- how low the robot reaches (st_robot_lowest_z) ---- */

/* radius of the sphere about geometry g's origin that holds it */
static double geom_radius(const stModel *m, int g) {
  const double *s = m->geom_size[g];
  switch (m->geom_type[g]) {
    case ST_GEOM_SPHERE: return s[0];
    case ST_GEOM_BOX: return 0.5 * st__norm3(s);
    case ST_GEOM_CYLINDER: return sqrt(s[0] * s[0] + 0.25 * s[1] * s[1]);
    default: {
      double r = 0.0;
      for (int v = 0; v < m->geom_nvert[g]; v++) r = fmax(r, st__norm3(m->mesh_vert[m->geom_vert0[g] + v]));
      return r;
    }
  }
}

enum { LOW_GRID_JOINTS = 3, LOW_GRID_POINTS = 110592 /* 48^3 */ };

void st_robot_lowest_z(const stRobot *r, double tol, double *geom_z, double *palm_z) {
  ST_ASSERT(r && geom_z && palm_z && tol >= 0.0);
  const stModel *m = r->model;
  const int nb = m->nbody;
  /* per body: revolute joints from the root to it (its own included), the sum of the joint
   * offsets from the root (|p_b - p_a| <= cum[b] - cum[a] for an ancestor a, any angles) */
  int *nrev = calloc((size_t)nb, sizeof *nrev), *anchor = calloc((size_t)nb, sizeof *anchor);
  double *cum = calloc((size_t)nb, sizeof *cum), *zmin = calloc((size_t)nb, sizeof *zmin);
  double *err = calloc((size_t)nb, sizeof *err), *angle = calloc((size_t)nb, sizeof *angle);
  double(*R)[9] = malloc(sizeof *R * (size_t)nb);
  double(*p)[3] = malloc(sizeof *p * (size_t)nb);
  if (!nrev || !anchor || !cum || !zmin || !err || !angle || !R || !p) {
    *geom_z = *palm_z = -INFINITY; /* no bound: nothing is ever out of reach */
    goto done;
  }
  for (int b = 1; b < nb; b++) {
    const int pb = m->body_parent[b];
    nrev[b] = nrev[pb] + (m->jnt_type[b] == ST_JOINT_REVOLUTE);
    cum[b] = cum[pb] + st__norm3(m->jnt_pos[b]);
  }
  /* the grid's joints: those with at most ng revolute joints up to them, at most three (a
   * chain's first three; fewer where the tree branches early) */
  int ng = LOW_GRID_JOINTS, grid[LOW_GRID_JOINTS], nj = 0;
  for (;; ng--) {
    nj = 0;
    for (int b = 1; b < nb; b++)
      if (m->jnt_type[b] == ST_JOINT_REVOLUTE && nrev[b] <= ng) {
        if (nj < LOW_GRID_JOINTS) grid[nj] = b;
        nj++;
      }
    if (nj <= LOW_GRID_JOINTS || ng == 0) break;
  }
  if (nj > LOW_GRID_JOINTS) nj = 0;
  /* a body's anchor: its deepest ancestor (or itself) whose origin only the grid's joints move
   * (every revolute joint above its own has nrev <= ng) */
  for (int b = 0; b < nb; b++) {
    int a = b;
    while (a > 0 && nrev[m->body_parent[a]] > ng) a = m->body_parent[a];
    anchor[b] = a;
    zmin[b] = INFINITY;
  }
  int cells = 1;
  while (nj > 0 && (long)(cells + 1) * (nj > 1 ? cells + 1 : 1) * (nj > 2 ? cells + 1 : 1) <= LOW_GRID_POINTS)
    cells++;
  double lo[LOW_GRID_JOINTS], h[LOW_GRID_JOINTS];
  for (int j = 0; j < nj; j++) {
    lo[j] = r->body_range[grid[j]][0] - tol;
    h[j] = (r->body_range[grid[j]][1] + tol - lo[j]) / cells;
  }
  long total = 1;
  for (int j = 0; j < nj; j++) total *= cells;
  for (long i = 0; i < total; i++) { /* cell centres */
    long k = i;
    for (int j = 0; j < nj; j++, k /= cells) angle[grid[j]] = lo[j] + ((double)(k % cells) + 0.5) * h[j];
    st_robot_fk_angles(r, angle, R, p);
    for (int b = 0; b < nb; b++)
      if (anchor[b] == b && p[b][2] < zmin[b]) zmin[b] = p[b][2];
  }
  /* within a cell an anchor's origin moves at most sum over the grid's joints above it of
   * |d p / d angle| * h / 2 <= (cum[a] - cum[joint's body]) * h / 2 (the joint's axis passes
   * through its body's origin) */
  for (int b = 0; b < nb; b++) {
    if (anchor[b] != b) continue;
    for (int j = 0; j < nj; j++)
      for (int a = b; a > 0; a = m->body_parent[a])
        if (a == grid[j]) err[b] += (cum[b] - cum[a]) * 0.5 * h[j];
  }
  *geom_z = INFINITY;
  for (int g = 0; g < m->ngeom; g++) {
    const int b = m->geom_body[g], a = anchor[b];
    const double z = zmin[a] - err[a] - (cum[b] - cum[a]) - st__norm3(m->geom_pos[g]) - geom_radius(m, g);
    if (z < *geom_z) *geom_z = z;
  }
  const int a = anchor[r->palm_body];
  *palm_z = zmin[a] - err[a] - (cum[r->palm_body] - cum[a]);
done:
  free(nrev);
  free(anchor);
  free(cum);
  free(zmin);
  free(err);
  free(angle);
  free(R);
  free(p);
}
