/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/ga.h"

struct stGa {
  stGaDef def;
  int generation;
  int told;           /* fitness known for the current generation */
  stGenome *pop;      /* population */
  stGenome *next;     /* scratch for breeding */
  double *fitness;
  int *rank;
  uint8_t mask[ST_GENOME_MAX_GENES];
};

stGaDef st_ga_def_from_config(const stConfig *cfg) {
  ST_ASSERT(cfg);
  stGaDef d;
  memset(&d, 0, sizeof d);
  d.population = cfg->ga_population;
  d.elites = cfg->ga_elites;
  d.parents = cfg->ga_parents;
  d.mutation_rate = cfg->ga_mutation_rate;
  d.seed = st_config_rng_seed(cfg);
  d.ngenes = st_arch_ngenes(ST_ARCH_BASE);
  d.first_generation = 0;
  return d;
}

stGaDef st_ga_default_def(void) {
  stConfig c;
  st_config_default(&c);
  return st_ga_def_from_config(&c);
}

/* the fields that are keys within the key table's ranges, then what the algorithm needs */
static stStatus check_def(const stGaDef *d, char *err, size_t errsz) {
  stStatus st;
  if ((st = st_config_check_number("ga", "population", d->population, err, errsz)) ||
      (st = st_config_check_number("ga", "elites", d->elites, err, errsz)) ||
      (st = st_config_check_number("ga", "parents", d->parents, err, errsz)) ||
      (st = st_config_check_number("ga", "mutation_rate", d->mutation_rate, err, errsz)))
    return st;
  if (d->elites > d->population || d->parents > d->population) {
    st__errf(err, errsz,
             "GA sizes: population %d, elites %d, parents %d (expected elites <= population and "
             "parents <= population)",
             d->population, d->elites, d->parents);
    return ST_ERR_ARG;
  }
  if (d->ngenes < 1 || d->ngenes > ST_GENOME_MAX_GENES) {
    st__errf(err, errsz, "GA genes %d (expected 1..%d)", d->ngenes, ST_GENOME_MAX_GENES);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

stStatus st_ga_create(const stGaDef *def, const stGenome *init, int ninit, const uint8_t *mask,
                      stGa **out, char *err, size_t errsz) {
  ST_ASSERT(def && out);
  ST_ASSERT(ninit >= 0 && (ninit == 0 || init));
  *out = NULL;
  const stGaDef *d = def;
  stStatus st = check_def(d, err, errsz);
  if (st) return st;
  if (init && ninit < d->population) {
    st__errf(err, errsz, "initial population has %d genotypes (expected at least %d)", ninit,
             d->population);
    return ST_ERR_ARG;
  }
  stGa *ga = calloc(1, sizeof *ga);
  if (!ga) return ST_ERR_NOMEM;
  size_t n = (size_t)d->population;
  ga->pop = malloc(sizeof *ga->pop * n);
  ga->next = malloc(sizeof *ga->next * n);
  ga->fitness = malloc(sizeof *ga->fitness * n);
  ga->rank = malloc(sizeof *ga->rank * n);
  if (!ga->pop || !ga->next || !ga->fitness || !ga->rank) {
    st_ga_destroy(ga);
    st__errf(err, errsz, "GA: out of memory");
    return ST_ERR_NOMEM;
  }
  ga->def = *d;
  ga->generation = d->first_generation;
  for (int i = 0; i < ST_GENOME_MAX_GENES; i++) ga->mask[i] = (uint8_t)(mask ? mask[i] != 0 : 1);
  for (int i = 0; i < d->population; i++) {
    if (init) {
      if (init[i].ngenes != d->ngenes) {
        st__errf(err, errsz, "initial genotype %d has %d genes (expected %d)", i, init[i].ngenes,
                 d->ngenes);
        st_ga_destroy(ga);
        return ST_ERR_ARG;
      }
      ga->pop[i] = init[i];
    } else {
      stRng rng = st_rng_keyed(d->seed, ST_RNG_INIT, (uint64_t)d->first_generation, (uint64_t)i, 0);
      st_genome_random(&ga->pop[i], d->ngenes, &rng);
    }
  }
  *out = ga;
  return ST_OK;
}

void st_ga_destroy(stGa *ga) {
  if (!ga) return;
  free(ga->pop);
  free(ga->next);
  free(ga->fitness);
  free(ga->rank);
  free(ga);
}

const stGaDef *st_ga_def(const stGa *ga) {
  ST_ASSERT(ga);
  return &ga->def;
}
int st_ga_generation(const stGa *ga) {
  ST_ASSERT(ga);
  return ga->generation;
}
const stGenome *st_ga_genome(const stGa *ga, int i) {
  ST_ASSERT(ga);
  ST_ASSERT(i >= 0 && i < ga->def.population);
  return &ga->pop[i];
}
int st_ga_ranked(const stGa *ga, int r) {
  ST_ASSERT(ga);
  ST_ASSERT(r >= 0 && r < ga->def.population);
  return ga->rank[r];
}
double st_ga_fitness(const stGa *ga, int i) {
  ST_ASSERT(ga);
  ST_ASSERT(i >= 0 && i < ga->def.population);
  return ga->fitness[i];
}

/* a before b: higher fitness, NaN last, then lower index (a total order: qsort is safe) */
static int rank_cmp_ctx(const double *f, int a, int b) {
  double fa = f[a], fb = f[b];
  int na = isnan(fa), nb = isnan(fb);
  if (na != nb) return na - nb;
  if (!na && fa != fb) return fa > fb ? -1 : 1;
  return (a > b) - (a < b);
}

void st_ga_tell(stGa *ga, const double *fitness) {
  ST_ASSERT(ga && fitness);
  int n = ga->def.population;
  memcpy(ga->fitness, fitness, sizeof *fitness * (size_t)n);
  /* insertion sort with an explicit total order: stable, reentrant, n is small */
  for (int i = 0; i < n; i++) {
    int v = i, j = i;
    while (j > 0 && rank_cmp_ctx(ga->fitness, v, ga->rank[j - 1]) < 0) {
      ga->rank[j] = ga->rank[j - 1];
      j--;
    }
    ga->rank[j] = v;
  }
  ga->told = 1;
}

int st_ga_mutate(stGenome *g, const uint8_t *mask, double rate, stRng *rng) {
  ST_ASSERT(g && rng);
  ST_ASSERT(rate >= 0.0 && rate <= 1.0);
  int flips = 0;
  for (int i = 0; i < g->ngenes; i++) {
    if (mask && !mask[i]) continue;
    for (int b = 15; b >= 0; b--) {
      if (st_rng_bernoulli(rng, rate)) {
        g->gene[i] ^= (uint16_t)(1u << b);
        flips++;
      }
    }
  }
  return flips;
}

stStatus st_ga_next(stGa *ga) {
  ST_ASSERT(ga);
  if (!ga->told) return ST_ERR_ARG;
  const stGaDef *d = &ga->def;
  int next_gen = ga->generation + 1;
  for (int e = 0; e < d->elites; e++) ga->next[e] = ga->pop[ga->rank[e]];
  for (int i = d->elites; i < d->population; i++) {
    int c = i - d->elites;
    ga->next[i] = ga->pop[ga->rank[c % d->parents]];
    stRng rng = st_rng_keyed(d->seed, ST_RNG_MUTATE, (uint64_t)next_gen, (uint64_t)i, 0);
    st_ga_mutate(&ga->next[i], ga->mask, d->mutation_rate, &rng);
  }
  stGenome *t = ga->pop;
  ga->pop = ga->next;
  ga->next = t;
  ga->generation = next_gen;
  ga->told = 0;
  return ST_OK;
}

stStatus st_ga_restore(stGa *ga, int generation, const stGenome *pop, int n, char *err,
                       size_t errsz) {
  ST_ASSERT(ga && (pop || n == 0));
  if (n < ga->def.population) {
    st__errf(err, errsz, "population has %d genotypes (expected %d)", n, ga->def.population);
    return ST_ERR_ARG;
  }
  for (int i = 0; i < ga->def.population; i++) {
    if (pop[i].ngenes != ga->def.ngenes) {
      st__errf(err, errsz, "genotype %d has %d genes (expected %d)", i, pop[i].ngenes,
               ga->def.ngenes);
      return ST_ERR_ARG;
    }
  }
  memcpy(ga->pop, pop, sizeof *pop * (size_t)ga->def.population);
  ga->generation = generation;
  ga->told = 0;
  return ST_OK;
}
