/* SPDX-License-Identifier: MIT */
#include "selftalk/trial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

stStatus st_protocol_create(const stConfig *cfg, stProtocol **out, char *err, size_t errsz) {
  *out = NULL;
  stStatus st = st_config_validate(cfg, err, errsz);
  if (st) return st;
  stProtocol *p = calloc(1, sizeof *p);
  if (!p) return ST_ERR_NOMEM;
  p->cfg = *cfg;
  if ((st = st_robot_create(cfg, &p->robot, err, errsz))) {
    free(p);
    return st;
  }
  st_scene_from_config(cfg, &p->scene);
  st_sensor_def_from_config(cfg, &p->sensor);
  st_fitness_def_from_config(cfg, &p->fitness);
  p->net = st_net_def_from_config(cfg);
  p->primitives = st_config_primitive_mask(cfg);
  if ((st = st_postures_all(p->robot, &p->scene, p->posture, err, errsz))) {
    st_protocol_destroy(p);
    return st;
  }
  *out = p;
  return ST_OK;
}

void st_protocol_destroy(stProtocol *p) {
  if (!p) return;
  st_robot_destroy(p->robot);
  free(p);
}

void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  memset(t, 0, sizeof *t);
  t->stage = stage;
  t->index = index;
  t->primitive = index / ST_NPOSTURE;
  t->k = index % ST_NPOSTURE;
  t->target_index = t->k % 2;
  memcpy(t->qhat0, p->posture[t->primitive][t->k], sizeof t->qhat0);
  /* offsets: object (reach trials only, thesis 2.5.1) then target (every trial, 2.5.2) */
  stRng rng = st_rng_keyed((uint64_t)c->run_seed, ST_RNG_TRIAL, (uint64_t)generation, 0, (uint64_t)index);
  st_scene_object(&p->scene, t->k, t->primitive == ST_PRIM_REACH, &rng, t->obj);
  st_scene_target(&p->scene, t->target_index, &rng, t->target);
  if (stage == ST_STAGE_SIMPLE) {
    t->steps = c->stage_simple_steps;
    t->table_off_step = -1;
  } else {
    const int steps[ST_NPRIM] = {c->stage_main_reach_steps, c->stage_main_open_steps,
                                 c->stage_main_grasp_steps, c->stage_main_move_steps};
    t->steps = steps[t->primitive];
    t->table_off_step = t->primitive == ST_PRIM_GRASP  ? c->stage_grasp_table_off_step
                        : t->primitive == ST_PRIM_MOVE ? c->stage_move_table_off_step
                                                       : -1;
  }
  st_net_label_input(t->primitive, c->network_linguistic_input, t->ling);
}

void st_workspace_free(stWorkspace *ws) {
  if (!ws) return;
  st_world_destroy(ws->kin);
  st_world_destroy(ws->dyn);
  ws->kin = ws->dyn = NULL;
}

/* ---- the world of a stage: kinematic (simple-prim) or dynamic (main-prim) ---- */

static stStatus stage_world(const stProtocol *p, stWorkspace *ws, stStage stage, stWorld **w,
                            char *err, size_t errsz) {
  stStatus st = ST_OK;
  if (stage == ST_STAGE_SIMPLE) {
    if (!ws->kin) st = st_world_create(p->robot, &p->scene, &ws->kin, err, errsz);
    *w = ws->kin;
  } else {
    if (!ws->dyn) {
      stDynDef dd;
      st_dyn_def_from_config(&p->cfg, &dd);
      st = st_world_create_dynamic(p->robot, &p->scene, &dd, &ws->dyn, err, errsz);
    }
    *w = ws->dyn;
  }
  return st;
}

/* ---- one trial ---- */

static double penalties(const stProtocol *p, const stWorld *w, int mask) {
  double pen = 0.0;
  if (mask & ST_PEN_TABLE) pen += st_penalty_table(w, &p->sensor);
  if (mask & ST_PEN_OBJECT) pen += st_penalty_object(w, &p->sensor);
  if (mask & ST_PEN_MOVING) pen += st_penalty_moving(w, &p->sensor);
  return pen;
}

