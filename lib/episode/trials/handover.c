/* SPDX-License-Identifier: MIT
 * The hand-over trials (selftalk/trialkind.h; stage.handover, SPEC 12, docs/PROTOCOL.md
 * "Hand-over trials and chained trials"; not the thesis's): open, grasp and move of main-prim
 * from the state in which the caretaker's chain, from reach posture k, hands over to them. The
 * chain runs unscored (the individual acts it, or with stage.handover_rollin = elite the
 * generation's elite: st_rollin_controller), then the primitive is scored as its own trial. */
#include <string.h>

#include "core/internal.h"
#include "episode/trials/trials.h"

static int handover_count(const stConfig *cfg, stStage stage) {
  return stage == ST_STAGE_MAIN && cfg->stage_handover ? ST_TRIAL_MAX_HANDOVER : 0;
}

/* open, grasp and move by fours */
static int handover_primitive(int j) { return ST_PRIM_OPEN + j / ST_NPOSTURE; }

/* from reach posture k with the reach trials' object offset, as a chain starts (SPEC 12). Grasp
 * keeps its table removal (its success is holding the object without the table), counted from
 * the hand-over; move keeps the table, since the chain hands it an object resting on it, not
 * one already held as its fixed trials do */
static void handover_spec(const stProtocol *p, stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  t->primitive = handover_primitive(t->j);
  t->k = t->j % ST_NPOSTURE;
  t->target_index = t->k % 2;
  t->rollin_steps = c->stage_handover_rollin_steps;
  memcpy(t->qhat0, p->posture[ST_PRIM_REACH][t->k], sizeof t->qhat0);
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_HANDOVER, (uint64_t)t->generation, 0,
                           (uint64_t)t->j);
  st_scene_object(&p->scene, t->k, 1, &rng, t->obj);
  st_scene_target(&p->scene, t->target_index, &rng, t->target);
  t->steps = st__main_steps(c, t->primitive);
  t->table_off_step = t->primitive == ST_PRIM_MOVE ? -1 : st__main_table_off(c, t->primitive);
}

/* elite roll-ins: one key for every individual, or ODE's shuffling would part their starts */
static uint64_t handover_seed_key(const stProtocol *p, int generation, int individual, int j) {
  if (p->cfg.stage_handover_rollin == ST_ROLLIN_ELITE) individual = 0;
  return st_rng_keyed(st_config_rng_seed(&p->cfg), ST_RNG_HANDOVER_SOLVER, (uint64_t)generation,
                      (uint64_t)individual, (uint64_t)j).key;
}

/* nothing is scored while the chain rolls in; a roll-in that fails (the object fell, the world
 * diverged, no hand-over in time) ends the episode for the fallback; from the hand-over on, the
 * primitive's scoring with steps counted from it */
static int handover_score(stPrimScorer *s, stTraceStep *ts) {
  const stTrialSpec *t = s->t;
  if (ts->handover < 0) {
    ts->S = ts->P = 0.0;
    ts->success_now = 0;
    return ts->fell || ts->unstable || ts->step + 1 >= t->rollin_steps ? ST_END_FAILURE : -1;
  }
  s->sc.r.handover_step = ts->handover;
  stTraceStep rel = *ts;
  rel.step = ts->step - ts->handover;
  int event = st__prim_score(s, &rel);
  ts->S = rel.S;
  ts->P = rel.P;
  ts->success_now = rel.success_now;
  if (event < 0 && rel.step + 1 >= t->steps) event = ST_END_FULL; /* the primitive's length */
  return event;
}

void st_handover_fallback(const stProtocol *p, const stTrialSpec *h, stTrialSpec *t) {
  ST_ASSERT(p && h && t);
  ST_ASSERT(h->kind == ST_TRIAL_HANDOVER && h->generation >= 0);
  ST_ASSERT(h->primitive >= ST_PRIM_OPEN && h->primitive < ST_NPRIM);
  ST_ASSERT(h->k >= 0 && h->k < ST_NPOSTURE);
  memset(t, 0, sizeof *t);
  t->stage = ST_STAGE_MAIN;
  t->generation = h->generation;
  t->kind = ST_TRIAL_FIXED;
  t->j = t->index = h->primitive * ST_NPOSTURE + h->k;
  /* the fixed posture, also in generations whose open and grasp starts are drawn */
  st__fixed_trial(p, t, h->primitive, h->k, 0);
  memcpy(t->target, h->target, sizeof t->target);
  t->index = h->index;
}

