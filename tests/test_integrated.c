/* SPDX-License-Identifier: MIT
 * The integrated stage (thesis §2.9, SPEC §10): eq. 2.14 and its bookkeeping on synthetic
 * trajectories worked out by hand, an individual's fitness from hand-made trial results, which
 * trials hear which words in each condition config (Table 2.1), the self-talk loop, the trial
 * table, and the initial population. Exp values from a calculator: e^-1 = 0.36787944117144233,
 * e^-0.5 = 0.6065306597126334; e^-100 < 1e-43 counts as 0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/assemble.h"
#include "selftalk/integrated.h"
#include "test_util.h"

#define E1 0.36787944117144233
#define E05 0.6065306597126334

static stFitnessDef fdef(void) {
  stConfig c;
  st_config_default(&c);
  stFitnessDef d;
  st_fitness_def_from_config(&c, &d);
  return d;
}

static stQuantities quant(double d_r, double d_g, double d_m, double h, double p, int touching,
                          int lifted) {
  stQuantities q;
  memset(&q, 0, sizeof q);
  q.d_r = d_r, q.d_g = d_g, q.d_m = d_m, q.h = h, q.p = p;
  q.touching = touching, q.lifted = lifted;
  return q;
}

/* eq. 2.14's three cases, with eq. 2.4 around it (w = 0.2). */
static void test_int_step_fitness(void) {
  stFitnessDef d = fdef();
  /* not opened, not lifted: s_o (eq. 2.6) at d_r 0.1, h 0.7, p 1 = 0.5 (1 + 1) e^-1; s_m = 0
   * (neither touching nor lifted): s_i = e^-1 / 4. Focus on the object (y 0.1, right):
   * S = 0.2 x 0.9 + 0.8 e^-1 / 4 */
  stQuantities q = quant(0.1, 0.05, 0.3, 0.7, 1.0, 0, 0);
  CU_ASSERT_DOUBLE_EQUAL(st_int_s(&d, &q, 0), E1 / 4, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_int_step_fitness(&d, &q, 0, 0.1, 0.5), 0.18 + 0.2 * E1, 1e-15);
  /* opened, not lifted, touching, h 0.4, d_g 0.05: s_g (eq. 2.7) = 0.5 (1 + 1) e^-0.5,
   * s_m = 0.1: s_i = 0.05 + (1 + e^-0.5) / 4 */
  q = quant(0.1, 0.05, 0.3, 0.4, 1.0, 1, 0);
  CU_ASSERT_DOUBLE_EQUAL(st_int_s(&d, &q, 1), 0.05 + (1 + E05) / 4, 1e-15);
  /* the same state before "opened": the s_o branch, h 0.4: 0.5 ((1 - 0.3 / 0.7) + 1) e^-1 */
  CU_ASSERT_DOUBLE_EQUAL(st_int_s(&d, &q, 0), 0.05 + 0.25 * 0.5 * (2 - 0.3 / 0.7) * E1, 1e-15);
  /* lifted and touching, d_m 0.1: s_m (eq. 2.12) = 0.1 + 0.1 + 0.8 e^-1, s_i = s_m / 2 + 2 / 4.
   * The right focus is now the target: y 0.9 -> 0.18 + 0.8 s_i; y 0.3 (the object) -> 0.06 */
  q = quant(0.5, 0.05, 0.1, 0.4, 1.0, 1, 1);
  const double si = 0.5 * (0.2 + 0.8 * E1) + 0.5;
  CU_ASSERT_DOUBLE_EQUAL(st_int_s(&d, &q, 0), si, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_int_step_fitness(&d, &q, 1, 0.9, 0.5), 0.18 + 0.8 * si, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(st_int_step_fitness(&d, &q, 1, 0.3, 0.5), 0.06, 1e-15);
  /* penalties: table throughout, object moving only while not lifted */
  CU_ASSERT_DOUBLE_EQUAL(st_int_penalty(&q, 1.0, 0.7), 1.0, 0.0);
  q.lifted = 0;
  CU_ASSERT_DOUBLE_EQUAL(st_int_penalty(&q, 1.0, 0.7), 1.7, 0.0);
}

static stIntegratedDef small_def(int steps, int hold) {
  stConfig c;
  st_config_default(&c);
  stIntegratedDef d;
  st_integrated_def_from_config(&c, &d);
  d.steps = steps;
  d.hold_steps = hold;
  return d;
}

/* Three states whose S is easy: FAR = the hand 10 m away, focus on the object (y 0), nothing
 * touched: S = 0.2 x 1 + 0.8 x s_o / 4 with s_o ~ e^-100: 0.2. HELD = lifted, touching, 10 m
 * from the target, focus on the target (y 1): s_m = 0.2, s_i = 0.1 + 0.5, S = 0.2 + 0.48 =
 * 0.68. IN = lifted, at the target (d_m 0), y 1: s_m = 1, s_i = 1, S = 1. */
enum { FAR, HELD, IN, DROPPED };
static stQuantities state(int k) {
  switch (k) {
    case FAR: return quant(10, 10, 10, 1.0, 0.0, 0, 0);
    case HELD: return quant(10, 10, 10, 0.4, 1.0, 1, 1);
    case IN: return quant(10, 10, 0.0, 0.4, 1.0, 1, 1);
    default: return quant(10, 10, 0.0, 0.4, 1.0, 0, 0); /* at the target, not held */
  }
}

/* steps 10, hold 2, focus bonus after 3 steps. t0 FAR (table: P 1), t1 FAR (moving 0.5: P 0.5),
 * t2 HELD (moving 1 while lifted: P 0), t3..t6 IN: reached at 3; the focus has been on the
 * target while lifted at t2, t3, t4: the focus bonus at t4; t6 - 3 = 3 > 2 and still lifted:
 * the trial ends at step 6 with S = 1 for the 3 steps left.
 * sum S = 0.2 + 0.2 + 0.68 + 4 x 1 + 3 = 8.08, sum P = 1.5; success (in the target, lifted at the
 * end) and the focus bonus: 2 x 10 bonus points. */
static void test_int_trial_success(void) {
  stFitnessDef fd = fdef();
  stIntegratedDef d = small_def(10, 2);
  const int seq[7] = {FAR, FAR, HELD, IN, IN, IN, IN};
  const double table[7] = {1, 0, 0, 0, 0, 0, 0}, moving[7] = {0, 0.5, 1, 0, 0, 0, 0};
  stIntScore sc;
  st_int_score_begin(&sc, &fd, 0.5, &d);
  int ev = -1, t = 0;
  for (; t < 10 && ev < 0; t++) {
    stQuantities q = state(seq[t]);
    ev = st_int_score_step(&sc, t, &q, seq[t] == FAR ? 0.0 : 1.0, table[t], moving[t], 0, 0, NULL, NULL);
  }
  CU_ASSERT_EQUAL(ev, ST_END_SUCCESS);
  CU_ASSERT_EQUAL(t, 7);
  stIntTrialResult r;
  st_int_score_end(&sc, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, 8.08, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 1.5, 0.0);
  CU_ASSERT_EQUAL(r.steps, 10);
  CU_ASSERT_EQUAL(r.steps_run, 7);
  CU_ASSERT_EQUAL(r.reached_step, 3);
  CU_ASSERT_EQUAL(r.success, 1);
  CU_ASSERT_EQUAL(r.focus_bonus, 1);
  CU_ASSERT_DOUBLE_EQUAL(st_int_trial_bonus(&r, 10, 1), 20.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_int_trial_bonus(&r, 10, 10), 200.0, 0.0); /* first generation */
  CU_ASSERT_DOUBLE_EQUAL(st_int_trial_points(&r), 6.58, 1e-12);
}

/* the same, but the focus leaves the target at t4 (S = 0: wrong focus while lifted): the
 * consecutive count restarts (t2, t3 | t5, t6): no focus bonus by the end at step 6 */
static void test_int_focus_bonus_consecutive(void) {
  stFitnessDef fd = fdef();
  stIntegratedDef d = small_def(10, 2);
  const int seq[7] = {FAR, FAR, HELD, IN, IN, IN, IN};
  stIntScore sc;
  st_int_score_begin(&sc, &fd, 0.5, &d);
  int ev = -1;
  for (int t = 0; t < 10 && ev < 0; t++) {
    stQuantities q = state(seq[t]);
    double S;
    ev = st_int_score_step(&sc, t, &q, seq[t] == FAR || t == 4 ? 0.0 : 1.0, 0, 0, 0, 0, &S, NULL);
    if (t == 4) CU_ASSERT_DOUBLE_EQUAL(S, 0.0, 0.0);
  }
  stIntTrialResult r;
  st_int_score_end(&sc, &r);
  CU_ASSERT_EQUAL(r.focus_bonus, 0);
  CU_ASSERT_EQUAL(r.success, 1);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, 0.2 + 0.2 + 0.68 + 1 + 0 + 1 + 1 + 3, 1e-12);
}

