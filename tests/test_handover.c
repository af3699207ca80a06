/* SPDX-License-Identifier: MIT
 * Main-prim's hand-over trials (stage.handover, SPEC 12, docs/PROTOCOL.md "Hand-over trials"):
 * their specs, the roll-in under the caretaker, the scoring from the hand-over, the fallback
 * and their share of F_p (eq. 2.3), checked against a caretaker episode and against eq. 2.3
 * recomputed by hand from the trials' own results. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/config.h"
#include "selftalk/genome.h"
#include "selftalk/integrated.h"
#include "selftalk/trial.h"
#include "test_util.h"

/* the best genotype of a committed primitive run that completed main-prim */
static const char EVOLVED[] = "data/evolved/prims_s2/population.genome";

/* a config's own rules, then its trial kinds' (selftalk/trialkind.h: st_trial_kinds_check),
 * as every run checks them */
static stStatus validate(const stConfig *c, char *err, size_t errsz) {
  stStatus st = st_config_validate(c, err, errsz);
  return st ? st : st_trial_kinds_check(c, NULL, err, errsz);
}

/* main-prim's protocol with stage.handover (and the fallback: rollin < 0; the roll-in's length:
 * |rollin| > 0) and stage.handover_rollin = elite when elite */
static stProtocol *protocol_elite(int handover, int rollin, int elite) {
  stConfig c;
  st_config_default(&c);
  c.stage_stages = ST_STAGES_MAIN;
  c.stage_handover = handover;
  c.stage_handover_fallback = rollin < 0;
  if (rollin < 0) rollin = -rollin;
  if (rollin > 0) c.stage_handover_rollin_steps = rollin;
  c.stage_handover_rollin = elite ? ST_ROLLIN_ELITE : ST_ROLLIN_SELF;
  stProtocol *p = NULL;
  char err[512] = "";
  if (st_protocol_create(&c, &p, err, sizeof err)) fprintf(stderr, "%s\n", err);
  return p;
}

static stProtocol *protocol(int handover, int rollin) { return protocol_elite(handover, rollin, 0); }
static stProtocol *elite_protocol(int elite) { return protocol_elite(1, 0, elite); }

static int evolved_net_at(stNetParams *np, int index);
static int evolved_net(stNetParams *np) { return evolved_net_at(np, 0); }

/* genotype `index` of that population (best first) */
static int evolved_net_at(stNetParams *np, int index) {
  stGenomeSet set;
  char err[512] = "";
  if (st_genome_set_read(EVOLVED, st_arch_ngenes(ST_ARCH_BASE), &set, err, sizeof err)) {
    fprintf(stderr, "%s\n", err);
    return 0;
  }
  const int ok = index < set.count &&
                 st_net_decode(NULL, ST_ARCH_BASE, &set.genome[index], np, err, sizeof err) == ST_OK;
  st_genome_set_free(&set);
  return ok;
}

/* Trials 16..27: open, grasp, move (1 + j / 4) from reach posture k = j % 4, the object
 * within the reach trials' +-2 cm of position k, the target within +-2 cm of T(k mod 2), the
 * primitive's main-prim length (60, 80, 70 steps), the grasp table removal 40 steps after the
 * hand-over, the table kept for open and move, a roll-in of 170 steps; the same in another
 * protocol, other offsets in another generation. The fixed trials are the same with and
 * without stage.handover. The fallback: the fixed posture and object of (primitive, k), the
 * hand-over trial's target. */