void st_score_begin(stTrialScore *sc, const stTrialSpec *t) {
  memset(sc, 0, sizeof *sc);
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

stStatus st_trial_run_controller(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                                 const stController *ctl, uint64_t seed_key, stTrialResult *r,
                                 stTraceFn trace, void *ctx, char *err, size_t errsz) {
  stWorld *w = NULL;
  stStatus st = stage_world(p, ws, t->stage, &w, err, errsz);
  if (st) return st;
  st_world_set_seed(w, seed_key); /* quickstep's shuffling: keyed by the trial, not the thread */
  st_world_reset(w, t->qhat0, t->obj, t->target);
  if (ctl->reset) ctl->reset(ctl->self, t);
  const int nin = ctl->ninputs;
  double in[ST_NET_MAX_IN], out[ST_NET_MAX_OUT];
  stQuantities q;
  st_quantities(w, &p->sensor, &q);
  stTrialScore sc;
  st_score_begin(&sc, t);
  int focus_target = 0;
  for (int step = 0; step < t->steps; step++) {
    if (t->table_off_step >= 0 && step == t->table_off_step) st_world_set_object_table_collision(w, 0);
    /* sense, think, act; primitive stages never give the secondary input */
    st_sensor_inputs(w, &p->sensor, &q, focus_target, step == 0, t->ling, 0.0, in, nin);
    ctl->act(ctl->self, w, &q, in, step, out);
    const double y_focus = out[ST_NET_OUT_FOCUS];
    focus_target = st_focus_is_target(&p->sensor, y_focus);
    st_world_step(w, out);
    st_quantities(w, &p->sensor, &q);
    /* score the state the step produced */
    const int mask = st_penalty_mask(t->stage, t->primitive, step,
                                     t->table_off_step >= 0 ? t->table_off_step : t->steps);
    double S, P;
    const int event = st_score_step(&sc, &p->fitness, step, &q, y_focus, p->sensor.focus_threshold,
                                    penalties(p, w, mask), st_world_object_fell(w),
                                    st_world_unstable(w), &S, &P);
    if (trace) {
      stTraceStep ts = {step, w, &q, in, out, focus_target,
                        S, P, st_success_now(&p->fitness, t->stage, t->primitive, &q), event};
      trace(ctx, &ts);
    }
    if (event >= 0) break;
  }
  st_score_end(&sc, &p->fitness, w->obj[2], p->scene.table_top_z, r);
  return ST_OK;
}

/* the evolved network as a controller, some outputs optionally forced */
typedef struct netCtl {
  const stNetParams *net;
  stNetState state;
  const stForce *force;
  int nforce;
} netCtl;

static void net_reset(void *self, const stTrialSpec *t) {
  (void)t;
  netCtl *c = self;
  st_net_reset(c->net, &c->state);
}

static void net_act(void *self, const stWorld *w, const stQuantities *q, const double *in, int step,
                    double *out) {
  (void)w;
  (void)q;
  netCtl *c = self;
  st_net_step(c->net, &c->state, in, out);
  for (int i = 0; i < c->nforce; i++)
    if (step >= c->force[i].from_step) out[c->force[i].output] = c->force[i].value;
}

stStatus st_trial_run_forced(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                             const stNetParams *net, const stForce *force, int nforce,
                             uint64_t seed_key, stTrialResult *r, stTraceFn trace, void *ctx,
                             char *err, size_t errsz) {
  if (nforce < 0 || (nforce > 0 && !force))
    return st__errf(err, errsz, "forced outputs: count %d (expected >= 0, and a list when > 0)",
                    nforce), ST_ERR_ARG;
  for (int i = 0; i < nforce; i++) {
    const stForce *f = &force[i];
    if (f->output < 0 || f->output > ST_NET_OUT_FOCUS)
      return st__errf(err, errsz, "forced output %d (expected 0..%d: the 12 DOF, then focus)",
                      f->output, ST_NET_OUT_FOCUS), ST_ERR_RANGE;
    if (!(f->value >= 0.0 && f->value <= 1.0))
      return st__errf(err, errsz, "forced output %d: value %g (expected 0..1)", f->output,
                      f->value), ST_ERR_RANGE;
    if (f->from_step < 0)
      return st__errf(err, errsz, "forced output %d: from step %d (expected >= 0)", f->output,
                      f->from_step), ST_ERR_RANGE;
  }
  netCtl c = {net, {{0}, {0}, {0}, {0}, 0}, force, nforce};
  stController ctl = {net_reset, net_act, st_net_ninputs(net->arch), &c};
  return st_trial_run_controller(p, ws, t, &ctl, seed_key, r, trace, ctx, err, errsz);
}

stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stNetParams *net, uint64_t seed_key, stTrialResult *r, stTraceFn trace,
                      void *ctx, char *err, size_t errsz) {
  return st_trial_run_forced(p, ws, t, net, NULL, 0, seed_key, r, trace, ctx, err, errsz);
}

stStatus st_stage_evaluate(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, stEvaluation *e, char *err,
                           size_t errsz) {
  memset(e, 0, sizeof *e);
  double sum_sp[ST_NPRIM] = {0}, bonus[ST_NPRIM] = {0};
  long n[ST_NPRIM] = {0};
  for (int i = 0; i < ST_PRIM_TRIALS; i++) {
    stTrialSpec t;
    st_trial_spec(p, stage, generation, i, &t);
    if (!(p->primitives >> t.primitive & 1u)) continue;
    e->ntrials++;
    stTrialResult r;
    uint64_t key = st_rng_keyed((uint64_t)p->cfg.run_seed, ST_RNG_TRIAL, (uint64_t)generation,
                                (uint64_t)individual, (uint64_t)i).key;
    stStatus st = st_trial_run(p, ws, &t, net, key, &r, NULL, NULL, err, errsz);
    if (st) return st;
    sum_sp[t.primitive] += r.sum_s - r.sum_p;
    n[t.primitive] += r.steps;
    bonus[t.primitive] += r.success ? p->fitness.bonus : 0.0;
    e->success[i] = (uint8_t)r.success;
    e->successes += r.success;
    e->unstable += r.unstable;
  }
  double fp[ST_NPRIM];
  int nprim = 0;
  for (int k = 0; k < ST_NPRIM; k++) {
    e->fp[k] = st_primitive_fitness(&p->fitness, bonus[k], sum_sp[k], n[k]);
    if (p->primitives >> k & 1u) fp[nprim++] = e->fp[k];
  }
  e->fitness = st_harmonic_fitness(&p->fitness, fp, nprim);
  return ST_OK;
}
