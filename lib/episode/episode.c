/* SPDX-License-Identifier: MIT
 * The one episode loop (selftalk/episode.h). */
#include "selftalk/episode.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/caretaker.h"
#include "selftalk/trialkind.h"

/* ---- protocol and workspace ---- */

/* builds (and frees) one dynamic world: its settings are refused now, naming the key, not at
 * the first dynamic trial, which may come after a whole simple-prim stage */
static stStatus check_dynamics(const stProtocol *p, char *err, size_t errsz) {
  stDynDef def;
  st_dyn_def_from_config(&p->cfg, &def);
  stWorld *w = NULL;
  const stStatus st = st_world_create_dynamic(p->robot, &p->scene, &def, &w, err, errsz);
  if (w) st_world_destroy(w);
  return st;
}

stStatus st_protocol_create(const stConfig *cfg, stProtocol **out, char *err, size_t errsz) {
  ST_ASSERT(cfg && out);
  *out = NULL;
  stStatus st = st_config_validate(cfg, err, errsz);
  if (!st) st = st_trial_kinds_check(cfg, NULL, err, errsz);
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
  p->reach_geom_z = p->reach_palm_z = -INFINITY;
  if (cfg->integrated_fail_end != ST_FAIL_END_PENALTY) /* runout: traced, for the proof */
    st_robot_lowest_z(p->robot, cfg->dynamics_limit_tolerance_deg * ST_DEG, &p->reach_geom_z,
                      &p->reach_palm_z);
  if ((st = st_postures_all(p->robot, &p->scene, p->posture, err, errsz)) ||
      (st = check_dynamics(p, err, errsz))) {
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

void st_workspace_free(stWorkspace *ws) {
  if (!ws) return;
  st_world_destroy(ws->kin);
  st_world_destroy(ws->dyn);
  free(ws->trials);
  ws->kin = ws->dyn = NULL;
  ws->trials = NULL;
}

const char *st_word_source_name(stWordSource s) {
  static const char *const names[ST_WORDS_COUNT] = {"none", "fixed", "caretaker", "selftalk",
                                                                    "handover"};
  return (int)s >= 0 && s < ST_WORDS_COUNT ? names[s] : "?";
}

const char *st_trial_end_name(stTrialEnd end) {
  static const char *const names[] = {"full", "success", "failure", "quiet"};
  return (int)end >= 0 && end <= ST_END_QUIET ? names[end] : "?";
}

int st_word_source_given(stWordSource s) {
  return s == ST_WORDS_FIXED || s == ST_WORDS_CARETAKER || s == ST_WORDS_HANDOVER;
}

int st_episode_label(const double *ling4) {
  ST_ASSERT(ling4);
  int best = 0;
  for (int m = 1; m < ST_NET_NLING; m++)
    if (ling4[m] > ling4[best]) best = m;
  return best;
}

/* ---- the network as a controller ---- */

static void net_reset(void *self, const stEpisodeSpec *e) {
  (void)e;
  stNetController *c = self;
  st_net_reset(c->net, &c->state);
}

static void net_act(void *self, const stWorld *w, const stQuantities *q, const double *in, int step,
                    double *out) {
  (void)w;
  (void)q;
  stNetController *c = self;
  st_net_step(c->net, &c->state, in, out);
  for (int i = 0; i < c->nforce; i++)
    if (step >= c->force[i].from_step) out[c->force[i].output] = c->force[i].value;
}

stController st_net_controller(stNetController *c, const stNetParams *net, const stForce *force,
                               int nforce) {
  ST_ASSERT(c && net);
  ST_ASSERT(nforce >= 0);
  memset(c, 0, sizeof *c);
  c->net = net;
  c->force = force;
  c->nforce = force ? nforce : 0;
  stController ctl = {net_reset, net_act, st_net_ninputs(net->arch), c,
                      st_net_noutputs(net->arch), net->arch == ST_ARCH_A, NULL};
  return ctl;
}

/* ---- a roll-in and the controller that takes over ---- */

static void rollin_reset(void *self, const stEpisodeSpec *e) {
  stRollinController *c = self;
  if (c->rollin.reset) c->rollin.reset(c->rollin.self, e);
  if (c->then.reset) c->then.reset(c->then.self, e);
  c->rolling = 0;
}

/* the roll-in acts while hand-over words have not handed over: the switch is decided by the
 * word source just before this step's action, on the state before it */
static void rollin_hear(void *self, stWordSource source, int word, int handover) {
  stRollinController *c = self;
  c->rolling = source == ST_WORDS_HANDOVER && handover < 0;
  const stController *actor = c->rolling ? &c->rollin : &c->then;
  if (actor->hear) actor->hear(actor->self, source, word, handover);
}

static void rollin_act(void *self, const stWorld *w, const stQuantities *q, const double *in,
                       int step, double *out) {
  stRollinController *c = self;
  const stController *actor = c->rolling ? &c->rollin : &c->then;
  actor->act(actor->self, w, q, in, step, out);
}

/* a controller of the base network's shape: 25 inputs, 13 outputs, no labels */
static int base_shaped(const stController *c) {
  const int nout = c->noutputs ? c->noutputs : ST_NET_NOUT;
  return c->act && c->ninputs == ST_NET_NIN && nout == ST_NET_NOUT && !c->talks;
}

stStatus st_rollin_controller(stRollinController *c, const stController *rollin,
                              const stController *then, stController *out, char *err,
                              size_t errsz) {
  ST_ASSERT(c && rollin && then && out);
  if (!base_shaped(rollin) || !base_shaped(then))
    return st__errf(err, errsz, "roll-in: two controllers of the base network's shape (%d inputs, "
                    "%d outputs, not talking; here %d/%d and %d/%d): only a network without "
                    "memory can take over mid-episode", ST_NET_NIN, ST_NET_NOUT, rollin->ninputs,
                    rollin->noutputs ? rollin->noutputs : ST_NET_NOUT, then->ninputs,
                    then->noutputs ? then->noutputs : ST_NET_NOUT), ST_ERR_ARG;
  memset(c, 0, sizeof *c);
  c->rollin = *rollin;
  c->then = *then;
  const stController ctl = {rollin_reset, rollin_act, ST_NET_NIN, c, ST_NET_NOUT, 0, rollin_hear};
  *out = ctl;
  return ST_OK;
}

stStatus st_force_check(const stForce *force, int nforce, char *err, size_t errsz) {
  ST_ASSERT(nforce >= 0 && (force || nforce == 0));
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
  return ST_OK;
}

/* ---- the loop ---- */

/* the world of a mode, created on first use */
static stStatus episode_world(const stProtocol *p, stWorkspace *ws, int dynamic, stWorld **w,
                              char *err, size_t errsz) {
  stStatus st = ST_OK;
  if (!dynamic) {
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

static stStatus check_episode(const stController *ctl, const stWords *words, char *err,
                              size_t errsz) {
  const int nout = ctl->noutputs ? ctl->noutputs : ST_NET_NOUT;
  if (nout < ST_NET_NOUT || nout > ST_NET_MAX_OUT || ctl->ninputs < ST_NET_NIN ||
      ctl->ninputs > ST_NET_MAX_IN)
    return st__errf(err, errsz, "episode: controller with %d inputs, %d outputs (expected %d..%d "
                    "and %d..%d)", ctl->ninputs, nout, ST_NET_NIN, ST_NET_MAX_IN, ST_NET_NOUT,
                    ST_NET_MAX_OUT), ST_ERR_ARG;
  if (words->source == ST_WORDS_SELFTALK && !(ctl->talks && nout >= ST_NET_MAX_OUT))
    return st__errf(err, errsz, "episode: self talk needs a controller that produces labels "
                    "(linguistic outputs 13-16: a type A network)"), ST_ERR_ARG;
  if ((int)words->source < 0 || words->source >= ST_WORDS_COUNT ||
      ((words->source == ST_WORDS_FIXED || words->source == ST_WORDS_HANDOVER) &&
       (words->word < 0 || words->word >= ST_NPRIM)))
    return st__errf(err, errsz, "episode: word source %d, word %d (expected a source of "
                    "stWordSource; a fixed or handed-over word 0..3)", (int)words->source,
                    words->word), ST_ERR_ARG;
  return ST_OK;
}

/* what the robot hears at this step, sensing the state before the action */
typedef struct hearing {
  stCaretaker ct;
  int last_label; /* self talk: the label of the previous step */
  int handover;   /* hand-over: the step the word was handed over at, -1 before */
  int gate;       /* self talk: integrated.selftalk_gate */
} hearing;

/* self talk's label as heard, through the diagnostic gate (integrated.selftalk_gate): the
 * caretaker is followed in step, unheard, to tell whether the label is ahead of the action */
static int gated(hearing *h, const stProtocol *p, int step, const stQuantities *q,
                 const stWorld *w) {
  const int label = h->last_label;
  switch (h->gate) {
    case ST_SELFTALK_GATE_MOVE:
      return label == ST_PRIM_MOVE &&
                     !st_caretaker_done(&h->ct, &p->fitness, ST_PRIM_GRASP, q, &w->contacts)
                 ? ST_PRIM_GRASP
                 : label;
    case ST_SELFTALK_GATE_AHEAD: {
      const int ct = st_caretaker_word(&h->ct, &p->fitness, step, q, &w->contacts);
      return label > ct ? ct : label;
    }
    default: return label;
  }
}

static int heard_word(hearing *h, const stProtocol *p, const stWords *words, int step,
                      const stQuantities *q, const stWorld *w) {
  switch (words->source) {
    case ST_WORDS_FIXED: return words->word;
    case ST_WORDS_CARETAKER: return st_caretaker_word(&h->ct, &p->fitness, step, q, &w->contacts);
    case ST_WORDS_SELFTALK: {
      const int label = gated(h, p, step, q, w); /* the gate's caretaker hears every step */
      return step == 0 ? -1 : label;
    }
    case ST_WORDS_HANDOVER:
      if (h->handover < 0 && st_caretaker_word(&h->ct, &p->fitness, step, q, &w->contacts) >= words->word)
        h->handover = step;
      return h->handover >= 0 ? words->word : h->ct.label;
    default: return -1;
  }
}

/* what no later step can undo (stTraceStep.out_of_reach, pen_moving_floor): the object's
 * energy bound against how low the robot reaches and how far the object is from its start */
static void future(const stProtocol *p, const stWorld *w, stTraceStep *s) {
  const stScene *sc = &p->scene;
  const double top = st_world_object_ceiling(w) + ST_REACH_MARGIN;
  if (!(top < INFINITY)) return;
  /* the object's extent about its centre: the sphere, or the rim of its flattened base */
  const double extent = sc->base_height > 0.0 ? hypot(sc->obj_radius, sc->base_radius) : sc->obj_radius;
  s->out_of_reach = top + extent < p->reach_geom_z &&
                    top + p->sensor.reach_height + p->fitness.success_dist < p->reach_palm_z;
  /* below its start by D, its distance from the start is at least D: the penalty's cap */
  const double D = fmax(p->sensor.move_free, p->sensor.move_max * p->sensor.move_scale);
  if (top + D <= w->obj_start[2]) s->pen_moving_floor = p->sensor.move_max;
}

/* the state after the action, for the scorer */
static void observe(const stProtocol *p, const stWorld *w, stTraceStep *s) {
  s->pen_table = st_penalty_table(w, &p->sensor);
  s->pen_object = st_penalty_object(w, &p->sensor);
  s->pen_moving = st_penalty_moving(w, &p->sensor);
  s->fell = st_world_object_fell(w);
  s->unstable = st_world_unstable(w);
  s->out_of_reach = 0;
  s->pen_moving_floor = 0.0;
  if (p->reach_geom_z > -INFINITY) future(p, w, s);
  s->S = s->P = 0.0;
  s->success_now = 0;
  s->event = -1;
}

stStatus st_episode_run(const stProtocol *p, stWorkspace *ws, const stEpisodeSpec *e,
                        const stController *ctl, const stWords *words, const stScorer *scorer,
                        stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && ws && e && ctl && ctl->act && words && scorer && scorer->step);
  ST_ASSERT(e->steps >= 0);
  stWorld *w = NULL;
  stStatus st = check_episode(ctl, words, err, errsz);
  if (!st) st = episode_world(p, ws, e->dynamic, &w, err, errsz);
  if (st) return st;
  st_world_set_seed(w, e->seed_key); /* quickstep's shuffling: keyed by the trial, not the thread */
  st_world_reset(w, e->qhat0, e->obj, e->target);
  if (ctl->reset) ctl->reset(ctl->self, e);
  if (scorer->begin) scorer->begin(scorer->self);
  hearing h;
  st_caretaker_init(&h.ct, &p->cfg);
  h.last_label = -1;
  h.handover = -1;
  h.gate = p->cfg.integrated_selftalk_gate;
  double in[ST_NET_MAX_IN] = {0}, out[ST_NET_MAX_OUT] = {0}, ling[ST_NET_NLING];
  stQuantities q;
  st_quantities(w, &p->sensor, &q);
  stTraceStep s;
  memset(&s, 0, sizeof s);
  s.world = w, s.q = &q, s.in = in, s.out = out, s.source = words->source;
  s.nout = ctl->noutputs ? ctl->noutputs : ST_NET_NOUT;
  const int relative_off = words->source == ST_WORDS_HANDOVER;
  for (int step = 0; step < e->steps; step++) {
    if (!relative_off && e->table_off_step >= 0 && step == e->table_off_step)
      st_world_set_object_table_collision(w, 0);
    /* hear, sense, think, act */
    s.step = step;
    s.word = heard_word(&h, p, words, step, &q, w);
    s.handover = h.handover;
    if (relative_off && e->table_off_step >= 0 && h.handover >= 0 &&
        step == h.handover + e->table_off_step)
      st_world_set_object_table_collision(w, 0);
    st_net_label_input(s.word, words->scale, ling);
    st_sensor_inputs(w, &p->sensor, &q, s.focus_target, step == 0, ling, words->secondary, in,
                     ctl->ninputs);
    if (ctl->hear) ctl->hear(ctl->self, words->source, s.word, h.handover);
    ctl->act(ctl->self, w, &q, in, step, out);
    s.label = ctl->talks ? st_episode_label(out + ST_NET_NOUT) : -1;
    h.last_label = s.label;
    s.focus_target = st_focus_is_target(&p->sensor, out[ST_NET_OUT_FOCUS]);
    st_world_step(w, out);
    /* score the state the step produced */
    st_quantities(w, &p->sensor, &q);
    observe(p, w, &s);
    s.event = scorer->step(scorer->self, &s);
    if (trace) trace(ctx, &s);
    if (s.event >= 0) break;
  }
  if (scorer->end) scorer->end(scorer->self, w);
  return ST_OK;
}
