/* SPDX-License-Identifier: MIT
 * selftalk/stats.h against values derived without the library: exact p by enumerating every
 * split of the ranks, the normal approximation by its textbook formula, both re-derived by
 * tests/fixtures/stats/derive_mwu.py (itertools, math.erfc) and cross-checked there with SciPy
 * 1.10.1's mannwhitneyu (Debian's python3-scipy); textbook cases cited where they come from. */
#include <float.h>
#include <math.h>

#include "selftalk/stats.h"
#include "test_util.h"

#define N_OF(x) ((int)(sizeof(x) / sizeof(x)[0]))

/* |got - want| <= rel |want| */
static void assert_rel(double got, double want, double rel) {
  const int ok = fabs(got - want) <= rel * fabs(want);
  if (!ok) fprintf(stderr, "\n  got %.17g, want %.17g\n", got, want);
  CU_ASSERT(ok);
}

static stMwuResult mwu(const stMwuDef *def, const double *a, int na, const double *b, int nb) {
  stMwuResult r;
  char err[256] = "";
  memset(&r, 0, sizeof r);
  const stStatus st = st_mwu(def, a, na, b, nb, &r, err, sizeof err);
  if (st) fprintf(stderr, "\n  st_mwu: %s\n", err);
  CU_ASSERT_EQUAL(st, ST_OK);
  return r;
}

/* Hollander & Wolfe (1973), p. 69, the example of R's ?wilcox.test: permeability constants of
 * the human chorioamnion at term (x) and at 12-26 weeks (y). R: W = 35, one-sided p = 0.1272.
 * No ties, 10 and 5 values: exact. Of the C(15, 5) = 3003 splits, 382 have U <= 15, so the
 * two-tailed p = 2 * 382 / 3003. */
