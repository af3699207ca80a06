/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>

#include "selftalk/ga.h"
#include "test_util.h"

static stGa *make_ga(uint64_t seed, int ngenes, double rate, const uint8_t *mask) {
  stGaDef d = st_ga_default_def();
  d.seed = seed;
  d.ngenes = ngenes;
  d.mutation_rate = rate;
  stGa *ga = NULL;
  char err[256];
  CU_ASSERT_EQUAL_FATAL(st_ga_create(&d, NULL, 0, mask, &ga, err, sizeof err), ST_OK);
  return ga;
}

/* a fitness that is distinct for every genotype: number of set bits of gene 0..3 */
static void toy_fitness(const stGa *ga, double *f) {
  for (int i = 0; i < 100; i++) {
    const stGenome *g = st_ga_genome(ga, i);
    int ones = 0;
    for (int b = 0; b < 16 * g->ngenes; b++) ones += st_genome_bit(g, b);
    f[i] = ones + 1e-3 * i;
  }
}

static void test_ga_defaults(void) {
  stGaDef d = st_ga_default_def();
  CU_ASSERT_EQUAL(d.population, 100);
  CU_ASSERT_EQUAL(d.elites, 10);
  CU_ASSERT_EQUAL(d.parents, 20);
  CU_ASSERT_DOUBLE_EQUAL(d.mutation_rate, 0.005, 0.0);
  CU_ASSERT_EQUAL(d.ngenes, 612);
  CU_ASSERT_EQUAL(d.seed, 1);
  CU_ASSERT_EQUAL(d.first_generation, 0);
  /* from a config: its ga.* keys and run.seed */
  stConfig c;
  char err[256];
  st_config_default(&c);
  const char *sets[] = {"ga.population=30", "ga.elites=3", "ga.parents=6", "ga.mutation_rate=0.01",
                        "run.seed=9", "ga.success_genotypes=2"};
  CU_ASSERT_EQUAL_FATAL(st_config_set_all(&c, sets, 6, err, sizeof err), ST_OK);
  d = st_ga_def_from_config(&c);
  CU_ASSERT(d.population == 30 && d.elites == 3 && d.parents == 6 && d.seed == 9);
  CU_ASSERT_DOUBLE_EQUAL(d.mutation_rate, 0.01, 0.0);
  CU_ASSERT_EQUAL(d.ngenes, 612);
}

static void test_ga_elites_and_children(void) {
  stGa *ga = make_ga(11, 612, 0.005, NULL);
  stGenome *old = malloc(sizeof(stGenome) * 100);
  for (int i = 0; i < 100; i++) old[i] = *st_ga_genome(ga, i);
  double f[100];
  toy_fitness(ga, f);
  st_ga_tell(ga, f);
  int rank[100];
  for (int r = 0; r < 100; r++) rank[r] = st_ga_ranked(ga, r);
  /* ranking is by fitness, descending */
  for (int r = 1; r < 100; r++) CU_ASSERT(f[rank[r - 1]] >= f[rank[r]]);
  CU_ASSERT_EQUAL(st_ga_next(ga), ST_OK);
  CU_ASSERT_EQUAL(st_ga_generation(ga), 1);
  for (int e = 0; e < 10; e++)
    CU_ASSERT_EQUAL(memcmp(st_ga_genome(ga, e)->gene, old[rank[e]].gene, 612 * 2), 0);
  /* child c descends from parent rank c mod 20, with a handful of flipped bits */
  int differing = 0;
  for (int i = 10; i < 100; i++) {
    const stGenome *child = st_ga_genome(ga, i), *parent = &old[rank[(i - 10) % 20]];
    int flips = 0;
    for (int b = 0; b < 612 * 16; b++) flips += st_genome_bit(child, b) != st_genome_bit(parent, b);
    CU_ASSERT(flips < 200); /* expected 49, far from the ~4900 of an unrelated genotype */
    differing += flips > 0;
  }
  CU_ASSERT(differing > 80); /* P(no flip in 9792 bits) = 0.995^9792 ~ 5e-22 */
  CU_ASSERT_EQUAL(st_ga_next(ga), ST_ERR_ARG); /* no fitness told for generation 1 yet */
  free(old);
  st_ga_destroy(ga);
}

/* integrated stage: 696 genes, only 612..695 mutable, rate 0.04 */
static void test_ga_mask_and_rate(void) {
  uint8_t mask[ST_GENOME_MAX_GENES];
  st_genome_mask_new_genes(mask, 696);
  stGa *ga = make_ga(3, 696, 0.04, mask);
  stGenome *old = malloc(sizeof(stGenome) * 100);
  long flips = 0;
  const int gens = 5;
  for (int gen = 0; gen < gens; gen++) {
    for (int i = 0; i < 100; i++) old[i] = *st_ga_genome(ga, i);
    double f[100];
    toy_fitness(ga, f);
    st_ga_tell(ga, f);
    int rank[100];
    for (int r = 0; r < 100; r++) rank[r] = st_ga_ranked(ga, r);
    st_ga_next(ga);
    for (int i = 10; i < 100; i++) {
      const stGenome *c = st_ga_genome(ga, i), *p = &old[rank[(i - 10) % 20]];
      CU_ASSERT_EQUAL(memcmp(c->gene, p->gene, 612 * 2), 0); /* frozen genes never change */
      for (int b = 612 * 16; b < 696 * 16; b++) flips += st_genome_bit(c, b) != st_genome_bit(p, b);
    }
  }
  /* binomial: n = 5 gens x 90 children x 1344 bits, p = 0.04: mean 24192, sd 152.4 */
  double n = gens * 90.0 * 84 * 16, mean = n * 0.04, sd = sqrt(n * 0.04 * 0.96);
  CU_ASSERT(fabs(flips - mean) < 5 * sd);
  if (fabs(flips - mean) >= 5 * sd) fprintf(stderr, "\n  flips %ld, expected %.0f +- %.0f\n", flips, mean, sd);
  free(old);
  st_ga_destroy(ga);
}

