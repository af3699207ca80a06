/* SPDX-License-Identifier: MIT
 * Robot model, kinematic world and sensors. Reference values come from the iKin v1.0 DH table
 * (computed here independently of the URDF), from SPEC §3 / §6 and from hand arithmetic. */
#include <math.h>
#include <stdlib.h>

#include "selftalk/sensors.h"
#include "test_util.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* the shared default config, robot and scene (tests/main.c) */
#define g_cfg (st_test_fixture()->cfg)
#define g_scene (st_test_fixture()->scene)
static stRobot *robot(void) { return st_test_fixture()->robot; }

/* standard DH link: Rz(theta) Tz(d) Tx(a) Rx(alpha), composed onto T (4x4 row-major) */
static void dh(double *T, double a, double d, double alpha, double theta) {
  double ct = cos(theta), st = sin(theta), ca = cos(alpha), sa = sin(alpha);
  double A[16] = {ct, -st * ca, st * sa, a * ct, st, ct * ca, -ct * sa, a * st, 0, sa, ca, d, 0, 0, 0, 1};
  double out[16];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      out[4 * i + j] = 0;
      for (int k = 0; k < 4; k++) out[4 * i + j] += T[4 * i + k] * A[4 * k + j];
    }
  memcpy(T, out, sizeof out);
}

/* iKin iCubArm("left") v1.0 end-effector (icub_facts §1.3), world frame = Rz(pi) root frame.
 * deg: torso yaw, torso pitch, 7 arm joints (SPEC DOF order). */
static void ikin_ee(const double *deg, double out[3]) {
  static const double tab[10][4] = {/* a, d, alpha, offset(deg) */
                                    {0.032, 0, PI / 2, 0},          {0, -0.0055, PI / 2, -90},
                                    {0.0233647, -0.1433, -PI / 2, 105}, {0, 0.10774, -PI / 2, 90},
                                    {0, 0, PI / 2, -90},            {0.015, 0.15228, -PI / 2, 75},
                                    {-0.015, 0, PI / 2, 0},         {0, 0.1373, PI / 2, -90},
                                    {0, 0, PI / 2, 90},             {0.0625, -0.016, 0, 0}};
  /* chain order: torso pitch, roll (0), yaw, then the arm */
  double q[10] = {deg[1], 0.0, deg[0], deg[2], deg[3], deg[4], deg[5], deg[6], deg[7], deg[8]};
  double T[16] = {0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1}; /* H0 */
  for (int k = 0; k < 10; k++) dh(T, tab[k][0], tab[k][1], tab[k][2], (q[k] + tab[k][3]) * DEG);
  out[0] = -T[3];
  out[1] = -T[7];
  out[2] = T[11];
}

