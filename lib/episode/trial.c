/* SPDX-License-Identifier: MIT
 * Trials of the primitive stages (selftalk/trial.h): a trial's spec and episode through its
 * kind's row (selftalk/trialkind.h, lib/episode/trials/), its scoring, and an individual's
 * evaluation over the kinds' trials. */
#include "selftalk/trial.h"

#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "episode/trials/trials.h"

/* the index ranges are whole postures: index % ST_NPOSTURE is a trial's posture in each */
#define ST__TRIAL_KIND_WHOLE(E, name, max, indexed) &&(max) % ST_NPOSTURE == 0
typedef char st__trial_ranges_aligned[(1 ST_TRIAL_KINDS(ST__TRIAL_KIND_WHOLE)) ? 1 : -1];
#undef ST__TRIAL_KIND_WHOLE
typedef char st__fixed_are_16[ST_TRIAL_MAX_FIXED == ST_PRIM_TRIALS ? 1 : -1];

/* ---- a trial's spec, through its kind ---- */

void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t) {
  ST_ASSERT(p && t);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  ST_ASSERT(generation >= 0);
  ST_ASSERT(index >= 0 && index < (stage == ST_STAGE_MAIN ? ST_MAIN_TRIALS_MAX : ST_PRIM_TRIALS));
  memset(t, 0, sizeof *t);
  t->stage = stage;
  t->index = index;
  t->generation = generation;
  t->kind = st_trial_kind(index);
  t->j = index - st_trial_kind_first(t->kind);
  st_trial_kind_def(t->kind)->spec(p, t);
}

int st_trial_primitive(int index) {
  const stTrialKind k = st_trial_kind(index);
  return st_trial_kind_def(k)->primitive(index - st_trial_kind_first(k));
}

uint64_t st_trial_seed_key(const stProtocol *p, int generation, int individual, int index) {
  ST_ASSERT(p);
  ST_ASSERT(generation >= 0 && individual >= 0);
  ST_ASSERT(index >= 0 && index < ST_MAIN_TRIALS_MAX);
  const stTrialKind k = st_trial_kind(index);
  return st_trial_kind_def(k)->seed_key(p, generation, individual,
                                         index - st_trial_kind_first(k));
}

int st_stage_trials(const stProtocol *p, stStage stage) {
  ST_ASSERT(p);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  int n = 0;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (d->indexed && d->count(&p->cfg, stage) > 0) n = st_trial_kind_first(d->kind) + d->max;
  }
  return n;
}

int st_stage_trial_active(const stProtocol *p, stStage stage, int generation, int i) {
  ST_ASSERT(p);
  ST_ASSERT(generation >= 0);
  ST_ASSERT(i >= 0 && i < st_stage_trials(p, stage));
  return (p->primitives >> st_trial_primitive(i) & 1u) &&
         st_trial_kind_runs(&p->cfg, stage, generation, st_trial_kind(i));
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

void st_trial_episode(const stProtocol *p, const stTrialSpec *t, uint64_t seed_key,
                      stEpisodeSpec *e, stWords *words) {
  ST_ASSERT(p && t && e && words);
  ST_ASSERT(t->primitive >= 0 && t->primitive < ST_NPRIM);
  memset(e, 0, sizeof *e);
  e->dynamic = t->stage != ST_STAGE_SIMPLE;
  memcpy(e->qhat0, t->qhat0, sizeof e->qhat0);
  memcpy(e->obj, t->obj, sizeof e->obj);
  memcpy(e->target, t->target, sizeof e->target);
  e->steps = t->rollin_steps + t->steps;
  e->table_off_step = t->table_off_step;
  e->seed_key = seed_key;
  /* the primitive's word every step (hand-over trials: once the caretaker hands over);
   * primitive stages never give the secondary input */
  words->source = t->kind == ST_TRIAL_HANDOVER ? ST_WORDS_HANDOVER : ST_WORDS_FIXED;
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

int st__prim_score(stPrimScorer *s, stTraceStep *ts) {
  const stTrialSpec *t = s->t;
  const int mask = st_penalty_mask(t->stage, t->primitive, ts->step,
                                   t->table_off_step >= 0 ? t->table_off_step : t->steps);
  const int event = st_score_step(&s->sc, &s->p->fitness, ts->step, ts->q, ts->out[ST_NET_OUT_FOCUS],
                                  s->p->sensor.focus_threshold, masked_penalty(ts, mask), ts->fell,
                                  ts->unstable, &ts->S, &ts->P);
  ts->success_now = st_success_now(&s->p->fitness, t->stage, t->primitive, ts->q);
  return event;
}

/* the kind's scoring of a step (a hand-over trial's counts from the hand-over) */
static int prim_step(void *self, stTraceStep *ts) {
  stPrimScorer *s = self;
  const stTrialKindDef *d = st_trial_kind_def(s->t->kind);
  return d->score ? d->score(s, ts) : st__prim_score(s, ts);
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

/* ---- one trial ---- */

stStatus st__trial_episode_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                               const stController *ctl, uint64_t seed_key, stTrialResult *r,
                               stTraceFn trace, void *ctx, char *err, size_t errsz) {
  stEpisodeSpec e;
  stWords words;
  st_trial_episode(p, t, seed_key, &e, &words);
  stPrimScorer ps;
  const stScorer sc = st_prim_scorer(&ps, p, t, r);
  return st_episode_run(p, ws, &e, ctl, &words, &sc, trace, ctx, err, errsz);
}

stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stController *ctl, uint64_t seed_key, stTrialResult *r,
                      stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && t && ctl && ctl->act && r);
  const stTrialKindDef *d = st_trial_kind_def(t->kind);
  stStatus st = st__trial_episode_run(p, ws, t, ctl, seed_key, r, trace, ctx, err, errsz);
  if (!st && d->finish) st = d->finish(p, ws, t, ctl, seed_key, r, trace, ctx, err, errsz);
  return st;
}