static void test_handover_specs(void) {
  stProtocol *p = protocol(1, 0), *off = protocol(0, 0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  CU_ASSERT_PTR_NOT_NULL_FATAL(off);
  CU_ASSERT_EQUAL(st_stage_trials(p, ST_STAGE_MAIN), 28);
  CU_ASSERT_EQUAL(st_stage_trials(p, ST_STAGE_SIMPLE), 16);
  CU_ASSERT_EQUAL(st_stage_trials(off, ST_STAGE_MAIN), 16);
  static const int steps[4] = {100, 60, 80, 70}, table_off[4] = {-1, -1, 40, -1};
  const double T[2][3] = {{0.25, 0.10, 0.17}, {0.25, -0.10, 0.17}}; /* T0 at +y, T1 at -y (SPEC 3) */
  for (int gen = 0; gen < 2; gen++) {
    for (int i = 0; i < ST_PRIM_TRIALS; i++) {
      stTrialSpec a, b;
      st_trial_spec(p, ST_STAGE_MAIN, gen, i, &a);
      st_trial_spec(off, ST_STAGE_MAIN, gen, i, &b);
      CU_ASSERT(memcmp(&a, &b, sizeof a) == 0);
      CU_ASSERT_EQUAL(a.kind, ST_TRIAL_FIXED);
    }
    for (int j = 0; j < ST_TRIAL_MAX_HANDOVER; j++) {
      stTrialSpec t, t2, other, fb;
      st_trial_spec(p, ST_STAGE_MAIN, gen, ST_PRIM_TRIALS + j, &t);
      st_trial_spec(off, ST_STAGE_MAIN, gen, ST_PRIM_TRIALS + j, &t2);
      st_trial_spec(p, ST_STAGE_MAIN, gen + 2, ST_PRIM_TRIALS + j, &other);
      const int prim = 1 + j / 4, k = j % 4;
      CU_ASSERT_EQUAL(t.primitive, prim);
      CU_ASSERT_EQUAL(t.k, k);
      CU_ASSERT(t.kind == ST_TRIAL_HANDOVER && t.j == j);
      CU_ASSERT_EQUAL(t.rollin_steps, 170);
      CU_ASSERT_EQUAL(t.steps, steps[prim]);
      CU_ASSERT_EQUAL(t.table_off_step, table_off[prim]);
      CU_ASSERT(memcmp(t.qhat0, p->posture[ST_PRIM_REACH][k], sizeof t.qhat0) == 0);
      double base[3];
      st_scene_object(&p->scene, k, 0, NULL, base);
      CU_ASSERT(fabs(t.obj[0] - base[0]) <= 0.02 && fabs(t.obj[1] - base[1]) <= 0.02);
      CU_ASSERT(t.obj[0] != base[0] && t.obj[2] == base[2]);
      for (int a = 0; a < 3; a++) CU_ASSERT(fabs(t.target[a] - T[k % 2][a]) <= 0.02 + 1e-12);
      CU_ASSERT(memcmp(t.obj, t2.obj, sizeof t.obj) == 0); /* the spec, not the key, decides */
      CU_ASSERT(memcmp(t.obj, other.obj, sizeof t.obj) != 0);
      st_handover_fallback(p, &t, &fb);
      CU_ASSERT_EQUAL(fb.kind, ST_TRIAL_FIXED);
      CU_ASSERT_EQUAL(fb.primitive, prim);
      CU_ASSERT_EQUAL(fb.index, ST_PRIM_TRIALS + j);
      CU_ASSERT(memcmp(fb.qhat0, p->posture[prim][k], sizeof fb.qhat0) == 0);
      CU_ASSERT(memcmp(fb.obj, base, sizeof base) == 0);
      CU_ASSERT(memcmp(fb.target, t.target, sizeof fb.target) == 0);
      CU_ASSERT_EQUAL(fb.table_off_step, prim == ST_PRIM_MOVE ? 10 : table_off[prim]);
    }
  }
  st_protocol_destroy(p);
  st_protocol_destroy(off);
}

/* what a trace keeps of each step (inputs and outputs: for the roll-in comparisons) */
typedef struct rec {
  int n;
  int word[400], handover[400];
  double obj[400][3], S[400], P[400], pen_table[400], pen_moving[400];
  double in[400][ST_NET_MAX_IN], out[400][ST_NET_MAX_OUT];
} rec;

static void on_step(void *ctx, const stTraceStep *s) {
  rec *r = ctx;
  if (r->n >= 400) return;
  r->word[r->n] = s->word;
  r->handover[r->n] = s->handover;
  memcpy(r->obj[r->n], s->world->obj, sizeof r->obj[0]);
  memcpy(r->in[r->n], s->in, sizeof r->in[0]);
  memcpy(r->out[r->n], s->out, sizeof(double) * (size_t)s->nout);
  r->S[r->n] = s->S;
  r->P[r->n] = s->P;
  r->pen_table[r->n] = s->pen_table;
  r->pen_moving[r->n] = s->pen_moving;
  r->n++;
}

/* nothing is scored in an integrated-free caretaker episode: only the words and states */
static int null_step(void *self, stTraceStep *s) {
  (void)self;
  (void)s;
  return -1;
}

/* A hand-over trial rolls in as the caretaker's chain does: the same words and, bit for bit,
 * the same states up to the step where the caretaker's word first reaches the primitive; from
 * there the primitive's word every step, its main-prim scoring with steps counted from the
 * hand-over (the grasp's moving penalty for its first 40 steps only), its length at most. */
static void test_handover_rollin(void) {
  stProtocol *p = protocol(1, 0);
  stNetParams np;
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  CU_ASSERT_FATAL(evolved_net(&np));
  stWorkspace ws = {NULL, NULL, NULL};
  char err[512] = "";
  int handed = 0;
  for (int j = 0; j < ST_TRIAL_MAX_HANDOVER; j++) {
    stTrialSpec t;
    st_trial_spec(p, ST_STAGE_MAIN, 0, ST_PRIM_TRIALS + j, &t);
    const uint64_t key = st_trial_seed_key(p, 0, 0, ST_PRIM_TRIALS + j);
    static rec h, c;
    memset(&h, 0, sizeof h);
    memset(&c, 0, sizeof c);
    stTrialResult r;
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, NULL, 0, key, &r, on_step, &h, err, sizeof err), ST_OK);
    /* the caretaker's chain from the same start, unscored, the table kept */
    stEpisodeSpec e;
    stWords w;
    st_trial_episode(p, &t, key, &e, &w);
    e.table_off_step = -1;
    w.source = ST_WORDS_CARETAKER;
    stNetController nc;
    const stController ctl = st_net_controller(&nc, &np, NULL, 0);
    const stScorer none = {NULL, null_step, NULL, NULL};
    CU_ASSERT_EQUAL_FATAL(st_episode_run(p, &ws, &e, &ctl, &w, &none, on_step, &c, err, sizeof err), ST_OK);
    int first = -1;
    for (int s = 0; s < c.n && first < 0; s++)
      if (c.word[s] >= t.primitive) first = s;
    if (first < 0 || first >= t.rollin_steps) { /* no hand-over in time: nothing earned */
      CU_ASSERT_EQUAL(r.handover_step, -1);
      CU_ASSERT(r.sum_s == 0.0 && r.sum_p == 0.0 && r.success == 0 && r.steps_run == 0);
      CU_ASSERT_EQUAL(r.steps, t.steps);
      continue;
    }
    handed++;
    CU_ASSERT_EQUAL(r.handover_step, first);
    for (int s = 0; s < first; s++) {
      CU_ASSERT_EQUAL(h.word[s], c.word[s]);
      CU_ASSERT(memcmp(h.obj[s], c.obj[s], sizeof h.obj[s]) == 0);
      CU_ASSERT(h.S[s] == 0.0 && h.P[s] == 0.0 && h.handover[s] == -1);
    }
    CU_ASSERT(h.n <= first + t.steps);
    CU_ASSERT_EQUAL(r.steps_run, h.n - first);
    double sum_s = 0.0;
    for (int s = first; s < h.n; s++) {
      CU_ASSERT_EQUAL(h.word[s], t.primitive);
      CU_ASSERT_EQUAL(h.handover[s], first);
      sum_s += h.S[s];
      if (t.primitive == ST_PRIM_GRASP) /* table, and object moving before the table goes */
        CU_ASSERT_EQUAL(h.P[s], h.pen_table[s] + (s - first < 40 ? h.pen_moving[s] : 0.0));
    }
    if (r.end == ST_END_FULL) CU_ASSERT_DOUBLE_EQUAL(r.sum_s, sum_s, 1e-9);
  }
  CU_ASSERT(handed >= 4); /* this individual reaches, and often opens, from most starts */
  st_workspace_free(&ws);
  st_protocol_destroy(p);
}

