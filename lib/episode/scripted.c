/* SPDX-License-Identifier: MIT
 * The scripted controller: every primitive by inverse kinematics and hand-written rules (see
 * selftalk/scripted.h; the reasons for the numbers in docs/PROTOCOL.md, "Scripted
 * controller"). */
#include "selftalk/scripted.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/ik.h"
#include "selftalk/sensors.h"

/* ---- the controller's numbers ---------------------------------------------------------------
 * Distances in metres, hand DOF in normalised units. "Ball frame": the object centre in the
 * palm frame (+x along the fingers, +y towards the thumb, +z the palm normal out of the palm;
 * with the palm down, +z points at the table). */
typedef struct scriptedDef {
  double gain;           /* arm: fraction of the joint-space error closed per control step */
  double hand_gain;      /* hand DOF moving in free space: the same */
  double torso_weight;   /* IK mobility of torso yaw and pitch relative to the arm */
  double down_weight;    /* IK weight of the palm normal pointing down (rad^2 vs m^2) */
  double reach_oppose;   /* reach / open: thumb opposition (beside the palm, clear of the ball) */
  double open_rise;      /* open: the palm rises at most this per step while the hand is closed */
  double grasp_oppose;   /* grasp: thumb opposition (it closes behind and under the ball) */
  double oppose_tol;     /* the thumb closes once its opposition is within this of its target */
  double caged_flex;     /* a grasp start with the thumb opposed, the fingers flexed more than
                            this ... */
  double caged_xy;       /* ... and the ball this close to under the palm centre already cages
                            it: the hand closes from there (no approach) */
  double pre_x;          /* approach: ball centre this far ahead of the palm centre (the opposed
                            thumb clear behind it) ... */
  double pre_gap;        /* ... the palm this far above the ball top ... */
  double pre_thumb;      /* ... thumb flexion at least this (more to keep the tip off the table) */
  double align_tol;      /* approach done: ball within this of its place in the ball frame */
  double thumb_clear;    /* the thumb tip stays this far above the table top while approaching */
  double thumb_ball_clear; /* the thumb tip passes the ball no closer than this to its surface
                              (the distal phalanx is a 6.5 mm cylinder) */
  double grasp_x;        /* closing: the ball (where it was) this far ahead of the palm ... */
  double grasp_gap;      /* ... the palm this far above its top */
  double close_thumb;    /* thumb and finger flexion commands while closing: full speed ... */
  double close_fingers;
  int finger_touches;    /* ... until this many fingertips touch the ball, */
  double squeeze;        /* ... then held this far beyond their flexion at contact */
  double still;          /* hand DOF moving less than this per step have stopped: gripped */
  double seat_gap;       /* while the ball top is further than this from the palm ... */
  double seat_rate;      /* ... the thumb's command rises by this per step ... */
  double seat_max;       /* ... up to this: the thumb pushes the ball up into the palm */
  int secure_steps;      /* move from a held posture: squeeze this long before lifting */
  double lift_height;    /* move: lift the ball this far straight up first ... */
  double lift_step;      /* ... its via point rising this much per step ... */
  double lift_lead;      /* ... while the ball is within this of it */
  double carry_gain;     /* move: fraction of the joint-space error closed per step */
  double carry_down_weight; /* move: IK weight of the palm normal pointing down */
  double restart_step;   /* move: the goal posture is searched from the current posture and
                            from it with each arm DOF moved by +- this ... */
  double motion_weight;  /* ... minimising IK cost + this x squared joint-space distance */
} scriptedDef;