/* ---- an individual's evaluation ---- */

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

/* an individual's sums over its trials, per primitive (eq. 2.3) */
typedef struct stageSums {
  double sum_sp[ST_NPRIM], bonus[ST_NPRIM];
  long n[ST_NPRIM];
} stageSums;

/* the controllers of an evaluation: the individual's network, and with a roll-in network the
 * two composed (st_rollin_controller), which acts as the individual alone but in a hand-over
 * trial's roll-in */
typedef struct evalActors {
  stNetController net, rollin_net;
  stRollinController rolled;
  stController ctl;
} evalActors;

/* the base network has no memory (hidden from the inputs at t, outputs from the hidden at t:
 * lib/core/net.c), so the individual can take over from the elite at the hand-over step as if it
 * had acted the roll-in itself; a type A or B network's linguistic units carry the past, which
 * the switch would drop */
static stStatus make_actors(const stProtocol *p, stStage stage, const stNetParams *net,
                            const stNetParams *rollin, evalActors *a, char *err, size_t errsz) {
  if (st_stage_rollin_elite(p, stage) != (rollin != NULL))
    return st__errf(err, errsz, "stage.handover_rollin = %s: %s (expected the generation's "
                    "elite's network exactly when main-prim's hand-over trials are rolled in by it)",
                    st_config_enum_name("stage", "handover_rollin", p->cfg.stage_handover_rollin),
                    rollin ? "a roll-in network was given" : "no roll-in network was given"),
           ST_ERR_ARG;
  a->ctl = st_net_controller(&a->net, net, NULL, 0);
  if (!rollin) return ST_OK;
  if (rollin->arch != ST_ARCH_BASE || net->arch != ST_ARCH_BASE)
    return st__errf(err, errsz, "stage.handover_rollin = elite: networks %s and %s (expected two "
                    "base networks: only a network without memory can take over from the "
                    "roll-in)", st_arch_name(net->arch), st_arch_name(rollin->arch)), ST_ERR_ARG;
  const stController individual = a->ctl, elite = st_net_controller(&a->rollin_net, rollin, NULL, 0);
  return st_rollin_controller(&a->rolled, &elite, &individual, &a->ctl, err, errsz);
}