/* a roll-in that did not hand over: the chain broke before the primitive, and the trial earns
 * nothing, or with stage.handover_fallback runs from the fixed posture */
static stStatus handover_finish(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                                const stController *ctl, uint64_t seed_key, stTrialResult *r,
                                stTraceFn trace, void *ctx, char *err, size_t errsz) {
  if (r->handover_step >= 0) return ST_OK;
  if (!p->cfg.stage_handover_fallback) {
    memset(r, 0, sizeof *r);
    r->steps = t->steps;
    r->success_step = r->handover_step = -1;
    r->end = ST_END_QUIET;
    return ST_OK;
  }
  stTrialSpec fallback;
  st_handover_fallback(p, t, &fallback);
  return st__trial_episode_run(p, ws, &fallback, ctl, seed_key, r, trace, ctx, err, errsz);
}

static int handover_counts(const stTrialSpec *t, const stTrialResult *r) {
  (void)t;
  return r->handover_step >= 0; /* handed over (the others ran the fallback, or nothing) */
}

static int handover_note(const stEvaluation *e, char *buf, size_t n) {
  const stKindEvaluation *r = &e->kind[ST_TRIAL_HANDOVER];
  return r->trials ? snprintf(buf, n, " (hand-over %2d/%d, %2d handed over)", r->successes,
                              r->trials, r->count)
                   : 0;
}

int st_stage_rollin_elite(const stProtocol *p, stStage stage) {
  ST_ASSERT(p);
  return handover_count(&p->cfg, stage) > 0 && p->cfg.stage_handover_rollin == ST_ROLLIN_ELITE;
}

/* the hand-over trials are open's, grasp's and move's; the elite is genotype 0, which
 * st_ga_next fills with the previous generation's best only when it keeps elites */
static int handover_check(const stConfig *c, char *msg, size_t n) {
  const unsigned prims = st_config_primitive_mask(c);
  const unsigned theirs = 1u << ST_PRIM_OPEN | 1u << ST_PRIM_GRASP | 1u << ST_PRIM_MOVE;
  if (c->stage_handover_rollin == ST_ROLLIN_ELITE && c->ga_elites < 1) {
    snprintf(msg, n, "elite rolls the hand-over trials in with the generation's genotype 0, "
             "which is the previous generation's best only with ga.elites >= 1 (expected "
             "ga.elites >= 1, or stage.handover_rollin = self)");
    return st_config_find("stage", "handover_rollin");
  }
  if (c->stage_handover && prims && !(prims & theirs)) {
    snprintf(msg, n, "the hand-over trials are open's, grasp's and move's, and stage.primitives "
             "= %s evaluates none of them (expected one of them in stage.primitives, or "
             "stage.handover = false)", c->stage_primitives);
    return st_config_find("stage", "handover");
  }
  return -1;
}

/* the row: what it is and its keys; its streams; its hooks; its fitness.csv columns */
const stTrialKindDef st__trial_handover = {
    ST__TRIAL_KIND(HANDOVER, handover), .title = "hand-over trials",
    .switch_key = "stage.handover", .family = "stage.handover_", .shapes = "the hand-over trials",
    .offsets = ST_RNG_HANDOVER, .solver = ST_RNG_HANDOVER_SOLVER,
    .count = handover_count, .primitive = handover_primitive, .spec = handover_spec,
    .seed_key = handover_seed_key, .score = handover_score, .finish = handover_finish,
    .counts = handover_counts, .note = handover_note, .check = handover_check,
    .column = ST_CSV_COL_INT(stKindEvaluation, count, "best_handovers", 0),
    .trial_column = "best_h%d",
};