static void test_ee_matches_ikin(void) {
  stRobot *r = robot();
  CU_ASSERT_PTR_NOT_NULL_FATAL(r);
  CU_ASSERT_FATAL(r->ee_body >= 0);
  double (*R)[9] = malloc(sizeof(double[9]) * (size_t)r->nbody);
  double (*p)[3] = malloc(sizeof(double[3]) * (size_t)r->nbody);
  /* column A ranges (icub_facts §3) and the thesis's torso range */
  static const double lo[9] = {-10, -10, -95.5, 0, -37, 15, -90, -90, -20};
  static const double hi[9] = {40, 40, 10, 160.8, 80, 106, 90, 0, 40};
  stRng rng = st_rng_keyed(77, ST_RNG_USER, 0, 0, 0);
  double worst = 0;
  for (int c = 0; c < 40; c++) {
    double deg[9], qhat[ST_NDOF] = {0};
    for (int d = 0; d < 9; d++) {
      deg[d] = c == 0 ? (lo[d] > 0 ? lo[d] : hi[d] < 0 ? hi[d] : 0) : st_rng_range(&rng, lo[d], hi[d]);
      qhat[d] = (deg[d] - lo[d]) / (hi[d] - lo[d]);
    }
    st_robot_fk(r, qhat, R, p);
    double ref[3];
    ikin_ee(deg, ref);
    double e = sqrt(pow(p[r->ee_body][0] - ref[0], 2) + pow(p[r->ee_body][1] - ref[1], 2) +
                    pow(p[r->ee_body][2] - ref[2], 2));
    if (e > worst) worst = e;
  }
  CU_ASSERT(worst < 1e-3); /* measured: about 1e-16 m */
  if (worst >= 1e-3) fprintf(stderr, "\n  worst EE error %.3g m\n", worst);
  /* zero pose (elbow at its 15 deg minimum aside): icub_facts §1.4 gives the EE at root
   * (-0.0108, -0.0941, -0.1768) with all joints 0, i.e. world (0.0108, 0.0941, -0.1768) */
  double zero[9] = {0}, ref0[3];
  ikin_ee(zero, ref0);
  CU_ASSERT_DOUBLE_EQUAL(ref0[0], 0.0108, 1e-4);
  CU_ASSERT_DOUBLE_EQUAL(ref0[1], 0.0941, 1e-4);
  CU_ASSERT_DOUBLE_EQUAL(ref0[2], -0.1768, 1e-4);
  free(R);
  free(p);
}

static void test_actuation_law(void) {
  /* kinematic: alpha 37, elbow range 91 deg; y - qhat = 1 -> 37 deg/s (below the clamp):
   * one 50 ms step moves 1.85 deg = 1.85/91 of the range */
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.0, 1.0, 37, 40, 0.05, 91), 1.85 / 91, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.5, 0.25, 37, 40, 0.05, 91), 0.5 - 9.25 * 0.05 / 91, 1e-15);
  /* dynamic gain: alpha 100, error 0.5 -> 50 deg/s, clamped to 40 */
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.2, 0.7, 100, 40, 0.05, 90), 0.2 + 2.0 / 90, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.7, 0.2, 100, 40, 0.05, 90), 0.7 - 2.0 / 90, 1e-15);
  /* limits: 0.99 + 40 deg/s x 0.05 s / 10 deg = 1.19 is held at 1 (and likewise at 0) */
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.99, 2.0, 100, 40, 0.05, 10), 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_actuate(0.01, -1.0, 100, 40, 0.05, 10), 0.0, 0.0);
}

/* a kinematic world of the default scene, reset with every DOF at qhat 0.5 and the object at
 * obj; NULL on failure */
static stWorld *half_way_world(const double obj[3]) {
  stRobot *r = robot();
  stWorld *w = NULL;
  char err[256];
  if (!r || st_world_create(r, &g_scene, &w, err, sizeof err)) return NULL;
  double q0[ST_NDOF];
  for (int d = 0; d < ST_NDOF; d++) q0[d] = 0.5;
  st_world_reset(w, q0, obj, g_scene.target[0]);
  return w;
}

static void test_world_saturating(void) {
  stWorld *w = half_way_world(g_scene.obj_pos[0]);
  CU_ASSERT_PTR_NOT_NULL_FATAL(w);
  double y[ST_NDOF];
  /* torso yaw range 50 deg: from 0.5 with alpha 37 the first step moves 0.925 deg */
  for (int d = 0; d < ST_NDOF; d++) y[d] = d % 2 ? 1.0 : 0.0;
  st_world_step_kinematic(w, y);
  CU_ASSERT_DOUBLE_EQUAL(w->qhat[0], 0.5 - 18.5 * 0.05 / 50, 1e-15);
  for (int t = 0; t < 400; t++) {
    for (int d = 0; d < ST_NDOF; d++) y[d] = (t / 50) % 2 ? 5.0 : -5.0; /* far beyond [0, 1] */
    st_world_step_kinematic(w, y);
    for (int d = 0; d < ST_NDOF; d++) CU_ASSERT(w->qhat[d] >= 0.0 && w->qhat[d] <= 1.0);
  }
  CU_ASSERT_EQUAL(w->step, 401);
  st_world_destroy(w);
}

