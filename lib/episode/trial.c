/* SPDX-License-Identifier: MIT */
#include "selftalk/trial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/integrated.h"
#include "selftalk/postures.h"

/* the index ranges are whole postures: index % ST_NPOSTURE is a trial's posture in each */
typedef char st__trial_ranges_aligned[(ST_PRIM_TRIALS % ST_NPOSTURE == 0 &&
                                       ST_VARIED_FIRST % ST_NPOSTURE == 0) ? 1 : -1];

stTrialKind st_trial_kind(int index) {
  ST_ASSERT(index >= 0 && index < ST_MAIN_TRIALS_MAX);
  return index < ST_PRIM_TRIALS ? ST_TRIAL_FIXED
         : index < ST_VARIED_FIRST ? ST_TRIAL_HANDOVER
                                   : ST_TRIAL_VARIED;
}

/* postures.vary_starts: an open or grasp trial starts from the first drawn variation of its
 * posture that has the SPEC 8 properties; the draws are keyed by (generation, trial), common to
 * every individual, on a stream of their own so the other draws are unchanged */
static void vary_start(const stProtocol *p, int generation, stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_STARTS, (uint64_t)generation, 0,
                           (uint64_t)t->index);
  for (int i = 1; i <= c->postures_vary_draws; i++) {
    stPostureVariation v;
    double q[ST_NDOF];
    st_posture_variation_draw(&p->scene, &rng, &v);
    if (st_posture_varied(p->robot, &p->scene, t->primitive, t->k, &v, q, NULL, 0) == ST_OK) {
      memcpy(t->qhat0, q, sizeof q);
      t->start_draws = i;
      return;
    }
  }
}

/* main-prim's trial lengths, and when the object-table collision goes off (-1: never) */
static int main_steps(const stConfig *c, int primitive) {
  const int steps[ST_NPRIM] = {c->stage_main_reach_steps, c->stage_main_open_steps,
                               c->stage_main_grasp_steps, c->stage_main_move_steps};
  return steps[primitive];
}

static int main_table_off(const stConfig *c, int primitive) {
  return primitive == ST_PRIM_GRASP  ? c->stage_grasp_table_off_step
         : primitive == ST_PRIM_MOVE ? c->stage_move_table_off_step
                                     : -1;
}

/* hand-over trial j: from reach posture k with the reach trials' object offset, as a chain
 * starts (SPEC 12). Grasp keeps its table removal (its success is holding the object without
 * the table), counted from the hand-over; move keeps the table, since the chain hands it an
 * object resting on it, not one already held as its fixed trials do */
static void handover_spec(const stProtocol *p, int j, stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  t->primitive = st_trial_primitive(ST_PRIM_TRIALS + j);
  t->k = j % ST_NPOSTURE;
  t->target_index = t->k % 2;
  t->handover = 1;
  t->rollin_steps = c->stage_handover_rollin_steps;
  memcpy(t->qhat0, p->posture[ST_PRIM_REACH][t->k], sizeof t->qhat0);
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_HANDOVER, (uint64_t)t->generation, 0,
                           (uint64_t)j);
  st_scene_object(&p->scene, t->k, 1, &rng, t->obj);
  st_scene_target(&p->scene, t->target_index, &rng, t->target);
  t->steps = main_steps(c, t->primitive);
  t->table_off_step = t->primitive == ST_PRIM_MOVE ? -1 : main_table_off(c, t->primitive);
}

/* st_trial_spec (which checks the arguments); draw 0: the fixed posture whatever
 * postures.vary_* say */
