/* SPDX-License-Identifier: MIT
 * The prediction fitness (eq. 2.15-2.24, SPEC §10's reading) on synthetic output sequences,
 * against values worked out by hand. Notation: w = the caretaker's words per step (-1 none,
 * R O G M = 0 1 2 3), o(t) = (reach, open, grasp, move) outputs; c(t) = [argmax o(t) = w(t+1)];
 * d1(p, t) = 1 - (h1(t) - o(p, t)). Sigmoids from a calculator:
 *   S8 = 1 / (1 + e^-0.8) = 1 / 1.4493289641172216 = 0.6899744811276125
 *   S4 = 1 / (1 + e^-0.4) = 1 / 1.6703200460356393 = 0.598687660112452 */
#include <math.h>
#include <string.h>

#include "selftalk/prediction.h"
#include "test_util.h"

#define R 0
#define O 1
#define G 2
#define M 3
#define S8 0.6899744811276125
#define S4 0.598687660112452

/* "one-hot" outputs: word p at 0.9, the others at 0.1 (h1 - h2 = 0.8 >= 0.25) */
static void hot(double o[4], int p) {
  for (int m = 0; m < 4; m++) o[m] = m == p ? 0.9 : 0.1;
}

static stPredScore score(const int *w, double (*o)[4], int n) {
  stPredDef d = st_pred_default_def();
  stPredTrial t = {n, w, (const double(*)[4])o};
  stPredScore s;
  char err[256] = "";
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_OK);
  if (err[0]) fprintf(stderr, "\n  %s\n", err);
  return s;
}

/* the outputs at t always name w(t + 1) with a 0.8 lead. f_step = 3/4 + min(1/4, 0.8) = 1 at
 * the 7 judged steps: F_step = 100 / 7 * 7 = 100. First word R: c(0), f = 1, +10. O, G, M are
 * switched to after steps 2, 4, 6; at t_s the prediction has just switched (t_pr = t_s):
 * f_ii = 1, f_iii = 1 - 0/20 = 1; d1(p, t_s) = 1, d1(p, max(0, t_s - 20) = 0) = 1 - 0.8 = 0.2,
 * f_i = sigma(1 - 0.2) = S8; f_switch = 0.5 S8 + 0.1 + 0.4 = 0.8449872405638063, +10 each.
 * F_switch = 25 (1 + 3 x 0.8449872405638063) = 88.37404304228547; B_pred = 40. */
static void test_pred_perfect(void) {
  const int w[8] = {-1, R, R, O, O, G, G, M};
  const int pred[8] = {R, R, O, O, G, G, M, M};
  double o[8][4];
  for (int t = 0; t < 8; t++) hot(o[t], pred[t]);
  stPredScore s = score(w, o, 8);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 100.0, 1e-12);
  CU_ASSERT_EQUAL(s.correct, 7);
  const double fsw = 0.5 * S8 + 0.5;
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[R], 1.0, 0.0);
  for (int p = O; p <= M; p++) CU_ASSERT_DOUBLE_EQUAL(s.fsw[p], fsw, 1e-12);
  CU_ASSERT_EQUAL(s.t_s[O], 2);
  CU_ASSERT_EQUAL(s.t_s[G], 4);
  CU_ASSERT_EQUAL(s.t_s[M], 6);
  CU_ASSERT_EQUAL(s.t_pr[M], 6);
  CU_ASSERT_DOUBLE_EQUAL(s.f_switch, 88.37404304228547, 1e-9);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 40.0, 0.0);
  /* eq. 2.24 for this one trial: 40 + (100 / 3 + 2 x 88.37404304228547 / 3) = 132.24936202819031 */
  const int one = 1;
  CU_ASSERT_DOUBLE_EQUAL(st_pred_fitness(&s, &one, 1, NULL), 132.24936202819031, 1e-9);
}

/* the prediction switches one step late: at t_s = 2 (w(3) = O) it still says R.
 * f_step: t0, t1 R -> R with lead 0.8 - 0.2 = 0.6: 1, 1; t2 predicts R, w(3) = O:
 * 1/4 d1(O, 2) = 1/4 (1 - (0.7 - 0.5)) = 0.2; t3 O -> O: 1. F_step = 100 / 4 x 3.2 = 80.
 * O: c(2) false: f_ii = d1(O, 2) = 0.8, f_iii = 0, f_i = sigma(0.8 - d1(O, 0)) with
 * d1(O, 0) = 1 - (0.8 - 0.2) = 0.4: sigma(0.4) = S4; f = 0.5 S4 + 0.08 = 0.379343830056226,
 * no bonus. G and M never given: 1 each, +10 each. F_switch = 25 (1 + 0.379343830056226 + 2)
 * = 84.48359575140565; B_pred = 10 + 20 = 30. */
