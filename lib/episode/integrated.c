/* SPDX-License-Identifier: MIT
 * Integrated trials in the simulator: their episodes, the integrated scorer of the episode
 * loop, and an individual's evaluation (selftalk/integrated.h). */
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/integrated.h"

void st_int_episode(const stProtocol *p, const stIntegratedDef *def, int k, int t, stRng *rng,
                    uint64_t seed_key, stEpisodeSpec *e) {
  ST_ASSERT(p && def && e);
  ST_ASSERT(k >= 0 && k < ST_NPOSTURE);
  ST_ASSERT(t >= 0 && t <= ST_TARGET_GENERAL);
  memset(e, 0, sizeof *e);
  e->dynamic = 1;
  memcpy(e->qhat0, p->posture[ST_PRIM_REACH][k], sizeof e->qhat0);
  /* offsets: object x/y, then target x/y/z (thesis 2.5.1-2.5.2), as in the primitive trials */
  st_scene_object(&p->scene, k, rng != NULL, rng, e->obj);
  st_scene_target(&p->scene, t, rng, e->target);
  e->steps = def->steps;
  e->table_off_step = -1; /* the object-table collision stays on */
  e->seed_key = seed_key;
}

int st_int_trial_type(const stProtocol *p, int i) {
  ST_ASSERT(p && i >= 0);
  /* pairs: trials 2k and 2k+1 share type k, so each parity (the caretaker's trials and the
   * others in ST-CT and CT) has every type once in 8 trials */
  return p->cfg.integrated_trial_order == ST_TRIAL_ORDER_PAIRS ? i / 2 % ST_NPOSTURE : i % ST_NPOSTURE;
}

void st_int_trial(const stProtocol *p, const stIntegratedDef *def, int generation, int individual,
                  int i, stEpisodeSpec *e) {
  ST_ASSERT(p && def && e);
  ST_ASSERT(generation >= 0 && individual >= 0 && i >= 0);
  const uint64_t seed = st_config_rng_seed(&p->cfg);
  stRng rng = st_rng_keyed(seed, ST_RNG_INTEGRATED, (uint64_t)generation, 0, (uint64_t)i);
  const uint64_t key =
      st_rng_keyed(seed, ST_RNG_SOLVER, (uint64_t)generation, (uint64_t)individual, (uint64_t)i).key;
  const int k = st_int_trial_type(p, i);
  st_int_episode(p, def, k, k % 2, &rng, key, e);
}

stWords st_int_words(const stProtocol *p, stWordSource source) {
  ST_ASSERT(p);
  stWords w = {source, -1, p->cfg.network_linguistic_input, p->cfg.network_secondary_input};
  return w;
}

/* ---- the scorer ---- */

static void int_begin(void *self) {
  stIntScorer *s = self;
  st_int_score_begin(&s->sc, &s->p->fitness, s->p->sensor.focus_threshold, s->def);
  s->sc.keep = s->keep;
  if (s->rec) s->rec->n = 0;
}

/* the word heard and the linguistic outputs of this step, for the prediction fitness */
static void record(stIntRecord *rec, const stTraceStep *ts) {
  if (!rec || rec->n >= rec->cap) return;
  rec->word[rec->n] = ts->word;
  for (int m = 0; m < ST_PRED_NWORDS; m++)
    rec->o[rec->n][m] = ts->nout >= ST_NET_MAX_OUT ? ts->out[ST_NET_NOUT + m] : 0.0;
  rec->n++;
}

static int int_step(void *self, stTraceStep *ts) {
  stIntScorer *s = self;
  int event = st_int_score_step(&s->sc, ts->step, ts->q, ts->out[ST_NET_OUT_FOCUS],
                                ts->pen_table, ts->pen_moving, ts->fell, ts->unstable, &ts->S,
                                &ts->P);
  ts->success_now = ts->q->lifted && ts->q->d_m < s->p->fitness.target_radius;
  if (ts->word > s->sc.r.furthest_word) s->sc.r.furthest_word = ts->word;
  record(s->rec, ts);
  /* the caretaker's word cannot move on once the object is out of reach (its switches need the
   * palm near it or a touch); self talk's labels are the controller's */
  if (event < 0)
    event = st_int_score_settle(&s->sc, ts->out_of_reach, ts->pen_moving_floor,
                                ts->source != ST_WORDS_SELFTALK);
  return event;
}

static void int_end(void *self, const stWorld *w) {
  (void)w;
  stIntScorer *s = self;
  st_int_score_end(&s->sc, s->r);
}

