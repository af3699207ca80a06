/* SPDX-License-Identifier: MIT
 * The 16 initial postures of thesis §2.5.3 / SPEC §8, by inverse kinematics from the scene's
 * object positions (see selftalk/postures.h). */
#include "selftalk/postures.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/ik.h"
#include "selftalk/world.h"

/* ---- protocol numbers (SPEC §8) -------------------------------------------------------------
 * The numbers that define the postures are config keys (postures.*, read into
 * stScene.posture, written PD below); what remains here are the IK start postures, the reach
 * targets and the tolerances of the checks. Distances
 * in metres, hand DOF in normalised units (0 open / neutral, 1 closed / fully opposed). The
 * palm frame (robot.palm_frame) has +z = outward palm normal, +x = towards the fingers; the
 * object-relative postures put the ball centre at a fixed point of that frame, with the palm
 * normal pointing straight down, so the hand-object geometry is the same for every object
 * position (only the arm differs). */

#define PD (s->posture) /* the postures.* keys of the scene in scope */
#define REACH_SUCCESS_DIST 0.03 /* fitness.success_dist: the reach-time check's "reached" */
static double dist3(const double *a, const double *b);
/* st_posture_check with open's kind given (near: k=0,1's, around the ball) */
static int check_kind(const stRobot *r, const stScene *s, int prim, int k, int near,
                      const double qhat[ST_NDOF], char *why, size_t n);

/* reach: start postures (degrees, SPEC §3 order, torso at 0) and the palm-centre target as an
 * offset from the centre of the four object positions; position only, torso fixed at 0 */
static const double REACH_START_DEG[ST_NPOSTURE][9] = {
    {0, 0, -30, 20, 0, 90, 0, 0, 0},      /* hand raised in front */
    {0, 0, -10, 80, 0, 30, 0, 0, 0},      /* arm out to the side, elbow almost straight */
    {0, 0, -20, 60, 0, 60, 0, 0, 0},      /* arm half raised to the side */
    {0, 0, -60, 30, 40, 80, 40, -30, 0},  /* hand across in front, wrist turned */
};
/* chosen so that every reach start is >= 0.18 m from every object position (0.15 + the 2 cm
 * offsets) and a full-speed controller reaches its object position within 40 steps (see
 * st_posture_reach_steps; the first choice here needed 70 steps for P1 and stalled evolution) */
static const double REACH_PALM_OFFSET[ST_NPOSTURE][3] = {
    {-0.08, -0.16, 0.18}, /* palm (0.22, -0.06, 0.135): right of the objects */
    {-0.08, 0.04, 0.18},  /* palm (0.22, 0.14, 0.135): middle left */
    {-0.12, -0.12, 0.18}, /* palm (0.18, -0.02, 0.135): near the body */
    {-0.04, -0.04, 0.26}, /* palm (0.26, 0.06, 0.215): high in the middle */
};
#define REACH_THUMB_OPPOSE 0.0 /* flat hand: thumb in the palm plane */
#define REACH_DISTINCT 0.10    /* two reach postures differ by >= this in some arm DOF qhat */

/* open, k = 0, 1: hand around the ball, almost grasping it */
/* open, k = 2, 3: palm a few centimetres above the ball, hand almost closed */
/* grasp: palm down, centred a few centimetres above the ball */
/* move: the ball held (kinematic construction; the dynamic hold is checked in dynamic mode) */
#define MOVE_CLOSE_STEP 0.01   /* thumb, then fingers, close on this grid until they touch */

/* IK: start posture of the object-relative postures (degrees; the torso pitch and the wrist's
 * pronation and pitch come from postures.ik_*, whose defaults are 0, 80 and -30), mobility of
 * the torso relative to the arm (the arm does most of the work), alignment weight of the palm
 * normal */
static const double START_DEG[9] = {0, 0, -40, 30, 0, 90, 0, 0, 0};
#define TORSO_WEIGHT 0.25
#define NORMAL_WEIGHT 0.01 /* 1 rad of palm-normal error costs like 0.1 m of position */

