/* SPDX-License-Identifier: MIT */
#include <math.h>

#include "selftalk/rng.h"
#include "test_util.h"

/* splitmix64 from state 0 gives 0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f
 * (Vigna's reference); a key-0 counter stream must reproduce it */
static void test_rng_golden(void) {
  stRng r = {0, 0};
  CU_ASSERT_EQUAL(st_rng_u64(&r), 0xe220a8397b1dcdafull);
  CU_ASSERT_EQUAL(st_rng_u64(&r), 0x6e789e6aa1b965f4ull);
  CU_ASSERT_EQUAL(st_rng_u64(&r), 0x06c45d188009454full);
}

static void test_rng_keys(void) {
  stRng a = st_rng_keyed(5, ST_RNG_MUTATE, 3, 7, 0);
  stRng b = st_rng_keyed(5, ST_RNG_MUTATE, 3, 7, 0);
  CU_ASSERT_EQUAL(st_rng_u64(&a), st_rng_u64(&b));
  /* each coordinate changes the stream, and swapping two coordinates does too */
  stRng c[6] = {st_rng_keyed(6, ST_RNG_MUTATE, 3, 7, 0), st_rng_keyed(5, ST_RNG_INIT, 3, 7, 0),
                st_rng_keyed(5, ST_RNG_MUTATE, 4, 7, 0), st_rng_keyed(5, ST_RNG_MUTATE, 3, 8, 0),
                st_rng_keyed(5, ST_RNG_MUTATE, 3, 7, 1), st_rng_keyed(5, ST_RNG_MUTATE, 7, 3, 0)};
  stRng ref = st_rng_keyed(5, ST_RNG_MUTATE, 3, 7, 0);
  uint64_t r0 = st_rng_u64(&ref);
  for (int i = 0; i < 6; i++) CU_ASSERT_NOT_EQUAL(st_rng_u64(&c[i]), r0);
}

static void test_rng_uniform(void) {
  stRng r = st_rng_keyed(1, ST_RNG_USER, 0, 0, 0);
  const int n = 200000;
  double sum = 0, lo = 1, hi = 0;
  int hits = 0;
  for (int i = 0; i < n; i++) {
    double u = st_rng_uniform(&r);
    sum += u;
    if (u < lo) lo = u;
    if (u > hi) hi = u;
  }
  for (int i = 0; i < n; i++) hits += st_rng_bernoulli(&r, 0.1);
  /* mean of U(0,1): sd of the mean is 1/sqrt(12 n) = 6.5e-4; allow 5 sd */
  CU_ASSERT(fabs(sum / n - 0.5) < 5 * sqrt(1.0 / (12.0 * n)));
  CU_ASSERT(lo >= 0.0 && hi < 1.0);
  /* binomial(n, 0.1): sd = sqrt(n 0.1 0.9) = 134 */
  CU_ASSERT(fabs(hits - 0.1 * n) < 5 * sqrt(n * 0.09));
  double x = st_rng_range(&r, -0.02, 0.02);
  CU_ASSERT(x >= -0.02 && x < 0.02);
}

void st_suite_rng(void) {
  ST_ADD_SUITE("rng");
  ST_ADD_TEST(test_rng_golden);
  ST_ADD_TEST(test_rng_keys);
  ST_ADD_TEST(test_rng_uniform);
}
