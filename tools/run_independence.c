/* SPDX-License-Identifier: MIT
 * run_independence: are an integrated study's runs independent draws? A diagnostic for issue 47
 * (docs/PROTOCOL.md, "Are the integrated runs independent?"), not part of the protocol. Run
 * from the repository root (the configs name their population files relatively).
 *
 *   build/run_independence streams CONFIG [section.key=value]...
 *       the random streams of the integrated stage across run seeds 1-5, as the library draws
 *       them: trial offsets (generations 0-99), solver keys, the assembled population's genes,
 *       the mutation flips (generations 1-30); then the keys shared between runs of seeds 1-10
 *       (every stream, a few coordinates) and between the draws the integrated runs of seeds
 *       1-5 use, under the config's run.rng_seed
 *   build/run_independence founders STUDY COND [G,G,...]
 *       STUDY/int-COND-sS/best.genome, S = 1..5: the founder of every generation's best (the
 *       assembled genotype whose genes 0-611 it carries: they never mutate), and at generations
 *       G how many bits of the new genes (612-) the bests of two seeds share (0.5: unrelated)
 *   build/run_independence eval CONFIG GENOMES RECORD SEED G0 G1
 *       genotype RECORD of a file evaluated as evolve evaluates it at generations G0..G1 of run
 *       seed SEED: generation, F, F_int, F_pred, bonus, autonomous bonus, successes, trials
 *   build/run_independence breed CONFIG CHECKPOINT SEED K
 *       the breeding of generation G from evolve's checkpoint, either the one a run stopped by
 *       --generations G writes (done: generation G - 1 ranked, best first, so ranks 0-19 are
 *       G's parents) or one written during a run (generation G bred: the elites, then child i
 *       of rank (i - elites) mod parents, from which each parent is recovered by mutating the
 *       child again from its stream (SEED, mutate, G, i): a flip is its own inverse, and the
 *       children of a rank must agree). Then the run's children (from the run's streams) and K
 *       other sets of children of the same parents (streams of their own) are evaluated at
 *       generation G: which earn the autonomous bonus */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/assemble.h"
#include "selftalk/config.h"
#include "selftalk/episode.h"
#include "selftalk/ga.h"
#include "selftalk/genome.h"
#include "selftalk/integrated.h"
#include "selftalk/net.h"
#include "selftalk/rng.h"
#include "selftalk/scene.h"

#define NSEED 5
#define NGEN 100
#define NTRIAL 8
#define NOFF 5 /* object dx dy, target dx dy dz */

static int fail(const char *err) {
  fprintf(stderr, "run_independence: %s\n", err);
  return 1;
}

static int load(const char *path, char **sets, int nsets, stConfig *cfg) {
  char err[512];
  st_config_default(cfg);
  if (st_config_load(path, cfg, err, sizeof err)) return fail(err);
  if (nsets > 0 && st_config_set_all(cfg, (const char *const *)sets, nsets, err, sizeof err))
    return fail(err);
  return 0;
}

static double corr(const double *a, const double *b, int n) {
  double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
  for (int i = 0; i < n; i++) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  for (int i = 0; i < n; i++) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / sqrt(saa * sbb);
}

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

typedef struct usedKey {
  uint64_t key;
  int seed, stream, g, i, t;
} usedKey;

static int cmp_used(const void *a, const void *b) {
  return cmp_u64(&((const usedKey *)a)->key, &((const usedKey *)b)->key);
}

static int bits_equal(const stGenome *a, const stGenome *b, int from) {
  int eq = 0;
  for (int g = from; g < a->ngenes; g++)
    for (int bit = 0; bit < 16; bit++) eq += ((a->gene[g] ^ b->gene[g]) >> bit & 1) == 0;
  return eq;
}

/* ---- streams ---- */