/* reached at 1, dropped at 4 (DROPPED: at the target, not held) although 4 - 1 > 2: no early
 * end while not lifted; the trial runs its 6 steps and ends not lifted: no success (move's
 * condition), no move bonus. When the object is held again at step 5 (5 - 1 > 2, lifted) the
 * trial ends there by success. */
static void test_int_no_early_end_when_dropped(void) {
  stFitnessDef fd = fdef();
  stIntegratedDef d = small_def(6, 2);
  for (int regrab = 0; regrab < 2; regrab++) {
    const int seq[6] = {HELD, IN, IN, IN, DROPPED, regrab ? IN : DROPPED};
    stIntScore sc;
    st_int_score_begin(&sc, &fd, 0.5, &d);
    int ended = 0;
    for (int t = 0; t < 6; t++) {
      stQuantities q = state(seq[t]);
      ended |= st_int_score_step(&sc, t, &q, 1.0, 0, 0, 0, 0, NULL, NULL) >= 0;
    }
    stIntTrialResult r;
    st_int_score_end(&sc, &r);
    CU_ASSERT_EQUAL(ended, regrab);
    CU_ASSERT_EQUAL(r.end, regrab ? ST_END_SUCCESS : ST_END_FULL);
    CU_ASSERT_EQUAL(r.steps_run, 6);
    CU_ASSERT_EQUAL(r.reached_step, 1);
    CU_ASSERT_EQUAL(r.success, regrab);
    CU_ASSERT_EQUAL(r.focus_bonus, 1); /* HELD, IN, IN: three lifted steps with the target focus */
  }
}