static void test_pred_late_switch(void) {
  const int w[5] = {-1, R, R, O, O};
  double o[5][4] = {{0.8, 0.2, 0.1, 0.1}, {0.8, 0.2, 0.1, 0.1}, {0.7, 0.5, 0.1, 0.1},
                    {0.2, 0.8, 0.1, 0.1}, {0.2, 0.8, 0.1, 0.1}};
  stPredScore s = score(w, o, 5);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 80.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[O], 0.5 * S4 + 0.08, 1e-12);
  CU_ASSERT_EQUAL(s.t_pr[O], -1);
  CU_ASSERT_DOUBLE_EQUAL(s.f_switch, 84.48359575140565, 1e-9);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 30.0, 0.0);
}

/* the caretaker jumps open (R, R, G, G): open gets f_switch = 1 and its bonus. A perfect
 * predictor: F_step = 100; G switched to after step 2 as in the perfect case:
 * 0.8449872405638063, +10; M never given: 1, +10. F_switch = 25 (1 + 1 + 0.8449872405638063 +
 * 1) = 96.12468101409516; B_pred = 40: the same maximum as a trial that gives all words. */
static void test_pred_jumped_word(void) {
  const int w[5] = {-1, R, R, G, G};
  const int pred[5] = {R, R, G, G, G};
  double o[5][4];
  for (int t = 0; t < 5; t++) hot(o[t], pred[t]);
  stPredScore s = score(w, o, 5);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 100.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[O], 1.0, 0.0);
  CU_ASSERT_EQUAL(s.t_s[O], -1);
  CU_ASSERT_EQUAL(s.t_s[G], 2);
  CU_ASSERT_DOUBLE_EQUAL(s.f_switch, 96.12468101409516, 1e-9);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 40.0, 0.0);
}

/* step 0 predicts open, the first word is reach: f_step(0) = 1/4 d1(R, 0) = 1/4 (1 - (0.6 -
 * 0.3)) = 0.175; t1, t2 R with lead 0.8: 1, 1. F_step = 100 / 3 x 2.175 = 72.5. First word:
 * d1(R, 0) / 2 = 0.35, no bonus; O, G, M never given: 1 each, +30. F_switch = 25 x 3.35 =
 * 83.75, B_pred = 30. */
static void test_pred_wrong_first_word(void) {
  const int w[4] = {-1, R, R, R};
  double o[4][4] = {{0.3, 0.6, 0.2, 0.1}, {0.9, 0.1, 0.1, 0.1}, {0.9, 0.1, 0.1, 0.1},
                    {0.9, 0.1, 0.1, 0.1}};
  stPredScore s = score(w, o, 4);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 72.5, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[R], 0.35, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(s.f_switch, 83.75, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 30.0, 0.0);
  CU_ASSERT_EQUAL(s.correct, 2);
}

/* right, but the lead is under 0.25: f_step = 3/4 + lead. t0: 0.6 - 0.5 = 0.1 -> 0.85; t1 a
 * tie (0.5, 0.5) goes to the lowest index, reach, which is right, with lead 0 -> 0.75.
 * F_step = 100 / 2 x 1.6 = 80. */
static void test_pred_close_outputs(void) {
  const int w[3] = {-1, R, R};
  double o[3][4] = {{0.6, 0.5, 0.2, 0.1}, {0.5, 0.5, 0.3, 0.0}, {0.5, 0.5, 0.3, 0.0}};
  stPredScore s = score(w, o, 3);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 80.0, 1e-12);
  CU_ASSERT_EQUAL(s.correct, 2);
  CU_ASSERT_DOUBLE_EQUAL(st_pred_d1(o[0], O), 0.9, 1e-15);
}

/* the prediction switches to open 4 steps before t_s = 6 (t_pr = 2): f_iii = 1 - 4/20 = 0.8
 * and the bonus (4 < 5); f_i = S8 as in the perfect case, f_ii = 1: f = 0.5 S8 + 0.1 + 0.32.
 * f_step: t0, t1 right (1, 1); t2..t5 predict O while R is next: 1/4 d1(R) = 1/4 x 0.2 = 0.05
 * each; t6..t10 right: 5. F_step = 100 / 11 x 7.2 = 65.45454545454545. One step earlier
 * (t_pr = 1, 5 steps): f_iii = 0.75, no bonus, and f_step(1) = 0.05 too. */
static void test_pred_early_switch(void) {
  int w[12];
  double o[12][4];
  for (int t = 0; t < 12; t++) {
    w[t] = t == 0 ? -1 : t <= 6 ? R : O;
    hot(o[t], t < 2 ? R : O);
  }
  stPredScore s = score(w, o, 12);
  CU_ASSERT_EQUAL(s.t_s[O], 6);
  CU_ASSERT_EQUAL(s.t_pr[O], 2);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[O], 0.5 * S8 + 0.42, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 100.0 / 11.0 * 7.2, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 40.0, 0.0);
  hot(o[1], O);
  s = score(w, o, 12);
  CU_ASSERT_EQUAL(s.t_pr[O], 1);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[O], 0.5 * S8 + 0.4, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.b_pred, 30.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 100.0 / 11.0 * 6.25, 1e-12);
}

