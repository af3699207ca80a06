/* SPDX-License-Identifier: MIT */
#include "selftalk/rng.h"

#include "core/internal.h"

#define GOLDEN 0x9E3779B97F4A7C15ull

uint64_t st_rng_mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  return x;
}

/* fold one coordinate into the key; the multiplier keeps (a, b) and (b, a) apart */
static uint64_t fold(uint64_t h, uint64_t v, uint64_t salt) {
  return st_rng_mix64(h ^ st_rng_mix64(v + salt * GOLDEN));
}

stRng st_rng_keyed(uint64_t seed, stRngStream stream, uint64_t generation, uint64_t individual,
                   uint64_t trial) {
  uint64_t h = st_rng_mix64(seed + GOLDEN);
  h = fold(h, (uint64_t)stream, 1);
  h = fold(h, generation, 2);
  h = fold(h, individual, 3);
  h = fold(h, trial, 4);
  stRng r = {h, 0};
  return r;
}

uint64_t st_rng_u64(stRng *rng) {
  ST_ASSERT(rng);
  rng->counter++;
  return st_rng_mix64(rng->key + rng->counter * GOLDEN);
}

double st_rng_uniform(stRng *rng) {
  ST_ASSERT(rng);
  return (double)(st_rng_u64(rng) >> 11) * (1.0 / 9007199254740992.0);
}

double st_rng_range(stRng *rng, double lo, double hi) {
  ST_ASSERT(rng);
  return lo + (hi - lo) * st_rng_uniform(rng);
}

int st_rng_bernoulli(stRng *rng, double p) {
  ST_ASSERT(rng);
  double u = st_rng_uniform(rng);
  return u < p;
}
