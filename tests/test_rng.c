/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>

#include "selftalk/config.h"
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

/* run.rng_seed (issue 47): st_rng_keyed mixes the seed as it mixes the stream's number, so with
 * plain (the default, every committed run) seed a's stream b is seed b's stream a, and seed a's
 * stream a is seed b's stream b; apart keys the seed 2^32 higher, above every stream's number,
 * and no two runs share a key */
static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static void test_rng_seed_apart(void) {
  stConfig c;
  st_config_default(&c);
  c.run_seed = 4;
  CU_ASSERT_EQUAL(c.run_rng_seed, ST_RNG_SEED_PLAIN);
  CU_ASSERT_EQUAL(st_config_rng_seed(&c), 4u);
  /* the collision plain keeps: run seed 4's integrated offsets of generation 0, trial 0 are run
   * seed 5's new genes of individual 0 */
  CU_ASSERT_EQUAL(st_rng_keyed(4, ST_RNG_INTEGRATED, 0, 0, 0).key,
                  st_rng_keyed(5, ST_RNG_GROW, 0, 0, 0).key);
  CU_ASSERT_EQUAL(st_rng_keyed(2, ST_RNG_INTEGRATED, 11, 0, 3).key,
                  st_rng_keyed(5, ST_RNG_MUTATE, 11, 0, 3).key);
  CU_ASSERT_EQUAL(st_rng_keyed(5, ST_RNG_INTEGRATED, 0, 0, 0).key,
                  st_rng_keyed(4, ST_RNG_GROW, 0, 0, 0).key);
  CU_ASSERT_EQUAL(st_rng_keyed(1, ST_RNG_INIT, 0, 7, 0).key,
                  st_rng_keyed(4, ST_RNG_GROW, 0, 7, 0).key);
  CU_ASSERT_EQUAL(st_config_set(&c, "run.rng_seed=apart", NULL, 0), ST_OK);
  CU_ASSERT_EQUAL(st_config_rng_seed(&c), (UINT64_C(1) << 32) + 4u);
  /* seeds 1-10, every stream the library has, a few coordinates: plain repeats keys, apart none */
  enum { NSEED = 10, NSTREAM = ST_RNG_HANDOVER_SOLVER, NC = 3 };
  static uint64_t key[2][NSEED * NSTREAM * NC * NC * NC];
  int dup[2] = {0, 0};
  for (int mode = 0; mode < 2; mode++) {
    int n = 0;
    c.run_rng_seed = mode ? ST_RNG_SEED_APART : ST_RNG_SEED_PLAIN;
    for (int s = 1; s <= NSEED; s++) {
      c.run_seed = s;
      for (int st = 1; st <= NSTREAM; st++)
        for (int g = 0; g < NC; g++)
          for (int i = 0; i < NC; i++)
            for (int t = 0; t < NC; t++)
              key[mode][n++] = st_rng_keyed(st_config_rng_seed(&c), (stRngStream)st, g, i, t).key;
    }
    qsort(key[mode], (size_t)n, sizeof key[mode][0], cmp_u64);
    for (int k = 1; k < n; k++) dup[mode] += key[mode][k] == key[mode][k - 1];
  }
  /* plain: (seed a, stream b) = (seed b, stream a) for the 45 pairs a < b of 1-10, and
   * (seed a, stream a) is one key for every a (the seed's and the stream's mixes cancel: 9 more),
   * at each of the 27 coordinates */
  CU_ASSERT_EQUAL(dup[0], (45 + 9) * NC * NC * NC);
  CU_ASSERT_EQUAL(dup[1], 0);
}

void st_suite_rng(void) {
  ST_ADD_SUITE("rng");
  ST_ADD_TEST(test_rng_golden);
  ST_ADD_TEST(test_rng_keys);
  ST_ADD_TEST(test_rng_uniform);
  ST_ADD_TEST(test_rng_seed_apart);
}