/* the penalty cap: 4 FAR steps on the table: sum S 0.8, sum P 4 -> the trial adds max(0, -3.2)
 * = 0; the object falls at step 1 of 4: P = 4 (fitness.fail_penalty) for the 2 steps left */
static void test_int_penalty_cap_and_failure(void) {
  stFitnessDef fd = fdef();
  stIntegratedDef d = small_def(4, 2);
  stIntScore sc;
  st_int_score_begin(&sc, &fd, 0.5, &d);
  for (int t = 0; t < 4; t++) {
    stQuantities q = state(FAR);
    st_int_score_step(&sc, t, &q, 0.0, 1.0, 0, 0, 0, NULL, NULL);
  }
  stIntTrialResult r;
  st_int_score_end(&sc, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s - r.sum_p, 0.8 - 4.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(st_int_trial_points(&r), 0.0, 0.0);
  st_int_score_begin(&sc, &fd, 0.5, &d);
  stQuantities q = state(FAR);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 0, &q, 0.0, 0, 0, 0, 0, NULL, NULL), -1);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 1, &q, 0.0, 0, 0, 1, 0, NULL, NULL), ST_END_FAILURE);
  st_int_score_end(&sc, &r);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 8.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_s, 0.4, 1e-12);
  CU_ASSERT_EQUAL(r.success, 0);
}

/* an ST-CT individual: trials 0, 2 prediction (caretaker), 1, 3 integrated (self talk).
 * Integrated: trial 1 sum S 100, sum P 20, success and focus bonus (20 points); trial 3 sum S 10,
 * sum P 30 (capped: 0), focus bonus only (10). N = 480: F_int = 30 + 100 / 480 x 80 = 30 +
 * 16.666666666666668. Prediction: trial 0 reached (F_step 60, F_switch 30, B_pred 20), trial 2
 * never reached (ignored, but T = 2): F_pred = 20 + (60 / 3 + 2 x 30 / 3) / 2 = 40. Bonus: 30 +
 * 20 = 50, autonomous 30. In the first generation (factor 10) every trial is integrated. */
