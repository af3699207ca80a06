/* SPDX-License-Identifier: MIT
 * The world's shapes (st_world_shapes, selftalk/world.h): what ./apps/replay --shapes writes
 * and tools/draw_trial.py draws. Expected numbers come from the default config's keys worked
 * by hand (table, ball, target) and from the URDF's fingertip frames through forward
 * kinematics (the tip frames are joints of their own, independent of the collision shapes'
 * offsets). */
#include <math.h>
#include <stdlib.h>

#include "selftalk/postures.h"
#include "selftalk/world.h"
#include "test_util.h"

#define g_cfg (st_test_fixture()->cfg)
#define g_scene (st_test_fixture()->scene)
static stRobot *robot(void) { return st_test_fixture()->robot; }

#define MAX_SHAPES 128

static double dist3(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* R R^T = I and det R = 1 */
static int rotation_ok(const double *R) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const double d =
          R[3 * i] * R[3 * j] + R[3 * i + 1] * R[3 * j + 1] + R[3 * i + 2] * R[3 * j + 2];
      if (fabs(d - (i == j)) > 1e-9) return 0;
    }
  const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                     R[2] * (R[3] * R[7] - R[4] * R[6]);
  return fabs(det - 1.0) < 1e-9;
}

/* the only shape of a kind and type (-1 when there is none or more than one) */
static int find_shape(const stShape *s, int n, stShapeKind kind, stGeomType type) {
  int found = -1;
  for (int i = 0; i < n; i++)
    if (s[i].kind == kind && s[i].type == type) {
      if (found >= 0) return -1;
      found = i;
    }
  return found;
}

/* a kinematic world at the grasp posture k = 0 (the hand around the ball), object P0, T0 */
static stWorld *grasp_world(int dynamic) {
  stRobot *r = robot();
  if (!r) return NULL;
  char err[512];
  double q[ST_NDOF], obj[3], tgt[3];
  if (st_posture(r, &g_scene, ST_PRIM_GRASP, 0, q, err, sizeof err)) {
    fprintf(stderr, "\n  %s\n", err);
    return NULL;
  }
  stWorld *w = NULL;
  stDynDef def;
  st_dyn_def_from_config(&g_cfg, &def);
  stStatus st = dynamic ? st_world_create_dynamic(r, &g_scene, &def, &w, err, sizeof err)
                        : st_world_create(r, &g_scene, &w, err, sizeof err);
  if (st) {
    fprintf(stderr, "\n  %s\n", err);
    return NULL;
  }
  st_scene_object(&g_scene, 0, 0, NULL, obj);
  st_scene_target(&g_scene, 0, NULL, tgt);
  st_world_reset(w, q, obj, tgt);
  return w;
}

/* ---- the scene's shapes: numbers of the default config, by hand -------------------------- */