static int cmd_streams(int argc, char **argv) {
  if (argc < 1) return fail("streams CONFIG [section.key=value]...");
  stConfig cfg;
  if (load(argv[0], argv + 1, argc - 1, &cfg)) return 1;
  char err[512];
  stScene sc;
  st_scene_from_config(&cfg, &sc);
  static double off[NSEED][NGEN * NTRIAL * NOFF];
  for (int s = 0; s < NSEED; s++)
    for (int g = 0; g < NGEN; g++)
      for (int i = 0; i < NTRIAL; i++) { /* as st_int_trial draws them (type i mod 4) */
        stConfig c = cfg;
        c.run_seed = s + 1;
        const int k = i % 4;
        stRng r = st_rng_keyed(st_config_rng_seed(&c), ST_RNG_INTEGRATED, (uint64_t)g, 0, (uint64_t)i);
        double o[3], o0[3], t[3], t0[3];
        st_scene_object(&sc, k, 1, &r, o);
        st_scene_target(&sc, k % 2, &r, t);
        st_scene_object(&sc, k, 0, NULL, o0);
        st_scene_target(&sc, k % 2, NULL, t0);
        double *v = &off[s][(g * NTRIAL + i) * NOFF];
        v[0] = o[0] - o0[0], v[1] = o[1] - o0[1];
        for (int d = 0; d < 3; d++) v[2 + d] = t[d] - t0[d];
      }
  double rmax = 0;
  int same = 0;
  for (int a = 0; a < NSEED; a++)
    for (int b = a + 1; b < NSEED; b++) {
      const double r = fabs(corr(off[a], off[b], NGEN * NTRIAL * NOFF));
      if (r > rmax) rmax = r;
      for (int k = 0; k < NGEN * NTRIAL; k++)
        same += !memcmp(&off[a][k * NOFF], &off[b][k * NOFF], sizeof(double) * NOFF);
    }
  printf("trial offsets, seeds 1-%d, generations 0-%d, %d trials: largest |correlation| between two "
         "seeds %.3f (%d numbers each); (seed pair, generation, trial) identical: %d of %d\n",
         NSEED, NGEN - 1, NTRIAL, rmax, NGEN * NTRIAL * NOFF, same,
         NSEED * (NSEED - 1) / 2 * NGEN * NTRIAL);
  long samekey = 0;
  for (int a = 1; a <= NSEED; a++)
    for (int b = a + 1; b <= NSEED; b++) {
      stConfig ca = cfg, cb = cfg;
      ca.run_seed = a, cb.run_seed = b;
      for (int g = 0; g < NGEN; g++)
        for (int ind = 0; ind < cfg.ga_population; ind++)
          for (int i = 0; i < NTRIAL; i++)
            samekey += st_rng_keyed(st_config_rng_seed(&ca), ST_RNG_SOLVER, g, ind, i).key ==
                       st_rng_keyed(st_config_rng_seed(&cb), ST_RNG_SOLVER, g, ind, i).key;
    }
  printf("solver keys equal between two seeds (same generation, individual, trial): %ld\n", samekey);
  /* the assembled population */
  static stAssembly as[NSEED];
  for (int s = 0; s < NSEED; s++) {
    stConfig c = cfg;
    c.run_seed = s + 1;
    if (st_assemble_population(&c, &as[s], err, sizeof err)) return fail(err);
  }
  int base_same = 1;
  for (int s = 1; s < NSEED; s++)
    for (int i = 0; i < as[0].count; i++)
      if (memcmp(as[0].genome[i].gene, as[s].genome[i].gene, sizeof(uint16_t) * ST_GENES_BASE))
        base_same = 0;
  const int ngenes = as[0].genome[0].ngenes;
  double lo = 1, hi = 0;
  for (int a = 0; a < NSEED; a++)
    for (int b = a + 1; b < NSEED; b++) {
      long eq = 0;
      for (int i = 0; i < as[0].count; i++) eq += bits_equal(&as[a].genome[i], &as[b].genome[i], ST_GENES_BASE);
      const double f = (double)eq / ((double)as[0].count * (ngenes - ST_GENES_BASE) * 16);
      if (f < lo) lo = f;
      if (f > hi) hi = f;
    }
  printf("assembled population: %d genotypes from %d files; genes 0-%d of individual i the same in "
         "every seed: %s; bits of genes %d-%d equal between two seeds: %.4f-%.4f\n",
         as[0].count, as[0].nfiles, ST_GENES_BASE - 1, base_same ? "yes" : "no", ST_GENES_BASE,
         ngenes - 1, lo, hi);
  /* mutation flips: one bit per (generation, child, gene bit) */
  uint8_t mask[ST_GENOME_MAX_GENES];
  st_genome_mask_new_genes(mask, ngenes);
  const int G1 = 30, nbits = ngenes * 16;
  const int E = cfg.ga_elites, N = cfg.ga_population;
  const size_t per = (size_t)G1 * (size_t)(N - E) * (size_t)nbits;
  unsigned char *flip = calloc((size_t)NSEED * per, 1);
  if (!flip) return fail("out of memory");
  long nf[NSEED] = {0};
  for (int s = 0; s < NSEED; s++) {
    stConfig c = cfg;
    c.run_seed = s + 1;
    for (int g = 1; g <= G1; g++)
      for (int i = E; i < N; i++) {
        stGenome z;
        memset(&z, 0, sizeof z);
        z.ngenes = ngenes;
        stRng r = st_rng_keyed(st_config_rng_seed(&c), ST_RNG_MUTATE, (uint64_t)g, (uint64_t)i, 0);
        nf[s] += st_ga_mutate(&z, mask, cfg.ga_mutation_rate_integrated, &r);
        unsigned char *f = flip + (size_t)s * per + ((size_t)(g - 1) * (size_t)(N - E) + (size_t)(i - E)) * (size_t)nbits;
        for (int b = 0; b < nbits; b++) f[b] = (unsigned char)(z.gene[b / 16] >> (b % 16) & 1);
      }
  }
  printf("mutation flips, generations 1-%d, children %d-%d, rate %g: seed 1 %ld; shared with seed 1 "
         "(chance: %.0f):", G1, E, N - 1, cfg.ga_mutation_rate_integrated, nf[0],
         nf[0] * cfg.ga_mutation_rate_integrated);
  for (int s = 1; s < NSEED; s++) {
    long shared = 0;
    for (size_t k = 0; k < per; k++) shared += flip[k] & flip[(size_t)s * per + k];
    printf(" seed %d %ld", s + 1, shared);
  }
  printf("\n");
  free(flip);
  for (int s = 0; s < NSEED; s++) st_assembly_free(&as[s]);
  /* keys shared between runs: seeds 1-10, every stream, coordinates 0-2 */
  enum { KS = 10, KST = ST_RNG_HANDOVER_SOLVER, KC = 3 };
  static uint64_t key[KS * KST * KC * KC * KC];
  int n = 0;
  for (int s = 1; s <= KS; s++) {
    stConfig c = cfg;
    c.run_seed = s;
    for (int st = 1; st <= KST; st++)
      for (int g = 0; g < KC; g++)
        for (int i = 0; i < KC; i++)
          for (int t = 0; t < KC; t++) key[n++] = st_rng_keyed(st_config_rng_seed(&c), (stRngStream)st, g, i, t).key;
  }
  qsort(key, (size_t)n, sizeof key[0], cmp_u64);
  int dup = 0;
  for (int k = 1; k < n; k++) dup += key[k] == key[k - 1];
  printf("run.rng_seed = %s: keys of seeds 1-%d x streams 1-%d x coordinates 0-%d repeated: %d of %d\n",
         st_config_enum_name("run", "rng_seed", cfg.run_rng_seed), KS, KST, KC - 1, dup, n);
  /* every key the integrated runs of seeds 1-5 use (100 generations): shared between two? */
  const int NG = cfg.ga_integrated_generations, NT = cfg.integrated_trials;
  const size_t cap = (size_t)NSEED * ((size_t)N + (size_t)(NG - 1) * (size_t)(N - E) +
                                      (size_t)NG * (size_t)NT + (size_t)NG * (size_t)N * (size_t)NT);
  usedKey *u = malloc(sizeof *u * cap);
  if (!u) return fail("out of memory");
  size_t m = 0;
  for (int s = 1; s <= NSEED; s++) {
    stConfig c = cfg;
    c.run_seed = s;
    const uint64_t seed = st_config_rng_seed(&c);
    for (int i = 0; i < N; i++) u[m++] = (usedKey){st_rng_keyed(seed, ST_RNG_GROW, 0, i, 0).key, s, ST_RNG_GROW, 0, i, 0};
    for (int g = 1; g < NG; g++)
      for (int i = E; i < N; i++) u[m++] = (usedKey){st_rng_keyed(seed, ST_RNG_MUTATE, g, i, 0).key, s, ST_RNG_MUTATE, g, i, 0};
    for (int g = 0; g < NG; g++)
      for (int t = 0; t < NT; t++) u[m++] = (usedKey){st_rng_keyed(seed, ST_RNG_INTEGRATED, g, 0, t).key, s, ST_RNG_INTEGRATED, g, 0, t};
    for (int g = 0; g < NG; g++)
      for (int i = 0; i < N; i++)
        for (int t = 0; t < NT; t++) u[m++] = (usedKey){st_rng_keyed(seed, ST_RNG_SOLVER, g, i, t).key, s, ST_RNG_SOLVER, g, i, t};
  }
  qsort(u, m, sizeof *u, cmp_used);
  int shared = 0;
  for (size_t k = 1; k < m; k++)
    if (u[k].key == u[k - 1].key) {
      shared++;
      printf("  shared: seed %d stream %d (%d, %d, %d) = seed %d stream %d (%d, %d, %d)\n", u[k - 1].seed,
             u[k - 1].stream, u[k - 1].g, u[k - 1].i, u[k - 1].t, u[k].seed, u[k].stream, u[k].g, u[k].i, u[k].t);
    }
  printf("keys the integrated runs of seeds 1-%d use (growth, mutation, offsets, solver; %d generations) "
         "shared between two: %d of %zu\n", NSEED, NG, shared, m);
  free(u);
  return 0;
}

