/* SPDX-License-Identifier: MIT
 * Fitness functions and trial scoring against values worked out by hand from thesis
 * eq. 2.2-2.12 (exp values from a calculator: e^-1 = 0.36787944117144233,
 * e^-0.5 = 0.6065306597126334, e^-2 = 0.1353352832366127). */
#include <math.h>
#include <string.h>

#include "selftalk/trial.h"
#include "test_util.h"

static stFitnessDef def(void) {
  stConfig c;
  st_config_default(&c);
  stFitnessDef d;
  st_fitness_def_from_config(&c, &d);
  return d;
}

static stQuantities quant(double d_r, double d_g, double d_m, double d_mhat, double h, double p) {
  stQuantities q;
  memset(&q, 0, sizeof q);
  q.d_r = d_r;
  q.d_g = d_g;
  q.d_m = d_m;
  q.d_mhat = d_mhat;
  q.h = h;
  q.p = p;
  return q;
}

static void test_step_fitness(void) {
  stFitnessDef d = def();
  const double E1 = 0.36787944117144233, E05 = 0.6065306597126334, E2 = 0.1353352832366127;
  /* reach, d_r = 0.1: s = e^-1. Focus right (object, y = 0.2): 0.2 * 0.8 + 0.8 e^-1 */
  stQuantities q = quant(0.1, 0, 0, 0, 1, 0);
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_SIMPLE, ST_PRIM_REACH, &q), E1, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_step_fitness(&d, ST_STAGE_SIMPLE, ST_PRIM_REACH, &q, 0.2, 0.5),
                         0.16 + 0.8 * E1, 1e-15);
  /* focus wrong (y = 0.7 picks the target): only 0.2 f_f = 0.2 * 0.3 */
  CU_ASSERT_DOUBLE_EQUAL(st_step_fitness(&d, ST_STAGE_SIMPLE, ST_PRIM_REACH, &q, 0.7, 0.5), 0.06,
                         1e-15);
  /* open at its goal: h = 0.7, p = 1, d_r = 0 -> s = 1, S = 0.2 * 1 + 0.8 = 1 */
  q = quant(0, 0, 0, 0, 0.7, 1);
  CU_ASSERT_DOUBLE_EQUAL(st_step_fitness(&d, ST_STAGE_MAIN, ST_PRIM_OPEN, &q, 0.0, 0.5), 1.0, 1e-15);
  /* open, h = 0.35 (half way), p = 0.5, d_r = 0.05: 0.5 ((1 - 0.5) + 0.5) e^-0.5 */
  q = quant(0.05, 0, 0, 0, 0.35, 0.5);
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_SIMPLE, ST_PRIM_OPEN, &q), 0.5 * E05, 1e-15);
  /* grasp: h = 0.4, p = 1, d_g = 0 -> 1; h = 1 (open) -> 0.5 (0 + p) e^(-10 d_g) */
  q = quant(0.3, 0, 0, 0, 0.4, 1);
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_SIMPLE, ST_PRIM_GRASP, &q), 1.0, 1e-15);
  q = quant(0.3, 0.1, 0, 0, 1.0, 0.5);
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_MAIN, ST_PRIM_GRASP, &q), 0.25 * E1, 1e-15);
  /* simplified move: palm to target (d_mhat 0.2), not the object (d_m 0.05); the right focus
   * is the target: y = 0.9 -> 0.2 * 0.9 + 0.8 e^-2 */
  q = quant(0, 0, 0.05, 0.2, 1, 0);
  CU_ASSERT_DOUBLE_EQUAL(st_step_fitness(&d, ST_STAGE_SIMPLE, ST_PRIM_MOVE, &q, 0.9, 0.5),
                         0.18 + 0.8 * E2, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_step_fitness(&d, ST_STAGE_SIMPLE, ST_PRIM_MOVE, &q, 0.4, 0.5),
                         0.2 * 0.4, 1e-15);
  /* main move (eq. 2.12), d_m = 0.1: touching and lifted 0.1 + 0.1 + 0.8 e^-1 */
  q = quant(0, 0, 0.1, 0.5, 1, 0);
  q.touching = 1;
  q.lifted = 1;
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_MAIN, ST_PRIM_MOVE, &q), 0.2 + 0.8 * E1, 1e-15);
  q.lifted = 0;
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_MAIN, ST_PRIM_MOVE, &q), 0.1, 1e-15);
  q.touching = 0;
  CU_ASSERT_DOUBLE_EQUAL(st_step_s(&d, ST_STAGE_MAIN, ST_PRIM_MOVE, &q), 0.0, 0.0);
}