/* A roll-in that cannot hand over (the caretaker first speaks at step 1, the roll-in must hand
 * over before step 1) scores nothing over the primitive's length, or, with
 * stage.handover_fallback, falls back: the result is, bit for bit, the fallback trial's. */
static void test_handover_fallback(void) {
  stProtocol *p = protocol(1, -1), *none = protocol(1, 1);
  CU_ASSERT_PTR_NOT_NULL_FATAL(none);
  stNetParams np;
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  CU_ASSERT_FATAL(evolved_net(&np));
  stWorkspace ws = {NULL, NULL, NULL};
  char err[512] = "";
  for (int j = 0; j < ST_TRIAL_MAX_HANDOVER; j += 3) {
    stTrialSpec t, fb;
    st_trial_spec(p, ST_STAGE_MAIN, 3, ST_PRIM_TRIALS + j, &t);
    st_handover_fallback(p, &t, &fb);
    const uint64_t key = st_trial_seed_key(p, 3, 7, ST_PRIM_TRIALS + j);
    stTrialResult r, want;
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &np, NULL, NULL, 0, key, &r, NULL, NULL, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &fb, &np, NULL, NULL, 0, key, &want, NULL, NULL, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(r.handover_step, -1);
    CU_ASSERT(r.sum_s == want.sum_s && r.sum_p == want.sum_p && r.success == want.success &&
              r.steps == want.steps && r.steps_run == want.steps_run);
    CU_ASSERT(want.sum_s > 0.0);
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(none, &ws, &t, &np, NULL, NULL, 0, key, &r, NULL, NULL, err, sizeof err), ST_OK);
    CU_ASSERT(r.handover_step == -1 && r.sum_s == 0.0 && r.sum_p == 0.0 && r.success == 0 &&
              r.steps == t.steps && r.steps_run == 0 && r.end == ST_END_QUIET);
  }
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  st_protocol_destroy(none);
}

/* eq. 2.3's sums per primitive, from trials run one by one */
typedef struct handSums {
  double sp[4], bonus[4]; /* sums of S - P; 10 a success */
  long n[4];              /* the trials' lengths */
  int successes;
} handSums;

/* runs trial i of protocol p alone (individual ind, generation gen) and adds it to h */
static stTrialResult hand_trial(const stProtocol *p, stWorkspace *ws, const stNetParams *np,
                                int gen, int ind, int i, handSums *h) {
  stTrialSpec t;
  st_trial_spec(p, ST_STAGE_MAIN, gen, i, &t);
  stTrialResult r;
  char err[512] = "";
  memset(&r, 0, sizeof r);
  CU_ASSERT_EQUAL(st_test_net_trial(p, ws, &t, np, NULL, NULL, 0, st_trial_seed_key(p, gen, ind, i), &r, NULL, NULL,
                               err, sizeof err), ST_OK);
  h->sp[t.primitive] += r.sum_s - r.sum_p;
  h->n[t.primitive] += r.steps;
  h->bonus[t.primitive] += 10.0 * r.success;
  h->successes += r.success;
  return r;
}

/* eq. 2.3 from the sums (lengths expected want_n), F their harmonic mean (F_p floored at
 * 0.001), against e */
static void check_eq_2_3(const stEvaluation *e, const handSums *h, const long want_n[4]) {
  double inv = 0.0;
  for (int k = 0; k < 4; k++) {
    CU_ASSERT_EQUAL(h->n[k], want_n[k]);
    const double fp = h->bonus[k] + 100.0 / (double)h->n[k] * h->sp[k];
    CU_ASSERT_DOUBLE_EQUAL(e->fp[k], fp, 1e-9 * fabs(fp));
    inv += 1.0 / (fp > 0.001 ? fp : 0.001);
  }
  CU_ASSERT_DOUBLE_EQUAL(e->fitness, 4.0 / inv, 1e-9 * e->fitness);
}

/* The evaluation: F_p of eq. 2.3 over a primitive's fixed and hand-over trials (bonus 10 per
 * success, 100 / N_p times the sum of S - P, N_p the trials' full lengths), F their harmonic
 * mean, recomputed here from each trial run alone; the counts of the evaluation. */