static const scriptedDef DEF = {
    .gain = 0.5,
    .hand_gain = 1.0,
    .torso_weight = 0.25,
    .down_weight = 0.02,
    .reach_oppose = 0.5,
    .open_rise = 0.005,
    .grasp_oppose = 0.9,
    .oppose_tol = 0.1,
    .caged_flex = 0.1,
    .caged_xy = 0.01,
    .pre_x = 0.045,
    .pre_gap = 0.015,
    .pre_thumb = 0.1,
    .align_tol = 0.008,
    .thumb_clear = 0.01,
    .thumb_ball_clear = 0.007,
    .grasp_x = 0.03,
    .grasp_gap = 0.005,
    .close_thumb = 1.0,
    .close_fingers = 1.0,
    .finger_touches = 2,
    .squeeze = 0.05,
    .still = 0.004,
    .seat_gap = 0.003,
    .seat_rate = 0.01,
    .seat_max = 0.4,
    .secure_steps = 4,
    .lift_height = 0.06,
    .lift_step = 0.02,
    .lift_lead = 0.05,
    .carry_gain = 0.25,
    .carry_down_weight = 0.003,
    .restart_step = 0.25,
    .motion_weight = 1e-3,
};

enum { GR_APPROACH = 0, GR_CLOSE, GR_HOLD };
enum { MV_SECURE = 0, MV_LIFT, MV_CARRY };

struct stScripted {
  const stProtocol *p;
  scriptedDef def;
  stIkDef ik;
  double range_deg[ST_NDOF]; /* DOF ranges, degrees */
  double (*R)[9], (*x)[3];   /* forward-kinematics scratch (nbody) */
  int word;                  /* primitive being performed (-1: none) */
  int word_steps;            /* ... for this many steps */
  double prev_q[ST_NDOF];    /* qhat at the previous step */
  int have_prev;
  /* grasp */
  int grasp_phase;
  int grasp_steps;           /* steps of grasp performed since the reset */
  int gripped;               /* the grasp closed on the ball */
  double close_ball[2];      /* ball frame (x, y) the palm closes to; grasp_x, 0 after an approach */
  double finger_hold, thumb_hold; /* flexion commands once in contact, else -1 */
  double close_obj[3];       /* object centre when closing started */
  double hold_ball[3];       /* ball frame once gripped ... */
  double hold_pos[3];        /* ... and where the ball is held */
  /* move */
  int move_phase;
  int secure_left;           /* steps of squeezing left before the lift */
  int have_carry;
  double lift_z;             /* the straight lift ends at this height */
  double via[3];             /* the lift's via point */
  double lift_q[ST_NDOF];    /* the lift's last solution */
  double goal_q[ST_NDOF];    /* posture holding the ball at the target */
};

/* ---- small helpers ------------------------------------------------------------------------- */

static double clamp01(double x) { return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x; }