static void test_success_conditions(void) {
  stFitnessDef d = def();
  stQuantities q = quant(0.029, 0.029, 0.059, 0.029, 0.71, 0.91);
  CU_ASSERT(st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_REACH, &q));
  CU_ASSERT(st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_OPEN, &q));
  CU_ASSERT(!st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_GRASP, &q)); /* h 0.71 not < 0.4 */
  CU_ASSERT(st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_MOVE, &q));
  CU_ASSERT(st_success_now(&d, ST_STAGE_MAIN, ST_PRIM_MOVE, &q)); /* d_m 0.059 < 0.06 */
  q.h = 0.39;
  CU_ASSERT(st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_GRASP, &q));
  CU_ASSERT(!st_success_now(&d, ST_STAGE_MAIN, ST_PRIM_GRASP, &q)); /* judged at the end */
  CU_ASSERT(!st_success_now(&d, ST_STAGE_SIMPLE, ST_PRIM_OPEN, &q)); /* h 0.39 not > 0.7 */
  q = quant(0.031, 0.031, 0.061, 0.031, 0.5, 0.89);
  for (int p = 0; p < ST_NPRIM; p++) {
    CU_ASSERT(!st_success_now(&d, ST_STAGE_SIMPLE, p, &q));
    CU_ASSERT(!st_success_now(&d, ST_STAGE_MAIN, p, &q));
  }
}

static void test_penalty_masks(void) {
  /* thesis 2.7.2 and 2.8.1.2 */
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_SIMPLE, ST_PRIM_REACH, 0, 40), ST_PEN_TABLE | ST_PEN_OBJECT);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_SIMPLE, ST_PRIM_OPEN, 0, 40), ST_PEN_TABLE | ST_PEN_OBJECT);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_SIMPLE, ST_PRIM_GRASP, 0, 40), ST_PEN_TABLE);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_SIMPLE, ST_PRIM_MOVE, 0, 40), ST_PEN_TABLE);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_MAIN, ST_PRIM_REACH, 0, 40),
                  ST_PEN_TABLE | ST_PEN_OBJECT | ST_PEN_MOVING);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_MAIN, ST_PRIM_GRASP, 39, 40), ST_PEN_TABLE | ST_PEN_MOVING);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_MAIN, ST_PRIM_GRASP, 40, 40), ST_PEN_TABLE);
  CU_ASSERT_EQUAL(st_penalty_mask(ST_STAGE_MAIN, ST_PRIM_MOVE, 0, 40), ST_PEN_TABLE);
}

static void test_fp_and_harmonic(void) {
  stFitnessDef d = def();
  /* eq. 2.3: 2 successes (20) + 100 / 240 * 30 = 32.5 */
  CU_ASSERT_DOUBLE_EQUAL(st_primitive_fitness(&d, 20, 30, 240), 32.5, 1e-12);
  /* maximum: 40 + 100 = 140 */
  CU_ASSERT_DOUBLE_EQUAL(st_primitive_fitness(&d, 40, 240, 240), 140, 1e-12);
  double same[4] = {40, 40, 40, 40}, mixed[4] = {10, 20, 40, 80}, neg[4] = {100, 50, 25, -3};
  CU_ASSERT_DOUBLE_EQUAL(st_harmonic_fitness(&d, same, 4), 40.0, 1e-12);
  /* 4 / (0.1 + 0.05 + 0.025 + 0.0125) = 4 / 0.1875 */
  CU_ASSERT_DOUBLE_EQUAL(st_harmonic_fitness(&d, mixed, 4), 4.0 / 0.1875, 1e-12);
  /* F_p <= 0 is clamped to 0.001: 4 / (0.01 + 0.02 + 0.04 + 1000) */
  CU_ASSERT_DOUBLE_EQUAL(st_harmonic_fitness(&d, neg, 4), 4.0 / 1000.07, 1e-12);
}

static stTrialSpec spec(stStage stage, int prim, int steps, int off) {
  stTrialSpec t;
  memset(&t, 0, sizeof t);
  t.stage = stage;
  t.primitive = prim;
  t.steps = steps;
  t.table_off_step = off;
  return t;
}