static void test_handover_fitness(void) {
  stProtocol *p = protocol(1, 0), *off = protocol(0, 0);
  stNetParams np;
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  CU_ASSERT_PTR_NOT_NULL_FATAL(off);
  CU_ASSERT_FATAL(evolved_net(&np));
  stWorkspace ws = {NULL, NULL, NULL};
  char err[512] = "";
  const int gen = 1, ind = 5;
  stEvaluation e, e0;
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(p, &ws, ST_STAGE_MAIN, gen, ind, &np, NULL, &e, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(off, &ws, ST_STAGE_MAIN, gen, ind, &np, NULL, &e0, err, sizeof err), ST_OK);
  handSums h;
  memset(&h, 0, sizeof h);
  int hs = 0, handovers = 0;
  CU_ASSERT_EQUAL_FATAL(st_stage_trials(p, ST_STAGE_MAIN), 28);
  for (int i = 0; i < 28; i++) {
    const stTrialResult r = hand_trial(p, &ws, &np, gen, ind, i, &h);
    if (i < ST_PRIM_TRIALS) {
      CU_ASSERT_EQUAL(e.kind[ST_TRIAL_FIXED].success[i], r.success);
      CU_ASSERT_EQUAL(e0.kind[ST_TRIAL_FIXED].success[i], r.success);
    } else {
      CU_ASSERT_EQUAL(e.kind[ST_TRIAL_HANDOVER].success[i - ST_PRIM_TRIALS], r.success);
      hs += r.success;
      handovers += r.handover_step >= 0;
    }
  }
  const long want_n[4] = {400, 480, 640, 560};
  check_eq_2_3(&e, &h, want_n);
  CU_ASSERT_EQUAL(e.fp[0], e0.fp[0]); /* reach has no hand-over trials */
  CU_ASSERT(e.fp[3] != e0.fp[3]);
  CU_ASSERT_EQUAL(e.ntrials, 28);
  CU_ASSERT_EQUAL(e0.ntrials, 16);
  CU_ASSERT_EQUAL(e0.kind[ST_TRIAL_HANDOVER].trials, 0);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_HANDOVER].trials, 12);
  CU_ASSERT_EQUAL(e.successes, h.successes);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_HANDOVER].successes, hs);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_HANDOVER].count, handovers);
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  st_protocol_destroy(off);
}

/* postures.vary_trials = extra: F_p of eq. 2.3 over a primitive's 16 fixed trials and its
 * varied trials (open and grasp 8 trials each: 480 and 640 steps; reach 400, move 280), F their
 * harmonic mean, recomputed from each trial run alone; the fixed trials solved as without the
 * varied ones, the counts; the hand-over trials join when stage.handover is on too (44 trials) */
static void test_varied_fitness(void) {
  stConfig c;
  st_config_default(&c);
  c.stage_stages = ST_STAGES_MAIN;
  stProtocol *off = NULL, *p = NULL, *both = NULL;
  char err[512] = "";
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &off, err, sizeof err), ST_OK);
  c.postures_vary_starts = 1, c.postures_vary_trials = ST_VARY_EXTRA;
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &p, err, sizeof err), ST_OK);
  c.stage_handover = 1;
  CU_ASSERT_EQUAL_FATAL(st_protocol_create(&c, &both, err, sizeof err), ST_OK);
  stNetParams np;
  CU_ASSERT_FATAL(evolved_net(&np));
  stWorkspace ws = {NULL, NULL, NULL};
  const int gen = 2, ind = 4;
  stEvaluation e, e0, eb;
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(p, &ws, ST_STAGE_MAIN, gen, ind, &np, NULL, &e, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(off, &ws, ST_STAGE_MAIN, gen, ind, &np, NULL, &e0, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(both, &ws, ST_STAGE_MAIN, gen, ind, &np, NULL, &eb, err, sizeof err), ST_OK);
  handSums h;
  memset(&h, 0, sizeof h);
  int vs = 0;
  for (int i = 0; i < 36; i++) {
    if (i >= 16 && i < 28) continue;
    const stTrialResult r = hand_trial(p, &ws, &np, gen, ind, i, &h);
    if (i < 16) {
      CU_ASSERT_EQUAL(e.kind[ST_TRIAL_FIXED].success[i], r.success);
      CU_ASSERT_EQUAL(e0.kind[ST_TRIAL_FIXED].success[i], r.success);
    } else {
      CU_ASSERT_EQUAL(e.kind[ST_TRIAL_VARIED].success[i - 28], r.success);
      CU_ASSERT_EQUAL(eb.kind[ST_TRIAL_VARIED].success[i - 28], r.success);
      vs += r.success;
    }
  }
  const long want_n[4] = {400, 480, 640, 280};
  check_eq_2_3(&e, &h, want_n);
  CU_ASSERT(e.fp[0] == e0.fp[0] && e.fp[3] == e0.fp[3]); /* no varied reach or move trials */
  CU_ASSERT(e.ntrials == 24 && e.kind[ST_TRIAL_VARIED].trials == 8 && e.kind[ST_TRIAL_HANDOVER].trials == 0);
  CU_ASSERT(e0.kind[ST_TRIAL_VARIED].trials == 0 && eb.ntrials == 36 && eb.kind[ST_TRIAL_VARIED].trials == 8 && eb.kind[ST_TRIAL_HANDOVER].trials == 12);
  CU_ASSERT_EQUAL(e.successes, h.successes);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_VARIED].successes, vs);
  CU_ASSERT(vs > 0); /* prims_s2's best solves drawn starts too: the sums are not all failures */
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  st_protocol_destroy(off);
  st_protocol_destroy(both);
}

/* main-prim without chained trials (off) and with cfg's (p), both evaluated for genotype
 * `index` of EVOLVED at generation 2, individual 3 (e0, e); ws and np for the trials rerun */
typedef struct chainCase {
  stProtocol *off, *p;
  stNetParams np;
  stWorkspace ws;
  stEvaluation e, e0;
} chainCase;

static int chain_case(const stConfig *cfg, int index, chainCase *k) {
  stConfig c;
  st_config_default(&c);
  c.stage_stages = ST_STAGES_MAIN;
  memset(k, 0, sizeof *k);
  char err[512] = "";
  if (st_protocol_create(&c, &k->off, err, sizeof err) || st_protocol_create(cfg, &k->p, err, sizeof err) ||
      !evolved_net_at(&k->np, index) ||
      st_stage_evaluate(k->p, &k->ws, ST_STAGE_MAIN, 2, 3, &k->np, NULL, &k->e, err, sizeof err) ||
      st_stage_evaluate(k->off, &k->ws, ST_STAGE_MAIN, 2, 3, &k->np, NULL, &k->e0, err, sizeof err)) {
    fprintf(stderr, "%s\n", err);
    return 0;
  }
  return 1;
}