static void trial_spec(const stProtocol *p, stStage stage, int generation, int index, int draw,
                       stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  memset(t, 0, sizeof *t);
  t->stage = stage;
  t->index = index;
  t->generation = generation;
  const stTrialKind kind = st_trial_kind(index);
  if (kind == ST_TRIAL_HANDOVER) {
    handover_spec(p, index - ST_PRIM_TRIALS, t);
    return;
  }
  const int varied = kind == ST_TRIAL_VARIED;
  t->primitive = st_trial_primitive(index);
  t->k = index % ST_NPOSTURE;
  t->target_index = t->k % 2;
  memcpy(t->qhat0, p->posture[t->primitive][t->k], sizeof t->qhat0);
  /* offsets: object (reach trials only, thesis 2.5.1) then target (every trial, 2.5.2) */
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_TRIAL, (uint64_t)generation, 0, (uint64_t)index);
  st_scene_object(&p->scene, t->k, t->primitive == ST_PRIM_REACH, &rng, t->obj);
  st_scene_target(&p->scene, t->target_index, &rng, t->target);
  if (draw && (varied || (st_vary_replacing(c, generation) &&
                         (t->primitive == ST_PRIM_OPEN || t->primitive == ST_PRIM_GRASP))))
    vary_start(p, generation, t);
  if (stage == ST_STAGE_SIMPLE) {
    t->steps = c->stage_simple_steps;
    t->table_off_step = -1;
  } else {
    t->steps = main_steps(c, t->primitive);
    t->table_off_step = main_table_off(c, t->primitive);
  }
}

void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t) {
  ST_ASSERT(p && t);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  ST_ASSERT(generation >= 0);
  ST_ASSERT(index >= 0 && index < (stage == ST_STAGE_MAIN ? ST_MAIN_TRIALS_MAX : ST_PRIM_TRIALS));
  trial_spec(p, stage, generation, index, 1, t);
}

void st_handover_fallback(const stProtocol *p, const stTrialSpec *h, stTrialSpec *t) {
  ST_ASSERT(p && h && t);
  ST_ASSERT(h->handover && h->generation >= 0);
  ST_ASSERT(h->primitive >= ST_PRIM_OPEN && h->primitive < ST_NPRIM);
  ST_ASSERT(h->k >= 0 && h->k < ST_NPOSTURE);
  /* the fixed posture, also in generations whose open and grasp starts are drawn */
  trial_spec(p, ST_STAGE_MAIN, h->generation, h->primitive * ST_NPOSTURE + h->k, 0, t);
  memcpy(t->target, h->target, sizeof t->target);
  t->index = h->index;
}

void st_trial_episode(const stProtocol *p, const stTrialSpec *t, uint64_t seed_key,
                      stEpisodeSpec *e, stWords *words) {
  ST_ASSERT(p && t && e && words);
  ST_ASSERT(t->primitive >= 0 && t->primitive < ST_NPRIM);
  memset(e, 0, sizeof *e);
  e->dynamic = t->stage != ST_STAGE_SIMPLE;
  memcpy(e->qhat0, t->qhat0, sizeof e->qhat0);
  memcpy(e->obj, t->obj, sizeof e->obj);
  memcpy(e->target, t->target, sizeof e->target);
  e->steps = t->handover ? t->rollin_steps + t->steps : t->steps;
  e->table_off_step = t->table_off_step;
  e->seed_key = seed_key;
  /* the primitive's word every step (hand-over trials: once the caretaker hands over);
   * primitive stages never give the secondary input */
  words->source = t->handover ? ST_WORDS_HANDOVER : ST_WORDS_FIXED;
  words->word = t->primitive;
  words->scale = p->cfg.network_linguistic_input;
  words->secondary = 0.0;
}

/* ---- one trial ---- */

/* the penalties that apply, summed in the order table, object, moving */
static double masked_penalty(const stTraceStep *s, int mask) {
  double pen = 0.0;
  if (mask & ST_PEN_TABLE) pen += s->pen_table;
  if (mask & ST_PEN_OBJECT) pen += s->pen_object;
  if (mask & ST_PEN_MOVING) pen += s->pen_moving;
  return pen;
}

void st_score_begin(stTrialScore *sc, const stTrialSpec *t) {
  ST_ASSERT(sc && t);
  memset(sc, 0, sizeof *sc);
  sc->r.handover_step = -1;
  sc->stage = t->stage;
  sc->primitive = t->primitive;
  sc->steps = t->steps;
  sc->table_off_step = t->table_off_step;
  sc->reached_at = -1;
  sc->r.success_step = -1;
}