/* lib/world/world.c: every step function of a kinematic world is the kinematic step, and the
 * dynamic-mode queries give the answers world.h states for a kinematic world */
static void test_world_kinematic_dispatch(void) {
  const stRobot *r = robot();
  /* the object 1 m below the table top: a dynamic world would report it fallen */
  const double low[3] = {g_scene.obj_pos[0][0], g_scene.obj_pos[0][1], g_scene.table_top_z - 1.0};
  stWorld *w = half_way_world(low);
  CU_ASSERT_PTR_NOT_NULL_FATAL(w);
  double y[ST_NDOF];
  for (int d = 0; d < ST_NDOF; d++) y[d] = 1.0;
  /* torso yaw, range 50 deg, alpha 37 deg/s: 0.5 -> 0.5 + 18.5 * 0.05 / 50 = 0.5185, then
   * 0.5185 + 37 * 0.4815 * 0.05 / 50 = 0.5363155 */
  st_world_step_dynamic(w, y);
  CU_ASSERT_DOUBLE_EQUAL(w->qhat[0], 0.5185, 1e-12);
  st_world_step(w, y);
  CU_ASSERT_DOUBLE_EQUAL(w->qhat[0], 0.5363155, 1e-12);
  CU_ASSERT_EQUAL(w->step, 2);
  CU_ASSERT_EQUAL(w->dynamic, 0);
  st_world_set_seed(w, 12345);
  st_world_set_object_table_collision(w, 0);
  CU_ASSERT_EQUAL(st_world_object_fell(w), 0);
  CU_ASSERT_EQUAL(st_world_unstable(w), 0);
  CU_ASSERT_STRING_EQUAL(st_world_unstable_reason(w), "");
  stDynInfo info, zero;
  memset(&info, 0xff, sizeof info);
  memset(&zero, 0, sizeof zero);
  st_world_dynamic_info(w, &info);
  CU_ASSERT_EQUAL(memcmp(&info, &zero, sizeof info), 0);
  /* joint angles are those of qhat: torso yaw's master joint at its range's 0.5363155 */
  double *angle = calloc((size_t)r->nbody, sizeof *angle);
  CU_ASSERT_PTR_NOT_NULL_FATAL(angle);
  st_world_joint_angles(w, angle);
  const double lo = r->dof_lo[0], hi = r->dof_hi[0];
  CU_ASSERT_DOUBLE_EQUAL(angle[r->dof_body[0]], lo + 0.5363155 * (hi - lo), 1e-12);
  free(angle);
  st_world_destroy(w);
  st_world_destroy(NULL);
}

/* posture of the thesis-like check in data/README.md: shoulder -30/30/0, elbow 60 */
static void reach_like_qhat(const stRobot *r, double *qhat) {
  static const double deg[9] = {0, 0, -30, 30, 0, 60, 0, 0, 0};
  for (int d = 0; d < 9; d++) qhat[d] = st_robot_dof_qhat(r, d, deg[d] * DEG);
  qhat[9] = qhat[10] = qhat[11] = 0.0;
}