static void chain_case_free(chainCase *k) {
  st_workspace_free(&k->ws);
  st_protocol_destroy(k->p);
  st_protocol_destroy(k->off);
}

/* Main-prim's chained trials (stage.kind[ST_TRIAL_CHAINED].trials): F is the harmonic mean of the four F_p,
 * which they leave unchanged, and f_chain; f_chain is eq. 2.14 over the integrated stage's
 * trials with the caretaker's words: B (10 per move or focus bonus) + 100 / (n x 240) times
 * the sum of max(0, S - P), recomputed here from each trial run alone; the stage's trial and
 * success counts include them. */
static void test_chain_fitness(void) {
  stConfig c;
  st_config_default(&c);
  c.stage_stages = ST_STAGES_MAIN;
  c.stage_chain_trials = 3;
  chainCase cc;
  CU_ASSERT_FATAL(chain_case(&c, 0, &cc));
  stProtocol *p = cc.p;
  const stNetParams np = cc.np;
  const stEvaluation e = cc.e, e0 = cc.e0;
  const int gen = 2, ind = 3;
  char err[512] = "";
  stIntegratedDef def;
  st_chain_def_from_config(&p->cfg, &def);
  CU_ASSERT_EQUAL(def.arch, ST_ARCH_BASE);
  CU_ASSERT_EQUAL(def.steps, 240);
  double bonus = 0.0, points = 0.0;
  int successes = 0;
  for (int i = 0; i < 3; i++) {
    stIntPlan plan;
    stIntTrialResult r;
    CU_ASSERT_EQUAL_FATAL(st_int_trial_run(p, &def, &cc.ws, gen, ind, i, &np, &plan, &r, NULL, NULL,
                                           NULL, err, sizeof err), ST_OK);
    CU_ASSERT(plan.words == ST_WORDS_CARETAKER && plan.fitness == ST_FIT_INTEGRATED &&
              plan.bonus_factor == 1.0);
    CU_ASSERT_EQUAL(e.kind[ST_TRIAL_CHAINED].success[i], r.success);
    bonus += 10.0 * (r.success + r.focus_bonus);
    points += fmax(0.0, r.sum_s - r.sum_p);
    successes += r.success;
  }
  const double f_chain = bonus + 100.0 / (3.0 * 240.0) * points;
  CU_ASSERT_DOUBLE_EQUAL(e.kind[ST_TRIAL_CHAINED].fitness, f_chain, 1e-9 * f_chain);
  CU_ASSERT(e.kind[ST_TRIAL_CHAINED].fitness > 0.0);
  double inv = 1.0 / f_chain;
  for (int k = 0; k < 4; k++) {
    CU_ASSERT_EQUAL(e.fp[k], e0.fp[k]);
    inv += 1.0 / e0.fp[k];
  }
  CU_ASSERT_DOUBLE_EQUAL(e.fitness, 5.0 / inv, 1e-9 * e.fitness);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_CHAINED].trials, 3);
  CU_ASSERT_EQUAL(e.ntrials, 19);
  CU_ASSERT_EQUAL(e.successes, e0.successes + successes);
  /* the integrated trials' keys act in main-prim with chained trials only */
  st_config_default(&c);
  c.integrated_steps = 200;
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "integrated.steps");
  c.stage_chain_trials = 2;
  CU_ASSERT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  c.integrated_trials = 4; /* the chained trials' count is stage.kind[ST_TRIAL_CHAINED].trials */
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "integrated.trials");
  chain_case_free(&cc);
}

/* stage.chain_combine = sum: F is the harmonic mean of the four F_p (those of the protocol
 * without chained trials) plus (fixed trials solved / 16)^chain_gate times F_chain, and
 * F_chain is eq. 2.14 plus chain_progress times the mean over the chained trials of the
 * furthest word the caretaker said (reach 0 .. move 3), read here from each trial's trace. */
/* stage.chain_complete: an evaluation of 16 fixed, 12 hand-over, 8 varied and 8 chained
 * trials completes under all only with all 44 solved; under fixed_chained with the 16 and the 8
 * chained solved, whatever the hand-over and varied ones; without chained trials (simple-prim
 * generations of a prims run) both rules are every trial */
/* kind k's trials of an evaluation: n run, those of `solved` (bit j: trial j) solved, the
 * totals kept */
static void set_kind(stEvaluation *e, stTrialKind k, int n, unsigned long solved) {
  stKindEvaluation *r = &e->kind[k];
  e->ntrials += n - r->trials;
  e->successes -= r->successes;
  r->trials = n;
  r->successes = 0;
  for (int j = 0; j < ST_TRIAL_KIND_MAX; j++) {
    r->success[j] = j < n && (solved >> j & 1ul);
    r->successes += r->success[j];
  }
  e->successes += r->successes;
}