/* simplified reach over 5 steps, success at step 2; focus right throughout */
static void test_score_success_mid_trial(void) {
  stFitnessDef d = def();
  stTrialSpec t = spec(ST_STAGE_SIMPLE, ST_PRIM_REACH, 5, -1);
  stTrialScore sc;
  st_score_begin(&sc, &t);
  const double dr[5] = {0.1, 0.05, 0.02, 0.05, 0.1};
  double want = 0;
  for (int s = 0; s < 5; s++) {
    stQuantities q = quant(dr[s], 0, 0, 0, 1, 0);
    CU_ASSERT_EQUAL(st_score_step(&sc, &d, s, &q, 0.2, 0.5, s == 3 ? 1.0 : 0.0, 0, 0, NULL, NULL), -1);
    want += 0.16 + 0.8 * exp(-10 * dr[s]);
  }
  stTrialResult r;
  st_score_end(&sc, &d, 0, 0, &r);
  CU_ASSERT_EQUAL(r.success, 1);
  CU_ASSERT_EQUAL(r.success_step, 2);
  CU_ASSERT_EQUAL(r.end, ST_END_FULL);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, want, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 1.0, 0.0);
  CU_ASSERT_EQUAL(r.steps, 5);
}

/* main-prim reach reached at step 1 and held: ends after step 22 ("more than 20 steps ago"),
 * the 7 remaining steps of 30 score S = 1 each */
static void test_score_reach_hold(void) {
  stFitnessDef d = def();
  stTrialSpec t = spec(ST_STAGE_MAIN, ST_PRIM_REACH, 30, -1);
  stTrialScore sc;
  st_score_begin(&sc, &t);
  int ended = -1, s = 0;
  double S, sum = 0;
  for (; s < 30 && ended < 0; s++) {
    stQuantities q = quant(s == 0 ? 0.2 : 0.02, 0, 0, 0, 1, 0);
    ended = st_score_step(&sc, &d, s, &q, 0.0, 0.5, 0, 0, 0, &S, NULL);
    sum += S;
  }
  CU_ASSERT_EQUAL(ended, ST_END_SUCCESS);
  CU_ASSERT_EQUAL(s, 23);
  stTrialResult r;
  st_score_end(&sc, &d, 0, 0, &r);
  CU_ASSERT_EQUAL(r.success, 1);
  CU_ASSERT_EQUAL(r.steps_run, 23);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, sum + 7.0, 1e-12);
  CU_ASSERT_EQUAL(r.steps, 30);
}

/* main-prim open: the object falls at step 3 of 10: P = 4 for the 6 steps left */
static void test_score_early_failure(void) {
  stFitnessDef d = def();
  stTrialSpec t = spec(ST_STAGE_MAIN, ST_PRIM_OPEN, 10, -1);
  stTrialScore sc;
  st_score_begin(&sc, &t);
  stQuantities q = quant(0.2, 0, 0, 0, 1, 0);
  for (int s = 0; s < 3; s++) CU_ASSERT_EQUAL(st_score_step(&sc, &d, s, &q, 0, 0.5, 0.5, 0, 0, NULL, NULL), -1);
  CU_ASSERT_EQUAL(st_score_step(&sc, &d, 3, &q, 0, 0.5, 0.5, 1, 0, NULL, NULL), ST_END_FAILURE);
  stTrialResult r;
  st_score_end(&sc, &d, -0.2, -0.08, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 4 * 0.5 + 6 * 4.0, 1e-12);
  CU_ASSERT_EQUAL(r.success, 0);
  CU_ASSERT_EQUAL(r.end, ST_END_FAILURE);
}

/* main-prim grasp: a fall after the table is removed ends quietly (nothing added), before it
 * it is a failure; success needs the object above the table at the end */