int st_score_step(stTrialScore *sc, const stFitnessDef *fd, int step, const stQuantities *q,
                  double y_focus, double threshold, double penalty, int fell, int unstable,
                  double *S_out, double *P_out) {
  ST_ASSERT(sc && fd && q);
  ST_ASSERT(step >= 0);
  stTrialResult *r = &sc->r;
  const double S = st_step_fitness(fd, sc->stage, sc->primitive, q, y_focus, threshold);
  r->sum_s += S;
  r->sum_p += penalty;
  r->steps_run++;
  sc->lifted = q->lifted;
  const int now = st_success_now(fd, sc->stage, sc->primitive, q);
  if (now && r->success_step < 0) r->success_step = step;
  if (sc->primitive == ST_PRIM_MOVE) sc->was_in_target |= now;
  else if (now) r->success = 1;
  if (sc->primitive == ST_PRIM_REACH && now && sc->reached_at < 0) sc->reached_at = step;
  if (S_out) *S_out = S;
  if (P_out) *P_out = penalty;
  if (sc->stage != ST_STAGE_MAIN) return -1; /* simple-prim trials always run their length */
  int event = -1;
  if (unstable || fell) {
    r->unstable = unstable;
    /* grasp: falling once the table is gone ends the trial without a penalty (2.8.1.2) */
    event = !unstable && sc->primitive == ST_PRIM_GRASP && sc->table_off_step >= 0 &&
                    step >= sc->table_off_step
                ? ST_END_QUIET
                : ST_END_FAILURE;
  } else if (sc->primitive == ST_PRIM_REACH && sc->reached_at >= 0 &&
             step - sc->reached_at > fd->reach_hold_steps) {
    event = ST_END_SUCCESS; /* reached "more than 20 steps ago" */
  }
  if (event >= 0) r->end = (stTrialEnd)event;
  return event;
}

void st_score_end(stTrialScore *sc, const stFitnessDef *fd, double obj_z, double table_top_z,
                  stTrialResult *out) {
  ST_ASSERT(sc && fd && out);
  stTrialResult *r = &sc->r;
  const long remaining = sc->steps - r->steps_run;
  if (r->end == ST_END_SUCCESS) r->sum_s += (double)remaining;
  if (r->end == ST_END_FAILURE) r->sum_p += fd->fail_penalty * (double)remaining;
  r->steps = sc->steps;
  const int is_main = sc->stage == ST_STAGE_MAIN;
  if (r->unstable) r->success = 0;
  else if (is_main && sc->primitive == ST_PRIM_GRASP)
    r->success = r->end == ST_END_FULL && obj_z > table_top_z;
  else if (sc->primitive == ST_PRIM_MOVE)
    r->success = is_main ? sc->was_in_target && r->end == ST_END_FULL && sc->lifted
                         : sc->was_in_target;
  *out = *r;
}

/* ---- the primitive scorer ---- */

static void prim_begin(void *self) {
  stPrimScorer *s = self;
  st_score_begin(&s->sc, s->t);
}

static int prim_score(stPrimScorer *s, stTraceStep *ts) {
  const stTrialSpec *t = s->t;
  const int mask = st_penalty_mask(t->stage, t->primitive, ts->step,
                                   t->table_off_step >= 0 ? t->table_off_step : t->steps);
  const int event = st_score_step(&s->sc, &s->p->fitness, ts->step, ts->q, ts->out[ST_NET_OUT_FOCUS],
                                  s->p->sensor.focus_threshold, masked_penalty(ts, mask), ts->fell,
                                  ts->unstable, &ts->S, &ts->P);
  ts->success_now = st_success_now(&s->p->fitness, t->stage, t->primitive, ts->q);
  return event;
}

/* a hand-over trial: nothing is scored while the chain rolls in; a roll-in that fails (the
 * object fell, the world diverged, no hand-over in time) ends the episode for the fallback;
 * from the hand-over on, the primitive's scoring with steps counted from it */
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
  int event = prim_score(s, &rel);
  ts->S = rel.S;
  ts->P = rel.P;
  ts->success_now = rel.success_now;
  if (event < 0 && rel.step + 1 >= t->steps) event = ST_END_FULL; /* the primitive's length */
  return event;
}

static int prim_step(void *self, stTraceStep *ts) {
  stPrimScorer *s = self;
  return s->t->handover ? handover_score(s, ts) : prim_score(s, ts);
}

static void prim_end(void *self, const stWorld *w) {
  stPrimScorer *s = self;
  st_score_end(&s->sc, &s->p->fitness, w->obj[2], s->p->scene.table_top_z, s->r);
}