static void test_touch_and_contacts(void) {
  stRobot *r = robot();
  CU_ASSERT_PTR_NOT_NULL_FATAL(r);
  char err[256];
  double qhat[ST_NDOF];
  reach_like_qhat(r, qhat);
  stWorld *w = NULL;
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &g_scene, &w, err, sizeof err), ST_OK);
  /* free space: the hand is 12 cm above the table, far from the object */
  st_world_reset(w, qhat, g_scene.obj_pos[1], g_scene.target[0]);
  for (int i = 0; i < ST_NTOUCH; i++) CU_ASSERT_EQUAL(w->contacts.touch[i], 0);
  CU_ASSERT_EQUAL(w->contacts.arm_table, 0);
  CU_ASSERT_EQUAL(w->contacts.robot_object, 0);
  CU_ASSERT_EQUAL(w->contacts.object_table, 1); /* the resting object sits on the table */
  /* object centred on the palm centre: palm sensor and object contact, not the table */
  double palm[3];
  memcpy(palm, w->p[r->palm_body], sizeof palm);
  st_world_reset(w, qhat, palm, g_scene.target[0]);
  CU_ASSERT_EQUAL(w->contacts.touch[ST_TOUCH_PALM], 1);
  CU_ASSERT_EQUAL(w->contacts.touch_object[ST_TOUCH_PALM], 1);
  CU_ASSERT_EQUAL(w->contacts.robot_object, 1);
  CU_ASSERT_EQUAL(w->contacts.arm_table, 0);
  /* touching (a sensor on the object) and lifted (on the robot, off the table) */
  stSensorDef sd0;
  st_sensor_def_from_config(&g_cfg, &sd0);
  stQuantities q0;
  st_quantities(w, &sd0, &q0);
  CU_ASSERT_EQUAL(q0.touching, 1);
  CU_ASSERT_EQUAL(q0.lifted, 1);
  st_world_reset(w, qhat, g_scene.obj_pos[1], g_scene.target[0]);
  st_quantities(w, &sd0, &q0);
  CU_ASSERT_EQUAL(q0.touching, 0);
  CU_ASSERT_EQUAL(q0.lifted, 0);
  /* raise the table so its top slab (3 cm) contains the palm centre: table contact on the palm
   * and the arm, no object contact */
  stConfig c = g_cfg;
  c.scene_table_top_z = palm[2] + 0.01;
  stScene high;
  st_scene_from_config(&c, &high);
  stWorld *w2 = NULL;
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &high, &w2, err, sizeof err), ST_OK);
  double far_obj[3] = {0.5, -0.25, 1.0};
  st_world_reset(w2, qhat, far_obj, high.target[0]);
  CU_ASSERT_EQUAL(w2->contacts.touch[ST_TOUCH_PALM], 1);
  CU_ASSERT_EQUAL(w2->contacts.touch_object[ST_TOUCH_PALM], 0);
  CU_ASSERT_EQUAL(w2->contacts.arm_table, 1);
  CU_ASSERT_EQUAL(w2->contacts.robot_object, 0);
  stSensorDef sd;
  st_sensor_def_from_config(&c, &sd);
  CU_ASSERT_DOUBLE_EQUAL(st_penalty_table(w2, &sd), 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_penalty_object(w2, &sd), 0.0, 0.0);
  st_world_destroy(w2);
  st_world_destroy(w);
}

