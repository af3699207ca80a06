/* SPDX-License-Identifier: MIT
 * integrated.fail_end = exact (docs/PROTOCOL.md, "Speed"): an integrated trial whose object can
 * never again be touched ends early only when the rest cannot change what it reports. The
 * settle rules on hand-made scorers; then the proof on real trials where the ball falls
 * (committed genotypes of a chain candidate, with no words and with the caretaker): exact and
 * runout give bit-identical points, bonuses, success, reached step and fitness, exact ends some
 * of them early, and the run-out trials never touch the object after exact would have ended. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/config.h"
#include "selftalk/genome.h"
#include "selftalk/integrated.h"
#include "test_util.h"

/* best.genome of a chain candidate whose chains drop or push the ball off (its no-words
 * integration test: 192 of 400 trials failed) */
static const char DROPPERS[] = "data/evolved/chain_candidates/hcg_p2_s1/best.genome";

static stIntegratedDef def_of(int steps) {
  stIntegratedDef d;
  memset(&d, 0, sizeof d);
  d.trials = 8, d.steps = steps, d.hold_steps = 2, d.focus_bonus_steps = 3;
  d.fail_end = ST_FAIL_END_EXACT;
  return d;
}

/* a state far from everything: S = 0.2 x (1 - y) = 0.2 at y = 0 */
static stQuantities far(void) {
  stQuantities q;
  memset(&q, 0, sizeof q);
  q.d_r = q.d_g = q.d_m = 1.0, q.h = 0.7, q.p = 1.0;
  return q;
}

/* what each ST_INT_KEEP_* holds back; points: 10 steps of 0.2 S, 2 P each (the moving cap):
 * after step 0 cur = -1.8, 9 left: -1.8 + 9 (0.6 - 2) < 0 and -1.8 - 9 x 4 < 0: settled */
static void test_early_settle_rules(void) {
  stConfig c;
  st_config_default(&c);
  stFitnessDef fd;
  st_fitness_def_from_config(&c, &fd);
  stIntegratedDef d = def_of(10);
  stIntScore sc;
  stQuantities q = far();
  st_int_score_begin(&sc, &fd, 0.5, &d);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 0, &q, 0.0, 0.0, 2.0, 1, 0, NULL, NULL), -1); /* fell */
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 0, 2.0, 1), -1); /* still within reach */
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 2.0, 1), ST_END_FAILURE);
  stIntTrialResult r;
  st_int_score_end(&sc, &r);
  CU_ASSERT_EQUAL(r.steps_run, 1);
  CU_ASSERT_EQUAL(r.end, ST_END_FAILURE);
  CU_ASSERT_DOUBLE_EQUAL(r.sum_p, 2.0 + 9 * 2.0, 0.0); /* the certain penalty filled */
  CU_ASSERT_DOUBLE_EQUAL(st_int_trial_points(&r), 0.0, 0.0);
  CU_ASSERT_EQUAL(r.success, 0);
  /* points that could stay positive: no moving penalty certain (floor 0), or ahead by 20 */
  st_int_score_begin(&sc, &fd, 0.5, &d);
  st_int_score_step(&sc, 0, &q, 0.0, 0.0, 2.0, 1, 0, NULL, NULL);
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 0.0, 1), -1);
  sc.r.sum_s += 20.0;
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 2.0, 1), -1);
  /* a prediction trial: its points do not matter, its record does once reached */
  st_int_score_begin(&sc, &fd, 0.5, &d);
  sc.keep = ST_INT_KEEP_RECORD;
  st_int_score_step(&sc, 0, &q, 0.0, 0.0, 0.0, 1, 0, NULL, NULL);
  sc.r.sum_s += 20.0;
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 0.0, 1), ST_END_FAILURE);
  st_int_score_begin(&sc, &fd, 0.5, &d);
  sc.keep = ST_INT_KEEP_RECORD;
  sc.r.reached_step = 0; /* it was in the target while lifted before it fell */
  st_int_score_step(&sc, 1, &q, 0.0, 0.0, 0.0, 1, 0, NULL, NULL);
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 0.0, 1), -1);
  /* posteval's words: self talk can still change them */
  st_int_score_begin(&sc, &fd, 0.5, &d);
  sc.keep = ST_INT_KEEP_WORDS;
  st_int_score_step(&sc, 0, &q, 0.0, 0.0, 0.0, 1, 0, NULL, NULL);
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 0.0, 0), -1);
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 0.0, 1), ST_END_FAILURE);
  /* other modes never settle; penalty ends at the fall, runout only on a diverged world */
  d.fail_end = ST_FAIL_END_RUNOUT;
  st_int_score_begin(&sc, &fd, 0.5, &d);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 0, &q, 0.0, 0.0, 2.0, 1, 0, NULL, NULL), -1);
  CU_ASSERT_EQUAL(st_int_score_settle(&sc, 1, 2.0, 1), -1);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 1, &q, 0.0, 0.0, 2.0, 1, 1, NULL, NULL), ST_END_FAILURE);
  d.fail_end = ST_FAIL_END_PENALTY;
  st_int_score_begin(&sc, &fd, 0.5, &d);
  CU_ASSERT_EQUAL(st_int_score_step(&sc, 0, &q, 0.0, 0.0, 2.0, 1, 0, NULL, NULL), ST_END_FAILURE);
}