stScorer st_prim_scorer(stPrimScorer *s, const stProtocol *p, const stTrialSpec *t,
                        stTrialResult *r) {
  ST_ASSERT(s && p && t && r);
  s->p = p;
  s->t = t;
  s->r = r;
  stScorer sc = {prim_begin, prim_step, prim_end, s};
  return sc;
}

/* rollin (nullable): who acts a hand-over trial's roll-in (st_episode_run_rollin) */
static stStatus run_episode(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                            const stController *ctl, const stController *rollin,
                            uint64_t seed_key, stTrialResult *r, stTraceFn trace, void *ctx,
                            char *err, size_t errsz) {
  stEpisodeSpec e;
  stWords words;
  st_trial_episode(p, t, seed_key, &e, &words);
  stPrimScorer ps;
  const stScorer sc = st_prim_scorer(&ps, p, t, r);
  return st_episode_run_rollin(p, ws, &e, ctl, rollin, &words, &sc, trace, ctx, err, errsz);
}

/* st_trial_run_with, the roll-in of a hand-over trial acted by rollin (nullable); the
 * fallback is ctl's alone */
static stStatus trial_run_rollin_with(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                                      const stController *ctl, const stController *rollin,
                                      uint64_t seed_key, stTrialResult *r, stTraceFn trace,
                                      void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && t && ctl && ctl->act && r);
  stStatus st = run_episode(p, ws, t, ctl, rollin, seed_key, r, trace, ctx, err, errsz);
  if (st || !t->handover || r->handover_step >= 0) return st;
  if (!p->cfg.stage_handover_fallback) { /* the chain broke before the primitive: nothing earned */
    memset(r, 0, sizeof *r);
    r->steps = t->steps;
    r->success_step = r->handover_step = -1;
    r->end = ST_END_QUIET;
    return ST_OK;
  }
  stTrialSpec fallback;
  st_handover_fallback(p, t, &fallback);
  return run_episode(p, ws, &fallback, ctl, NULL, seed_key, r, trace, ctx, err, errsz);
}

stStatus st_trial_run_with(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                           const stController *ctl, uint64_t seed_key, stTrialResult *r,
                           stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && t && ctl && r);
  return trial_run_rollin_with(p, ws, t, ctl, NULL, seed_key, r, trace, ctx, err, errsz);
}

stStatus st_trial_run_rollin(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                             const stNetParams *net, const stNetParams *rollin,
                             const stForce *force, int nforce, uint64_t seed_key, stTrialResult *r,
                             stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && t && net);
  stStatus st = st_force_check(force, nforce, err, errsz);
  if (st) return st;
  /* the base network has no memory (hidden from the inputs at t, outputs from the hidden at t:
   * lib/core/net.c), so the individual can take over from the elite at the hand-over step as
   * if it had acted the roll-in itself; a type A or B network's linguistic units carry the
   * past, which the switch would drop */
  if (rollin && (!t->handover || rollin->arch != ST_ARCH_BASE || net->arch != ST_ARCH_BASE))
    return st__errf(err, errsz, "stage.handover_rollin = elite: trial %d is %s, networks %s and "
                    "%s (expected a hand-over trial and two base networks: only a network "
                    "without memory can take over from the roll-in)", t->index,
                    t->handover ? "a hand-over trial" : "no hand-over trial",
                    st_arch_name(net->arch), st_arch_name(rollin->arch)), ST_ERR_ARG;
  stNetController c, rc;
  const stController ctl = st_net_controller(&c, net, force, nforce);
  stController rctl;
  if (rollin) rctl = st_net_controller(&rc, rollin, NULL, 0);
  return trial_run_rollin_with(p, ws, t, &ctl, rollin ? &rctl : NULL, seed_key, r, trace, ctx,
                               err, errsz);
}

stStatus st_trial_run_forced(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                             const stNetParams *net, const stForce *force, int nforce,
                             uint64_t seed_key, stTrialResult *r, stTraceFn trace, void *ctx,
                             char *err, size_t errsz) {
  ST_ASSERT(p && ws && t && net && r);
  return st_trial_run_rollin(p, ws, t, net, NULL, force, nforce, seed_key, r, trace, ctx, err,
                             errsz);
}

stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stNetParams *net, uint64_t seed_key, stTrialResult *r, stTraceFn trace,
                      void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && t && net && r);
  return st_trial_run_forced(p, ws, t, net, NULL, 0, seed_key, r, trace, ctx, err, errsz);
}

/* an individual's sums over its trials, per primitive (eq. 2.3) */
typedef struct stageSums {
  double sum_sp[ST_NPRIM], bonus[ST_NPRIM];
  long n[ST_NPRIM];
} stageSums;

uint64_t st_trial_seed_key(const stProtocol *p, int generation, int individual, int index) {
  ST_ASSERT(p);
  ST_ASSERT(generation >= 0 && individual >= 0);
  ST_ASSERT(index >= 0 && index < ST_MAIN_TRIALS_MAX);
  const uint64_t seed = st_config_rng_seed(&p->cfg);
  /* elite roll-ins: one key for every individual, or ODE's shuffling would part their starts */
  const int handover = st_trial_kind(index) == ST_TRIAL_HANDOVER;
  if (handover && p->cfg.stage_handover_rollin == ST_ROLLIN_ELITE) individual = 0;
  if (handover)
    return st_rng_keyed(seed, ST_RNG_HANDOVER_SOLVER, (uint64_t)generation, (uint64_t)individual,
                        (uint64_t)(index - ST_PRIM_TRIALS)).key;
  return st_rng_keyed(seed, ST_RNG_TRIAL, (uint64_t)generation, (uint64_t)individual,
                      (uint64_t)index).key;
}

int st_vary_replacing(const stConfig *cfg, int generation) {
  ST_ASSERT(cfg);
  ST_ASSERT(generation >= 0);
  return cfg->postures_vary_starts && (cfg->postures_vary_trials == ST_VARY_REPLACE ||
                                       generation < cfg->postures_vary_replace_generations);
}

int st_stage_varied(const stConfig *cfg, stStage stage) {
  ST_ASSERT(cfg);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  return stage == ST_STAGE_MAIN && cfg->postures_vary_starts &&
         cfg->postures_vary_trials == ST_VARY_EXTRA;
}

int st_stage_trials(const stProtocol *p, stStage stage) {
  ST_ASSERT(p);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  return st_stage_varied(&p->cfg, stage)                   ? ST_MAIN_TRIALS_MAX
         : stage == ST_STAGE_MAIN && p->cfg.stage_handover ? ST_VARIED_FIRST
                                                           : ST_PRIM_TRIALS;
}

/* fixed trials i / 4; hand-over and varied trials open, grasp (and move) by fours */
int st_trial_primitive(int i) {
  switch (st_trial_kind(i)) {
    case ST_TRIAL_FIXED: return i / ST_NPOSTURE;
    case ST_TRIAL_HANDOVER: return ST_PRIM_OPEN + (i - ST_PRIM_TRIALS) / ST_NPOSTURE;
    default: return ST_PRIM_OPEN + (i - ST_VARIED_FIRST) / ST_NPOSTURE;
  }
}

int st_stage_trial_active(const stProtocol *p, stStage stage, int generation, int i) {
  ST_ASSERT(p);
  ST_ASSERT(generation >= 0);
  ST_ASSERT(i >= 0 && i < st_stage_trials(p, stage));
  if (!(p->primitives >> st_trial_primitive(i) & 1u)) return 0;
  switch (st_trial_kind(i)) {
    case ST_TRIAL_FIXED: return 1;
    case ST_TRIAL_HANDOVER: return p->cfg.stage_handover;
    default: return st_stage_varied(&p->cfg, stage) && !st_vary_replacing(&p->cfg, generation);
  }
}

void st_trial_table(const stProtocol *p, stStage stage, int generation, stTrialTable *table) {
  ST_ASSERT(p && table);
  memset(table, 0, sizeof *table);
  memcpy(&table->cfg, &p->cfg, sizeof table->cfg);
  table->stage = stage;
  table->generation = generation;
  table->n = st_stage_trials(p, stage);
  for (int i = 0; i < table->n; i++)
    if (st_stage_trial_active(p, stage, generation, i))
      st_trial_spec(p, stage, generation, i, &table->t[i]);
}