static void test_score_grasp(void) {
  stFitnessDef d = def();
  stTrialSpec t = spec(ST_STAGE_MAIN, ST_PRIM_GRASP, 80, 40);
  stTrialScore sc;
  stTrialResult r;
  stQuantities q = quant(0.2, 0.02, 0, 0, 0.3, 1);
  st_score_begin(&sc, &t);
  for (int s = 0; s < 45; s++) CU_ASSERT_EQUAL(st_score_step(&sc, &d, s, &q, 0, 0.5, 0, 0, 0, NULL, NULL), -1);
  CU_ASSERT_EQUAL(st_score_step(&sc, &d, 45, &q, 0, 0.5, 0, 1, 0, NULL, NULL), ST_END_QUIET);
  double s_before = sc.r.sum_s;
  st_score_end(&sc, &d, -0.3, -0.08, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, s_before, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 0.0, 0.0);
  CU_ASSERT_EQUAL(r.success, 0);
  st_score_begin(&sc, &t);
  CU_ASSERT_EQUAL(st_score_step(&sc, &d, 0, &q, 0, 0.5, 0, 1, 0, NULL, NULL), ST_END_FAILURE);
  st_score_end(&sc, &d, -0.3, -0.08, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 79 * 4.0, 1e-12);
  st_score_begin(&sc, &t);
  for (int s = 0; s < 80; s++) st_score_step(&sc, &d, s, &q, 0, 0.5, 0, 0, 0, NULL, NULL);
  st_score_end(&sc, &d, -0.05, -0.08, &r);
  CU_ASSERT_EQUAL(r.success, 1); /* centre 3 cm above the table top at the end */
  CU_ASSERT_EQUAL(r.end, ST_END_FULL);
}

/* main-prim move: in the target at step 2, success only if still lifted at the end */
static void test_score_move(void) {
  stFitnessDef d = def();
  stTrialSpec t = spec(ST_STAGE_MAIN, ST_PRIM_MOVE, 6, 2);
  for (int lifted_end = 0; lifted_end < 2; lifted_end++) {
    stTrialScore sc;
    st_score_begin(&sc, &t);
    for (int s = 0; s < 6; s++) {
      stQuantities q = quant(0, 0, s == 2 ? 0.05 : 0.2, 0, 0.3, 1);
      q.lifted = s < 5 || lifted_end;
      st_score_step(&sc, &d, s, &q, 0.9, 0.5, 0, 0, 0, NULL, NULL);
    }
    stTrialResult r;
    st_score_end(&sc, &d, 0, 0, &r);
    CU_ASSERT_EQUAL(r.success, lifted_end);
    CU_ASSERT_EQUAL(r.success_step, 2);
  }
}

/* trace sink for test_forced_outputs: finger flexion q-hat and S of every step */
typedef struct forcedTrace {
  double qf[200], S[200];
  int n;
} forcedTrace;

static void forced_on_step(void *ctx, const stTraceStep *s) {
  forcedTrace *t = ctx;
  if (t->n < 200) {
    t->qf[t->n] = s->world->qhat[ST_DOF_FINGER_FLEX];
    t->S[t->n] = s->S;
    t->n++;
  }
}

/* forced outputs (st_net_controller): a forced output is what the robot does, whatever the network says.
 * Kinematic mode, finger flexion forced to 1 from the open hand of reach posture 0: each step
 * moves q-hat by alpha (1 - q) dt / range = 37 x 0.05 / 90 of the remaining (SPEC §3; 37 deg/s
 * < the 40 deg/s cap, the finger hinges span 90 deg), so 1 - q_n = (1 - q_from) r^(n - from)
 * with r = 1 - 37 x 0.05 / 90. Forcing the focus output to 1 (target) in a reach trial makes
 * f_f = 0 and the focus wrong: S = 0 at every step (eq. 2.4). The ranges are in radians, so
 * q-hat drifts from the law by ~1e-14 per step: tolerance 1e-9 (alpha 40 instead of 37 would
 * be off by 1e-3 at the first step). */