/* f_i looks 20 steps back: t_s = 21, so d1(O, 1) = 1 - (0.9 - 0.5) = 0.6 (step 0 would give
 * 0.2): f_i = sigma(1 - 0.6) = S4, f = 0.5 S4 + 0.5; every judged step is right with lead
 * >= 0.25 (t1: 0.9 - 0.5 = 0.4): F_step = 100. */
static void test_pred_window(void) {
  int w[25];
  double o[25][4];
  for (int t = 0; t < 25; t++) {
    w[t] = t == 0 ? -1 : t <= 21 ? R : O;
    hot(o[t], t <= 20 ? R : O);
  }
  o[1][O] = 0.5;
  stPredScore s = score(w, o, 25);
  CU_ASSERT_EQUAL(s.t_s[O], 21);
  CU_ASSERT_DOUBLE_EQUAL(s.fsw[O], 0.5 * S4 + 0.5, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(s.f_step, 100.0, 1e-12);
}

/* eq. 2.24 over three caretaker trials, the third never reached the target (T = 3 still):
 * (30 + 20) + (1/3) ((90 / 3 + 2 x 60 / 3) + (30 / 3 + 2 x 45 / 3)) = 50 + (70 + 40) / 3 */
static void test_pred_total(void) {
  stPredScore s[3];
  memset(s, 0, sizeof s);
  s[0].f_step = 90, s[0].f_switch = 60, s[0].b_pred = 30;
  s[1].f_step = 30, s[1].f_switch = 45, s[1].b_pred = 20;
  s[2].f_step = 99, s[2].f_switch = 99, s[2].b_pred = 40;
  const int counts[3] = {1, 1, 0};
  double b = -1;
  CU_ASSERT_DOUBLE_EQUAL(st_pred_fitness(s, counts, 3, &b), 50.0 + 110.0 / 3.0, 1e-12);
  CU_ASSERT_DOUBLE_EQUAL(b, 50.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_pred_fitness(s, counts, 0, NULL), 0.0, 0.0);
}

static void test_pred_refusals(void) {
  stPredDef d = st_pred_default_def();
  double o[4][4] = {{0.1, 0.2, 0.3, 0.4}, {0.1, 0.2, 0.3, 0.4}, {0.1, 0.2, 0.3, 0.4},
                    {0.1, 0.2, 0.3, 0.4}};
  const int ok[3] = {-1, R, R}, bad_word[3] = {-1, R, 4}, silent[3] = {-1, R, -1};
  stPredScore s;
  char err[256];
  stPredTrial t = {1, ok, (const double(*)[4])o};
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "a trial of 1 steps (expected at least 2)");
  t.n = 3;
  t.word = bad_word;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "step 2: word 4 (expected -1..3)");
  const int back[4] = {-1, R, M, G}; /* the caretaker never goes back (issue 48) */
  t.word = back;
  t.n = 4;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "step 3: word 2 after 3 (expected the caretaker's words in order, never back)");
  t.n = 3;
  t.word = silent;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "step 2: no word");
  t.word = ok;
  o[1][2] = NAN;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "step 1: output 2 is nan (expected a finite number within +-1e+06)");
  /* finite outputs whose differences overflow to -inf (1 - (h1 - o) with h1 = 1e308 and
   * o = -1e308) are refused, and the bound itself scores finitely */
  o[1][2] = -1e308;
  o[1][0] = 1e308;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "step 1: output 0 is 1e+308 (expected a finite number within +-1e+06)");
  for (int k = 0; k < 3; k++)
    for (int p = 0; p < ST_PRED_NWORDS; p++) o[k][p] = (k + p) % 2 ? ST_PRED_OUTPUT_MAX : -ST_PRED_OUTPUT_MAX;
  CU_ASSERT_EQUAL(st_pred_trial(&d, &t, &s, err, sizeof err), ST_OK);
  CU_ASSERT(isfinite(s.f_step) && isfinite(s.f_switch) && isfinite(s.b_pred));
}

void st_suite_prediction(void) {
  ST_ADD_SUITE("prediction");
  ST_ADD_TEST(test_pred_perfect);
  ST_ADD_TEST(test_pred_late_switch);
  ST_ADD_TEST(test_pred_jumped_word);
  ST_ADD_TEST(test_pred_wrong_first_word);
  ST_ADD_TEST(test_pred_close_outputs);
  ST_ADD_TEST(test_pred_early_switch);
  ST_ADD_TEST(test_pred_window);
  ST_ADD_TEST(test_pred_total);
  ST_ADD_TEST(test_pred_refusals);
}