static const double HW_X[] = {0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
static const double HW_Y[] = {1.15, 0.88, 0.90, 0.74, 1.21};

static void test_mwu_hollander_wolfe_exact(void) {
  const stMwuResult r = mwu(NULL, HW_X, N_OF(HW_X), HW_Y, N_OF(HW_Y));
  CU_ASSERT_EQUAL(r.method, ST_MWU_EXACT);
  CU_ASSERT_EQUAL(r.ties, 0);
  CU_ASSERT_EQUAL(r.u_a, 35.0);
  CU_ASSERT_EQUAL(r.u_b, 15.0);
  CU_ASSERT_EQUAL(r.u, 15.0);
  assert_rel(r.p, 2.0 * 382.0 / 3003.0, 1e-15);
  CU_ASSERT(fabs(r.p / 2.0 - 0.1272) < 5e-5); /* R's one-sided value, 4 digits */
  /* swapping the samples swaps U_A and U_B, not p */
  const stMwuResult s = mwu(NULL, HW_Y, N_OF(HW_Y), HW_X, N_OF(HW_X));
  CU_ASSERT_EQUAL(s.u_a, 15.0);
  CU_ASSERT_EQUAL(s.u_b, 35.0);
  CU_ASSERT_EQUAL(s.p, r.p);
}

/* The same data forced to the normal approximation (exact_max_n = 0): mu = 25, sigma^2 =
 * 10 * 5 * 16 / 12 = 66.667, z = (35 - 25 - 0.5) / 8.165 = 1.1635, p = erfc(z / sqrt 2). */
static void test_mwu_hollander_wolfe_normal(void) {
  stMwuDef d = st_mwu_default_def();
  d.exact_max_n = 0;
  const stMwuResult r = mwu(&d, HW_X, N_OF(HW_X), HW_Y, N_OF(HW_Y));
  CU_ASSERT_EQUAL(r.method, ST_MWU_NORMAL);
  assert_rel(r.z, 9.5 / sqrt(50.0 * 16.0 / 12.0), 1e-15);
  assert_rel(r.p, 0.24462360512698333, 1e-13);
  /* without the continuity correction: z = 10 / 8.165 */
  d.continuity = 0.0;
  assert_rel(mwu(&d, HW_X, N_OF(HW_X), HW_Y, N_OF(HW_Y)).z, 10.0 / sqrt(50.0 * 16.0 / 12.0), 1e-15);
}

/* Critical values of the two-tailed test for n1 = n2 = 10 (tables of e.g. Siegel 1956, Table
 * K; the thesis's Tables 3.1 and 3.2: 23 at alpha 0.05, 16 at 0.01): the largest U whose exact
 * p is <= alpha. Counts of the C(20, 10) = 184756 splits with U <= k: 825 (16), 1062 (17), 3996
 * (23), 4843 (24). */
static void test_mwu_exact_critical_values(void) {
  static const struct { double u; double le; } c[] = {{16, 825}, {17, 1062}, {23, 3996}, {24, 4843}};
  for (int i = 0; i < N_OF(c); i++) {
    double p = -1.0, q = -1.0;
    CU_ASSERT_EQUAL(st_mwu_exact_p(10, 10, c[i].u, &p, NULL, 0), ST_OK);
    assert_rel(p, 2.0 * c[i].le / 184756.0, 1e-15);
    CU_ASSERT_EQUAL(st_mwu_exact_p(10, 10, 100.0 - c[i].u, &q, NULL, 0), ST_OK); /* U_B */
    CU_ASSERT_EQUAL(p, q);
  }
  double p16, p17, p23, p24;
  st_mwu_exact_p(10, 10, 16, &p16, NULL, 0);
  st_mwu_exact_p(10, 10, 17, &p17, NULL, 0);
  st_mwu_exact_p(10, 10, 23, &p23, NULL, 0);
  st_mwu_exact_p(10, 10, 24, &p24, NULL, 0);
  CU_ASSERT(p16 <= 0.01 && p17 > 0.01);
  CU_ASSERT(p23 <= 0.05 && p24 > 0.05);
}

/* Complete separation: only 2 of the C(n1 + n2, n1) splits are as extreme, p = 2 / C. 3 and 3:
 * 2 / 20; 4 and 4: 2 / 70; 1 and 1: 2 / 2 = 1; the middle U of 4 and 4 (8): 1. */
static void test_mwu_exact_small(void) {
  const double a[] = {1, 2, 3, 4}, b[] = {5, 6, 7, 8};
  assert_rel(mwu(NULL, a, 3, b, 3).p, 0.1, 1e-15);
  assert_rel(mwu(NULL, a, 4, b, 4).p, 2.0 / 70.0, 1e-15);
  CU_ASSERT_EQUAL(mwu(NULL, a, 1, b, 1).p, 1.0);
  double p = 0.0;
  CU_ASSERT_EQUAL(st_mwu_exact_p(4, 4, 8, &p, NULL, 0), ST_OK);
  CU_ASSERT_EQUAL(p, 1.0);
  CU_ASSERT_EQUAL(st_mwu_exact_p(4, 4, 7, &p, NULL, 0), ST_OK); /* 2 * 31 / 70 (P(U <= 7) = 31/70) */
  assert_rel(p, 62.0 / 70.0, 1e-15);
}

/* Ties by hand: a = 1 2 2 5, b = 2 4 4 6 7. Ranks 1; 2, 2, 2 -> 3; 4, 4 -> 5.5; 5 -> 7; 6 -> 8;
 * 7 -> 9. R_a = 1 + 3 + 3 + 7 = 14, U_a = 14 - 10 = 4, mu = 10; ties: 3^3 - 3 + 2^3 - 2 = 30;
 * sigma^2 = 20 / 12 (10 - 30 / 72) = 15.972; z = -(6 - 0.5) / sigma; 5 tied values (the 2s
 * and the 4s). p = erfc(|z| / sqrt 2): SciPy 0.16876122858514953 (no continuity correction:
 * 0.13327700744249354). */
static void test_mwu_ties_by_hand(void) {
  const double a[] = {1, 2, 2, 5}, b[] = {2, 4, 4, 6, 7};
  stMwuResult r = mwu(NULL, a, 4, b, 5);
  CU_ASSERT_EQUAL(r.method, ST_MWU_NORMAL);
  CU_ASSERT_EQUAL(r.ties, 5);
  CU_ASSERT_EQUAL(r.u_a, 4.0);
  CU_ASSERT_EQUAL(r.u, 4.0);
  const double sigma = sqrt(20.0 / 12.0 * (10.0 - 30.0 / 72.0));
  assert_rel(r.z, -5.5 / sigma, 1e-15);
  assert_rel(r.p, 0.16876122858514953, 1e-13);
  stMwuDef d = st_mwu_default_def();
  d.continuity = 0.0;
  assert_rel(mwu(&d, a, 4, b, 5).p, 0.13327700744249354, 1e-13);
  /* |U - mu| within the correction: p = 1 (SciPy's clipping). a = 1 3, b = 2 3: U_a = 1.5, mu = 2 */
  const double c[] = {1, 3}, e[] = {2, 3};
  r = mwu(NULL, c, 2, e, 2);
  CU_ASSERT_EQUAL(r.u_a, 1.5);
  CU_ASSERT_EQUAL(r.p, 1.0);
  CU_ASSERT_EQUAL(r.z, 0.0);
}

/* The thesis's Table A.1 (robustness test, percent of 40 trials, runs 0-9) gives its Table 3.1:
 * the row's U = the column's U_A, e.g. ST-CT vs CT: 9.5. Many zeros tie: normal approximation.
 * p from the formula (derive_mwu.py) and SciPy agree to 1e-15; * and ** of Table 3.1 follow. */
static const double A1[4][10] = {
    {95, 95, 87.5, 100, 67.5, 90, 92.5, 97.5, 0, 97.5}, /* ST-CT */
    {67.5, 0, 95, 90, 0, 90, 75, 80, 87.5, 82.5},       /* ST */
    {0, 0, 0, 62.5, 62.5, 0, 0, 0, 50, 90},             /* CT */
    {0, 0, 32.5, 0, 0, 32.5, 62.5, 60, 75, 0}};         /* NI */

static void test_mwu_thesis_table_3_1(void) {
  static const struct { int r, c; double u_row, p; } t[] = {
      {0, 1, 24, 0.05255229831226267},  {0, 2, 9.5, 0.001972660030195866},
      {0, 3, 8.5, 0.0016633881375488087}, {1, 2, 20, 0.020967491577565302},
      {1, 3, 16.5, 0.010716561804915573}, {2, 3, 51, 0.9669241298142008}};
  for (int i = 0; i < N_OF(t); i++) {
    const stMwuResult r = mwu(NULL, A1[t[i].r], 10, A1[t[i].c], 10);
    CU_ASSERT_EQUAL(r.method, ST_MWU_NORMAL);
    CU_ASSERT_EQUAL(r.u_b, t[i].u_row); /* pairs where the row's value is the smaller */
    CU_ASSERT_EQUAL(r.u_a, 100.0 - t[i].u_row);
    assert_rel(r.p, t[i].p, 1e-13);
  }
}

/* More than 20 values (26 and 30, no ties): the normal approximation by default; with
 * exact_max_n = 50 the exact p, SciPy's mannwhitneyu(method="exact") 0.06923340791597107. */
static void test_mwu_large_samples(void) {
  double a[26], b[30];
  for (int i = 0; i < 25; i++) a[i] = 2.0 * i;
  a[25] = 7.5;
  for (int i = 0; i < 30; i++) b[i] = 2.0 * i + 3.0;
  stMwuResult r = mwu(NULL, a, 26, b, 30);
  CU_ASSERT_EQUAL(r.method, ST_MWU_NORMAL);
  CU_ASSERT_EQUAL(r.u_a, 279.0);
  CU_ASSERT_EQUAL(r.u, 279.0);
  assert_rel(r.p, 0.06946513102532155, 1e-13);
  stMwuDef d = st_mwu_default_def();
  d.exact_max_n = ST_MWU_EXACT_LIMIT;
  r = mwu(&d, a, 26, b, 30);
  CU_ASSERT_EQUAL(r.method, ST_MWU_EXACT);
  assert_rel(r.p, 0.06923340791597107, 1e-12);
  /* 20 values each is still exact by default, 21 is not */
  CU_ASSERT_EQUAL(mwu(NULL, a, 20, b, 20).method, ST_MWU_EXACT);
  CU_ASSERT_EQUAL(mwu(NULL, a, 21, b, 20).method, ST_MWU_NORMAL);
}

static void test_mwu_all_equal(void) {
  const double a[] = {3, 3, 3}, b[] = {3, 3};
  const stMwuResult r = mwu(NULL, a, 3, b, 2);
  CU_ASSERT_EQUAL(r.u_a, 3.0);
  CU_ASSERT_EQUAL(r.p, 1.0);
  CU_ASSERT_EQUAL(r.z, 0.0);
  CU_ASSERT_EQUAL(r.ties, 5);
}

static void test_mwu_errors(void) {
  const double a[] = {1, 2}, bad[] = {1, NAN};
  stMwuResult r;
  char err[256] = "";
  CU_ASSERT_EQUAL(st_mwu(NULL, a, 0, a, 2, &r, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "sample A: no values");
  CU_ASSERT_EQUAL(st_mwu(NULL, a, 2, bad, 2, &r, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "sample B: value 1 is nan (expected a finite number)");
  stMwuDef d = st_mwu_default_def();
  d.exact_max_n = ST_MWU_EXACT_LIMIT + 1;
  CU_ASSERT_EQUAL(st_mwu(&d, a, 2, a, 2, &r, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "exact_max_n 51 (expected 0..50)");
  double p;
  CU_ASSERT_EQUAL(st_mwu_exact_p(3, 3, 9.5, &p, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "U 9.5 (expected 0..9)");
  CU_ASSERT_EQUAL(st_mwu_exact_p(0, 3, 0, &p, err, sizeof err), ST_ERR_RANGE);
}

/* R: quantile(c(1, 2, 3, 4)) = 1, 1.75, 2.5, 3.25, 4 (type 7, the default; numpy the same);
 * quantile(c(7, 1, 3)) = 1, 2, 3, 5, 7; quantile(c(2, 0, 1)) = 0, 0.5, 1, 1.5, 2
 * (tools/runs_summary.py's "inclusive" quartiles, tests/check_tools.sh). */
static void test_quartiles_type7(void) {
  static const struct { double x[4]; int n; double want[5]; } t[] = {
      {{4, 2, 1, 3}, 4, {1, 1.75, 2.5, 3.25, 4}},
      {{7, 1, 3}, 3, {1, 2, 3, 5, 7}},
      {{2, 0, 1}, 3, {0, 0.5, 1, 1.5, 2}},
      {{42}, 1, {42, 42, 42, 42, 42}}};
  for (int i = 0; i < N_OF(t); i++) {
    stQuartiles q;
    CU_ASSERT_EQUAL(st_quartiles(t[i].x, t[i].n, &q, NULL, 0), ST_OK);
    const double got[5] = {q.min, q.q1, q.median, q.q3, q.max};
    for (int k = 0; k < 5; k++) CU_ASSERT_EQUAL(got[k], t[i].want[k]);
    CU_ASSERT_EQUAL(q.n, t[i].n);
  }
  const double s[] = {10, 20, 30, 40, 50, 60};
  CU_ASSERT_EQUAL(st_quantile_sorted(s, 6, 0.1), 15.0); /* h = 0.5 */
  CU_ASSERT_EQUAL(st_quantile_sorted(s, 6, 0.9), 55.0); /* h = 4.5 */
  CU_ASSERT_EQUAL(st_quantile_sorted(s, 6, 1.0), 60.0);
  CU_ASSERT_EQUAL(st_quantile_sorted(s, 6, 0.0), 10.0);
}

/* finite values whose differences overflow: the quartiles stay finite and between them */
static void test_quartiles_extremes(void) {
  const double x[] = {-DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX}; /* median: h = 1.5 */
  stQuartiles q;
  CU_ASSERT_EQUAL(st_quartiles(x, 4, &q, NULL, 0), ST_OK);
  CU_ASSERT(isfinite(q.q1) && isfinite(q.median) && isfinite(q.q3));
  CU_ASSERT_EQUAL(q.q1, -DBL_MAX);
  CU_ASSERT_EQUAL(q.median, 0.0);
  CU_ASSERT_EQUAL(q.q3, DBL_MAX);
  const double y[] = {-DBL_MAX, DBL_MAX};
  CU_ASSERT_EQUAL(st_quartiles(y, 2, &q, NULL, 0), ST_OK);
  CU_ASSERT(isfinite(q.q1) && isfinite(q.q3));
  CU_ASSERT(fabs(q.median) <= DBL_MAX * 1e-15); /* the midpoint, 0 up to rounding */
  CU_ASSERT(q.q1 < 0.0 && q.q3 > 0.0);
}

static void test_quartiles_errors(void) {
  const double x[] = {1, INFINITY};
  stQuartiles q;
  char err[256] = "";
  CU_ASSERT_EQUAL(st_quartiles(x, 0, &q, err, sizeof err), ST_ERR_ARG);
  CU_ASSERT_EQUAL(st_quartiles(x, 2, &q, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "quartiles: value 1 is inf");
}

void st_suite_stats(void) {
  ST_ADD_SUITE("stats");
  ST_ADD_TEST(test_mwu_hollander_wolfe_exact);
  ST_ADD_TEST(test_mwu_hollander_wolfe_normal);
  ST_ADD_TEST(test_mwu_exact_critical_values);
  ST_ADD_TEST(test_mwu_exact_small);
  ST_ADD_TEST(test_mwu_ties_by_hand);
  ST_ADD_TEST(test_mwu_thesis_table_3_1);
  ST_ADD_TEST(test_mwu_large_samples);
  ST_ADD_TEST(test_mwu_all_equal);
  ST_ADD_TEST(test_mwu_errors);
  ST_ADD_TEST(test_quartiles_type7);
  ST_ADD_TEST(test_quartiles_extremes);
  ST_ADD_TEST(test_quartiles_errors);
}