static void test_forced_outputs(void) {
  stConfig c;
  st_config_default(&c);
  stProtocol *p = NULL;
  char err[512] = "";
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &p, err, sizeof err), ST_OK);
  stGenomeSet evolved;
  CU_ASSERT_EQUAL_FATAL(st_genome_set_read("data/evolved/simple_prim_s3.genome",
                                           st_arch_ngenes(ST_ARCH_BASE), &evolved, err, sizeof err), ST_OK);
  stNetParams np;
  CU_ASSERT_EQUAL_FATAL(st_net_decode(NULL, ST_ARCH_BASE, &evolved.genome[0], &np, err, sizeof err), ST_OK);
  stWorkspace ws = {0};
  stTrialSpec t;
  st_trial_spec(p, ST_STAGE_SIMPLE, 5, 0, &t); /* reach, posture 0: fingers fully extended */
  CU_ASSERT_EQUAL_FATAL(t.primitive, ST_PRIM_REACH);
  CU_ASSERT_EQUAL(t.qhat0[ST_DOF_FINGER_FLEX], 0.0);
  const double r = 1.0 - 37.0 * 0.05 / 90.0;
  stTrialResult res, res0;
  static forcedTrace free_run, from0, from10, focus;
  memset(&free_run, 0, sizeof free_run);
  memset(&from0, 0, sizeof from0);
  memset(&from10, 0, sizeof from10);
  memset(&focus, 0, sizeof focus);
  CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, NULL, 0, 1, &res0, forced_on_step, &free_run, err, sizeof err), ST_OK);
  stForce f0 = {ST_DOF_FINGER_FLEX, 1.0, 0};
  CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, &f0, 1, 1, &res, forced_on_step, &from0, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(from0.n, t.steps);
  for (int n = 0; n < from0.n; n++) /* the trace shows the state after step n: n + 1 moves */
    CU_ASSERT_DOUBLE_EQUAL(from0.qf[n], 1.0 - pow(r, n + 1), 1e-9);
  /* from step 10: the free run's trajectory bit for bit before, the law from there on */
  stForce f10 = {ST_DOF_FINGER_FLEX, 1.0, 10};
  CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, &f10, 1, 1, &res, forced_on_step, &from10, err, sizeof err), ST_OK);
  for (int n = 0; n < 10; n++) CU_ASSERT_EQUAL(from10.qf[n], free_run.qf[n]);
  for (int n = 10; n < from10.n; n++)
    CU_ASSERT_DOUBLE_EQUAL(1.0 - from10.qf[n], (1.0 - free_run.qf[9]) * pow(r, n - 9), 1e-9);
  /* the evolved reach keeps its fingers open: the forced run really differs */
  CU_ASSERT(free_run.qf[free_run.n - 1] < 0.5 && from10.qf[from10.n - 1] > 0.6);
  stForce ff = {ST_NET_OUT_FOCUS, 1.0, 0};
  CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, &ff, 1, 1, &res, forced_on_step, &focus, err, sizeof err), ST_OK);
  for (int n = 0; n < focus.n; n++) CU_ASSERT_EQUAL(focus.S[n], 0.0);
  CU_ASSERT_EQUAL(res.sum_s, 0.0);
  CU_ASSERT(res0.sum_s > 10.0); /* with its own focus the evolved reach scores */
  /* nothing forced: st_trial_run exactly */
  CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, NULL, 0, 1, &res, NULL, NULL, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(res.sum_s, res0.sum_s);
  CU_ASSERT_EQUAL(res.sum_p, res0.sum_p);
  /* out of range: refused, naming the output */
  stForce bad[3] = {{13, 1.0, 0}, {9, 1.5, 0}, {9, 1.0, -1}};
  for (int i = 0; i < 3; i++) {
    err[0] = 0;
    CU_ASSERT_EQUAL(st_test_net_trial(p, &ws, &t, &np, NULL, &bad[i], 1, 1, &res, NULL, NULL, err, sizeof err), ST_ERR_RANGE);
    CU_ASSERT_PTR_NOT_NULL(strstr(err, i == 0 ? "forced output 13" : "forced output 9"));
  }
  st_genome_set_free(&evolved);
  st_workspace_free(&ws);
  st_protocol_destroy(p);
}

/* stage.primitives: a subset evaluates only its primitives' trials, each scored exactly as in
 * the full set (same index, offsets, key), and F is the harmonic mean over the subset alone:
 * for one primitive F = F_p, for two F = 2 / (1/F_a + 1/F_b) (eq. 2.2 with n = 2). Kinematic
 * stage, so that the test is quick. */
