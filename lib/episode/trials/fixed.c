/* SPDX-License-Identifier: MIT
 * The fixed trials (selftalk/trialkind.h): the thesis's 16 of each primitive stage (§2.7-§2.8,
 * SPEC §2, §8), primitive i / 4 from posture and object position i % 4, the target i % 4 mod 2. */
#include <string.h>

#include "core/internal.h"
#include "episode/trials/trials.h"
#include "selftalk/postures.h"

int st__main_steps(const stConfig *c, int primitive) {
  const int steps[ST_NPRIM] = {c->stage_main_reach_steps, c->stage_main_open_steps,
                               c->stage_main_grasp_steps, c->stage_main_move_steps};
  return steps[primitive];
}

int st__main_table_off(const stConfig *c, int primitive) {
  return primitive == ST_PRIM_GRASP  ? c->stage_grasp_table_off_step
         : primitive == ST_PRIM_MOVE ? c->stage_move_table_off_step
                                     : -1;
}

void st__drawn_start(const stProtocol *p, stTrialSpec *t) {
  const stConfig *c = &p->cfg;
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_STARTS, (uint64_t)t->generation, 0,
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

void st__fixed_trial(const stProtocol *p, stTrialSpec *t, int primitive, int k, int drawn) {
  const stConfig *c = &p->cfg;
  t->primitive = primitive;
  t->k = k;
  t->target_index = k % 2;
  memcpy(t->qhat0, p->posture[primitive][k], sizeof t->qhat0);
  stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_TRIAL, (uint64_t)t->generation, 0,
                           (uint64_t)t->index);
  st_scene_object(&p->scene, k, primitive == ST_PRIM_REACH, &rng, t->obj);
  st_scene_target(&p->scene, t->target_index, &rng, t->target);
  if (drawn) st__drawn_start(p, t);
  if (t->stage == ST_STAGE_SIMPLE) {
    t->steps = c->stage_simple_steps;
    t->table_off_step = -1;
  } else {
    t->steps = st__main_steps(c, primitive);
    t->table_off_step = st__main_table_off(c, primitive);
  }
}

static int fixed_count(const stConfig *cfg, stStage stage) {
  (void)cfg;
  (void)stage;
  return ST_PRIM_TRIALS;
}

static int fixed_primitive(int j) { return j / ST_NPOSTURE; }

/* open's and grasp's start from drawn postures in the generations that replace theirs */
static void fixed_spec(const stProtocol *p, stTrialSpec *t) {
  const int primitive = fixed_primitive(t->j);
  const int drawn = st_vary_replacing(&p->cfg, t->generation) &&
                    (primitive == ST_PRIM_OPEN || primitive == ST_PRIM_GRASP);
  st__fixed_trial(p, t, primitive, t->j % ST_NPOSTURE, drawn);
}

/* the solver's key of a trial index (the fixed and the varied trials) */
static uint64_t fixed_seed_key(const stProtocol *p, int generation, int individual, int j) {
  return st_rng_keyed(st_config_rng_seed(&p->cfg), ST_RNG_TRIAL, (uint64_t)generation,
                      (uint64_t)individual,
                      (uint64_t)(st_trial_kind_first(ST_TRIAL_FIXED) + j)).key;
}

static int fixed_counts(const stTrialSpec *t, const stTrialResult *r) {
  (void)r;
  return t->start_draws > 0; /* a generation that replaces drew its start */
}

/* the row: what it is; its streams; its hooks; its fitness.csv column */
const stTrialKindDef st__trial_fixed = {
    ST__TRIAL_KIND(FIXED, fixed), .title = "fixed trials",
    .offsets = ST_RNG_TRIAL, .starts = ST_RNG_STARTS, .solver = ST_RNG_TRIAL,
    .count = fixed_count, .primitive = fixed_primitive, .spec = fixed_spec, .counts = fixed_counts,
    .seed_key = fixed_seed_key,
    .trial_column = ST_TRIAL_COLUMN,
};