/* ---- founders ---- */

static int cmd_founders(int argc, char **argv) {
  if (argc < 2) return fail("founders STUDY COND [G,G,...]");
  char path[1024], err[512];
  static stGenomeSet best[NSEED];
  stAssembly as;
  for (int s = 0; s < NSEED; s++) {
    snprintf(path, sizeof path, "%s/int-%s-s%d/config.ini", argv[0], argv[1], s + 1);
    stConfig cfg;
    if (load(path, NULL, 0, &cfg)) return 1;
    if (s == 0 && st_assemble_population(&cfg, &as, err, sizeof err)) return fail(err);
    snprintf(path, sizeof path, "%s/int-%s-s%d/best.genome", argv[0], argv[1], s + 1);
    if (st_genome_set_read(path, 0, &best[s], err, sizeof err)) return fail(err);
    printf("seed %d: the best's founder (of the %d assembled genotypes) by generation:", s + 1, as.taken);
    int last = -2;
    for (int g = 0; g < best[s].count; g++) {
      int f = -1;
      for (int t = 0; t < as.taken && f < 0; t++)
        if (!memcmp(as.genome[t].gene, best[s].genome[g].gene, sizeof(uint16_t) * ST_GENES_BASE)) f = t;
      if (f != last) printf(" %d from %d", f, g);
      last = f;
    }
    printf(" (to %d)\n", best[s].count - 1);
  }
  const char *list = argc > 2 ? argv[2] : "10,11,21,22";
  for (const char *p = list; *p;) {
    const int g = atoi(p);
    double lo = 1, hi = 0;
    for (int a = 0; a < NSEED; a++)
      for (int b = a + 1; b < NSEED; b++) {
        if (g >= best[a].count || g >= best[b].count) continue;
        const stGenome *x = &best[a].genome[g], *y = &best[b].genome[g];
        const double f = (double)bits_equal(x, y, ST_GENES_BASE) / ((x->ngenes - ST_GENES_BASE) * 16.0);
        if (f < lo) lo = f;
        if (f > hi) hi = f;
      }
    printf("generation %d: bits of the bests' genes %d- equal between two seeds: %.3f-%.3f\n", g,
           ST_GENES_BASE, lo, hi);
    p += strcspn(p, ",");
    if (*p) p++;
  }
  st_assembly_free(&as);
  for (int s = 0; s < NSEED; s++) st_genome_set_free(&best[s]);
  return 0;
}