static void test_ga_mutation_rate_base(void) {
  stGenome g;
  stRng rng = st_rng_keyed(9, ST_RNG_USER, 0, 0, 0);
  long flips = 0;
  const int reps = 200;
  for (int r = 0; r < reps; r++) {
    memset(&g, 0, sizeof g);
    g.ngenes = 612;
    int f = st_ga_mutate(&g, NULL, 0.005, &rng);
    flips += f;
    int ones = 0; /* from an all-zero genotype, the bits set are exactly the flips */
    for (int b = 0; b < 612 * 16; b++) ones += st_genome_bit(&g, b);
    CU_ASSERT_EQUAL(ones, f);
  }
  double n = reps * 9792.0, mean = n * 0.005, sd = sqrt(n * 0.005 * 0.995);
  CU_ASSERT(fabs(flips - mean) < 5 * sd); /* mean 9792, sd 98.7 */
}

static void test_ga_reproducible(void) {
  stGa *a = make_ga(42, 612, 0.005, NULL), *b = make_ga(42, 612, 0.005, NULL),
       *c = make_ga(43, 612, 0.005, NULL);
  for (int gen = 0; gen < 4; gen++) {
    double fa[100], fb[100], fc[100];
    toy_fitness(a, fa);
    toy_fitness(b, fb);
    toy_fitness(c, fc);
    st_ga_tell(a, fa);
    st_ga_tell(b, fb);
    st_ga_tell(c, fc);
    st_ga_next(a);
    st_ga_next(b);
    st_ga_next(c);
  }
  int same_ab = 1, same_ac = 1;
  for (int i = 0; i < 100; i++) {
    same_ab &= !memcmp(st_ga_genome(a, i)->gene, st_ga_genome(b, i)->gene, 612 * 2);
    same_ac &= !memcmp(st_ga_genome(a, i)->gene, st_ga_genome(c, i)->gene, 612 * 2);
  }
  CU_ASSERT(same_ab);
  CU_ASSERT(!same_ac);
  st_ga_destroy(a);
  st_ga_destroy(b);
  st_ga_destroy(c);
}

static void test_ga_ties_and_nan(void) {
  stGa *ga = make_ga(1, 612, 0.005, NULL);
  double f[100];
  for (int i = 0; i < 100; i++) f[i] = 1.0;
  f[3] = NAN;
  f[50] = 2.0;
  st_ga_tell(ga, f);
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 0), 50);
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 1), 0); /* equal fitness: lower index first */
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 2), 1);
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 3), 2);
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 4), 4);
  CU_ASSERT_EQUAL(st_ga_ranked(ga, 99), 3); /* NaN ranks last */
  st_ga_destroy(ga);
}

static void test_ga_create_errors(void) {
  stGaDef d = st_ga_default_def();
  stGa *ga = NULL;
  char err[256];
  d.elites = 200;
  CU_ASSERT_EQUAL(st_ga_create(&d, NULL, 0, NULL, &ga, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "elites 200");
  /* the key table's ranges */
  d = st_ga_default_def();
  d.population = 1;
  d.elites = d.parents = 1;
  CU_ASSERT_EQUAL(st_ga_create(&d, NULL, 0, NULL, &ga, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ga.population: 1 is out of range (expected an integer in [2, 100000])");
  d = st_ga_default_def();
  d.mutation_rate = 1.5;
  CU_ASSERT_EQUAL(st_ga_create(&d, NULL, 0, NULL, &ga, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ga.mutation_rate: 1.5 is out of range");
  d = st_ga_default_def();
  stGenome init[100];
  memset(init, 0, sizeof init);
  for (int i = 0; i < 100; i++) init[i].ngenes = 612;
  CU_ASSERT_EQUAL(st_ga_create(&d, init, 50, NULL, &ga, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "50 genotypes (expected at least 100)");
  init[7].ngenes = 696;
  CU_ASSERT_EQUAL(st_ga_create(&d, init, 100, NULL, &ga, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "genotype 7 has 696 genes");
  init[7].ngenes = 612;
  init[5].gene[0] = 0xabcd;
  CU_ASSERT_EQUAL(st_ga_create(&d, init, 100, NULL, &ga, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_ga_genome(ga, 5)->gene[0], 0xabcd);
  st_ga_destroy(ga);
  st_ga_destroy(NULL);
}

void st_suite_ga(void) {
  ST_ADD_SUITE("ga");
  ST_ADD_TEST(test_ga_defaults);
  ST_ADD_TEST(test_ga_elites_and_children);
  ST_ADD_TEST(test_ga_mask_and_rate);
  ST_ADD_TEST(test_ga_mutation_rate_base);
  ST_ADD_TEST(test_ga_reproducible);
  ST_ADD_TEST(test_ga_ties_and_nan);
  ST_ADD_TEST(test_ga_create_errors);
}