static void test_evaluation_completes(void) {
  stConfig all, fc;
  st_config_default(&all);
  st_config_default(&fc);
  fc.stage_chain_complete = ST_CHAIN_COMPLETE_FIXED_CHAINED;
  stEvaluation e;
  memset(&e, 0, sizeof e);
  set_kind(&e, ST_TRIAL_FIXED, 16, 0xfffful);
  set_kind(&e, ST_TRIAL_HANDOVER, 12, 0xffful);
  set_kind(&e, ST_TRIAL_VARIED, 8, 0xfful);
  set_kind(&e, ST_TRIAL_CHAINED, 8, 0xfful);
  CU_ASSERT_EQUAL(e.ntrials, 44);
  CU_ASSERT(st_evaluation_completes(&all, &e) && st_evaluation_completes(&fc, &e));
  set_kind(&e, ST_TRIAL_HANDOVER, 12, 0x1fful);
  set_kind(&e, ST_TRIAL_VARIED, 8, 0x1ful);
  CU_ASSERT(!st_evaluation_completes(&all, &e) && st_evaluation_completes(&fc, &e));
  set_kind(&e, ST_TRIAL_CHAINED, 8, 0x7ful);
  CU_ASSERT(!st_evaluation_completes(&fc, &e));
  set_kind(&e, ST_TRIAL_CHAINED, 8, 0xfful);
  set_kind(&e, ST_TRIAL_FIXED, 16, 0x7ffful);
  CU_ASSERT(!st_evaluation_completes(&fc, &e));
  /* postures.vary_replace_generations: the 16 and the 8 chained solved, but the open and grasp
   * trials from drawn starts (no varied trials run), under fixed_chained: not the thesis's 16 */
  set_kind(&e, ST_TRIAL_FIXED, 16, 0xfffful);
  set_kind(&e, ST_TRIAL_VARIED, 0, 0);
  CU_ASSERT_EQUAL(e.ntrials, 36);
  CU_ASSERT(st_evaluation_completes(&fc, &e));
  e.kind[ST_TRIAL_FIXED].count = 8;
  CU_ASSERT(!st_evaluation_completes(&fc, &e));
  /* and under chain_complete = all, every trial solved (the 16 from drawn starts): with extra
   * the drawn starts are its first phase, so still not complete; under replace they are the
   * protocol, so complete */
  set_kind(&e, ST_TRIAL_HANDOVER, 12, 0xffful);
  all.postures_vary_starts = 1, all.postures_vary_trials = ST_VARY_EXTRA;
  all.postures_vary_replace_generations = 30;
  CU_ASSERT(!st_evaluation_completes(&all, &e));
  all.postures_vary_trials = ST_VARY_REPLACE, all.postures_vary_replace_generations = 0;
  CU_ASSERT(st_evaluation_completes(&all, &e));
  st_config_default(&all);
  /* simple-prim: 16 trials, no chained ones */
  memset(&e, 0, sizeof e);
  set_kind(&e, ST_TRIAL_FIXED, 16, 0x7ffful);
  CU_ASSERT(!st_evaluation_completes(&all, &e) && !st_evaluation_completes(&fc, &e));
  set_kind(&e, ST_TRIAL_FIXED, 16, 0xfffful);
  CU_ASSERT(st_evaluation_completes(&all, &e) && st_evaluation_completes(&fc, &e));
  /* stage.primitives = reach,grasp: 8 fixed trials (reach's and grasp's) and 8 chained */
  memset(&e, 0, sizeof e);
  set_kind(&e, ST_TRIAL_FIXED, 8, 0xfful);
  set_kind(&e, ST_TRIAL_CHAINED, 8, 0xfful);
  CU_ASSERT(st_evaluation_completes(&fc, &e));
  set_kind(&e, ST_TRIAL_FIXED, 8, 0xfdul);
  CU_ASSERT(!st_evaluation_completes(&fc, &e));
}

static void test_chain_sum(void) {
  stConfig c;
  st_config_default(&c);
  c.stage_stages = ST_STAGES_MAIN;
  c.stage_chain_trials = 3;
  c.stage_chain_combine = ST_CHAIN_SUM;
  c.stage_chain_gate = 2.0;
  c.stage_chain_progress = 10.0;
  chainCase cc; /* genotype 60: it fails some fixed trials, so that the gate weighs */
  CU_ASSERT_FATAL(chain_case(&c, 60, &cc));
  stProtocol *p = cc.p;
  const stNetParams np = cc.np;
  const stEvaluation e = cc.e, e0 = cc.e0;
  const int gen = 2, ind = 3;
  char err[512] = "";
  stIntegratedDef def;
  st_chain_def_from_config(&p->cfg, &def);
  double bonus = 0.0, points = 0.0, furthest = 0.0;
  for (int i = 0; i < 3; i++) {
    stIntPlan plan;
    stIntTrialResult r;
    rec *t = calloc(1, sizeof *t);
    CU_ASSERT_FATAL(t != NULL);
    CU_ASSERT_EQUAL_FATAL(st_int_trial_run(p, &def, &cc.ws, gen, ind, i, &np, &plan, &r, NULL, on_step,
                                           t, err, sizeof err), ST_OK);
    int far = 0;
    for (int k = 0; k < t->n; k++) far = t->word[k] > far ? t->word[k] : far;
    furthest += far;
    bonus += 10.0 * (r.success + r.focus_bonus);
    points += fmax(0.0, r.sum_s - r.sum_p);
    free(t);
  }
  CU_ASSERT(furthest > 0.0); /* the term is not empty here */
  const double f_chain = bonus + 100.0 / (3.0 * 240.0) * points + 10.0 * furthest / 3.0;
  CU_ASSERT_DOUBLE_EQUAL(e.kind[ST_TRIAL_CHAINED].fitness, f_chain, 1e-9 * f_chain);
  int solved = 0;
  double inv = 0.0;
  for (int i = 0; i < 16; i++) solved += e0.kind[ST_TRIAL_FIXED].success[i];
  for (int k = 0; k < 4; k++) inv += 1.0 / e0.fp[k];
  const double w = (solved / 16.0) * (solved / 16.0);
  CU_ASSERT(solved > 0 && solved < 16);
  CU_ASSERT_DOUBLE_EQUAL(e.fitness, 4.0 / inv + w * f_chain, 1e-9 * e.fitness);
  /* the gate and the progress weight act only where they shape something */
  st_config_default(&c);
  c.stage_chain_progress = 5.0;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "expected stage.chain_trials > 0");
  c.stage_chain_trials = 2;
  CU_ASSERT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  c.stage_chain_gate = 4.0;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.chain_gate");
  ST_ASSERT_CONTAINS(err, "expected stage.chain_combine = sum");
  c.stage_chain_combine = ST_CHAIN_SUM;
  CU_ASSERT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  chain_case_free(&cc);
}

