/* SPDX-License-Identifier: MIT
 * The press scenario's plan, one home for apps/bench.c and tools/compare/compare.c: the scripted
 * controller's grasp (lib/episode/scripted.c) from grasp start k with the table kept on, run once
 * (untimed) and recorded: its commands and the posture from ST_PRESS_LEAD steps before its hand
 * starts closing on the ball ("grasp:close"). A timed press trial starts at rest from that
 * posture and replays the next `steps` commands: the palm lowered over the ball, thumb and
 * fingers closing and squeezing it on the table. Header-only (static): the apps and the tools
 * link the library alone. */
#ifndef ST_APPS_PRESS_PLAN_H
#define ST_APPS_PRESS_PLAN_H

#include <stdlib.h>
#include <string.h>

#include "selftalk/episode.h"
#include "selftalk/scripted.h"
#include "selftalk/trial.h"
#include "selftalk/world.h"

enum { ST_PRESS_LEAD = 2, ST_PRESS_EXTRA = 40 }; /* steps before grasp:close; recorded beyond */

typedef struct stPressRec {
  stController inner;
  stScripted *s;
  int start, n;                        /* first step of grasp:close (-1 before); steps kept */
  double (*y)[ST_NDOF], (*q)[ST_NDOF]; /* commands and postures of steps 0..n-1 */
} stPressRec;

static void st_press_rec_reset(void *self, const stEpisodeSpec *e) {
  stPressRec *r = self;
  r->start = -1;
  if (r->inner.reset) r->inner.reset(r->inner.self, e);
}

static void st_press_rec_act(void *self, const stWorld *w, const stQuantities *q, const double *in,
                             int step, double *out) {
  stPressRec *r = self;
  r->inner.act(r->inner.self, w, q, in, step, out);
  if (step < r->n) {
    memcpy(r->y[step], out, sizeof r->y[step]);
    memcpy(r->q[step], w->qhat, sizeof r->q[step]);
  }
  if (r->start < 0 && !strcmp(st_scripted_phase(r->s), "grasp:close")) r->start = step;
}

static int st_press_rec_step(void *self, stTraceStep *ts) {
  (void)self;
  return ts->unstable ? ST_END_FAILURE : -1;
}

/* Press trial k's start posture q0, object, target and `steps` commands y (steps x ST_NDOF),
 * in a world of `def`. ST_OK, or the status and err of what failed. */
static stStatus st_press_plan(const stProtocol *p, const stDynDef *def, int k, int steps,
                              double *q0, double *obj, double *target, double *y, char *err,
                              size_t errsz) {
  stWorld *w = NULL;
  stScripted *s = NULL;
  stPressRec r = {{0}, NULL, -1, steps + ST_PRESS_EXTRA, NULL, NULL};
  r.y = calloc((size_t)r.n, sizeof *r.y);
  r.q = calloc((size_t)r.n, sizeof *r.q);
  stStatus st = !r.y || !r.q ? (snprintf(err, errsz, "out of memory"), ST_ERR_NOMEM) : ST_OK;
  if (!st) st = st_world_create_dynamic(p->robot, &p->scene, def, &w, err, errsz);
  if (!st) st = st_scripted_create(p, &s, err, errsz);
  if (!st) {
    stWorkspace ws = {NULL, w, NULL};
    r.inner = st_scripted_controller(s);
    r.s = s;
    stController ctl = r.inner;
    ctl.reset = st_press_rec_reset;
    ctl.act = st_press_rec_act;
    ctl.self = &r;
    const stScorer sc = {NULL, st_press_rec_step, NULL, NULL};
    stTrialSpec spec;
    st_trial_spec(p, ST_STAGE_MAIN, 0, ST_PRIM_GRASP * ST_NPOSTURE + k, &spec);
    stEpisodeSpec ep;
    stWords words;
    st_trial_episode(p, &spec, (uint64_t)k, &ep, &words);
    ep.steps = r.n;
    ep.table_off_step = -1;
    st = st_episode_run(p, &ws, &ep, &ctl, &words, &sc, NULL, NULL, err, errsz);
    if (!st) {
      int s0 = r.start - ST_PRESS_LEAD;
      if (r.start < 0 || s0 + steps > r.n) s0 = r.n - steps;
      memcpy(q0, r.q[s0], sizeof r.q[s0]);
      memcpy(obj, ep.obj, sizeof ep.obj);
      memcpy(target, ep.target, sizeof ep.target);
      memcpy(y, r.y[s0], sizeof(double) * ST_NDOF * (size_t)steps);
    }
  }
  if (s) st_scripted_destroy(s);
  if (w) st_world_destroy(w);
  free(r.y), free(r.q);
  return st;
}

#endif