/* the run-out trace after exact's end: what the proof says can no longer happen */
typedef struct after {
  const stProtocol *p;
  int from;     /* the first out-of-reach step, -1 before */
  double floor; /* its moving penalty floor */
  int checked, broken;
} after;

static void watch(void *ctx, const stTraceStep *ts) {
  after *a = ctx;
  if (a->from < 0 && ts->out_of_reach) a->from = ts->step, a->floor = ts->pen_moving_floor;
  if (a->from < 0 || ts->step == a->from || ts->unstable) return;
  a->checked++;
  a->broken += ts->q->lifted || ts->q->touching || ts->world->contacts.robot_object ||
               ts->q->d_r < a->p->fitness.success_dist || ts->pen_moving < a->floor;
}

static stProtocol *protocol(int fail_end) {
  stConfig c;
  st_config_default(&c);
  c.integrated_fail_end = fail_end;
  stProtocol *p = NULL;
  char err[512] = "";
  if (st_protocol_create(&c, &p, err, sizeof err)) fprintf(stderr, "%s\n", err);
  return p;
}

#define NGENO 3

/* main-prim's chained trials (eq. 2.14, the integrated stage's table) of three genotypes, with
 * no words (the ball falls in about half) and with the caretaker */
static void test_early_exact_equals_runout(void) {
  stProtocol *px = protocol(ST_FAIL_END_EXACT), *pr = protocol(ST_FAIL_END_RUNOUT);
  CU_ASSERT_PTR_NOT_NULL_FATAL(px);
  CU_ASSERT_PTR_NOT_NULL_FATAL(pr);
  CU_ASSERT_TRUE(px->reach_geom_z > -1.0 && px->reach_geom_z < 0.0);
  stGenomeSet set;
  char err[512] = "";
  CU_ASSERT_EQUAL_FATAL(st_genome_set_read(DROPPERS, st_arch_ngenes(ST_ARCH_BASE), &set, err,
                                           sizeof err), ST_OK);
  stWorkspace wx = {0}, wr = {0};
  int early = 0, fell = 0, stayed = 0;
  long saved = 0, checked = 0, broken = 0;
  /* EARLY_NGENO=37: every record of the file, each trial that goes out of reach printed (how
   * the genotypes were chosen: 203 of 592 trials out of reach, all ended early) */
  const int ngeno = getenv("EARLY_NGENO") ? atoi(getenv("EARLY_NGENO")) : NGENO;
  for (int g = 0; g < ngeno && g < set.count; g++) {
    stNetParams net;
    CU_ASSERT_EQUAL_FATAL(st_net_decode(NULL, ST_ARCH_BASE, &set.genome[set.count - 1 - g], &net,
                                        err, sizeof err), ST_OK);
    for (int words = 0; words < 2; words++) {
      stIntegratedDef dx, dr;
      st_chain_def_from_config(&px->cfg, &dx);
      st_chain_def_from_config(&pr->cfg, &dr);
      CU_ASSERT_EQUAL(dx.fail_end, ST_FAIL_END_EXACT);
      CU_ASSERT_EQUAL(dr.fail_end, ST_FAIL_END_RUNOUT);
      dx.words[0] = dx.words[1] = dr.words[0] = dr.words[1] =
          words ? ST_WORDS_CARETAKER : ST_WORDS_NONE;
      dx.trials = dr.trials = 8; /* stage.kind[ST_TRIAL_CHAINED].trials' table of the integrated stage */
      stIntPlan plan[ST_INT_MAX_TRIALS];
      stIntTrialResult rx[ST_INT_MAX_TRIALS], rr[ST_INT_MAX_TRIALS];
      for (int i = 0; i < dx.trials; i++) {
        stPredScore pred;
        after a = {pr, -1, 0.0, 0, 0};
        CU_ASSERT_EQUAL_FATAL(st_int_trial_run(px, &dx, &wx, 3, g, i, &net, &plan[i], &rx[i], &pred,
                                               NULL, NULL, err, sizeof err), ST_OK);
        CU_ASSERT_EQUAL_FATAL(st_int_trial_run(pr, &dr, &wr, 3, g, i, &net, &plan[i], &rr[i], &pred,
                                               watch, &a, err, sizeof err), ST_OK);
        /* what the trial reports, bit for bit */
        const double ptx = st_int_trial_points(&rx[i]), ptr = st_int_trial_points(&rr[i]);
        CU_ASSERT_EQUAL(memcmp(&ptx, &ptr, sizeof ptx), 0);
        CU_ASSERT_EQUAL(rx[i].success, rr[i].success);
        CU_ASSERT_EQUAL(rx[i].focus_bonus, rr[i].focus_bonus);
        CU_ASSERT_EQUAL(rx[i].reached_step, rr[i].reached_step);
        CU_ASSERT_EQUAL(rx[i].opened, rr[i].opened);
        CU_ASSERT_EQUAL(rx[i].furthest_word, rr[i].furthest_word);
        CU_ASSERT_EQUAL(rx[i].steps, rr[i].steps);
        const int ended = rx[i].end == ST_END_FAILURE && !rx[i].unstable;
        early += ended;
        saved += rx[i].steps - rx[i].steps_run;
        fell += a.from >= 0;
        stayed += a.from >= 0 && !ended; /* out of reach, but points could stay positive */
        if (getenv("EARLY_NGENO") && a.from >= 0)
          printf("\n g %d words %d trial %d out at %d ended %d steps %ld points %g", g, words, i,
                 a.from, ended, rx[i].steps_run, ptr);
        /* an exact end comes at or after the first step out of reach; the run-out trial from
         * there on never touches the object nor brings the palm near it */
        if (ended) CU_ASSERT_TRUE(a.from >= 0 && rx[i].steps_run - 1 >= a.from);
        checked += a.checked;
        broken += a.broken;
      }
      stIntEvaluation ex, er;
      st_int_combine(px->fitness.bonus, px->fitness.scale, plan, rx, NULL, dx.trials, &ex);
      st_int_combine(pr->fitness.bonus, pr->fitness.scale, plan, rr, NULL, dr.trials, &er);
      CU_ASSERT_EQUAL(memcmp(&ex.fitness, &er.fitness, sizeof ex.fitness), 0);
      CU_ASSERT_EQUAL(memcmp(&ex.f_int, &er.f_int, sizeof ex.f_int), 0);
      CU_ASSERT_EQUAL(memcmp(&ex.bonus, &er.bonus, sizeof ex.bonus), 0);
      CU_ASSERT_EQUAL(memcmp(&ex.progress, &er.progress, sizeof ex.progress), 0);
      CU_ASSERT_EQUAL(ex.successes, er.successes);
      CU_ASSERT_EQUAL(memcmp(ex.success, er.success, sizeof ex.success), 0);
    }
  }
  printf("\n    early ends %d (%ld steps saved), out of reach %d, ran out %d; %ld run-out steps "
         "checked after them, %ld broken ", early, saved, fell, stayed, checked, broken);
  CU_ASSERT_TRUE(early >= 4); /* the proof is about trials that really end early */
  CU_ASSERT_TRUE(checked > 100);
  CU_ASSERT_EQUAL(broken, 0);
  st_genome_set_free(&set);
  st_workspace_free(&wx);
  st_workspace_free(&wr);
  st_protocol_destroy(px);
  st_protocol_destroy(pr);
}

void st_suite_early(void) {
  ST_ADD_SUITE("early");
  ST_ADD_TEST(test_early_settle_rules);
  ST_ADD_TEST(test_early_exact_equals_runout);
}