/* ---- eval, breed ---- */

typedef struct evaluator {
  stProtocol *p;
  stIntegratedDef def;
  stWorkspace ws;
  int arch;
} evaluator;

static int eval_open(evaluator *ev, const stConfig *cfg) {
  char err[512];
  memset(ev, 0, sizeof *ev);
  if (st_protocol_create(cfg, &ev->p, err, sizeof err)) return fail(err);
  st_integrated_def_from_config(cfg, &ev->def);
  ev->arch = cfg->network_arch;
  return 0;
}

static int eval_one(evaluator *ev, const stGenome *g, int generation, int individual, stIntEvaluation *e) {
  char err[512];
  stNetParams np;
  if (st_net_decode(&ev->p->net, (stNetArch)ev->arch, g, &np, err, sizeof err)) return fail(err);
  if (st_int_evaluate(ev->p, &ev->def, &ev->ws, generation, individual, &np, e, err, sizeof err))
    return fail(err);
  return 0;
}

static void eval_close(evaluator *ev) {
  st_workspace_free(&ev->ws);
  st_protocol_destroy(ev->p);
}

static int cmd_eval(int argc, char **argv) {
  if (argc < 6) return fail("eval CONFIG GENOMES RECORD SEED G0 G1");
  stConfig cfg;
  if (load(argv[0], NULL, 0, &cfg)) return 1;
  cfg.run_seed = atoi(argv[3]);
  char err[512];
  stGenomeSet set;
  if (st_genome_set_read(argv[1], 0, &set, err, sizeof err)) return fail(err);
  const int rec = atoi(argv[2]), g0 = atoi(argv[4]), g1 = atoi(argv[5]);
  if (rec < 0 || rec >= set.count) return fail("RECORD out of range");
  evaluator ev;
  if (eval_open(&ev, &cfg)) return 1;
  printf("generation,F,F_int,F_pred,bonus,bonus_auto,successes,trials\n");
  for (int g = g0; g <= g1; g++) {
    stIntEvaluation e;
    if (eval_one(&ev, &set.genome[rec], g, 0, &e)) return 1;
    printf("%d,%.17g,%.17g,%.17g,%g,%g,%d,", g, e.fitness, e.f_int, e.f_pred, e.bonus, e.bonus_auto,
           e.successes);
    for (int i = 0; i < e.ntrials; i++) printf("%d", e.success[i]);
    printf("\n");
    fflush(stdout);
  }
  eval_close(&ev);
  st_genome_set_free(&set);
  return 0;
}