static double norm3(const double *a, const double *b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

/* a world point in the palm frame, for body poses R / x */
static void point_in_palm(const stScripted *s, double (*R)[9], double (*x)[3], const double *pt,
                          double *out) {
  const int pb = s->p->robot->palm_body;
  st_robot_point_local(R[pb], x[pb], pt, out);
}

static void ball_in_palm(const stScripted *s, const stWorld *w, double *b) {
  point_in_palm(s, w->R, w->p, w->obj, b);
}

/* thumb tip in the palm frame for a thumb opposition and flexion (forward kinematics) */
static void thumb_tip(stScripted *s, const stWorld *w, double oppose, double thumb, double *t) {
  double q[ST_NDOF];
  memcpy(q, w->qhat, sizeof q);
  q[ST_DOF_THUMB_OPPOSE] = oppose;
  q[ST_DOF_THUMB_FLEX] = thumb;
  st_robot_fk(s->p->robot, q, s->R, s->x);
  point_in_palm(s, s->R, s->x, s->x[s->p->robot->tip_body[0]], t);
}

static int fingertips_on_object(const stWorld *w) {
  int n = 0;
  for (int i = ST_TOUCH_INDEX; i <= ST_TOUCH_LITTLE; i++) n += w->contacts.touch_object[i];
  return n;
}

/* Inverse kinematics from the posture `start`: the palm-frame point `point` to the world
 * position `pos`, the palm normal down with weight down_w. Torso and arm DOF of q change;
 * returns the cost reached (the best posture found when not converged). */
static double solve_from(const stScripted *s, const double *start, const double point[3],
                         const double pos[3], double down_w, double q[ST_NDOF]) {
  static const double normal[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  const stRobot *r = s->p->robot;
  memcpy(q, start, sizeof(double) * ST_NDOF);
  stIkTarget t = st_ik_target(r->palm_body, pos);
  memcpy(t.point, point, sizeof t.point);
  if (down_w > 0.0) st_ik_target_align(&t, 0, normal, down, down_w);
  stIkResult res;
  res.cost = HUGE_VAL;
  (void)st_ik_solve(r, &s->ik, &t, q, &res);
  return res.cost;
}

static void solve(const stScripted *s, const stWorld *w, const double point[3],
                  const double pos[3], double q[ST_NDOF]) {
  solve_from(s, w->qhat, point, pos, s->def.down_weight, q);
}

/* The command that closes `gain` of the error to `goal` in one control step: under SPEC §3's
 * law the joint covers 1 - exp(-alpha dt / range) of (y - qhat) per step (unsaturated). */
static double command(const stScripted *s, int d, double qhat, double goal, double gain) {
  const stRobot *r = s->p->robot;
  const double frac = 1.0 - exp(-r->alpha_dynamic * r->dt / s->range_deg[d]);
  return clamp01(qhat + gain * (goal - qhat) / frac);
}

/* Torso and arm towards qg, `gain` of the error per step; when a joint would exceed the speed
 * limit all are slowed by the same factor, which keeps the joint-space direction (and so the
 * hand's path). */
static void arm_command(const stScripted *s, const stWorld *w, const double *qg, double gain,
                        double *y) {
  const stRobot *r = s->p->robot;
  double scale = 1.0;
  for (int d = 0; d <= ST_DOF_WRIST_YAW; d++) {
    const double vmax = r->max_velocity / ST_DEG * r->dt / s->range_deg[d]; /* qhat per step */
    const double want = fabs(gain * (qg[d] - w->qhat[d]));
    if (want * scale > vmax) scale = vmax / want;
  }
  for (int d = 0; d <= ST_DOF_WRIST_YAW; d++)
    y[d] = command(s, d, w->qhat[d], w->qhat[d] + scale * (qg[d] - w->qhat[d]), gain);
}

static void hand_command(const stScripted *s, const stWorld *w, double oppose, double thumb,
                         double fingers, double *y) {
  const double g = s->def.hand_gain;
  y[ST_DOF_THUMB_OPPOSE] = command(s, ST_DOF_THUMB_OPPOSE, w->qhat[ST_DOF_THUMB_OPPOSE], oppose, g);
  y[ST_DOF_THUMB_FLEX] = command(s, ST_DOF_THUMB_FLEX, w->qhat[ST_DOF_THUMB_FLEX], thumb, g);
  y[ST_DOF_FINGER_FLEX] = command(s, ST_DOF_FINGER_FLEX, w->qhat[ST_DOF_FINGER_FLEX], fingers, g);
}

/* ---- reach and open ------------------------------------------------------------------------ */

/* palm centre to the reach point, palm down, hand open (the thumb beside the palm); open also
 * rises slowly while the hand is still closed around the ball, so that the fingers open first */
static void do_reach_open(stScripted *s, const stWorld *w, int open, double *y) {
  static const double origin[3] = {0, 0, 0};
  const double *palm = w->p[s->p->robot->palm_body];
  double pos[3] = {w->obj[0], w->obj[1], w->obj[2] + s->p->sensor.reach_height}, qg[ST_NDOF];
  const double flex = fmax(w->qhat[ST_DOF_THUMB_FLEX], w->qhat[ST_DOF_FINGER_FLEX]);
  if (open && flex > 0.2) pos[2] = fmin(pos[2], palm[2] + s->def.open_rise);
  solve(s, w, origin, pos, qg);
  arm_command(s, w, qg, s->def.gain, y);
  hand_command(s, w, s->def.reach_oppose, 0.0, 0.0, y);
}

/* ---- grasp --------------------------------------------------------------------------------- */

static int hand_still(const stScripted *s, const stWorld *w) {
  if (!s->have_prev) return 0;
  for (int d = ST_DOF_THUMB_OPPOSE; d <= ST_DOF_FINGER_FLEX; d++)
    if (fabs(w->qhat[d] - s->prev_q[d]) > s->def.still) return 0;
  return 1;
}

/* the thumb flexion (at least f_min) that keeps the thumb tip thumb_clear above the table top,
 * the thumb at opposition `oppose` and the palm (down) at height palm_z */
static double thumb_clear_flex(stScripted *s, const stWorld *w, double oppose, double palm_z,
                               double f_min) {
  const double allowed = palm_z - w->scene->table_top_z - s->def.thumb_clear;
  double t[3];
  thumb_tip(s, w, oppose, f_min, t);
  if (t[2] <= allowed) return f_min;
  double lo = f_min, hi = 1.0; /* the tip rises monotonically with flexion */
  for (int i = 0; i < 10; i++) {
    const double mid = 0.5 * (lo + hi);
    thumb_tip(s, w, oppose, mid, t);
    if (t[2] <= allowed) hi = mid;
    else lo = mid;
  }
  return hi;
}

/* opposition while gripping: towards grasp_oppose; held where it is when the ball pushed it
 * further (the thumb further under the ball) */
static double grip_oppose(const stScripted *s, const stWorld *w) {
  const double q = w->qhat[ST_DOF_THUMB_OPPOSE];
  return q >= s->def.grasp_oppose ? q : command(s, ST_DOF_THUMB_OPPOSE, q, s->def.grasp_oppose,
                                                s->def.hand_gain);
}

/* The hand starts around the ball: thumb opposed behind it, fingers partly flexed in front, the
 * ball under the palm centre (postures.grasp_partial_oppose 0.9, the shipped configs). The
 * approach's re-placing would flex the thumb against the ball and kick it out of the cage (17 cm
 * in 20 steps), so the palm closes onto the ball along its normal from where it is and the hand
 * closes. The chain stage's drawn starts (palm moved and tilted) close so when the ball is within
 * caged_xy of the centre: generations 0-59 of configs/chain_prim.cfg, grasp k=2 56 and k=3 43
 * of 60 (47 and 35 with any offset, 38 and 37 within 5 mm; the thumb at 0.5: 58 and 55). */
static int caged_start(const stScripted *s, const double *q, const double b[3]) {
  return q[ST_DOF_THUMB_OPPOSE] >= s->def.grasp_oppose - s->def.oppose_tol &&
         q[ST_DOF_FINGER_FLEX] > s->def.caged_flex && hypot(b[0], b[1]) < s->def.caged_xy;
}

/* Approach: the palm goes over the ball, palm down, the ball pre_x ahead along the fingers,
 * while the thumb turns to opposition behind it; the thumb is flexed just enough for its tip
 * to clear the table once the palm is down, and the palm stays high while the tip would not
 * pass beside the ball (from a caged start, none: caged_start). Close: the palm moves to put
 * the ball (where it was) grasp_x ahead, or from a caged start where it is, grasp_gap below;
 * thumb and fingers close at full speed; each is held `squeeze` beyond its contact flexion
 * (its motor then pushes with its bounded torque). Hold: once both touch and the hand is
 * still, the palm keeps the ball where it is and the thumb's command rises while the ball
 * hangs below the palm: the thumb, under the ball, lifts it into the palm (the cage that holds
 * it without the table). */
static void do_grasp(stScripted *s, const stWorld *w, double *y) {
  const scriptedDef *D = &s->def;
  const stRobot *r = s->p->robot;
  const double rad = w->scene->obj_radius, *q = w->qhat;
  double b[3], qg[ST_NDOF];
  ball_in_palm(s, w, b);
  s->grasp_steps++;
  if (s->grasp_phase == GR_APPROACH && s->grasp_steps == 1 && caged_start(s, q, b)) {
    memcpy(s->close_obj, w->obj, sizeof s->close_obj);
    s->close_ball[0] = b[0], s->close_ball[1] = b[1]; /* down onto the ball from where it is */
    s->grasp_phase = GR_CLOSE;
  }
  if (s->grasp_phase == GR_APPROACH) {
    const double qo = q[ST_DOF_THUMB_OPPOSE];
    const double o_step = 1.5 * r->max_velocity * r->dt / (s->range_deg[ST_DOF_THUMB_OPPOSE] * ST_DEG);
    const double o = qo < D->grasp_oppose ? fmin(D->grasp_oppose, qo + o_step) : qo;
    const double low[3] = {D->pre_x, 0.0, rad + D->pre_gap}; /* the ball frame once down */
    const double f = thumb_clear_flex(s, w, o, w->obj[2] + low[2], D->pre_thumb);
    double t[3], want[3] = {low[0], low[1], low[2]};
    thumb_tip(s, w, o, f, t);
    if (hypot(t[0] - b[0], t[1] - b[1]) < rad + D->thumb_ball_clear)
      want[2] = fmax(want[2], t[2] + rad + D->thumb_ball_clear); /* the tip passes over the ball */
    if (norm3(b, low) < D->align_tol && fabs(qo - D->grasp_oppose) < D->oppose_tol) {
      memcpy(s->close_obj, w->obj, sizeof s->close_obj);
      s->grasp_phase = GR_CLOSE;
    } else {
      solve(s, w, want, w->obj, qg);
      arm_command(s, w, qg, D->gain, y);
      hand_command(s, w, D->grasp_oppose, f, 0.0, y);
      return;
    }
  }
  if (s->grasp_phase == GR_CLOSE) {
    const double want[3] = {s->close_ball[0], s->close_ball[1], rad + D->grasp_gap};
    solve(s, w, want, s->close_obj, qg);
    arm_command(s, w, qg, D->gain, y);
    if (s->thumb_hold < 0.0 && w->contacts.touch_object[ST_TOUCH_THUMB])
      s->thumb_hold = fmin(1.0, q[ST_DOF_THUMB_FLEX] + D->squeeze);
    if (s->finger_hold < 0.0 && fingertips_on_object(w) >= D->finger_touches)
      s->finger_hold = fmin(1.0, q[ST_DOF_FINGER_FLEX] + D->squeeze);
    if (s->thumb_hold >= 0.0 && s->finger_hold >= 0.0 && hand_still(s, w)) {
      s->gripped = 1;
      memcpy(s->hold_ball, b, sizeof b);
      memcpy(s->hold_pos, w->obj, sizeof s->hold_pos);
      s->grasp_phase = GR_HOLD;
    }
  }
  if (s->grasp_phase == GR_HOLD) {
    solve(s, w, s->hold_ball, s->hold_pos, qg);
    arm_command(s, w, qg, D->gain, y);
    if (b[2] > rad + D->seat_gap && s->thumb_hold < D->seat_max)
      s->thumb_hold = fmin(D->seat_max, s->thumb_hold + D->seat_rate);
  }
  y[ST_DOF_THUMB_OPPOSE] = grip_oppose(s, w);
  y[ST_DOF_THUMB_FLEX] = s->thumb_hold >= 0.0 ? s->thumb_hold : D->close_thumb;
  y[ST_DOF_FINGER_FLEX] = s->finger_hold >= 0.0 ? s->finger_hold : D->close_fingers;
}

/* ---- move ---------------------------------------------------------------------------------- */

/* Keep the grip (a grasp still closing is finished first; a ball held from a posture gets
 * `squeeze` more flexion than the posture's), the arm still for secure_steps; lift the ball
 * straight up by lift_height, then move the arm in joint space to the goal posture: the one
 * that puts the ball's point of the palm frame at the target with the palm down, searched by
 * inverse kinematics from several starts for the least IK cost plus motion. */
static void do_move(stScripted *s, const stWorld *w, double *y) {
  const scriptedDef *D = &s->def;
  const double rad = w->scene->obj_radius;
  double b[3], qg[ST_NDOF];
  if (s->word_steps == 0) {
    s->move_phase = MV_SECURE;
    s->secure_left = D->secure_steps;
    s->have_carry = 0;
  }
  ball_in_palm(s, w, b);
  if (s->move_phase == MV_SECURE) {
    const int seated = b[2] <= rad + D->seat_gap || s->thumb_hold >= D->seat_max;
    if (s->grasp_steps > 0 && (!s->gripped || !seated)) {
      do_grasp(s, w, y); /* the caretaker moved on when enough sensors touched: finish it */
      return;
    }
    if (!s->gripped && s->thumb_hold < 0.0) {
      s->thumb_hold = fmin(1.0, w->qhat[ST_DOF_THUMB_FLEX] + D->squeeze);
      s->finger_hold = fmin(1.0, w->qhat[ST_DOF_FINGER_FLEX] + D->squeeze);
    }
    if (--s->secure_left <= 0) {
      s->move_phase = MV_LIFT;
      s->lift_z = w->obj[2] + D->lift_height;
    }
  }
  if (b[2] > rad + D->seat_gap && s->thumb_hold >= 0.0 && s->thumb_hold < D->seat_max)
    s->thumb_hold = fmin(D->seat_max, s->thumb_hold + D->seat_rate);
  y[ST_DOF_THUMB_OPPOSE] = s->gripped ? grip_oppose(s, w) : w->qhat[ST_DOF_THUMB_OPPOSE];
  y[ST_DOF_THUMB_FLEX] = s->thumb_hold >= 0.0 ? s->thumb_hold : w->qhat[ST_DOF_THUMB_FLEX];
  y[ST_DOF_FINGER_FLEX] = s->finger_hold >= 0.0 ? s->finger_hold : w->qhat[ST_DOF_FINGER_FLEX];
  if (s->move_phase == MV_SECURE) return; /* the arm where it is */

  if (!s->have_carry) {
    memcpy(s->via, w->obj, sizeof s->via);
    memcpy(s->lift_q, w->qhat, sizeof s->lift_q);
    double q[ST_NDOF], start[ST_NDOF], best = HUGE_VAL;
    for (int i = -1; i < 2 * (ST_DOF_WRIST_YAW + 1); i++) {
      memcpy(start, w->qhat, sizeof start);
      if (i >= 0) start[i / 2] = clamp01(start[i / 2] + (i % 2 ? -D->restart_step : D->restart_step));
      double c = solve_from(s, start, b, w->target, D->carry_down_weight, q);
      for (int d = 0; d <= ST_DOF_WRIST_YAW; d++)
        c += D->motion_weight * (q[d] - w->qhat[d]) * (q[d] - w->qhat[d]);
      if (c < best) {
        best = c;
        memcpy(s->goal_q, q, sizeof q);
      }
    }
    s->have_carry = 1;
  } else {
    double q[ST_NDOF]; /* the ball settles in the hand: the goal posture follows */
    solve_from(s, s->goal_q, b, w->target, D->carry_down_weight, q);
    memcpy(s->goal_q, q, sizeof q);
  }
  if (s->move_phase == MV_LIFT) {
    /* a via point rises ahead of the ball; the posture follows it from its last solution */
    if (norm3(s->via, w->obj) < D->lift_lead) s->via[2] = fmin(s->lift_z, s->via[2] + D->lift_step);
    if (s->via[2] >= s->lift_z) s->move_phase = MV_CARRY;
    solve_from(s, s->lift_q, b, s->via, D->carry_down_weight, qg);
    memcpy(s->lift_q, qg, sizeof qg);
  }
  if (s->move_phase == MV_CARRY) memcpy(qg, s->goal_q, sizeof qg);
  arm_command(s, w, qg, D->carry_gain, y);
}

/* ---- the stController ------------------------------------------------------------------------ */

static void scripted_reset(void *self, const stEpisodeSpec *e) {
  (void)e;
  stScripted *s = self;
  s->word = -1;
  s->word_steps = 0;
  s->have_prev = 0;
  s->grasp_phase = GR_APPROACH;
  s->grasp_steps = 0;
  s->close_ball[0] = s->def.grasp_x, s->close_ball[1] = 0.0;
  s->gripped = 0;
  s->finger_hold = s->thumb_hold = -1.0;
  s->move_phase = MV_SECURE;
  s->have_carry = 0;
}

/* the word being given: the largest linguistic input; none (-1) when all are 0 */
static int word_of(const double *in) {
  int best = -1;
  double v = 0.0;
  for (int m = 0; m < ST_NET_NLING; m++)
    if (in[ST_NET_IN_LING + m] > v) {
      v = in[ST_NET_IN_LING + m];
      best = m;
    }
  return best;
}

static void scripted_act(void *self, const stWorld *w, const stQuantities *q, const double *in,
                         int step, double *out) {
  (void)q;
  (void)step;
  stScripted *s = self;
  const int word = word_of(in);
  if (word != s->word) {
    s->word = word;
    s->word_steps = 0;
  }
  double y[ST_NDOF];
  memcpy(y, w->qhat, sizeof y); /* no word: hold still */
  switch (word) {
    case ST_PRIM_REACH: do_reach_open(s, w, 0, y); break;
    case ST_PRIM_OPEN: do_reach_open(s, w, 1, y); break;
    case ST_PRIM_GRASP: do_grasp(s, w, y); break;
    case ST_PRIM_MOVE: do_move(s, w, y); break;
    default: break;
  }
  s->word_steps++;
  memcpy(s->prev_q, w->qhat, sizeof s->prev_q);
  s->have_prev = 1;
  memcpy(out, y, sizeof y);
  out[ST_NET_OUT_FOCUS] = word == ST_PRIM_MOVE ? 1.0 : 0.0; /* target only while moving */
}

/* ---- creation ------------------------------------------------------------------------------- */

stStatus st_scripted_create(const stProtocol *p, stScripted **out, char *err, size_t errsz) {
  ST_ASSERT(p && p->robot && out);
  *out = NULL;
  stScripted *s = calloc(1, sizeof *s);
  if (s) {
    s->R = calloc((size_t)p->robot->nbody, sizeof *s->R);
    s->x = calloc((size_t)p->robot->nbody, sizeof *s->x);
  }
  if (!s || !s->R || !s->x) {
    st_scripted_destroy(s);
    st__errf(err, errsz, "scripted controller: out of memory");
    return ST_ERR_NOMEM;
  }
  s->p = p;
  s->def = DEF;
  s->ik = st_ik_default_def();
  s->ik.dof_weight[ST_DOF_TORSO_YAW] = s->ik.dof_weight[ST_DOF_TORSO_PITCH] = DEF.torso_weight;
  for (int d = 0; d < ST_NDOF; d++)
    s->range_deg[d] = (p->robot->dof_hi[d] - p->robot->dof_lo[d]) / ST_DEG;
  scripted_reset(s, NULL);
  *out = s;
  return ST_OK;
}

void st_scripted_destroy(stScripted *s) {
  if (!s) return;
  free(s->R);
  free(s->x);
  free(s);
}

const char *st_scripted_phase(const stScripted *s) {
  ST_ASSERT(s);
  switch (s->word) {
    case ST_PRIM_REACH:
    case ST_PRIM_OPEN: return st_primitive_name(s->word);
    case ST_PRIM_GRASP:
      return s->grasp_phase == GR_APPROACH ? "grasp:approach"
             : s->grasp_phase == GR_CLOSE  ? "grasp:close"
                                           : "grasp:hold";
    case ST_PRIM_MOVE:
      return s->move_phase == MV_SECURE ? "move:secure"
             : s->move_phase == MV_LIFT ? "move:lift"
                                        : "move:carry";
    default: return "none";
  }
}

stController st_scripted_controller(stScripted *s) {
  ST_ASSERT(s);
  stController c = {scripted_reset, scripted_act, ST_NET_IN_LING + ST_NET_NLING, s, ST_NET_NOUT, 0,
                    NULL};
  return c;
}

/* ---- trials: episodes of the library's loop ---------------------------------------------- */

stStatus st_scripted_main_trial(const stProtocol *p, stWorkspace *ws, stScripted *s, int index,
                                stTrialResult *r, stTraceFn trace, void *ctx, char *err,
                                size_t errsz) {
  ST_ASSERT(p && ws && s && r);
  return st_scripted_main_trial_at(p, ws, s, 0, index, r, trace, ctx, err, errsz);
}

stStatus st_scripted_main_trial_at(const stProtocol *p, stWorkspace *ws, stScripted *s,
                                   int generation, int index, stTrialResult *r, stTraceFn trace,
                                   void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && s && r);
  if (index < 0 || index >= ST_PRIM_TRIALS || generation < 0) {
    memset(r, 0, sizeof *r);
    st__errf(err, errsz, "scripted: trial %d of generation %d (expected 0..%d, generation >= 0)",
             index, generation, ST_PRIM_TRIALS - 1);
    return ST_ERR_ARG;
  }
  stTrialSpec t;
  st_trial_spec(p, ST_STAGE_MAIN, generation, index, &t);
  /* individual 0's solver key of the generation (generation 0: the key the check has always
   * used, st_rng_keyed(seed, ST_RNG_TRIAL, 0, 0, index)) */
  const uint64_t key = st_trial_seed_key(p, generation, 0, index);
  const stController c = st_scripted_controller(s);
  return st_trial_run(p, ws, &t, &c, key, r, trace, ctx, err, errsz);
}

stStatus st_scripted_integrated(const stProtocol *p, stWorkspace *ws, stScripted *s, int k, int t,
                                stIntTrialResult *r, stTraceFn trace, void *ctx, char *err,
                                size_t errsz) {
  ST_ASSERT(p && ws && s && r);
  if (k < 0 || k >= ST_NPOSTURE || t < 0 || t > 1) {
    memset(r, 0, sizeof *r);
    st__errf(err, errsz, "scripted: integrated posture %d, target %d (expected 0..%d, 0..1)", k, t,
             ST_NPOSTURE - 1);
    return ST_ERR_ARG;
  }
  stIntegratedDef def;
  st_integrated_def_from_config(&p->cfg, &def);
  /* trial 2k + t of generation 0 keys the solver's generator, as an individual's trial would */
  const uint64_t key = st_rng_keyed(st_config_rng_seed(&p->cfg), ST_RNG_SOLVER, 0, 0,
                                    (uint64_t)(2 * k + t)).key;
  stEpisodeSpec e;
  st_int_episode(p, &def, k, t, NULL, key, &e);
  /* the caretaker's words, scored by the integrated fitness (no prediction: it does not talk) */
  const stIntPlan plan = {ST_WORDS_CARETAKER, ST_FIT_INTEGRATED, 1.0, 0};
  const stController c = st_scripted_controller(s);
  return st_int_run_with(p, &def, ws, &e, &c, &plan, r, NULL, trace, ctx, err, errsz);
}