/* the workspace's table for the generation, built when it holds another (or none) */
static const stTrialTable *generation_table(const stProtocol *p, stWorkspace *ws, stStage stage,
                                            int generation, char *err, size_t errsz) {
  if (!ws->trials && !(ws->trials = calloc(1, sizeof *ws->trials))) { /* n 0: empty */
    st__errf(err, errsz, "trial table: out of memory");
    return NULL;
  }
  stTrialTable *tab = ws->trials;
  if (tab->n == 0 || tab->generation != generation || tab->stage != stage ||
      memcmp(&tab->cfg, &p->cfg, sizeof tab->cfg) != 0)
    st_trial_table(p, stage, generation, tab);
  return tab;
}

/* runs trial t of the generation and adds it to its primitive's sums; rollin (nullable) acts
 * the hand-over trials' roll-in */
static stStatus add_trial(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                          int individual, const stNetParams *net, const stNetParams *rollin,
                          stageSums *sums, stTrialResult *r, char *err, size_t errsz) {
  const uint64_t key = st_trial_seed_key(p, t->generation, individual, t->index);
  stStatus st = st_trial_run_rollin(p, ws, t, net, t->handover ? rollin : NULL, NULL, 0, key, r,
                                    NULL, NULL, err, errsz);
  if (st) return st;
  sums->sum_sp[t->primitive] += r->sum_s - r->sum_p;
  sums->n[t->primitive] += r->steps;
  sums->bonus[t->primitive] += r->success ? p->fitness.bonus : 0.0;
  return ST_OK;
}

/* main-prim's chained trials: eq. 2.14 over the integrated stage's trials with the caretaker's
 * words (plus stage.chain_progress times how far the caretaker got); they count among the
 * trials that completing the stage needs solved */
static stStatus chain_evaluate(const stProtocol *p, stWorkspace *ws, int generation,
                               int individual, const stNetParams *net, stEvaluation *e, char *err,
                               size_t errsz) {
  stIntegratedDef def;
  st_chain_def_from_config(&p->cfg, &def);
  stIntEvaluation ie;
  stStatus st = st_int_evaluate(p, &def, ws, generation, individual, net, &ie, err, errsz);
  if (st) return st;
  e->f_chain = ie.fitness + p->cfg.stage_chain_progress * ie.progress;
  e->chain_trials = ie.ntrials;
  e->chain_successes = ie.successes;
  memcpy(e->chain_success, ie.success, sizeof e->chain_success);
  e->ntrials += ie.ntrials;
  e->successes += ie.successes;
  e->unstable += ie.unstable;
  return ST_OK;
}

/* the fixed trials (the thesis's 16, or those of stage.primitives) evaluated */
static int fixed_trials(const stProtocol *p) {
  int n = 0;
  for (int k = 0; k < ST_NPRIM; k++) n += (p->primitives >> k & 1u) ? ST_NPOSTURE : 0;
  return n;
}

/* stage.chain_combine = sum: F_chain's weight, (fixed trials solved / fixed trials)^chain_gate,
 * so that a chain bought with a fixed trial costs more than it earns (chain_gate 0: 1) */
static double chain_weight(const stProtocol *p, const stEvaluation *e, int fixed) {
  int solved = 0;
  for (int i = 0; i < ST_PRIM_TRIALS; i++) solved += e->success[i];
  return fixed ? pow((double)solved / fixed, p->cfg.stage_chain_gate) : 1.0;
}

int st_evaluation_fixed_trials(const stEvaluation *e) {
  ST_ASSERT(e);
  return e->ntrials - e->handover_trials - e->varied_trials - e->chain_trials;
}

int st_evaluation_completes(const stConfig *cfg, const stEvaluation *e) {
  ST_ASSERT(cfg && e);
  ST_ASSERT(e->successes >= 0 && e->successes <= e->ntrials);
  const int fixed_chained =
      cfg->stage_chain_complete == ST_CHAIN_COMPLETE_FIXED_CHAINED && e->chain_trials > 0;
  /* fixed trials from drawn starts count only under replace with every trial counted: with
   * extra they are its first phase (vary_replace_generations), and fixed_chained asks for the
   * thesis's 16 from their fixed starts */
  if (e->fixed_drawn > 0 && (cfg->postures_vary_trials == ST_VARY_EXTRA || fixed_chained))
    return 0;
  if (!fixed_chained) return e->successes == e->ntrials;
  int fixed = 0;
  for (int t = 0; t < ST_PRIM_TRIALS; t++) fixed += e->success[t];
  return fixed == st_evaluation_fixed_trials(e) &&
         e->chain_successes == e->chain_trials;
}