static void test_shapes_scene(void) {
  stWorld *w = grasp_world(0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(w);
  stShape s[MAX_SHAPES];
  const int n = st_world_shapes(w, s, MAX_SHAPES);
  /* every robot geometry, then ball, base, table, target */
  CU_ASSERT_EQUAL_FATAL(n, w->robot->model->ngeom + 4);
  CU_ASSERT_EQUAL(st_world_shapes(w, NULL, 0), n);
  /* table: x 0.10..0.60, y -0.30..0.50, top at -0.08, 0.03 thick */
  const int t = find_shape(s, n, ST_SHAPE_TABLE, ST_GEOM_BOX);
  CU_ASSERT_FATAL(t >= 0);
  CU_ASSERT_DOUBLE_EQUAL(s[t].pos[2] + 0.5 * s[t].size[2], -0.08, 1e-12); /* the top */
  CU_ASSERT_DOUBLE_EQUAL(s[t].pos[0], 0.35, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[t].pos[1], 0.10, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[t].pos[2], -0.095, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[t].size[0], 0.5, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[t].size[1], 0.8, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[t].size[2], 0.03, 1e-12);
  CU_ASSERT_STRING_EQUAL(s[t].owner, "table");
  /* ball: P0 = centre (0.30, 0.10) + 0.10 in x, resting on the table: z = -0.08 + 0.035 */
  const int b = find_shape(s, n, ST_SHAPE_BALL, ST_GEOM_SPHERE);
  CU_ASSERT_FATAL(b >= 0);
  const double p0[3] = {0.40, 0.10, -0.045};
  CU_ASSERT(dist3(s[b].pos, p0) < 1e-12);
  CU_ASSERT(dist3(s[b].pos, w->obj) == 0.0);
  for (int k = 0; k < 3; k++) CU_ASSERT_DOUBLE_EQUAL(s[b].size[k], 0.07, 1e-12);
  CU_ASSERT_STRING_EQUAL(s[b].owner, "ball");
  /* base: 3.5 cm wide, 1.5 cm high, its bottom at the ball's lowest point: centre z = -0.045 -
   * 0.035 + 0.0075 */
  const int c = find_shape(s, n, ST_SHAPE_BALL, ST_GEOM_CYLINDER);
  CU_ASSERT_FATAL(c >= 0);
  const double base[3] = {0.40, 0.10, -0.0725};
  CU_ASSERT(dist3(s[c].pos, base) < 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[c].size[0], 0.035, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[c].size[2], 0.015, 1e-12);
  /* target T0 (0.25, 0.10, 0.17), the 6 cm success radius */
  const int g = find_shape(s, n, ST_SHAPE_TARGET, ST_GEOM_SPHERE);
  CU_ASSERT_FATAL(g >= 0);
  const double t0[3] = {0.25, 0.10, 0.17};
  CU_ASSERT(dist3(s[g].pos, t0) < 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[g].size[0], 0.12, 1e-12);
  CU_ASSERT_STRING_EQUAL(s[g].owner, "target");
  for (int i = 0; i < n; i++) CU_ASSERT(rotation_ok(s[i].R));
  st_world_destroy(w);
}

/* ---- the robot's shapes against the URDF's fingertip frames ------------------------------- */

/* the distal phalanx's cylinder of fingertip f: its ends are the phalanx's joint and the tip */
static void check_tip(const stWorld *w, const stShape *s, int n, int f, const double (*R)[9],
                      const double (*p)[3]) {
  const stRobot *r = w->robot;
  const int link = r->touch_body[f], tip = r->tip_body[f];
  int found = 0;
  for (int i = 0; i < n; i++) {
    if (s[i].kind != ST_SHAPE_ROBOT || s[i].body != link) continue;
    found++;
    CU_ASSERT_EQUAL(s[i].type, ST_GEOM_CYLINDER);
    CU_ASSERT_STRING_EQUAL(s[i].owner, r->model->body_name[link]);
    double end[2][3];
    for (int k = 0; k < 3; k++) {
      const double axis = s[i].R[3 * k + 2] * 0.5 * s[i].size[2];
      end[0][k] = s[i].pos[k] - axis;
      end[1][k] = s[i].pos[k] + axis;
    }
    const int far = dist3(end[1], p[link]) > dist3(end[0], p[link]);
    const double e_tip = dist3(end[far], p[tip]), e_joint = dist3(end[!far], p[link]);
    CU_ASSERT(e_tip < 1e-9);
    CU_ASSERT(e_joint < 1e-9);
    /* the cylinder's axis is the tip frame's x axis (the phalanx's direction) */
    const double dot = s[i].R[2] * R[tip][0] + s[i].R[5] * R[tip][3] + s[i].R[8] * R[tip][6];
    CU_ASSERT_DOUBLE_EQUAL(fabs(dot), 1.0, 1e-9);
    if (e_tip >= 1e-9 || e_joint >= 1e-9)
      fprintf(stderr, "\n  fingertip %d: tip %.3g m, joint %.3g m off\n", f, e_tip, e_joint);
  }
  CU_ASSERT_EQUAL(found, 1);
}

static void test_shapes_fingertips(void) {
  stWorld *w = grasp_world(0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(w);
  const stRobot *r = w->robot;
  double (*R)[9] = malloc(sizeof(double[9]) * (size_t)r->nbody);
  double (*p)[3] = malloc(sizeof(double[3]) * (size_t)r->nbody);
  CU_ASSERT_FATAL(R && p);
  st_robot_fk(r, w->qhat, R, p);
  stShape s[MAX_SHAPES];
  const int n = st_world_shapes(w, s, MAX_SHAPES);
  CU_ASSERT_FATAL(n <= MAX_SHAPES);
  for (int f = 0; f < ST_NTIP; f++)
    check_tip(w, s, n, f, (const double (*)[9])R, (const double (*)[3])p);
  /* every robot shape in model order, named after its link */
  for (int i = 0; i < r->model->ngeom; i++) {
    CU_ASSERT_EQUAL(s[i].kind, ST_SHAPE_ROBOT);
    CU_ASSERT_EQUAL(s[i].geom, i);
    CU_ASSERT_EQUAL(s[i].body, r->model->geom_body[i]);
  }
  free(R);
  free(p);
  st_world_destroy(w);
}

/* ---- max, names, a mesh ------------------------------------------------------------------ */

static void test_shapes_partial_and_names(void) {
  stWorld *w = grasp_world(0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(w);
  stShape s[4];
  memset(s, 0x5a, sizeof s);
  const int n = st_world_shapes(w, s, 3);
  CU_ASSERT(n > 3);
  CU_ASSERT_EQUAL(s[2].kind, ST_SHAPE_ROBOT);
  const unsigned char *untouched = (const unsigned char *)&s[3];
  CU_ASSERT(untouched[0] == 0x5a && untouched[sizeof s[3] - 1] == 0x5a);
  CU_ASSERT_STRING_EQUAL(st_shape_kind_name(ST_SHAPE_ROBOT), "robot");
  CU_ASSERT_STRING_EQUAL(st_shape_kind_name(ST_SHAPE_TARGET), "target");
  CU_ASSERT_STRING_EQUAL(st_shape_kind_name(ST_SHAPE_KIND_COUNT), "?");
  CU_ASSERT_STRING_EQUAL(st_geom_type_name(ST_GEOM_CYLINDER), "cylinder");
  CU_ASSERT_STRING_EQUAL(st_geom_type_name(ST_GEOM_MESH), "mesh");
  CU_ASSERT_STRING_EQUAL(st_geom_type_name(-1), "?");
  st_world_destroy(w);
}

/* a mesh is given as its vertices' bounding box: a robot of its own whose hand box is swapped
 * for four vertices spanning x 0..2, y -1..2, z 1..5 (centre (1, 0.5, 3), extents 2, 3, 4) */
static void test_shapes_mesh_box(void) {
  stRobot *r = NULL;
  char err[512];
  CU_ASSERT_EQUAL_FATAL(st_robot_create(&g_cfg, &r, err, sizeof err), ST_OK);
  stWorld *w = NULL;
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &g_scene, &w, err, sizeof err), ST_OK);
  double q[ST_NDOF], obj[3] = {0.4, 0.1, -0.045}, tgt[3] = {0.25, 0.1, 0.17};
  for (int d = 0; d < ST_NDOF; d++) q[d] = 0.3 + 0.03 * d;
  st_world_reset(w, q, obj, tgt);
  stModel *m = r->model;
  int gi = -1;
  for (int i = 0; i < m->ngeom; i++)
    if (m->geom_body[i] == r->touch_body[ST_TOUCH_PALM]) gi = i; /* the hand's box */
  CU_ASSERT_FATAL(gi >= 0);
  double verts[4][3] = {{0, -1, 1}, {2, 0, 3}, {1, 2, 5}, {0.5, 0.5, 2}};
  double (*saved_vert)[3] = m->mesh_vert;
  const int saved[3] = {m->geom_type[gi], m->geom_vert0[gi], m->geom_nvert[gi]};
  m->mesh_vert = verts, m->geom_type[gi] = ST_GEOM_MESH;
  m->geom_vert0[gi] = 0, m->geom_nvert[gi] = 4;
  stShape s[MAX_SHAPES];
  st_world_shapes(w, s, MAX_SHAPES);
  m->mesh_vert = saved_vert, m->geom_type[gi] = saved[0];
  m->geom_vert0[gi] = saved[1], m->geom_nvert[gi] = saved[2];
  /* expected: the box centre in the body frame, geom_pos + geom_rot c, then the body's pose */
  const double c[3] = {1, 0.5, 3};
  const int b = m->geom_body[gi];
  double local[3], want[3];
  for (int i = 0; i < 3; i++)
    local[i] = m->geom_pos[gi][i] + m->geom_rot[gi][3 * i] * c[0] +
               m->geom_rot[gi][3 * i + 1] * c[1] + m->geom_rot[gi][3 * i + 2] * c[2];
  for (int i = 0; i < 3; i++)
    want[i] = w->p[b][i] + w->R[b][3 * i] * local[0] + w->R[b][3 * i + 1] * local[1] +
              w->R[b][3 * i + 2] * local[2];
  CU_ASSERT_EQUAL(s[gi].type, ST_GEOM_MESH);
  CU_ASSERT(dist3(s[gi].pos, want) < 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s[gi].size[0], 2.0, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(s[gi].size[1], 3.0, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(s[gi].size[2], 4.0, 1e-15);
  st_world_destroy(w);
  st_robot_destroy(r);
}

/* ---- dynamic mode: the ball turns with its body; asking changes nothing ------------------- */

/* close the fingers from the grasp posture for 30 steps; with shapes, each step's are asked
 * for and the ball's checked */
static void close_hand(stWorld *w, int shapes, int *turned) {
  double y[ST_NDOF];
  memcpy(y, w->qhat, sizeof y);
  y[ST_DOF_FINGER_FLEX] = y[ST_DOF_THUMB_FLEX] = 1.0;
  y[ST_DOF_SHOULDER_PITCH] = 0.0; /* and lift */
  for (int step = 0; step < 30; step++) {
    if (step == 10) st_world_set_object_table_collision(w, 0);
    st_world_step(w, y);
    if (!shapes) continue;
    stShape s[MAX_SHAPES];
    const int n = st_world_shapes(w, s, MAX_SHAPES);
    const int b = find_shape(s, n, ST_SHAPE_BALL, ST_GEOM_SPHERE);
    const int c = find_shape(s, n, ST_SHAPE_BALL, ST_GEOM_CYLINDER);
    CU_ASSERT_FATAL(b >= 0 && c >= 0);
    CU_ASSERT(memcmp(s[b].pos, w->obj, sizeof w->obj) == 0);
    CU_ASSERT(rotation_ok(s[b].R));
    CU_ASSERT(memcmp(s[b].R, s[c].R, sizeof s[b].R) == 0);
    /* the base hangs below the centre along the ball's own -z */
    const double off = -w->scene->obj_radius + 0.5 * w->scene->base_height;
    double want[3];
    for (int k = 0; k < 3; k++) want[k] = w->obj[k] + s[b].R[3 * k + 2] * off;
    CU_ASSERT(dist3(s[c].pos, want) < 1e-12);
    if (fabs(s[b].R[8] - 1.0) > 1e-6) *turned = 1;
  }
}

static void test_shapes_dynamic(void) {
  stWorld *a = grasp_world(1), *b = grasp_world(1);
  CU_ASSERT_PTR_NOT_NULL_FATAL(a);
  CU_ASSERT_PTR_NOT_NULL_FATAL(b);
  int turned = 0;
  close_hand(a, 1, &turned);
  close_hand(b, 0, &turned);
  CU_ASSERT(turned); /* the ball's rotation was exercised */
  /* the same trajectory, bit for bit, with and without asking for the shapes */
  CU_ASSERT(memcmp(a->obj, b->obj, sizeof a->obj) == 0);
  CU_ASSERT(memcmp(a->qhat, b->qhat, sizeof a->qhat) == 0);
  const int tip = a->robot->tip_body[0];
  CU_ASSERT(memcmp(a->p[tip], b->p[tip], sizeof(double[3])) == 0);
  st_world_destroy(a);
  st_world_destroy(b);
}

void st_suite_shapes(void) {
  ST_ADD_SUITE("shapes");
  ST_ADD_TEST(test_shapes_scene);
  ST_ADD_TEST(test_shapes_fingertips);
  ST_ADD_TEST(test_shapes_partial_and_names);
  ST_ADD_TEST(test_shapes_mesh_box);
  ST_ADD_TEST(test_shapes_dynamic);
}