static void test_quantities(void) {
  stRobot *r = robot();
  CU_ASSERT_PTR_NOT_NULL_FATAL(r);
  char err[256];
  double qhat[ST_NDOF];
  reach_like_qhat(r, qhat);
  qhat[ST_DOF_THUMB_FLEX] = 0.3;
  qhat[ST_DOF_FINGER_FLEX] = 0.5;
  stWorld *w = NULL;
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &g_scene, &w, err, sizeof err), ST_OK);
  st_world_reset(w, qhat, g_scene.obj_pos[0], g_scene.target[1]);
  stSensorDef sd;
  st_sensor_def_from_config(&g_cfg, &sd);
  stQuantities q;
  st_quantities(w, &sd, &q);
  const double *palm = w->p[r->palm_body];
  /* st_robot_point_local undoes st_world_point: a palm-frame point taken to the world and back
   * is the point again, and the palm origin is (0, 0, 0) in its own frame */
  {
    const int b = r->palm_body;
    const double local[3] = {0.03, -0.02, 0.05};
    double world[3], back[3], origin[3];
    st_world_point(w, b, local, world);
    st_robot_point_local(w->R[b], w->p[b], world, back);
    st_robot_point_local(w->R[b], w->p[b], palm, origin);
    for (int i = 0; i < 3; i++) {
      CU_ASSERT_DOUBLE_EQUAL(back[i], local[i], 1e-12);
      CU_ASSERT_DOUBLE_EQUAL(origin[i], 0.0, 1e-15);
    }
  }
  /* place the object so the reach point (9.5 cm above it) is (3, 0, 4) cm from the palm: d_r 5 cm */
  double obj[3] = {palm[0] + 0.03, palm[1], palm[2] + 0.04 - 0.095};
  double target[3] = {palm[0], palm[1] - 0.12, palm[2] + 0.05}; /* 13 cm from the palm */
  st_world_reset(w, qhat, obj, target);
  st_quantities(w, &sd, &q);
  CU_ASSERT_DOUBLE_EQUAL(q.d_r, 0.05, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(q.d_mhat, 0.13, 1e-12);
  /* object to target: (-0.03, -0.12, 0.105) -> sqrt(0.0009 + 0.0144 + 0.011025) */
  CU_ASSERT_DOUBLE_EQUAL(q.d_m, sqrt(0.0009 + 0.0144 + 0.011025), 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(q.h, 1.0 - 0.4, 1e-12); /* 1 - mean(0.3, 0.5) */
  /* palm normal from the frame: unit, p = (1 - n_z) / 2 */
  double nn = sqrt(q.normal[0] * q.normal[0] + q.normal[1] * q.normal[1] + q.normal[2] * q.normal[2]);
  CU_ASSERT_DOUBLE_EQUAL(nn, 1.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(q.p, 0.5 * (1.0 - q.normal[2]), 1e-15);
  /* d_g: centroid of thumb tip, little tip and palm centre */
  double cg[3];
  for (int i = 0; i < 3; i++) cg[i] = (w->p[r->tip_body[0]][i] + w->p[r->tip_body[4]][i] + palm[i]) / 3;
  double dg = sqrt(pow(cg[0] - obj[0], 2) + pow(cg[1] - obj[1], 2) + pow(cg[2] - obj[2], 2));
  CU_ASSERT_DOUBLE_EQUAL(q.d_g, dg, 1e-12);
  /* the palm at q=0 faces the body's midline: normal -y, so p = 1/2 */
  double q0[ST_NDOF];
  for (int d = 0; d < ST_NDOF; d++) q0[d] = st_robot_dof_qhat(r, d, 0.0);
  q0[ST_DOF_ELBOW] = 0.0;
  q0[9] = q0[10] = q0[11] = 0.0;
  st_world_reset(w, q0, obj, target);
  st_quantities(w, &sd, &q);
  CU_ASSERT_DOUBLE_EQUAL(q.normal[1], -1.0, 1e-6);
  CU_ASSERT_DOUBLE_EQUAL(q.p, 0.5, 1e-6);

  /* focus correctness and choice */
  CU_ASSERT_DOUBLE_EQUAL(st_focus_correctness(0.3, 0), 0.7, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_focus_correctness(0.3, 1), 0.3, 1e-15);
  CU_ASSERT_EQUAL(st_focus_is_target(&sd, 0.49), 0);
  CU_ASSERT_EQUAL(st_focus_is_target(&sd, 0.5), 1);

  /* inputs: qhat, touch, focus = (focus - palm) x 20, words, secondary */
  double in[26], ling[4] = {0, 10, 0, 0};
  st_quantities(w, &sd, &q);
  st_sensor_inputs(w, &sd, &q, 1, 0, ling, 10, in, 26);
  for (int d = 0; d < ST_NDOF; d++) CU_ASSERT_DOUBLE_EQUAL(in[d], q0[d], 0.0);
  for (int i = 0; i < 3; i++) CU_ASSERT_DOUBLE_EQUAL(in[18 + i], (target[i] - q.palm[i]) * 20, 1e-12);
  CU_ASSERT(in[21] == 0 && in[22] == 10 && in[23] == 0 && in[24] == 0 && in[25] == 10);
  st_sensor_inputs(w, &sd, &q, 0, 1, ling, 0, in, 25);
  CU_ASSERT(in[18] == 0 && in[19] == 0 && in[20] == 0); /* first step: no focus yet */
  st_world_destroy(w);
}

static void test_moving_penalty(void) {
  stRobot *r = robot();
  CU_ASSERT_PTR_NOT_NULL_FATAL(r);
  stWorld *w = NULL;
  char err[256];
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &g_scene, &w, err, sizeof err), ST_OK);
  double q[ST_NDOF] = {0};
  stSensorDef sd;
  st_sensor_def_from_config(&g_cfg, &sd);
  st_world_reset(w, q, g_scene.obj_pos[0], g_scene.target[0]);
  /* displacement in decimetres, nothing below 2 cm, at most 2 */
  static const double d[5] = {0.01, 0.0199, 0.05, 0.15, 0.30}, want[5] = {0, 0, 0.5, 1.5, 2.0};
  for (int i = 0; i < 5; i++) {
    w->obj[0] = w->obj_start[0] + d[i] * 0.6;
    w->obj[1] = w->obj_start[1] + d[i] * 0.8;
    w->obj[2] = w->obj_start[2];
    CU_ASSERT_DOUBLE_EQUAL(st_penalty_moving(w, &sd), want[i], 1e-12);
  }
  st_world_destroy(w);
}