int st_stage_rollin_elite(const stProtocol *p, stStage stage) {
  ST_ASSERT(p);
  return stage == ST_STAGE_MAIN && p->cfg.stage_handover &&
         p->cfg.stage_handover_rollin == ST_ROLLIN_ELITE;
}

stStatus st_stage_evaluate(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, stEvaluation *e, char *err,
                           size_t errsz) {
  ST_ASSERT(p && ws && net && e);
  return st_stage_evaluate_rollin(p, ws, stage, generation, individual, net, NULL, e, err, errsz);
}

stStatus st_stage_evaluate_rollin(const stProtocol *p, stWorkspace *ws, stStage stage,
                                  int generation, int individual, const stNetParams *net,
                                  const stNetParams *rollin, stEvaluation *e, char *err,
                                  size_t errsz) {
  ST_ASSERT(p && ws && net && e);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  ST_ASSERT(generation >= 0 && individual >= 0);
  memset(e, 0, sizeof *e);
  const int elite = st_stage_rollin_elite(p, stage);
  if (elite != (rollin != NULL))
    return st__errf(err, errsz, "stage.handover_rollin = %s: %s (expected the generation's "
                    "elite's network exactly when main-prim's hand-over trials are rolled in by it)",
                    st_config_enum_name("stage", "handover_rollin", p->cfg.stage_handover_rollin),
                    rollin ? "a roll-in network was given" : "no roll-in network was given"),
           ST_ERR_ARG;
  stageSums sums;
  memset(&sums, 0, sizeof sums);
  const stTrialTable *tab = generation_table(p, ws, stage, generation, err, errsz);
  if (!tab) return ST_ERR_NOMEM;
  for (int i = 0; i < tab->n; i++) {
    if (!st_stage_trial_active(p, stage, generation, i)) continue;
    stTrialResult r;
    stStatus st = add_trial(p, ws, &tab->t[i], individual, net, rollin, &sums, &r, err, errsz);
    if (st) return st;
    e->ntrials++;
    e->successes += r.success;
    e->unstable += r.unstable;
    switch (st_trial_kind(i)) {
      case ST_TRIAL_FIXED:
        e->success[i] = (uint8_t)r.success;
        e->fixed_drawn += tab->t[i].start_draws > 0;
        break;
      case ST_TRIAL_VARIED:
        e->varied_trials++;
        e->varied_successes += r.success;
        e->varied_success[i - ST_VARIED_FIRST] = (uint8_t)r.success;
        break;
      case ST_TRIAL_HANDOVER:
        e->handover_trials++;
        e->handover_successes += r.success;
        e->handovers += r.handover_step >= 0;
        e->handover_success[i - ST_PRIM_TRIALS] = (uint8_t)r.success;
        break;
    }
  }
  double fp[ST_NPRIM + 1];
  int nprim = 0;
  for (int k = 0; k < ST_NPRIM; k++) {
    e->fp[k] = st_primitive_fitness(&p->fitness, sums.bonus[k], sums.sum_sp[k], sums.n[k]);
    if (p->primitives >> k & 1u) fp[nprim++] = e->fp[k];
  }
  const int fixed = fixed_trials(p);
  if (stage == ST_STAGE_MAIN && p->cfg.stage_chain_trials > 0) {
    stStatus st = chain_evaluate(p, ws, generation, individual, net, e, err, errsz);
    if (st) return st;
    if (p->cfg.stage_chain_combine == ST_CHAIN_HARMONIC) fp[nprim++] = e->f_chain;
  }
  e->fitness = st_harmonic_fitness(&p->fitness, fp, nprim);
  if (e->chain_trials && p->cfg.stage_chain_combine == ST_CHAIN_SUM)
    e->fitness += chain_weight(p, e, fixed) * e->f_chain;
  return ST_OK;
}