/* checks (SPEC §8 properties; tolerances of the constructions above) */
#define CHECK_PALM_DOWN 0.9     /* p = (1 - n_z) / 2 above this: palm facing the table */
#define CHECK_REACH_DOWN 0.85   /* postures.reach_palm_down: reach 1's arm, out to the side,
                                 * turns its palm to p 0.86 at most there (its IK's optimum) */
#define CHECK_OPEN_XY 0.03      /* open: palm centre within this of the ball (horizontally) */
#define CHECK_OPEN_NEAR_MAX_GAP 0.03 /* open k=0,1: palm at most this above the ball top */
#define CHECK_OPEN_NEAR_FLEX_LO 0.1  /* open k=0,1: fingers partly closed */
#define CHECK_OPEN_NEAR_FLEX_HI 0.6
#define CHECK_OPEN_HIGH_MIN_GAP 0.02 /* open k=2,3: palm at least this above the ball top */
#define CHECK_OPEN_HIGH_MAX_GAP 0.08
#define CHECK_OPEN_HIGH_FLEX 0.7     /* open k=2,3: thumb and finger flexion at least this */
#define CHECK_GRASP_MIN_GAP 0.01     /* grasp: palm centre 1-8 cm above the ball top ("a few */
#define CHECK_GRASP_MAX_GAP 0.08     /* centimetres", as open k=2,3): 6 cm is where open ends */
#define CHECK_GRASP_XY 0.02          /* grasp: the palm point grasp_ball_x ahead of the centre
                                        within this of the ball (horiz.) */
#define CHECK_GRASP_BALL_X 0.05      /* grasp: |grasp_ball_x| at most this: the ball under the
                                        palm or the knuckles (the MCP hinges are 4.6 cm ahead) */
#define CHECK_GRASP_FLEX_LO 0.15     /* grasp k=2,3: partly extended */
#define CHECK_GRASP_FLEX_HI 0.4
#define CHECK_MOVE_TOUCHES 3         /* move: touch sensors on the object, at least */
#define CHECK_MOVE_DG 0.03           /* move: d_g below this */
#define CHECK_MOVE_OPPOSE 0.3        /* move: thumb opposition at least this */
#define CHECK_IK_POS 1e-3            /* IK must reach its target within this (m) ... */
#define CHECK_IK_DIR (1.0 * ST_DEG)  /* ... and align the palm normal within this (rad) */

/* ---------------------------------------------------------------------------------------- */



/* torso and arm from degrees (torso forced to 0), hand open */
static void start_posture(const stRobot *r, const double deg[9], double q[ST_NDOF]) {
  for (int d = 0; d < ST_NDOF; d++) q[d] = 0.0;
  for (int d = 0; d < 9; d++) q[d] = st_robot_dof_qhat(r, d, deg[d] * ST_DEG);
  q[ST_DOF_TORSO_YAW] = st_robot_dof_qhat(r, ST_DOF_TORSO_YAW, 0.0);
  q[ST_DOF_TORSO_PITCH] = st_robot_dof_qhat(r, ST_DOF_TORSO_PITCH, 0.0);
  for (int d = 0; d < ST_NDOF; d++) q[d] = q[d] < 0.0 ? 0.0 : q[d] > 1.0 ? 1.0 : q[d];
}

static int ik_run(const stRobot *r, const stIkDef *def, const stIkTarget *t, double q[ST_NDOF],
                  const char *what, int k, char *err, size_t errsz) {
  stIkResult res;
  stStatus st = st_ik_solve(r, def, t, q, &res);
  if (st == ST_OK || st == ST_ERR_RANGE) {
    int ok = res.pos_err < CHECK_IK_POS && res.dir_err[0] < CHECK_IK_DIR;
    if (ok) return 0;
    st__errf(err, errsz, "posture %s %d: inverse kinematics did not reach the target (position "
             "error %.4f m, palm normal error %.2f deg after %d iterations; expected a reachable "
             "object position)", what, k, res.pos_err, res.dir_err[0] / ST_DEG, res.iterations);
    return -1;
  }
  st__errf(err, errsz, "posture %s %d: inverse kinematics failed (%s)", what, k, st_status_str(st));
  return -1;
}

/* the palm over the ball: ball centre at `ball` in the palm frame, moved by (v->dx, v->dy),
 * the palm normal down tilted by v->tilt, the IK started from v->ik_deg (torso pitch, wrist
 * pronation, wrist pitch) */
static int place_palm_over_ball(const stRobot *r, const stScene *s, int k, const double ball[3],
                                const stPostureVariation *v, double q[ST_NDOF], const char *what,
                                char *err, size_t errsz) {
  stIkDef def = st_ik_default_def();
  def.dof_weight[ST_DOF_TORSO_YAW] = def.dof_weight[ST_DOF_TORSO_PITCH] = TORSO_WEIGHT;
  stIkTarget t = st_ik_target(r->palm_body, s->obj_pos[k]);
  /* the ball point moves by -d in the palm frame when the palm moves by +d */
  const double point[3] = {ball[0] - v->dx, ball[1] - v->dy, ball[2]};
  memcpy(t.point, point, sizeof t.point);
  static const double normal[3] = {0, 0, 1};
  const double sin_t = sin(v->tilt);
  const double down[3] = {sin_t * cos(v->azimuth), sin_t * sin(v->azimuth), -cos(v->tilt)};
  st_ik_target_align(&t, 0, normal, down, NORMAL_WEIGHT);
  /* the palm pose leaves the arm configuration open: the solver ends near where it starts */
  double deg[9];
  memcpy(deg, START_DEG, sizeof deg);
  deg[ST_DOF_WRIST_PROSUP] = v->ik_deg[1];
  deg[ST_DOF_WRIST_PITCH] = v->ik_deg[2];
  start_posture(r, deg, q);
  q[ST_DOF_TORSO_PITCH] = st_robot_dof_qhat(r, ST_DOF_TORSO_PITCH, v->ik_deg[0] * ST_DEG);
  return ik_run(r, &def, &t, q, what, k, err, errsz);
}

/* open k=0,1's kind (around the ball, almost grasping) unless the variation builds every open
 * start as k=2,3's (a few cm above, hand almost closed) */
static int open_near(int k, const stPostureVariation *v) { return k < 2 && !v->open_high; }

void st_posture_variation_none(const stScene *s, stPostureVariation *v) {
  ST_ASSERT(s && v);
  memset(v, 0, sizeof *v);
  v->ik_deg[0] = s->posture.ik_torso_pitch;
  v->ik_deg[1] = s->posture.ik_wrist_prosup;
  v->ik_deg[2] = s->posture.ik_wrist_pitch;
}

void st_posture_variation_draw(const stScene *s, stRng *rng, stPostureVariation *v) {
  ST_ASSERT(s && rng && v);
  const stPostureDef *d = &s->posture;
  /* uniform in the disc: the radius goes as the square root of a uniform draw */
  const double rad = d->vary_offset * sqrt(st_rng_uniform(rng));
  const double ang = st_rng_range(rng, 0.0, 2.0 * ST_PI);
  v->dx = rad * cos(ang);
  v->dy = rad * sin(ang);
  v->tilt = st_rng_range(rng, 0.0, d->vary_tilt * ST_DEG);
  v->azimuth = st_rng_range(rng, 0.0, 2.0 * ST_PI);
  v->ik_deg[0] = st_rng_range(rng, d->ik_torso_pitch, d->vary_torso_pitch);
  v->ik_deg[1] = st_rng_range(rng, d->ik_wrist_prosup, d->vary_wrist_prosup);
  v->ik_deg[2] = st_rng_range(rng, d->ik_wrist_pitch, d->vary_wrist_pitch);
  v->open_high = d->vary_open_high; /* a key, not a draw: the stream stays as it was */
}

static int count_fingertips(const stWorld *w) {
  int n = 0;
  for (int i = ST_TOUCH_INDEX; i <= ST_TOUCH_LITTLE; i++) n += w->contacts.touch_object[i];
  return n;
}

/* closes DOF d of w->qhat on the MOVE_CLOSE_STEP grid until done(w) with no table contact;
 * -1 if it never happens */
static int close_until(stWorld *w, int d, int which) {
  for (int i = 0; i * MOVE_CLOSE_STEP <= 1.0 + 1e-9; i++) {
    w->qhat[d] = fmin(1.0, i * MOVE_CLOSE_STEP);
    st_world_update(w);
    int done = which == 0 ? w->contacts.touch_object[ST_TOUCH_THUMB]
                          : count_fingertips(w) >= w->scene->posture.move_min_fingers;
    if (done && !w->contacts.arm_table) return 0;
  }
  return -1;
}

static stStatus move_close(const stRobot *r, const stScene *s, int k, double q[ST_NDOF],
                           char *err, size_t errsz) {
  stWorld *w = NULL;
  stStatus st = st_world_create(r, s, &w, err, errsz);
  if (st) return st;
  q[ST_DOF_THUMB_OPPOSE] = PD.move_oppose;
  q[ST_DOF_THUMB_FLEX] = q[ST_DOF_FINGER_FLEX] = 0.0;
  st_world_reset(w, q, s->obj_pos[k], s->target[k % 2]);
  const char *bad = NULL;
  if (close_until(w, ST_DOF_THUMB_FLEX, 0)) bad = "the thumb never touches the ball";
  else if (close_until(w, ST_DOF_FINGER_FLEX, 1)) bad = "the fingers never touch the ball";
  if (bad) {
    st_world_destroy(w);
    st__errf(err, errsz, "posture move %d: %s (expected a graspable object position)", k, bad);
    return ST_ERR_RANGE;
  }
  q[ST_DOF_THUMB_FLEX] = fmin(1.0, w->qhat[ST_DOF_THUMB_FLEX] + PD.move_squeeze);
  q[ST_DOF_FINGER_FLEX] = fmin(1.0, w->qhat[ST_DOF_FINGER_FLEX] + PD.move_squeeze);
  st_world_destroy(w);
  return ST_OK;
}

/* the posture without its final check; v varies open, grasp and move */
static stStatus compute(const stRobot *r, const stScene *s, int prim, int k,
                        const stPostureVariation *v, double q[ST_NDOF], char *err, size_t errsz) {
  const char *what = st_primitive_name(prim);
  const double rad = s->obj_radius;
  double ball[3] = {0, 0, 0};
  switch (prim) {
    case ST_PRIM_REACH: {
      double c[3] = {0, 0, 0};
      for (int j = 0; j < ST_NOBJPOS; j++)
        for (int i = 0; i < 3; i++) c[i] += s->obj_pos[j][i] / ST_NOBJPOS;
      double pos[3];
      for (int i = 0; i < 3; i++) pos[i] = c[i] + REACH_PALM_OFFSET[k][i];
      stIkDef def = st_ik_default_def();
      def.dof_weight[ST_DOF_TORSO_YAW] = def.dof_weight[ST_DOF_TORSO_PITCH] = 0.0;
      stIkTarget t = st_ik_target(r->palm_body, pos);
      start_posture(r, REACH_START_DEG[k], q);
      q[ST_DOF_THUMB_OPPOSE] = REACH_THUMB_OPPOSE;
      q[ST_DOF_THUMB_FLEX] = q[ST_DOF_FINGER_FLEX] = 0.0;
      if (PD.reach_palm_down) {
        /* the palm turned down first, as far as the arm allows there; the position-only solve
         * below then starts from that orientation and keeps most of it (the check asks
         * p > 0.9, not an exact normal) */
        static const double normal[3] = {0, 0, 1}, down[3] = {0, 0, -1};
        stIkTarget turn = t;
        st_ik_target_align(&turn, 0, normal, down, 10.0 * NORMAL_WEIGHT);
        stIkResult res;
        (void)st_ik_solve(r, &def, &turn, q, &res);
      }
      return ik_run(r, &def, &t, q, what, k, err, errsz) ? ST_ERR_RANGE : ST_OK;
    }
    case ST_PRIM_OPEN: {
      const int near = open_near(k, v);
      if (near) {
        ball[0] = PD.open_near_ball_x;
        ball[2] = rad + PD.open_near_gap;
      } else {
        ball[2] = rad + PD.open_high_gap;
      }
      if (place_palm_over_ball(r, s, k, ball, v, q, what, err, errsz)) return ST_ERR_RANGE;
      q[ST_DOF_THUMB_OPPOSE] = near ? PD.open_near_oppose : PD.open_high_oppose;
      q[ST_DOF_THUMB_FLEX] = near ? PD.open_near_thumb : PD.open_high_flex;
      q[ST_DOF_FINGER_FLEX] = near ? PD.open_near_fingers : PD.open_high_flex;
      return ST_OK;
    }
    case ST_PRIM_GRASP:
      ball[0] = PD.grasp_ball_x;
      ball[2] = rad + PD.grasp_gap;
      if (place_palm_over_ball(r, s, k, ball, v, q, what, err, errsz)) return ST_ERR_RANGE;
      q[ST_DOF_THUMB_OPPOSE] = k < 2 ? PD.grasp_oppose : PD.grasp_partial_oppose;
      q[ST_DOF_THUMB_FLEX] = k < 2 ? 0.0 : PD.grasp_partial_thumb_flex;
      q[ST_DOF_FINGER_FLEX] = k < 2 ? 0.0 : PD.grasp_partial_flex;
      return ST_OK;
    case ST_PRIM_MOVE:
      ball[0] = PD.move_ball_x;
      ball[2] = rad + PD.move_gap;
      if (place_palm_over_ball(r, s, k, ball, v, q, what, err, errsz)) return ST_ERR_RANGE;
      return move_close(r, s, k, q, err, errsz);
    default: return ST_ERR_ARG;
  }
}

/* the config keys a posture is built from (scene.*: where the object is; postures.*: where the
 * hand goes), named when it cannot be built: in-range values can still put it out of reach */
static const char *posture_keys(int prim, int k, int near) {
  switch (prim) {
    case ST_PRIM_REACH:
      return "scene.object_center_x, scene.object_center_y, scene.table_top_z, "
             "scene.object_radius, postures.reach_clearance, postures.reach_max_steps, "
             "fitness.reach_height";
    case ST_PRIM_OPEN:
      return near ? "scene.object_center_x, scene.object_center_y, scene.object_spacing, "
                     "scene.table_top_z, scene.object_radius, postures.open_near_ball_x, "
                     "postures.open_near_gap, postures.open_near_oppose, postures.open_near_thumb, "
                     "postures.open_near_fingers"
                   : "scene.object_center_x, scene.object_center_y, scene.object_spacing, "
                     "scene.table_top_z, scene.object_radius, postures.open_high_gap, "
                     "postures.open_high_oppose, postures.open_high_flex";
    case ST_PRIM_GRASP:
      return k < 2 ? "scene.object_center_x, scene.object_center_y, scene.object_spacing, "
                     "scene.table_top_z, scene.object_radius, postures.grasp_ball_x, "
                     "postures.grasp_gap, postures.grasp_oppose"
                   : "scene.object_center_x, scene.object_center_y, scene.object_spacing, "
                     "scene.table_top_z, scene.object_radius, postures.grasp_ball_x, "
                     "postures.grasp_gap, postures.grasp_partial_oppose, "
                     "postures.grasp_partial_flex, postures.grasp_partial_thumb_flex";
    default:
      return "scene.object_center_x, scene.object_center_y, scene.object_spacing, "
             "scene.table_top_z, scene.object_radius, postures.move_ball_x, postures.move_gap, "
             "postures.move_oppose, postures.move_squeeze, postures.move_min_fingers";
  }
}

/* appends the keys to the message in err */
static void name_keys(int prim, int k, int near, char *err, size_t errsz) {
  if (!err || !errsz) return;
  const size_t n = strlen(err);
  snprintf(err + n, errsz - n, " [keys: %s%s]", posture_keys(prim, k, near),
           prim == ST_PRIM_REACH ? ""
                                 : ", postures.ik_torso_pitch, postures.ik_wrist_prosup, "
                                   "postures.ik_wrist_pitch");
}

/* compute, then st_posture_check; qhat is written only on success */
static stStatus build(const stRobot *r, const stScene *s, int prim, int k,
                      const stPostureVariation *v, double qhat[ST_NDOF], char *err, size_t errsz) {
  double q[ST_NDOF];
  stStatus st = compute(r, s, prim, k, v, q, err, errsz);
  char why[256];
  if (!st && !check_kind(r, s, prim, k, open_near(k, v), q, why, sizeof why)) {
    st__errf(err, errsz, "posture %s %d: %s", st_primitive_name(prim), k, why);
    st = ST_ERR_RANGE;
  }
  if (st) {
    name_keys(prim, k, open_near(k, v), err, errsz);
    return st;
  }
  memcpy(qhat, q, sizeof q);
  return ST_OK;
}

stStatus st_posture(const stRobot *r, const stScene *s, int prim, int k, double qhat[ST_NDOF],
                    char *err, size_t errsz) {
  ST_ASSERT(r && s && qhat);
  if (prim < 0 || prim >= ST_NPRIM || k < 0 || k >= ST_NPOSTURE) {
    st__errf(err, errsz, "posture: primitive %d, posture %d (expected 0..%d and 0..%d)", prim, k,
             ST_NPRIM - 1, ST_NPOSTURE - 1);
    return ST_ERR_ARG;
  }
  stPostureVariation none;
  st_posture_variation_none(s, &none);
  return build(r, s, prim, k, &none, qhat, err, errsz);
}

stStatus st_posture_varied(const stRobot *r, const stScene *s, int prim, int k,
                           const stPostureVariation *v, double qhat[ST_NDOF], char *err,
                           size_t errsz) {
  ST_ASSERT(r && s && v && qhat);
  if (prim != ST_PRIM_OPEN && prim != ST_PRIM_GRASP) {
    st__errf(err, errsz, "posture: a varied start of primitive %d (expected open or grasp)", prim);
    return ST_ERR_ARG;
  }
  if (k < 0 || k >= ST_NPOSTURE) {
    st__errf(err, errsz, "posture: posture %d (expected 0..%d)", k, ST_NPOSTURE - 1);
    return ST_ERR_ARG;
  }
  return build(r, s, prim, k, v, qhat, err, errsz);
}

stStatus st_postures_all(const stRobot *r, const stScene *s,
                         double qhat[ST_NPRIM][ST_NPOSTURE][ST_NDOF], char *err, size_t errsz) {
  ST_ASSERT(r && s && qhat);
  for (int p = 0; p < ST_NPRIM; p++)
    for (int k = 0; k < ST_NPOSTURE; k++) {
      stStatus st = st_posture(r, s, p, k, qhat[p][k], err, errsz);
      if (st) return st;
    }
  return ST_OK;
}

/* ---- checks ------------------------------------------------------------------------------- */

#define FAIL(...)                                  \
  do {                                             \
    if (why && n) snprintf(why, n, __VA_ARGS__);   \
    return 0;                                      \
  } while (0)

static double hdist(const double *a, const double *b) { return hypot(a[0] - b[0], a[1] - b[1]); }

static double dist3(const double *a, const double *b) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

/* the properties that need the world; returns 1 / 0 with why */
int st_posture_reach_steps(const stRobot *r, const stScene *s, int k, const double qhat[ST_NDOF],
                           int max_steps) {
  ST_ASSERT(r && s && qhat);
  ST_ASSERT(k >= 0 && k < ST_NPOSTURE);
  double goal[3] = {s->obj_pos[k][0], s->obj_pos[k][1], s->obj_pos[k][2] + PD.reach_height};
  double q[ST_NDOF];
  memcpy(q, qhat, sizeof q);
  stIkDef def = st_ik_default_def();
  stIkTarget t = st_ik_target(r->palm_body, goal);
  stIkResult res;
  if (st_ik_solve(r, &def, &t, q, &res) != ST_OK) return -1;
  stWorld *w = NULL;
  if (st_world_create(r, s, &w, NULL, 0)) return -1;
  st_world_reset(w, qhat, s->obj_pos[k], s->target[0]);
  int reached = -1;
  for (int step = 0; step < max_steps && reached < 0; step++) {
    double y[ST_NDOF];
    for (int d = 0; d < ST_NDOF; d++) {
      double e = q[d] - w->qhat[d];
      y[d] = fabs(e) < 0.02 ? q[d] : e > 0 ? 1.0 : 0.0;
    }
    st_world_step_kinematic(w, y);
    const double *pc = w->p[r->palm_body];
    if (dist3(pc, goal) < REACH_SUCCESS_DIST) reached = step + 1;
  }
  st_world_destroy(w);
  return reached;
}

static int check_world(const stRobot *r, const stScene *s, const stWorld *w, int prim, int k,
                       int near, const double q[ST_NDOF], char *why, size_t n) {
  const stContacts *c = &w->contacts;
  const double *palm = w->p[r->palm_body];
  const double *R = w->R[r->palm_body];
  const double nz = R[8]; /* palm normal (frame +z), world z component */
  const double p = 0.5 * (1.0 - nz);
  const double *obj = s->obj_pos[k];
  const double top = obj[2] + s->obj_radius; /* ball top */
  const double tflex = q[ST_DOF_THUMB_FLEX], fflex = q[ST_DOF_FINGER_FLEX];
  int ntouch = 0;
  for (int i = 0; i < ST_NTOUCH; i++) ntouch += c->touch_object[i];

  /* every posture: arm and hand clear of the table, and above it */
  if (c->arm_table) FAIL("the arm or hand touches the table");
  if (!(palm[2] > s->table_top_z)) FAIL("palm centre z %.3f is not above the table", palm[2]);
  for (int i = 0; i < ST_NTIP; i++)
    if (!(w->p[r->tip_body[i]][2] > s->table_top_z))
      FAIL("fingertip %d is below the table top", i);

  switch (prim) {
    case ST_PRIM_REACH: {
      for (int d = ST_DOF_TORSO_YAW; d <= ST_DOF_TORSO_PITCH; d++)
        if (fabs(st_robot_dof_angle(r, d, q[d])) > 1e-9)
          FAIL("%s is %.3f deg (expected 0: torso centred)", r->dof_name[d],
               st_robot_dof_angle(r, d, q[d]) / ST_DEG);
      if (tflex != 0.0 || fflex != 0.0)
        FAIL("thumb / finger flexion %.3f / %.3f (expected 0: fully extended)", tflex, fflex);
      for (int j = 0; j < ST_NOBJPOS; j++) {
        double d = dist3(palm, s->obj_pos[j]);
        if (!(d >= PD.reach_clearance))
          FAIL("palm centre %.3f m from object position %d (expected >= %.2f)", d, j,
               PD.reach_clearance);
      }
      if (c->robot_object) FAIL("the hand touches the object");
      if (PD.reach_palm_down && !(p > CHECK_REACH_DOWN))
        FAIL("p = %.3f (expected > %.2f: palm down, postures.reach_palm_down)", p, CHECK_REACH_DOWN);
      int steps = st_posture_reach_steps(r, s, k, w->qhat, 4 * PD.reach_max_steps);
      if (steps < 0 || steps > PD.reach_max_steps)
        FAIL("a full-speed IK controller needs %d steps to reach (expected <= %d)", steps,
             PD.reach_max_steps);
      return 1;
    }
    case ST_PRIM_OPEN: {
      if (c->robot_object) FAIL("the hand touches the object (expected almost grasping)");
      double xy = hdist(palm, obj), gap = palm[2] - top;
      if (!(xy <= CHECK_OPEN_XY))
        FAIL("palm centre %.3f m from the ball horizontally (expected <= %.2f: above it)", xy,
             CHECK_OPEN_XY);
      if (!(gap > 0.0)) FAIL("palm centre %.3f m above the ball top (expected above it)", gap);
      if (near) {
        if (!(gap <= CHECK_OPEN_NEAR_MAX_GAP))
          FAIL("palm %.3f m above the ball top (expected <= %.2f: around the object)", gap,
               CHECK_OPEN_NEAR_MAX_GAP);
        if (!(fflex >= CHECK_OPEN_NEAR_FLEX_LO && fflex <= CHECK_OPEN_NEAR_FLEX_HI))
          FAIL("finger flexion %.3f (expected %.2f..%.2f: partly closed)", fflex,
               CHECK_OPEN_NEAR_FLEX_LO, CHECK_OPEN_NEAR_FLEX_HI);
      } else {
        if (!(gap >= CHECK_OPEN_HIGH_MIN_GAP && gap <= CHECK_OPEN_HIGH_MAX_GAP))
          FAIL("palm %.3f m above the ball top (expected %.2f..%.2f: a few cm above)", gap,
               CHECK_OPEN_HIGH_MIN_GAP, CHECK_OPEN_HIGH_MAX_GAP);
        if (!(tflex >= CHECK_OPEN_HIGH_FLEX && fflex >= CHECK_OPEN_HIGH_FLEX))
          FAIL("thumb / finger flexion %.3f / %.3f (expected >= %.2f: almost closed)", tflex,
               fflex, CHECK_OPEN_HIGH_FLEX);
      }
      return 1;
    }
    case ST_PRIM_GRASP: {
      if (!(p > CHECK_PALM_DOWN)) FAIL("p = %.3f (expected > %.2f: palm down)", p, CHECK_PALM_DOWN);
      if (c->robot_object) FAIL("the hand touches the object");
      const double bx = PD.grasp_ball_x; /* along the fingers: the palm frame's +x */
      if (!(fabs(bx) <= CHECK_GRASP_BALL_X))
        FAIL("postures.grasp_ball_x = %.3f m (expected within +-%.2f: the hand above the ball)", bx,
             CHECK_GRASP_BALL_X);
      const double g[3] = {palm[0] + bx * R[0], palm[1] + bx * R[3], palm[2] + bx * R[6]};
      double xy = hdist(g, obj), gap = palm[2] - top;
      if (!(xy <= CHECK_GRASP_XY))
        FAIL("palm point %.3f m ahead of its centre is %.3f m from the ball horizontally (expected "
             "<= %.2f)", bx, xy, CHECK_GRASP_XY);
      if (!(gap >= CHECK_GRASP_MIN_GAP && gap <= CHECK_GRASP_MAX_GAP))
        FAIL("palm %.3f m above the ball top (expected %.2f..%.2f)", gap, CHECK_GRASP_MIN_GAP,
             CHECK_GRASP_MAX_GAP);
      /* the thesis speaks of the fingers only: the thumb's flexion is the posture's choice */
      if (k < 2 && fflex != 0.0)
        FAIL("thumb / finger flexion %.3f / %.3f (expected fingers 0: fully extended)", tflex, fflex);
      if (k >= 2 && !(fflex >= CHECK_GRASP_FLEX_LO && fflex <= CHECK_GRASP_FLEX_HI))
        FAIL("thumb / finger flexion %.3f / %.3f (expected %.2f..%.2f: partly extended)", tflex,
             fflex, CHECK_GRASP_FLEX_LO, CHECK_GRASP_FLEX_HI);
      return 1;
    }
    case ST_PRIM_MOVE: {
      /* Kinematic part of "a stable grasp" only: palm down over the ball, thumb opposed and
       * touching, >= 3 sensors on the ball, the ball between thumb, little finger and palm
       * (d_g). That the object stays 3 s in the hand with the finger commands frozen (SPEC §8)
       * needs dynamic mode and is verified there. */
      if (!(p > CHECK_PALM_DOWN)) FAIL("p = %.3f (expected > %.2f: palm down)", p, CHECK_PALM_DOWN);
      if (!(q[ST_DOF_THUMB_OPPOSE] >= CHECK_MOVE_OPPOSE))
        FAIL("thumb opposition %.3f (expected >= %.2f)", q[ST_DOF_THUMB_OPPOSE], CHECK_MOVE_OPPOSE);
      if (!c->touch_object[ST_TOUCH_THUMB]) FAIL("the thumb does not touch the ball");
      if (ntouch < CHECK_MOVE_TOUCHES)
        FAIL("%d touch sensors on the ball (expected >= %d)", ntouch, CHECK_MOVE_TOUCHES);
      double cg[3];
      for (int i = 0; i < 3; i++)
        cg[i] = (w->p[r->tip_body[0]][i] + w->p[r->tip_body[ST_NTIP - 1]][i] + palm[i]) / 3.0;
      double dg = dist3(cg, obj);
      if (!(dg < CHECK_MOVE_DG)) FAIL("d_g = %.4f m (expected < %.2f)", dg, CHECK_MOVE_DG);
      return 1;
    }
    default: FAIL("unknown primitive %d", prim);
  }
}

int st_posture_check(const stRobot *r, const stScene *s, int prim, int k,
                     const double qhat[ST_NDOF], char *why, size_t n) {
  ST_ASSERT(r && s && qhat);
  return check_kind(r, s, prim, k, k < 2, qhat, why, n);
}

static int check_kind(const stRobot *r, const stScene *s, int prim, int k, int near,
                      const double qhat[ST_NDOF], char *why, size_t n) {
  if (prim < 0 || prim >= ST_NPRIM || k < 0 || k >= ST_NPOSTURE)
    FAIL("primitive %d, posture %d (expected 0..%d and 0..%d)", prim, k, ST_NPRIM - 1,
         ST_NPOSTURE - 1);
  for (int d = 0; d < ST_NDOF; d++)
    if (!(qhat[d] >= 0.0 && qhat[d] <= 1.0)) FAIL("qhat[%d] = %g (expected 0..1)", d, qhat[d]);
  stWorld *w = NULL;
  char err[256];
  if (st_world_create(r, s, &w, err, sizeof err)) FAIL("%s", err);
  st_world_reset(w, qhat, s->obj_pos[k], s->target[k % 2]);
  int ok = check_world(r, s, w, prim, k, near, qhat, why, n);
  st_world_destroy(w);
  if (!ok || prim != ST_PRIM_REACH) return ok;
  /* reach: four distinct arm postures */
  stPostureVariation none;
  st_posture_variation_none(s, &none);
  for (int j = 0; j < ST_NPOSTURE; j++) {
    if (j == k) continue;
    double other[ST_NDOF];
    if (compute(r, s, prim, j, &none, other, err, sizeof err)) FAIL("%s", err);
    double mx = 0.0;
    for (int d = ST_DOF_SHOULDER_PITCH; d <= ST_DOF_WRIST_YAW; d++)
      mx = fmax(mx, fabs(qhat[d] - other[d]));
    if (!(mx >= REACH_DISTINCT))
      FAIL("arm posture within %.3f (qhat) of reach posture %d (expected distinct: >= %.2f)", mx,
           j, REACH_DISTINCT);
  }
  return 1;
}