/* The keys: the roll-in length acts only with stage.handover; the caretaker's keys are read by
 * main-prim only when its hand-over trials hear the caretaker; stage.handover by main-prim
 * only. */
static void test_handover_keys(void) {
  stConfig c;
  char err[512] = "";
  st_config_default(&c);
  CU_ASSERT_EQUAL(c.stage_handover, 0);
  c.stage_handover_rollin_steps = 100;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover_rollin_steps");
  ST_ASSERT_CONTAINS(err, "expected stage.handover = true");
  c.stage_handover = 1;
  CU_ASSERT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  st_config_default(&c);
  c.stage_handover_fallback = 1;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover_fallback");

  st_config_default(&c);
  c.caretaker_grasp_touches = 4;
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "caretaker.grasp_touches");
  c.stage_handover = 1;
  CU_ASSERT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_SIMPLE_PRIM, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover");
}

/* ---- stage.handover_rollin = elite ---- */

/* The elite evaluated under elite roll-ins is, bit for bit, the elite evaluated under its own
 * (self) roll-ins as individual 0, whose solver key every elite roll-in takes: the same
 * network acts both phases. Checked trial by trial against st_trial_run of the self protocol
 * and for the whole evaluation. */
static void test_rollin_elite_self(void) {
  stProtocol *pe = elite_protocol(1), *ps = elite_protocol(0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(pe);
  CU_ASSERT_PTR_NOT_NULL_FATAL(ps);
  stNetParams elite;
  CU_ASSERT_FATAL(evolved_net(&elite));
  stWorkspace ws = {NULL, NULL, NULL};
  char err[512] = "";
  const int gen = 2;
  int handed = 0;
  for (int j = 0; j < ST_TRIAL_MAX_HANDOVER; j++) {
    const int i = ST_PRIM_TRIALS + j;
    stTrialSpec t;
    st_trial_spec(pe, ST_STAGE_MAIN, gen, i, &t);
    /* whoever runs it, an elite roll-in has individual 0's key; a self one its own */
    CU_ASSERT_EQUAL(st_trial_seed_key(pe, gen, 7, i), st_trial_seed_key(ps, gen, 0, i));
    CU_ASSERT_NOT_EQUAL(st_trial_seed_key(ps, gen, 7, i), st_trial_seed_key(ps, gen, 0, i));
    stTrialResult a, b;
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(pe, &ws, &t, &elite, &elite, NULL, 0,
                                              st_trial_seed_key(pe, gen, 7, i), &a, NULL, NULL,
                                              err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(ps, &ws, &t, &elite, NULL, NULL, 0, st_trial_seed_key(ps, gen, 0, i), &b,
                                       NULL, NULL, err, sizeof err), ST_OK);
    CU_ASSERT(memcmp(&a, &b, sizeof a) == 0);
    handed += a.handover_step >= 0;
  }
  CU_ASSERT(handed >= 4);
  stEvaluation e, e0;
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(pe, &ws, ST_STAGE_MAIN, gen, 0, &elite, &elite, &e,
                                                 err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_stage_evaluate(ps, &ws, ST_STAGE_MAIN, gen, 0, &elite, NULL, &e0, err,
                                          sizeof err), ST_OK);
  CU_ASSERT(memcmp(&e, &e0, sizeof e) == 0);
  CU_ASSERT_EQUAL(e.kind[ST_TRIAL_HANDOVER].trials, 12);
  st_workspace_free(&ws);
  st_protocol_destroy(pe);
  st_protocol_destroy(ps);
}

/* Another individual's hand-over trial under elite roll-ins: up to the hand-over step its
 * trace (words, inputs, outputs, object) is the elite's own, bit for bit, run as individual 7
 * against the elite's run as individual 0; it hands over at the same step; from that step the
 * outputs are the individual's: its base network on that step's inputs from a fresh state. */
static void test_rollin_elite_trace(void) {
  stProtocol *p = elite_protocol(1);
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  stNetParams elite, other;
  CU_ASSERT_FATAL(evolved_net(&elite));
  CU_ASSERT_FATAL(evolved_net_at(&other, 60));
  stWorkspace ws = {NULL, NULL, NULL};
  char err[512] = "";
  const int gen = 1;
  int handed = 0, differs = 0;
  for (int j = 0; j < ST_TRIAL_MAX_HANDOVER; j++) {
    const int i = ST_PRIM_TRIALS + j;
    stTrialSpec t;
    st_trial_spec(p, ST_STAGE_MAIN, gen, i, &t);
    static rec me, ind;
    memset(&me, 0, sizeof me);
    memset(&ind, 0, sizeof ind);
    stTrialResult rm, ri;
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &elite, &elite, NULL, 0,
                                              st_trial_seed_key(p, gen, 0, i), &rm, on_step, &me,
                                              err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL_FATAL(st_test_net_trial(p, &ws, &t, &other, &elite, NULL, 0,
                                              st_trial_seed_key(p, gen, 7, i), &ri, on_step, &ind,
                                              err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(ri.handover_step, rm.handover_step);
    const int h = rm.handover_step;
    if (h < 0) continue;
    handed++;
    for (int s = 0; s < h; s++) {
      CU_ASSERT_EQUAL(ind.word[s], me.word[s]);
      CU_ASSERT_EQUAL(ind.handover[s], -1);
      CU_ASSERT(memcmp(ind.in[s], me.in[s], sizeof ind.in[s]) == 0);
      CU_ASSERT(memcmp(ind.out[s], me.out[s], sizeof ind.out[s]) == 0);
      CU_ASSERT(memcmp(ind.obj[s], me.obj[s], sizeof ind.obj[s]) == 0);
    }
    /* the hand-over step: the same inputs, the individual's outputs */
    CU_ASSERT_FATAL(ind.n > h && me.n > h);
    CU_ASSERT(memcmp(ind.in[h], me.in[h], sizeof ind.in[h]) == 0);
    CU_ASSERT_EQUAL(ind.handover[h], h);
    for (int s = h; s < ind.n && s < h + 3; s++) {
      stNetState st;
      double out[ST_NET_MAX_OUT];
      st_net_reset(&other, &st);
      st_net_step(&other, &st, ind.in[s], out);
      CU_ASSERT(memcmp(out, ind.out[s], sizeof(double) * ST_NET_NOUT) == 0);
    }
    differs += memcmp(ind.out[h], me.out[h], sizeof(double) * ST_NET_NOUT) != 0;
  }
  CU_ASSERT(handed >= 4);
  CU_ASSERT_EQUAL(differs, handed); /* genotype 60 is not the elite */
  st_workspace_free(&ws);
  st_protocol_destroy(p);
}

/* Where elite roll-ins cannot act they are refused: stage.handover off, a stage without
 * hand-over trials (simple-prim, the integrated stage), no elites kept; a roll-in network
 * missing under elite or given under self; a network with memory (type A) on either side; and
 * a roll-in on a trial that is not a hand-over trial, where it never acts. */
static void test_rollin_elite_refused(void) {
  stConfig c;
  char err[512] = "";
  st_config_default(&c);
  CU_ASSERT_EQUAL(c.stage_handover_rollin, ST_ROLLIN_SELF);
  c.stage_handover_rollin = ST_ROLLIN_ELITE;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover_rollin");
  ST_ASSERT_CONTAINS(err, "expected stage.handover = true");
  c.stage_handover = 1;
  CU_ASSERT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, ST_CONFIG_MAIN_PRIM, err, sizeof err), ST_OK);
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_SIMPLE_PRIM, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover");
  CU_ASSERT_NOT_EQUAL(st_config_check_stages(&c, ST_CONFIG_INTEGRATED, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover");
  c.ga_elites = 0;
  CU_ASSERT_NOT_EQUAL(validate(&c, err, sizeof err), ST_OK);
  ST_ASSERT_CONTAINS(err, "stage.handover_rollin");
  ST_ASSERT_CONTAINS(err, "ga.elites >= 1");

  stProtocol *pe = elite_protocol(1), *ps = elite_protocol(0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(pe);
  CU_ASSERT_PTR_NOT_NULL_FATAL(ps);
  stNetParams np, a;
  CU_ASSERT_FATAL(evolved_net(&np));
  a = np;
  a.arch = ST_ARCH_A; /* only the field the check reads */
  stNetParams a0; /* another base network: genotype 0's genes shifted */
  CU_ASSERT_FATAL(evolved_net(&a0));
  for (int i = 0; i < (int)(sizeof a0.w_ih / sizeof a0.w_ih[0][0]); i++) (&a0.w_ih[0][0])[i] *= 0.5;
  stWorkspace ws = {NULL, NULL, NULL};
  stEvaluation e;
  CU_ASSERT_EQUAL(st_stage_evaluate(pe, &ws, ST_STAGE_MAIN, 0, 1, &np, NULL, &e, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "stage.handover_rollin = elite");
  CU_ASSERT_EQUAL(st_stage_evaluate(ps, &ws, ST_STAGE_MAIN, 0, 1, &np, &np, &e, err, sizeof err),
                  ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "stage.handover_rollin = self");
  CU_ASSERT_EQUAL(st_stage_rollin_elite(pe, ST_STAGE_SIMPLE), 0);
  CU_ASSERT_EQUAL(st_stage_rollin_elite(pe, ST_STAGE_MAIN), 1);
  CU_ASSERT_EQUAL(st_stage_rollin_elite(ps, ST_STAGE_MAIN), 0);
  stTrialSpec t, fixed;
  st_trial_spec(pe, ST_STAGE_MAIN, 0, ST_PRIM_TRIALS, &t);
  st_trial_spec(pe, ST_STAGE_MAIN, 0, 4, &fixed);
  stTrialResult r;
  CU_ASSERT_EQUAL(st_test_net_trial(pe, &ws, &t, &a, &np, NULL, 0, 1, &r, NULL, NULL, err, sizeof err),
                  ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "without memory");
  CU_ASSERT_EQUAL(st_test_net_trial(pe, &ws, &t, &np, &a, NULL, 0, 1, &r, NULL, NULL, err, sizeof err),
                  ST_ERR_ARG);
  /* on a trial that is not a hand-over trial the roll-in never acts: the individual's alone */
  stTrialResult alone;
  CU_ASSERT_EQUAL(st_test_net_trial(pe, &ws, &fixed, &np, &a0, NULL, 0, 1, &r, NULL, NULL, err,
                                    sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_test_net_trial(pe, &ws, &fixed, &np, NULL, NULL, 0, 1, &alone, NULL, NULL,
                                    err, sizeof err), ST_OK);
  CU_ASSERT(memcmp(&r, &alone, sizeof r) == 0);
  st_workspace_free(&ws);
  st_protocol_destroy(pe);
  st_protocol_destroy(ps);
}

void st_suite_handover(void) {
  ST_ADD_SUITE("handover");
  ST_ADD_TEST(test_handover_specs);
  ST_ADD_TEST(test_handover_rollin);
  ST_ADD_TEST(test_handover_fallback);
  ST_ADD_TEST(test_handover_fitness);
  ST_ADD_TEST(test_varied_fitness);
  ST_ADD_TEST(test_handover_keys);
  ST_ADD_TEST(test_chain_fitness);
  ST_ADD_TEST(test_chain_sum);
  ST_ADD_TEST(test_evaluation_completes);
  ST_ADD_TEST(test_rollin_elite_self);
  ST_ADD_TEST(test_rollin_elite_trace);
  ST_ADD_TEST(test_rollin_elite_refused);
}
