/* SPDX-License-Identifier: MIT
 * libselftalk: the bitwise genetic algorithm of thesis §2.4 / SPEC §5, ask/tell style.
 *
 * The GA never calls a fitness function: read the population with st_ga_genome(), evaluate
 * it anywhere (threads, processes, machines), hand the fitness back with st_ga_tell(), then
 * st_ga_next() breeds the next generation. Every random draw is keyed by (seed, generation,
 * individual), so the result does not depend on where or in which order evaluation ran.
 *
 * Owns: stGa (opaque; st_ga_create / st_ga_destroy) and its population. */
#ifndef SELFTALK_GA_H
#define SELFTALK_GA_H

#include <stdint.h>

#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/genome.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Definition of a GA; fill with st_ga_def_from_config() or st_ga_default_def() and change what
 * you need. The fields that are keys are checked against the key table's ranges. */
typedef struct stGaDef {
  int population;       /* genotypes per generation (ga.population) */
  int elites;           /* best genotypes copied unchanged (ga.elites) */
  int parents;          /* best genotypes that breed (ga.parents; children round-robin over them) */
  double mutation_rate; /* probability of flipping each mutable bit (ga.mutation_rate) */
  uint64_t seed;        /* keys every random stream (run.seed as st_config_rng_seed gives it) */
  int ngenes;           /* genes per genotype */
  int first_generation; /* number of the initial generation */
} stGaDef;

/* The GA of cfg's primitive stages: its ga.* keys and run.seed, the base network's 612 genes,
 * starting at generation 0. */
ST_API stGaDef st_ga_def_from_config(const stConfig *cfg);
/* The same with every key at its default (the thesis's GA: 100 genotypes, 10 elites, 20
 * parents, rate 0.005). */
ST_API stGaDef st_ga_default_def(void);

typedef struct stGa stGa;

/* Creates a GA. Nullable: init (then genotypes are fair coin flips keyed by (seed, 0,
 * individual)), mask (then every gene is mutable). init must hold at least def->population
 * genotypes of def->ngenes genes; the first def->population are used. mask has one byte per
 * gene (ST_GENOME_MAX_GENES), nonzero = mutable. */
ST_API stStatus st_ga_create(const stGaDef *def, const stGenome *init, int ninit, const uint8_t *mask,
                      stGa **ga, char *err, size_t errsz);

/* Nullable: ga. */
ST_API void st_ga_destroy(stGa *ga);

ST_API const stGaDef *st_ga_def(const stGa *ga);

/* Number of the current generation (the one st_ga_genome() returns). */
ST_API int st_ga_generation(const stGa *ga);

/* Genotype i (0 <= i < population) of the current generation. In generations after the first,
 * indices 0..elites-1 are the previous generation's elites, best first. */
ST_API const stGenome *st_ga_genome(const stGa *ga, int i);

/* Records the fitness of every genotype of the current generation and ranks them: higher
 * is better, ties keep the lower index first, NaN ranks last. */
ST_API void st_ga_tell(stGa *ga, const double *fitness);

/* After st_ga_tell: the index of the genotype at rank r (0 = best), and its fitness. */
ST_API int st_ga_ranked(const stGa *ga, int r);
ST_API double st_ga_fitness(const stGa *ga, int i);

/* After st_ga_tell: the next generation - elites unchanged, then children of the parents
 * (child c, c = 0.. population-elites-1, has parent rank c mod parents) with bit-flip
 * mutation on mutable genes, keyed by (seed, next generation, child's index). Returns
 * ST_ERR_ARG if st_ga_tell was not called for this generation. */
ST_API stStatus st_ga_next(stGa *ga);

/* Replaces the current population and generation (used to resume from a checkpoint). */
ST_API stStatus st_ga_restore(stGa *ga, int generation, const stGenome *pop, int n, char *err,
                       size_t errsz);

/* Mutates g in place: each bit of each gene with mask[gene] != 0 (nullable: all) flips with
 * probability rate, drawing one number per mutable bit from rng in layout order. Returns the
 * number of flipped bits. */
ST_API int st_ga_mutate(stGenome *g, const uint8_t *mask, double rate, stRng *rng);

#ifdef __cplusplus
}
#endif

#endif
