/* SPDX-License-Identifier: MIT
 * libselftalk: counter-based random numbers.
 *
 * Every random stream is keyed by (run seed, purpose, generation, individual, trial) and
 * nothing else, never by thread or completion order, so a run gives the same numbers
 * however its work is spread. The generator is splitmix64 run as a counter: output k is
 * mix(key + (k + 1) * golden), so an stRng is a plain value (copying it copies the stream). */
#ifndef SELFTALK_RNG_H
#define SELFTALK_RNG_H

#include <stdint.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Purpose of a stream; part of the key so that streams of different purposes of one seed never
 * alias. st_rng_keyed mixes the seed as it mixes this number, so across seeds they do: (seed a,
 * stream b) is (seed b, stream a), and (a, a) is (b, b); the library keys a run's streams by
 * st_config_rng_seed (selftalk/config.h, run.rng_seed = apart: no run's key another's).
 * Values are part of the reproducibility contract: append, never renumber. */
typedef enum stRngStream {
  ST_RNG_INIT = 1,   /* initial genotypes: (generation 0, individual) */
  ST_RNG_MUTATE = 2, /* mutation of one child: (generation, child index) */
  ST_RNG_TRIAL = 3,  /* trial offsets: (generation, trial); common to all individuals */
  ST_RNG_GROW = 4,   /* new genes when a genotype grows: (run, individual) */
  ST_RNG_INTEGRATED = 5, /* integrated-stage trial offsets: (generation, trial); common to all */
  ST_RNG_SOLVER = 6, /* the dynamic solver's generator of an integrated or scripted episode:
                        (generation, individual, trial) */
  ST_RNG_POSTEVAL = 7, /* post-evaluation trial offsets: (test, 0, trial); common to every
                          individual and condition (selftalk/posteval.h) */
  ST_RNG_POSTEVAL_SOLVER = 8, /* the dynamic solver's generator of a post-evaluation trial:
                                 (test, 0, trial) */
  ST_RNG_STARTS = 9, /* drawn open and grasp starts (postures.vary_starts): (generation, 0,
                        trial); common to all individuals */
  ST_RNG_HANDOVER = 10, /* hand-over trials' offsets (stage.handover): (generation, 0, trial);
                           common to all individuals */
  ST_RNG_HANDOVER_SOLVER = 11, /* the dynamic solver's generator of a hand-over trial:
                                  (generation, individual, trial) */
  ST_RNG_USER = 100  /* first value free for applications */
} stRngStream;

/* A counter-based generator: key fixed at creation, counter advanced per draw. */
typedef struct stRng {
  uint64_t key;
  uint64_t counter;
} stRng;

/* splitmix64's finaliser: a bijective 64-bit mix with good avalanche. */
ST_API uint64_t st_rng_mix64(uint64_t x);

/* Generator for one purpose, keyed by all of its coordinates. */
ST_API stRng st_rng_keyed(uint64_t seed, stRngStream stream, uint64_t generation, uint64_t individual,
                   uint64_t trial);

/* Next 64 random bits. */
ST_API uint64_t st_rng_u64(stRng *rng);

/* Uniform double in [0, 1) with 53 random bits. */
ST_API double st_rng_uniform(stRng *rng);

/* Uniform double in [lo, hi). */
ST_API double st_rng_range(stRng *rng, double lo, double hi);

/* True with probability p (p <= 0: never; p >= 1: always). Draws exactly one number. */
ST_API int st_rng_bernoulli(stRng *rng, double p);

#ifdef __cplusplus
}
#endif

#endif