static void test_primitive_subset(void) {
  stConfig c;
  st_config_default(&c);
  c.run_seed = 3; /* the run that evolved data/evolved/simple_prim_s3.genome */
  stProtocol *full = NULL, *grasp = NULL, *two = NULL;
  char err[512] = "";
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &full, err, sizeof err), ST_OK);
  strcpy(c.stage_primitives, "grasp");
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &grasp, err, sizeof err), ST_OK);
  strcpy(c.stage_primitives, " move , reach");
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &two, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(full->primitives, 15u);
  CU_ASSERT_EQUAL(grasp->primitives, 1u << ST_PRIM_GRASP);
  CU_ASSERT_EQUAL(two->primitives, (1u << ST_PRIM_REACH) | (1u << ST_PRIM_MOVE));
  stWorkspace ws = {0};
  /* an evolved genotype (the best of seed 3's simple-prim population, evolved with this hand:
   * every F_p well above 0) and two random ones (most F_p negative, so the harmonic mean clamps
   * them to fp_min), with the trial offsets of the generation at which that population was
   * evaluated and its best solved all 16 (the last row of simple_prim_s3.fitness.csv) */
  enum { EVOLVED = 0, GEN = 633 };
  stGenomeSet evolved;
  CU_ASSERT_EQUAL_FATAL(st_genome_set_read("data/evolved/simple_prim_s3.genome",
                                           st_arch_ngenes(ST_ARCH_BASE), &evolved, err, sizeof err), ST_OK);
  for (int ind = 0; ind < 3; ind++) {
    stRng rng = st_rng_keyed(7, ST_RNG_USER, 0, (uint64_t)ind, 0);
    stGenome g;
    if (ind == 0) g = evolved.genome[EVOLVED];
    else st_genome_random(&g, st_arch_ngenes(ST_ARCH_BASE), &rng);
    stNetParams np;
    CU_ASSERT_EQUAL_FATAL(st_net_decode(NULL, ST_ARCH_BASE, &g, &np, err, sizeof err), ST_OK);
    stEvaluation ef, eg, e2;
    CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(full, &ws, ST_STAGE_SIMPLE, GEN, ind, &np, NULL, &ef, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(grasp, &ws, ST_STAGE_SIMPLE, GEN, ind, &np, NULL, &eg, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(two, &ws, ST_STAGE_SIMPLE, GEN, ind, &np, NULL, &e2, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(ef.ntrials, 16);
    CU_ASSERT_EQUAL(eg.ntrials, 4);
    CU_ASSERT_EQUAL(e2.ntrials, 8);
    CU_ASSERT_EQUAL(eg.fp[ST_PRIM_GRASP], ef.fp[ST_PRIM_GRASP]); /* bit for bit */
    CU_ASSERT_EQUAL(eg.fp[ST_PRIM_REACH], 0.0);
    CU_ASSERT_EQUAL(eg.fp[ST_PRIM_MOVE], 0.0);
    /* F_p below fitness.fp_min (0.001) counts as fp_min (SPEC §7); random networks get there */
    const double fg = fmax(ef.fp[ST_PRIM_GRASP], 0.001);
    const double fr = fmax(ef.fp[ST_PRIM_REACH], 0.001), fm = fmax(ef.fp[ST_PRIM_MOVE], 0.001);
    CU_ASSERT_DOUBLE_EQUAL(eg.fitness, fg, 1e-12 * fg);
    CU_ASSERT_DOUBLE_EQUAL(e2.fitness, 2.0 / (1.0 / fr + 1.0 / fm), 1e-12 * (fr + fm));
    int sg = 0, s2 = 0;
    for (int t = 0; t < ST_PRIM_TRIALS; t++) {
      const int prim = t / ST_NPOSTURE;
      CU_ASSERT_EQUAL(eg.kind[ST_TRIAL_FIXED].success[t], prim == ST_PRIM_GRASP ? ef.kind[ST_TRIAL_FIXED].success[t] : 0);
      CU_ASSERT_EQUAL(e2.kind[ST_TRIAL_FIXED].success[t], prim == ST_PRIM_REACH || prim == ST_PRIM_MOVE ? ef.kind[ST_TRIAL_FIXED].success[t] : 0);
      sg += eg.kind[ST_TRIAL_FIXED].success[t];
      s2 += e2.kind[ST_TRIAL_FIXED].success[t];
    }
    CU_ASSERT_EQUAL(eg.successes, sg);
    CU_ASSERT_EQUAL(e2.successes, s2);
    if (ind == 0) { /* the evolved one: the subset values are real harmonic means */
      CU_ASSERT(ef.successes == 16 && fr > 50 && fm > 50 && fg > 50);
    }
  }
  st_genome_set_free(&evolved);
  st_workspace_free(&ws);
  st_protocol_destroy(full);
  st_protocol_destroy(grasp);
  st_protocol_destroy(two);
}

void st_suite_fitness(void) {
  ST_ADD_SUITE("fitness");
  ST_ADD_TEST(test_step_fitness);
  ST_ADD_TEST(test_success_conditions);
  ST_ADD_TEST(test_penalty_masks);
  ST_ADD_TEST(test_fp_and_harmonic);
  ST_ADD_TEST(test_score_success_mid_trial);
  ST_ADD_TEST(test_score_reach_hold);
  ST_ADD_TEST(test_score_early_failure);
  ST_ADD_TEST(test_score_grasp);
  ST_ADD_TEST(test_score_move);
  ST_ADD_TEST(test_primitive_subset);
  ST_ADD_TEST(test_forced_outputs);
}