/* runs indexed trial t of the generation: into its primitive's sums and its kind's results */
static stStatus add_trial(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                          int individual, const stController *ctl, stageSums *sums,
                          stEvaluation *e, char *err, size_t errsz) {
  const uint64_t key = st_trial_seed_key(p, t->generation, individual, t->index);
  stTrialResult r;
  stStatus st = st_trial_run(p, ws, t, ctl, key, &r, NULL, NULL, err, errsz);
  if (st) return st;
  sums->sum_sp[t->primitive] += r.sum_s - r.sum_p;
  sums->n[t->primitive] += r.steps;
  sums->bonus[t->primitive] += r.success ? p->fitness.bonus : 0.0;
  const stTrialKindDef *d = st_trial_kind_def(t->kind);
  stKindEvaluation *ke = &e->kind[t->kind];
  ke->trials++;
  ke->successes += r.success;
  ke->unstable += r.unstable;
  ke->count += d->counts ? d->counts(t, &r) : 0;
  ke->success[t->j] = r.success;
  return ST_OK;
}

/* the block kinds' trials (chained), after the indexed ones */
static stStatus add_blocks(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, stEvaluation *e, char *err,
                           size_t errsz) {
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (d->indexed || !st_trial_kind_runs(&p->cfg, stage, generation, d->kind)) continue;
    stStatus st = d->evaluate(p, ws, generation, individual, net, &e->kind[k], err, errsz);
    if (st) return st;
  }
  return ST_OK;
}

/* F: the harmonic mean of the evaluated primitives' F_p and the kinds' terms, plus what the
 * kinds add */
static double combined_fitness(const stProtocol *p, stStage stage, int generation,
                               const stEvaluation *e) {
  double terms[ST_NPRIM + ST_TRIAL_KIND_COUNT], added = 0.0;
  int n = 0;
  for (int k = 0; k < ST_NPRIM; k++)
    if (p->primitives >> k & 1u) terms[n++] = e->fp[k];
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (d->fitness && st_trial_kind_runs(&p->cfg, stage, generation, d->kind))
      d->fitness(p, e, terms, &n, &added);
  }
  return st_harmonic_fitness(&p->fitness, terms, n) + added;
}

stStatus st_stage_evaluate(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, const stNetParams *rollin,
                           stEvaluation *e, char *err, size_t errsz) {
  ST_ASSERT(p && ws && net && e);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  ST_ASSERT(generation >= 0 && individual >= 0);
  memset(e, 0, sizeof *e);
  evalActors a;
  stStatus st = make_actors(p, stage, net, rollin, &a, err, errsz);
  if (st) return st;
  const stTrialTable *tab = generation_table(p, ws, stage, generation, err, errsz);
  if (!tab) return ST_ERR_NOMEM;
  stageSums sums;
  memset(&sums, 0, sizeof sums);
  for (int i = 0; i < tab->n && !st; i++)
    if (st_stage_trial_active(p, stage, generation, i))
      st = add_trial(p, ws, &tab->t[i], individual, &a.ctl, &sums, e, err, errsz);
  if (!st) st = add_blocks(p, ws, stage, generation, individual, net, e, err, errsz);
  if (st) return st;
  for (int k = 0; k < ST_NPRIM; k++)
    e->fp[k] = st_primitive_fitness(&p->fitness, sums.bonus[k], sums.sum_sp[k], sums.n[k]);
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    e->ntrials += e->kind[k].trials;
    e->successes += e->kind[k].successes;
    e->unstable += e->kind[k].unstable;
  }
  e->fitness = combined_fitness(p, stage, generation, e);
  return ST_OK;
}

int st_evaluation_completes(const stConfig *cfg, const stEvaluation *e) {
  ST_ASSERT(cfg && e);
  ST_ASSERT(e->successes >= 0 && e->successes <= e->ntrials);
  const stKindEvaluation *fixed = &e->kind[ST_TRIAL_FIXED], *chained = &e->kind[ST_TRIAL_CHAINED];
  const int fixed_chained =
      cfg->stage_chain_complete == ST_CHAIN_COMPLETE_FIXED_CHAINED && chained->trials > 0;
  /* fixed trials from drawn starts count only under replace with every trial counted: with
   * extra they are its first phase (vary_replace_generations), and fixed_chained asks for the
   * thesis's 16 from their fixed starts */
  if (fixed->count > 0 && (cfg->postures_vary_trials == ST_VARY_EXTRA || fixed_chained))
    return 0;
  if (!fixed_chained) return e->successes == e->ntrials;
  return fixed->successes == fixed->trials && chained->successes == chained->trials;
}