static void test_scene_positions(void) {
  robot();
  /* SPEC §2: P0..P3 10 cm front/back/left/right of (0.30, 0.10), resting z = -0.045 */
  static const double P[4][2] = {{0.40, 0.10}, {0.20, 0.10}, {0.30, 0.20}, {0.30, 0.00}};
  for (int k = 0; k < 4; k++) {
    CU_ASSERT_DOUBLE_EQUAL(g_scene.obj_pos[k][0], P[k][0], 1e-15);
    CU_ASSERT_DOUBLE_EQUAL(g_scene.obj_pos[k][1], P[k][1], 1e-15);
    CU_ASSERT_DOUBLE_EQUAL(g_scene.obj_pos[k][2], -0.045, 1e-15);
  }
  CU_ASSERT_DOUBLE_EQUAL(g_scene.target[0][1], 0.10, 0);
  CU_ASSERT_DOUBLE_EQUAL(g_scene.target[1][1], -0.10, 0);
  CU_ASSERT_DOUBLE_EQUAL(g_scene.target[2][1], 0.0, 0);
  CU_ASSERT_DOUBLE_EQUAL(g_scene.target[2][2], 0.17, 0);
  /* offsets: within +-2 cm, and the same key gives the same trial */
  stRng a = st_rng_keyed(1, ST_RNG_TRIAL, 4, 0, 3), b = a;
  double pa[3], pb[3], t[3];
  st_scene_object(&g_scene, 2, 1, &a, pa);
  st_scene_object(&g_scene, 2, 1, &b, pb);
  CU_ASSERT(memcmp(pa, pb, sizeof pa) == 0);
  CU_ASSERT(fabs(pa[0] - 0.30) <= 0.02 && fabs(pa[1] - 0.20) <= 0.02 && pa[2] == -0.045);
  st_scene_target(&g_scene, 1, &a, t);
  CU_ASSERT(fabs(t[0] - 0.25) <= 0.02 && fabs(t[1] + 0.10) <= 0.02 && fabs(t[2] - 0.17) <= 0.02);
}

