/* SPDX-License-Identifier: MIT
 * The varied trials (selftalk/trialkind.h; postures.vary_starts with vary_trials = extra,
 * docs/PROTOCOL.md "Varied starts"; not the thesis's): main-prim's open and grasp trials k again,
 * from postures drawn per generation and trial beside the fixed ones. The drawn starts' keys
 * (postures.vary_*) are this row's; with vary_trials = replace the fixed trials take the drawn
 * starts themselves (st_vary_replacing, lib/episode/trials/fixed.c). */
#include "core/internal.h"
#include "episode/trials/trials.h"

int st_vary_replacing(const stConfig *cfg, int generation) {
  ST_ASSERT(cfg);
  ST_ASSERT(generation >= 0);
  return cfg->postures_vary_starts && (cfg->postures_vary_trials == ST_VARY_REPLACE ||
                                       generation < cfg->postures_vary_replace_generations);
}

static int varied_count(const stConfig *cfg, stStage stage) {
  return stage == ST_STAGE_MAIN && cfg->postures_vary_starts &&
                 cfg->postures_vary_trials == ST_VARY_EXTRA
             ? ST_TRIAL_MAX_VARIED
             : 0;
}

/* not in the generations that replace (postures.vary_replace_generations) */
static int varied_active(const stConfig *cfg, int generation) {
  return !st_vary_replacing(cfg, generation);
}

/* open and grasp by fours */
static int varied_primitive(int j) { return ST_PRIM_OPEN + j / ST_NPOSTURE; }

/* open or grasp k with the offsets of its own index, always from a drawn start (the fixed one
 * when no draw is accepted) */
static void varied_spec(const stProtocol *p, stTrialSpec *t) {
  st__fixed_trial(p, t, varied_primitive(t->j), t->j % ST_NPOSTURE, 1);
}

static uint64_t varied_seed_key(const stProtocol *p, int generation, int individual, int j) {
  return st_rng_keyed(st_config_rng_seed(&p->cfg), ST_RNG_TRIAL, (uint64_t)generation,
                      (uint64_t)individual,
                      (uint64_t)(st_trial_kind_first(ST_TRIAL_VARIED) + j)).key;
}

/* in the generations that replace (postures.vary_replace_generations), how many fixed trials
 * started from drawn postures */
static int varied_note(const stEvaluation *e, char *buf, size_t n) {
  const stKindEvaluation *r = &e->kind[ST_TRIAL_VARIED], *fixed = &e->kind[ST_TRIAL_FIXED];
  if (r->trials) return snprintf(buf, n, " (varied %d/%d)", r->successes, r->trials);
  return fixed->count ? snprintf(buf, n, " (varied: replacing %d)", fixed->count) : 0;
}

/* simple-prim's trials are the 16: its drawn starts can only replace theirs; a schedule of
 * replace, then extra: only extra has a second phase; the drawn starts are open's and grasp's */
static int varied_check(const stConfig *c, char *msg, size_t n) {
  if (c->postures_vary_trials == ST_VARY_EXTRA && c->stage_stages != ST_STAGES_MAIN) {
    snprintf(msg, n, "extra adds main-prim trials, and stage.stages = %s runs another stage "
             "(expected stage.stages = main_prim, or postures.vary_trials = replace)",
             st_config_enum_name("stage", "stages", c->stage_stages));
    return st_config_find("postures", "vary_trials");
  }
  if (c->postures_vary_replace_generations > 0 && c->postures_vary_trials != ST_VARY_EXTRA) {
    snprintf(msg, n, "%d generations of replace before extra, and postures.vary_trials = replace "
             "replaces throughout (expected postures.vary_trials = extra, or the key left out)",
             c->postures_vary_replace_generations);
    return st_config_find("postures", "vary_replace_generations");
  }
  const unsigned prims = st_config_primitive_mask(c);
  if (c->postures_vary_starts && prims && !(prims & (1u << ST_PRIM_OPEN | 1u << ST_PRIM_GRASP))) {
    snprintf(msg, n, "the drawn starts are open's and grasp's, and stage.primitives = %s "
             "evaluates neither (expected open or grasp in stage.primitives, or "
             "postures.vary_starts = false)", c->stage_primitives);
    return st_config_find("postures", "vary_starts");
  }
  /* (a replace schedule at least as long as ga.max_generations is not refused: the cap only
   * ends a run, which a resume may continue under a higher one, and --generations sets it:
   * the key acts from the first generation, replace's instead of extra's) */
  return -1;
}

/* the row: what it is and its keys; its streams; its hooks; its fitness.csv column */
const stTrialKindDef st__trial_varied = {
    ST__TRIAL_KIND(VARIED, varied), .title = "varied trials",
    .switch_key = "postures.vary_starts", .family = "postures.vary_", .shapes = "the drawn starts",
    .offsets = ST_RNG_TRIAL, .starts = ST_RNG_STARTS, .solver = ST_RNG_TRIAL,
    .count = varied_count, .active = varied_active, .primitive = varied_primitive,
    .spec = varied_spec, .seed_key = varied_seed_key, .note = varied_note, .check = varied_check,
    .trial_column = "best_v%d",
};