/* a checkpoint's "# generation" and "# done" header lines */
static void ckpt_header(const char *path, int *generation, int *done) {
  FILE *f = fopen(path, "r");
  char line[256];
  *generation = -1, *done = 0;
  while (f && fgets(line, sizeof line, f) && line[0] == '#') {
    if (sscanf(line, "# generation %d", generation) == 1) continue;
    if (sscanf(line, "# done %d", done) == 1) continue;
  }
  if (f) fclose(f);
}

static int cmd_breed(int argc, char **argv) {
  if (argc < 4) return fail("breed CONFIG CHECKPOINT SEED K");
  stConfig cfg;
  if (load(argv[0], NULL, 0, &cfg)) return 1;
  cfg.run_seed = atoi(argv[2]);
  const int K = atoi(argv[3]);
  int G, done;
  ckpt_header(argv[1], &G, &done);
  char err[512];
  stGenomeSet set;
  if (st_genome_set_read(argv[1], 0, &set, err, sizeof err)) return fail(err);
  const int E = cfg.ga_elites, P = cfg.ga_parents, N = cfg.ga_population;
  if (G < 1 || set.count < N || P > 64) return fail("expected a checkpoint of generation >= 1");
  const int ngenes = set.genome[0].ngenes;
  uint8_t mask[ST_GENOME_MAX_GENES];
  st_genome_mask_new_genes(mask, ngenes);
  const double rate = cfg.ga_mutation_rate_integrated;
  static stGenome parent[64];
  stGenome *child = malloc(sizeof *child * (size_t)N);
  if (!child) return fail("out of memory");
  if (done) { /* generation G - 1 ranked: its first P are the parents */
    for (int r = 0; r < P; r++) parent[r] = set.genome[r];
    for (int i = E; i < N; i++) {
      child[i] = parent[(i - E) % P];
      stRng r = st_rng_keyed(st_config_rng_seed(&cfg), ST_RNG_MUTATE, (uint64_t)G, (uint64_t)i, 0);
      st_ga_mutate(&child[i], mask, rate, &r);
    }
    printf("generation %d: parents = generation %d's ranks 0-%d (a stopped run's checkpoint); the "
           "run's children bred from the streams (seed %d, mutate, %d, i)\n", G, G - 1, P - 1,
           cfg.run_seed, G);
  } else { /* generation G bred: recover the parents */
    int have[64] = {0}, bad = 0, elites_ok = 1;
    for (int i = E; i < N; i++) {
      stGenome g = child[i] = set.genome[i];
      stRng r = st_rng_keyed(st_config_rng_seed(&cfg), ST_RNG_MUTATE, (uint64_t)G, (uint64_t)i, 0);
      st_ga_mutate(&g, mask, rate, &r);
      const int rank = (i - E) % P;
      if (!have[rank]) parent[rank] = g, have[rank] = 1;
      else if (memcmp(parent[rank].gene, g.gene, sizeof(uint16_t) * (size_t)ngenes)) bad++;
    }
    for (int e = 0; e < E && e < P; e++)
      if (memcmp(parent[e].gene, set.genome[e].gene, sizeof(uint16_t) * (size_t)ngenes)) elites_ok = 0;
    printf("generation %d: parents recovered from the streams (seed %d, mutate, %d, i): children "
           "disagreeing with their rank's others %d of %d; ranks 0-%d are the elites: %s\n",
           G, cfg.run_seed, G, bad, N - E, E - 1, elites_ok ? "yes" : "no");
  }
  fflush(stdout);
  evaluator ev;
  if (eval_open(&ev, &cfg)) return 1;
  for (int k = -1; k < K; k++) {
    int hits = 0;
    printf("%s: children earning the autonomous bonus:", k < 0 ? "the run's children" : "other streams");
    for (int i = E; i < N; i++) {
      stGenome g;
      if (k < 0) g = child[i];
      else {
        g = parent[(i - E) % P];
        stRng r = st_rng_keyed(0x47u, (stRngStream)(ST_RNG_USER + 1), (uint64_t)k, (uint64_t)G, (uint64_t)i);
        st_ga_mutate(&g, mask, rate, &r);
      }
      stIntEvaluation e;
      if (eval_one(&ev, &g, G, i, &e)) return 1;
      if (e.bonus_auto > 0) {
        hits++;
        printf(" %d (rank %d, auto %g, F %.1f)", i, (i - E) % P, e.bonus_auto, e.fitness);
      }
    }
    printf("; %d of %d\n", hits, N - E);
    fflush(stdout);
  }
  eval_close(&ev);
  free(child);
  st_genome_set_free(&set);
  return 0;
}

int main(int argc, char **argv) {
  if (argc >= 2 && !strcmp(argv[1], "streams")) return cmd_streams(argc - 2, argv + 2);
  if (argc >= 2 && !strcmp(argv[1], "founders")) return cmd_founders(argc - 2, argv + 2);
  if (argc >= 2 && !strcmp(argv[1], "eval")) return cmd_eval(argc - 2, argv + 2);
  if (argc >= 2 && !strcmp(argv[1], "breed")) return cmd_breed(argc - 2, argv + 2);
  fprintf(stderr, "usage: run_independence streams|founders|eval|breed ... (see tools/run_independence.c)\n");
  return 2;
}