static void test_robot_config_errors(void) {
  stConfig c;
  st_config_default(&c);
  char err[512];
  stRobot *r = NULL;
  snprintf(c.robot_dof_joints, sizeof c.robot_dof_joints, "%s",
           "torso_yaw,torso_pitch,l_shoulder_pitch,l_shoulder_roll,l_shoulder_yaw,l_elbw,"
           "l_wrist_prosup,l_wrist_pitch,l_wrist_yaw,l_thumb_oppose,l_thumb_proximal,l_index_proximal");
  CU_ASSERT_EQUAL(st_robot_create(&c, &r, err, sizeof err), ST_ERR_MODEL);
  ST_ASSERT_CONTAINS(err, "robot.dof_joints: joint 'l_elbw' is not in data/icub_left_arm.urdf");
  st_config_default(&c);
  snprintf(c.robot_palm_frame, sizeof c.robot_palm_frame, "%s", "l_palm");
  CU_ASSERT_EQUAL(st_robot_create(&c, &r, err, sizeof err), ST_ERR_MODEL);
  ST_ASSERT_CONTAINS(err, "robot.palm_frame: link 'l_palm' is not in data/icub_left_arm.urdf");
  st_config_default(&c);
  snprintf(c.robot_dof_joints, sizeof c.robot_dof_joints, "%s", "torso_yaw,torso_pitch");
  CU_ASSERT_EQUAL(st_robot_create(&c, &r, err, sizeof err), ST_ERR_MODEL);
  ST_ASSERT_CONTAINS(err, "robot.dof_joints: 2 names (expected 12");
  CU_ASSERT_PTR_NULL(r);
}

/* the culled, shortcut contact detection agrees with brute-force narrow phase on random
 * postures, with the table raised so that about half of them hit it */
static void test_contacts_match_reference(void) {
  stRobot *r = robot();
  CU_ASSERT_PTR_NOT_NULL_FATAL(r);
  char err[256];
  stConfig c = g_cfg;
  c.scene_table_top_z = 0.0;
  stScene high;
  st_scene_from_config(&c, &high);
  stWorld *w = NULL;
  CU_ASSERT_EQUAL_FATAL(st_world_create(r, &high, &w, err, sizeof err), ST_OK);
  stRng rng = st_rng_keyed(5, ST_RNG_USER, 0, 0, 0);
  int table_hits = 0, object_hits = 0, mismatches = 0;
  for (int i = 0; i < 3000; i++) {
    double q[ST_NDOF], obj[3];
    for (int d = 0; d < ST_NDOF; d++) q[d] = st_rng_uniform(&rng);
    st_world_reset(w, q, high.obj_pos[0], high.target[0]);
    /* put the object near the palm half of the time */
    memcpy(obj, w->p[r->palm_body], sizeof obj);
    for (int k = 0; k < 3; k++) obj[k] += st_rng_range(&rng, -0.06, 0.06);
    if (i % 2) st_world_reset(w, q, obj, high.target[0]);
    stContacts fast = w->contacts, ref;
    w->reference_contacts = 1;
    st_world_update(w);
    ref = w->contacts;
    w->reference_contacts = 0;
    mismatches += memcmp(&ref, &fast, sizeof ref) != 0;
    table_hits += ref.arm_table;
    object_hits += ref.robot_object;
  }
  CU_ASSERT_EQUAL(mismatches, 0);
  CU_ASSERT(table_hits > 300 && table_hits < 2700); /* both outcomes exercised */
  CU_ASSERT(object_hits > 100);
  st_world_destroy(w);
}

void st_suite_kin(void) {
  CU_pSuite st__suite = CU_add_suite("kin", NULL, NULL);
  ST_ADD_TEST(test_ee_matches_ikin);
  ST_ADD_TEST(test_actuation_law);
  ST_ADD_TEST(test_world_saturating);
  ST_ADD_TEST(test_world_kinematic_dispatch);
  ST_ADD_TEST(test_touch_and_contacts);
  ST_ADD_TEST(test_quantities);
  ST_ADD_TEST(test_moving_penalty);
  ST_ADD_TEST(test_scene_positions);
  ST_ADD_TEST(test_robot_config_errors);
  ST_ADD_TEST(test_contacts_match_reference);
}