stScorer st_int_scorer(stIntScorer *s, const stProtocol *p, const stIntegratedDef *def,
                       stIntTrialResult *r, stIntRecord *rec) {
  ST_ASSERT(s && p && def && r);
  s->p = p;
  s->def = def;
  s->r = r;
  s->rec = rec;
  /* a prediction trial's points are not in its fitness; its record is, once reached */
  s->keep = rec ? ST_INT_KEEP_RECORD : ST_INT_KEEP_POINTS;
  stScorer sc = {int_begin, int_step, int_end, s};
  return sc;
}

/* ---- a network's trials ---- */

static stStatus record_alloc(stIntRecord *rec, int steps, char *err, size_t errsz) {
  rec->cap = steps;
  rec->n = 0;
  rec->word = malloc(sizeof *rec->word * (size_t)steps);
  rec->o = malloc(sizeof *rec->o * (size_t)steps);
  if (rec->word && rec->o) return ST_OK;
  free(rec->word);
  free(rec->o);
  return st__errf(err, errsz, "integrated trial: out of memory"), ST_ERR_NOMEM;
}

/* the prediction score of a recorded caretaker trial (st_int_combine counts it only when the
 * object reached the target lifted, eq. 2.24); a trial cut short before its second step has
 * none */
static stStatus score_prediction(const stIntegratedDef *def, const stIntRecord *rec,
                                 stPredScore *pred, char *err, size_t errsz) {
  memset(pred, 0, sizeof *pred);
  if (rec->n < 2) return ST_OK;
  const stPredTrial t = {rec->n, rec->word, (const double(*)[ST_PRED_NWORDS])rec->o};
  return st_pred_trial(&def->pred, &t, pred, err, errsz);
}

stStatus st_int_trial_run(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                          int generation, int individual, int i, const stNetParams *net,
                          stIntPlan *plan, stIntTrialResult *r, stPredScore *pred,
                          stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && def && ws && net && plan && r);
  ST_ASSERT(generation >= 0 && individual >= 0 && i >= 0);
  *plan = st_integrated_plan(def, generation, i);
  stEpisodeSpec e;
  st_int_trial(p, def, generation, individual, i, &e);
  stNetController nc;
  const stController ctl = st_net_controller(&nc, net, NULL, 0);
  return st_int_run_with(p, def, ws, &e, &ctl, plan, r, pred, trace, ctx, err, errsz);
}

stStatus st_int_run_with(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                         const stEpisodeSpec *e, const stController *ctl, const stIntPlan *plan,
                         stIntTrialResult *r, stPredScore *pred, stTraceFn trace, void *ctx,
                         char *err, size_t errsz) {
  ST_ASSERT(p && def && ws && e && ctl && plan && r);
  const stWords words = st_int_words(p, plan->words);
  const int predicts = plan->fitness == ST_FIT_PREDICTION;
  stIntRecord rec = {0, 0, NULL, NULL};
  stStatus st = predicts ? record_alloc(&rec, e->steps, err, errsz) : ST_OK;
  stIntScorer is;
  const stScorer sc = st_int_scorer(&is, p, def, r, predicts ? &rec : NULL);
  if (!st) st = st_episode_run(p, ws, e, ctl, &words, &sc, trace, ctx, err, errsz);
  if (pred) memset(pred, 0, sizeof *pred);
  if (!st && pred && predicts) st = score_prediction(def, &rec, pred, err, errsz);
  free(rec.word);
  free(rec.o);
  return st;
}

stStatus st_int_evaluate(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                         int generation, int individual, const stNetParams *net,
                         stIntEvaluation *e, char *err, size_t errsz) {
  ST_ASSERT(p && def && ws && net && e);
  stIntPlan plan[ST_INT_MAX_TRIALS];
  stIntTrialResult r[ST_INT_MAX_TRIALS];
  stPredScore pred[ST_INT_MAX_TRIALS];
  const int n = def->trials < ST_INT_MAX_TRIALS ? def->trials : ST_INT_MAX_TRIALS;
  for (int i = 0; i < n; i++) {
    stStatus st = st_int_trial_run(p, def, ws, generation, individual, i, net, &plan[i], &r[i],
                                   &pred[i], NULL, NULL, err, errsz);
    if (st) return st;
  }
  st_int_combine(p->fitness.bonus, p->fitness.scale, plan, r, pred, n, e);
  return ST_OK;
}