static void test_int_combine(void) {
  stIntPlan plan[4];
  stIntTrialResult r[4];
  stPredScore pred[4];
  memset(r, 0, sizeof r);
  memset(pred, 0, sizeof pred);
  for (int i = 0; i < 4; i++) {
    plan[i].fitness = i % 2 ? ST_FIT_INTEGRATED : ST_FIT_PREDICTION;
    plan[i].words = i % 2 ? ST_WORDS_SELFTALK : ST_WORDS_CARETAKER;
    plan[i].autonomous = i % 2;
    plan[i].bonus_factor = 1.0;
    r[i].steps = 240;
    r[i].reached_step = -1;
  }
  r[1].sum_s = 100, r[1].sum_p = 20, r[1].success = 1, r[1].focus_bonus = 1;
  r[3].sum_s = 10, r[3].sum_p = 30, r[3].focus_bonus = 1;
  r[0].reached_step = 150;
  pred[0].f_step = 60, pred[0].f_switch = 30, pred[0].b_pred = 20;
  pred[2].f_step = 90, pred[2].f_switch = 90, pred[2].b_pred = 40; /* not reached: ignored */
  stIntEvaluation e;
  st_int_combine(10, 100, plan, r, pred, 4, &e);
  CU_ASSERT_DOUBLE_EQUAL(e.f_int, 30 + 100.0 / 480 * 80, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(e.f_pred, 40.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(e.fitness, 70 + 100.0 / 480 * 80, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(e.bonus, 50.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(e.bonus_auto, 30.0, 0.0);
  CU_ASSERT_EQUAL(e.successes, 1);
  CU_ASSERT_EQUAL(e.success[1], 1);
  /* first generation: all integrated, caretaker, bonuses x 10; N = 960; trial 0 and 2 add
   * max(0, 0 - 0) = 0: F = 10 x 30 + 100 / 960 x 80 */
  for (int i = 0; i < 4; i++) {
    plan[i].fitness = ST_FIT_INTEGRATED, plan[i].words = ST_WORDS_CARETAKER;
    plan[i].autonomous = 0, plan[i].bonus_factor = 10.0;
  }
  st_int_combine(10, 100, plan, r, NULL, 4, &e);
  CU_ASSERT_DOUBLE_EQUAL(e.fitness, 300 + 100.0 / 960 * 80, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(e.f_pred, 0.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(e.bonus_auto, 0.0, 0.0);
}

/* Table 2.1 from the four condition configs: (words, fitness) of even and odd trials after the
 * first generation, and the first generation's variant (caretaker everywhere, integrated
 * fitness, bonuses x 10) in all conditions but NI */
static void test_int_condition_plans(void) {
  static const struct {
    const char *file;
    stNetArch arch;
    stWordSource w[2];
    stIntFitness f[2];
    int first;
  } table[4] = {
      {"configs/integrated_stct.cfg", ST_ARCH_A, {ST_WORDS_CARETAKER, ST_WORDS_SELFTALK},
       {ST_FIT_PREDICTION, ST_FIT_INTEGRATED}, 1},
      {"configs/integrated_st.cfg", ST_ARCH_A, {ST_WORDS_SELFTALK, ST_WORDS_SELFTALK},
       {ST_FIT_INTEGRATED, ST_FIT_INTEGRATED}, 1},
      {"configs/integrated_ct.cfg", ST_ARCH_B, {ST_WORDS_CARETAKER, ST_WORDS_NONE},
       {ST_FIT_INTEGRATED, ST_FIT_INTEGRATED}, 1},
      {"configs/integrated_ni.cfg", ST_ARCH_B, {ST_WORDS_NONE, ST_WORDS_NONE},
       {ST_FIT_INTEGRATED, ST_FIT_INTEGRATED}, 0},
  };
  for (int c = 0; c < 4; c++) {
    stConfig cfg;
    char err[512] = "";
    st_config_default(&cfg);
    CU_ASSERT_EQUAL_FATAL(st_config_load(table[c].file, &cfg, err, sizeof err), ST_OK);
    stIntegratedDef d;
    st_integrated_def_from_config(&cfg, &d);
    CU_ASSERT_EQUAL(d.arch, table[c].arch);
    CU_ASSERT_EQUAL(d.trials, 8);
    CU_ASSERT_EQUAL(d.steps, 240);
    for (int i = 0; i < 8; i++) {
      stIntPlan p = st_integrated_plan(&d, 1, i), p0 = st_integrated_plan(&d, 0, i);
      CU_ASSERT_EQUAL(p.words, table[c].w[i % 2]);
      CU_ASSERT_EQUAL(p.fitness, table[c].f[i % 2]);
      CU_ASSERT_EQUAL(p.bonus_factor, 1.0);
      CU_ASSERT_EQUAL(p.autonomous, table[c].w[i % 2] != ST_WORDS_CARETAKER);
      CU_ASSERT_EQUAL(p0.words, table[c].first ? ST_WORDS_CARETAKER : table[c].w[i % 2]);
      CU_ASSERT_EQUAL(p0.fitness, table[c].first ? ST_FIT_INTEGRATED : table[c].f[i % 2]);
      CU_ASSERT_EQUAL(p0.bonus_factor, table[c].first ? 10.0 : 1.0);
    }
  }
}

/* configs that contradict Table 2.1's pairings are refused, naming the key */
static void test_int_config_rules(void) {
  static const struct {
    const char *text, *needle;
  } bad[] = {
      {"[stage]\nstages = integrated\n[integrated]\npopulations = x\n",
       "key 'network.arch': 'base' cannot run the integrated stage"},
      {"[stage]\nstages = integrated\n[network]\narch = B\n[integrated]\npopulations = x\n"
       "words_even = none\nfitness_even = integrated\n",
       "key 'integrated.words_odd': self talk needs linguistic outputs"},
      {"[stage]\nstages = integrated\n[network]\narch = A\n[integrated]\npopulations = x\n"
       "words_even = selftalk\n",
       "key 'integrated.fitness_even': the prediction fitness judges"},
      {"[stage]\nstages = integrated\n[network]\narch = A\n[integrated]\n",
       "key 'integrated.populations': empty"},
      {"[stage]\nstages = integrated\n[network]\narch = A\n[integrated]\npopulations = x\n"
       "[caretaker]\nfirst_step = 2\n",
       "key 'caretaker.first_step': 2: the prediction fitness needs a word at every step"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    char path[256], err[512] = "";
    stConfig cfg;
    st_config_default(&cfg);
    CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".cfg", bad[i].text));
    CU_ASSERT_EQUAL(st_config_load(path, &cfg, err, sizeof err), ST_ERR_RANGE);
    ST_ASSERT_CONTAINS(err, bad[i].needle);
  }
}

/* the default protocol (robot, scene, postures); NULL when it cannot be made */
static stProtocol *default_protocol(void) {
  const stTestFixture *fx = st_test_fixture();
  stProtocol *p = NULL;
  char err[512] = "";
  if (fx->robot && st_protocol_create(&fx->cfg, &p, err, sizeof err)) fprintf(stderr, "\n  %s\n", err);
  return p;
}

/* a talking controller that writes down what it hears: its label at step t is (3 t + 1) mod 4 */
typedef struct talker {
  double heard[8][ST_NET_MAX_IN];
  int n;
} talker;

static void talker_act(void *self, const stWorld *w, const stQuantities *q, const double *in,
                       int step, double *out) {
  (void)q;
  talker *t = self;
  memcpy(t->heard[t->n++], in, sizeof t->heard[0]);
  for (int d = 0; d < ST_NDOF; d++) out[d] = w->qhat[d]; /* hold still */
  out[ST_NET_OUT_FOCUS] = 0.0;
  for (int m = 0; m < ST_NET_NLING; m++) out[ST_NET_NOUT + m] = m == (3 * step + 1) % 4 ? 0.6 : 0.2;
}

static int nothing_step(void *self, stTraceStep *s) {
  int *labels = self;
  labels[s->step] = s->label;
  return -1;
}

/* self talk: the label produced at t is the word heard at t + 1 (one-hot x 10), none at step 0;
 * the secondary input is 10 at every step. The caretaker is silent at step 0, then says reach
 * (the hand is far from the object). Kinematic world: only the words matter here. */
static void test_int_selftalk_loop(void) {
  stProtocol *p = default_protocol();
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  char err[512] = "";
  stIntegratedDef d = small_def(6, 20);
  stEpisodeSpec e;
  st_int_episode(p, &d, 0, 0, NULL, 0, &e);
  e.dynamic = 0;
  static talker tk;
  int labels[8];
  stController ctl = {NULL, talker_act, ST_NET_MAX_IN, &tk, ST_NET_MAX_OUT, 1, NULL};
  stScorer sc = {NULL, nothing_step, NULL, labels};
  stWorkspace ws = {NULL, NULL, NULL};
  const stWordSource sources[2] = {ST_WORDS_SELFTALK, ST_WORDS_CARETAKER};
  for (int k = 0; k < 2; k++) {
    memset(&tk, 0, sizeof tk);
    const stWords words = st_int_words(p, sources[k]);
    CU_ASSERT_EQUAL_FATAL(st_episode_run(p, &ws, &e, &ctl, &words, &sc, NULL, NULL, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(tk.n, 6);
    for (int t = 0; t < 6; t++) {
      const int want = k == 0 ? (t == 0 ? -1 : (3 * (t - 1) + 1) % 4) : (t == 0 ? -1 : ST_PRIM_REACH);
      for (int m = 0; m < ST_NET_NLING; m++)
        CU_ASSERT_EQUAL(tk.heard[t][ST_NET_IN_LING + m], m == want ? 10.0 : 0.0);
      CU_ASSERT_EQUAL(tk.heard[t][ST_NET_IN_SECONDARY], 10.0);
      CU_ASSERT_EQUAL(labels[t], (3 * t + 1) % 4);
    }
  }
  /* the diagnostic gate (integrated.selftalk_gate), the same labels 1 0 3 2 1 0 heard a step
   * later: move, the move said at step 2 is heard at 3 as grasp (no touch, so the grasp is not
   * done); ahead, the caretaker says reach from step 1 (the hand far from the object), so every
   * label ahead of it is heard as reach */
  const int gated[2][6] = {{-1, ST_PRIM_OPEN, ST_PRIM_REACH, ST_PRIM_GRASP, ST_PRIM_GRASP, ST_PRIM_OPEN},
                           {-1, ST_PRIM_REACH, ST_PRIM_REACH, ST_PRIM_REACH, ST_PRIM_REACH, ST_PRIM_REACH}};
  const int gates[2] = {ST_SELFTALK_GATE_MOVE, ST_SELFTALK_GATE_AHEAD};
  for (int g = 0; g < 2; g++) {
    memset(&tk, 0, sizeof tk);
    p->cfg.integrated_selftalk_gate = gates[g];
    const stWords words = st_int_words(p, ST_WORDS_SELFTALK);
    CU_ASSERT_EQUAL_FATAL(st_episode_run(p, &ws, &e, &ctl, &words, &sc, NULL, NULL, err, sizeof err), ST_OK);
    for (int t = 0; t < 6; t++) {
      for (int m = 0; m < ST_NET_NLING; m++)
        CU_ASSERT_EQUAL(tk.heard[t][ST_NET_IN_LING + m], m == gated[g][t] ? 10.0 : 0.0);
      CU_ASSERT_EQUAL(labels[t], (3 * t + 1) % 4); /* the labels themselves are the controller's */
    }
  }
  p->cfg.integrated_selftalk_gate = ST_SELFTALK_GATE_NONE;
  /* a controller without linguistic outputs cannot talk to itself */
  ctl.talks = 0;
  const stWords st = st_int_words(p, ST_WORDS_SELFTALK);
  CU_ASSERT_EQUAL(st_episode_run(p, &ws, &e, &ctl, &st, &sc, NULL, NULL, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "self talk needs a controller that produces labels");
  st_workspace_free(&ws);
  st_protocol_destroy(p);
}

/* trial i: reach posture i mod 4, object position i mod 4 and target (i mod 4) mod 2, each
 * within +-2 cm (target also in z); the same for every individual of a generation, fresh in
 * the next generation; the solver's key differs per individual */
static void test_int_trial_table(void) {
  stProtocol *p = default_protocol();
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  stIntegratedDef d = small_def(240, 20);
  for (int i = 0; i < 8; i++) {
    stEpisodeSpec a, b, g;
    st_int_trial(p, &d, 3, 0, i, &a);
    st_int_trial(p, &d, 3, 7, i, &b);
    st_int_trial(p, &d, 4, 0, i, &g);
    const int k = i % 4;
    CU_ASSERT_EQUAL(memcmp(a.qhat0, p->posture[ST_PRIM_REACH][k], sizeof a.qhat0), 0);
    for (int c = 0; c < 3; c++) {
      CU_ASSERT(fabs(a.target[c] - p->scene.target[k % 2][c]) <= 0.02);
      CU_ASSERT(c == 2 ? a.obj[c] == p->scene.obj_pos[k][c] : fabs(a.obj[c] - p->scene.obj_pos[k][c]) <= 0.02);
    }
    CU_ASSERT(a.obj[0] != p->scene.obj_pos[k][0] && a.target[2] != p->scene.target[k % 2][2]);
    CU_ASSERT_EQUAL(memcmp(a.obj, b.obj, sizeof a.obj), 0);
    CU_ASSERT_EQUAL(memcmp(a.target, b.target, sizeof a.target), 0);
    CU_ASSERT(a.seed_key != b.seed_key);
    CU_ASSERT(memcmp(a.obj, g.obj, sizeof a.obj) != 0);
    CU_ASSERT(a.dynamic == 1 && a.steps == 240 && a.table_off_step == -1);
  }
  st_protocol_destroy(p);
}

/* integrated.trial_order (SPEC 13): mod4 gives trials 0-7 types 0 1 2 3 0 1 2 3, so the odd
 * trials (ST-CT's self talk, CT's silence) have only types 1 and 3, target 1; pairs gives
 * 0 0 1 1 2 2 3 3, every type once among the even and once among the odd trials. The trial's
 * offsets belong to its index, not its type: the same deviation from its posture's position
 * in both orders. */
static void test_int_trial_order(void) {
  const stTestFixture *fx = st_test_fixture();
  CU_ASSERT_PTR_NOT_NULL_FATAL(fx->robot);
  static const int want[2][8] = {{0, 1, 2, 3, 0, 1, 2, 3}, {0, 0, 1, 1, 2, 2, 3, 3}};
  stIntegratedDef d = small_def(240, 20);
  stEpisodeSpec e[2][8];
  for (int order = 0; order < 2; order++) {
    stConfig cfg = fx->cfg;
    cfg.integrated_trial_order = order ? ST_TRIAL_ORDER_PAIRS : ST_TRIAL_ORDER_MOD4;
    stProtocol *p = NULL;
    char err[512] = "";
    CU_ASSERT_EQUAL_FATAL(st_protocol_create(&cfg, &p, err, sizeof err), ST_OK);
    unsigned seen[2] = {0, 0}; /* types seen by even and odd trials, as bit masks */
    for (int i = 0; i < 8; i++) {
      const int k = st_int_trial_type(p, i);
      CU_ASSERT_EQUAL(k, want[order][i]);
      seen[i % 2] |= 1u << k;
      st_int_trial(p, &d, 3, 0, i, &e[order][i]);
      CU_ASSERT_EQUAL(memcmp(e[order][i].qhat0, p->posture[ST_PRIM_REACH][k], sizeof e[order][i].qhat0), 0);
      CU_ASSERT(fabs(e[order][i].target[0] - p->scene.target[k % 2][0]) <= 0.02);
      if (order) { /* the same offsets as trial i under mod4 */
        const int k0 = want[0][i];
        CU_ASSERT(fabs((e[1][i].obj[0] - p->scene.obj_pos[k][0]) - (e[0][i].obj[0] - p->scene.obj_pos[k0][0])) < 1e-12);
        CU_ASSERT(fabs((e[1][i].target[1] - p->scene.target[k % 2][1]) -
                       (e[0][i].target[1] - p->scene.target[k0 % 2][1])) < 1e-12);
      }
    }
    CU_ASSERT_EQUAL(seen[0], order ? 0xfu : 0x5u); /* even trials: types 0, 2 under mod4 */
    CU_ASSERT_EQUAL(seen[1], order ? 0xfu : 0xau); /* odd trials: types 1, 3 under mod4 */
    st_protocol_destroy(p);
  }
}

/* run.rng_seed (issue 47): with plain, run seed 4's generation-0 trial-0 offsets are drawn from
 * the stream that grows run seed 5's individual 0 (tests/test_rng.c); with apart they are keyed
 * by seed + 2^32, and the offsets move while every other part of the trial stays */
static void test_int_rng_seed_apart(void) {
  const stTestFixture *fx = st_test_fixture();
  CU_ASSERT_PTR_NOT_NULL_FATAL(fx->robot);
  stIntegratedDef d = small_def(240, 20);
  stEpisodeSpec e[2];
  for (int mode = 0; mode < 2; mode++) {
    stConfig cfg = fx->cfg;
    cfg.run_seed = 4;
    cfg.run_rng_seed = mode ? ST_RNG_SEED_APART : ST_RNG_SEED_PLAIN;
    stProtocol *p = NULL;
    char err[512] = "";
    CU_ASSERT_EQUAL_FATAL(st_protocol_create(&cfg, &p, err, sizeof err), ST_OK);
    st_int_trial(p, &d, 0, 0, 0, &e[mode]);
    /* the first draw of the trial's stream is its object's x offset (st_int_episode) */
    stRng r = st_rng_keyed(mode ? (UINT64_C(1) << 32) + 4 : 5, mode ? ST_RNG_INTEGRATED : ST_RNG_GROW,
                           0, 0, 0);
    const double dx = st_rng_range(&r, -p->scene.obj_offset, p->scene.obj_offset);
    CU_ASSERT(fabs(e[mode].obj[0] - p->scene.obj_pos[0][0] - dx) < 1e-12);
    st_protocol_destroy(p);
  }
  CU_ASSERT(e[0].obj[0] != e[1].obj[0]);
  CU_ASSERT_EQUAL(memcmp(e[0].qhat0, e[1].qhat0, sizeof e[0].qhat0), 0);
  CU_ASSERT_NOT_EQUAL(e[0].seed_key, e[1].seed_key);
}

/* three population files of 3 genotypes each (gene 0 = 16 f + i identifies genotype i of file
 * f), top 2, population 8: files f0, f1 by the pattern, then f2: f0g0 f0g1 f1g0 f1g1 f2g0 f2g1,
 * then repeated: f0g0 f0g1. Base genes copied, new genes grown per individual (the two copies
 * of f0g0 differ there), type B's block at typeb_init_gene. */
static void test_int_assembly(void) {
  char dir[128], path[512], err[512] = "";
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  stRng rng = st_rng_keyed(5, ST_RNG_USER, 0, 0, 0);
  for (int f = 0; f < 3; f++) {
    stGenome g[3];
    for (int i = 0; i < 3; i++) {
      st_genome_random(&g[i], ST_GENES_BASE, &rng);
      g[i].gene[0] = (uint16_t)(16 * f + i);
    }
    snprintf(path, sizeof path, "%s/%s%d.genome", dir, f < 2 ? "pop" : "other", f);
    CU_ASSERT_EQUAL_FATAL(st_genome_set_save(path, g, 3, NULL, NULL, err, sizeof err), ST_OK);
  }
  stConfig c;
  st_config_default(&c);
  c.network_arch = ST_ARCH_B;
  c.integrated_top = 2;
  c.ga_population = 8;
  CU_ASSERT_FATAL(strlen(dir) < 100);
  snprintf(c.integrated_populations, sizeof c.integrated_populations, "%.100s/pop*.genome, %.100s/other2.genome", dir, dir);
  stAssembly a;
  CU_ASSERT_EQUAL_FATAL(st_assemble_population(&c, &a, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(a.nfiles, 3);
  CU_ASSERT_EQUAL(a.taken, 6);
  CU_ASSERT_EQUAL(a.count, 8);
  const int want[8] = {0, 1, 16, 17, 32, 33, 0, 1};
  for (int i = 0; i < 8; i++) {
    CU_ASSERT_EQUAL(a.genome[i].ngenes, ST_GENES_B);
    CU_ASSERT_EQUAL(a.genome[i].gene[0], want[i]);
    for (int g = ST_GENES_A; g < ST_GENES_B; g++) CU_ASSERT_EQUAL(a.genome[i].gene[g], 32768);
  }
  CU_ASSERT_EQUAL(memcmp(a.genome[0].gene, a.genome[6].gene, 2 * ST_GENES_BASE), 0);
  CU_ASSERT(memcmp(a.genome[0].gene + ST_GENES_BASE, a.genome[6].gene + ST_GENES_BASE, 2 * 84) != 0);
  st_assembly_free(&a);
  /* refusals */
  c.ga_population = 5;
  CU_ASSERT_EQUAL(st_assemble_population(&c, &a, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "3 files x integrated.top 2 = 6 genotypes (expected at most ga.population = 5)");
  c.ga_population = 100;
  c.integrated_top = 4;
  CU_ASSERT_EQUAL(st_assemble_population(&c, &a, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "pop0.genome has 3 genotypes (expected at least integrated.top = 4)");
  snprintf(c.integrated_populations, sizeof c.integrated_populations, "%.100s/none*.genome", dir);
  CU_ASSERT_EQUAL(st_assemble_population(&c, &a, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "none*.genome' matches no file");
}

void st_suite_integrated(void) {
  ST_ADD_SUITE("integrated");
  ST_ADD_TEST(test_int_step_fitness);
  ST_ADD_TEST(test_int_trial_success);
  ST_ADD_TEST(test_int_focus_bonus_consecutive);
  ST_ADD_TEST(test_int_no_early_end_when_dropped);
  ST_ADD_TEST(test_int_penalty_cap_and_failure);
  ST_ADD_TEST(test_int_combine);
  ST_ADD_TEST(test_int_condition_plans);
  ST_ADD_TEST(test_int_config_rules);
  ST_ADD_TEST(test_int_selftalk_loop);
  ST_ADD_TEST(test_int_trial_table);
  ST_ADD_TEST(test_int_trial_order);
  ST_ADD_TEST(test_int_rng_seed_apart);
  ST_ADD_TEST(test_int_assembly);
}
