/* SPDX-License-Identifier: MIT
 * libselftalk: what the trial kinds' files (lib/episode/trials/NAME.c, one row each of
 * selftalk/trialkind.h's table) share with each other and with the dispatch
 * (lib/episode/trialkind.c, lib/episode/trial.c). Not installed. */
#ifndef SELFTALK_TRIALS_H
#define SELFTALK_TRIALS_H

#include "selftalk/trial.h"
#include "selftalk/trialkind.h"

/* the rows: st__trial_fixed, st__trial_handover, ... (ST_TRIAL_KINDS) */
#define ST__TRIAL_KIND_ROW(E, name, max, indexed) extern const stTrialKindDef st__trial_##name;
ST_TRIAL_KINDS(ST__TRIAL_KIND_ROW)
#undef ST__TRIAL_KIND_ROW

/* a row's kind, name, most trials and whether it is indexed: its line of ST_TRIAL_KINDS */
#define ST__TRIAL_KIND_IS_INDEXED(E, name, max, indexed) ST__TRIAL_INDEXED_##E = (indexed),
enum { ST_TRIAL_KINDS(ST__TRIAL_KIND_IS_INDEXED) ST__TRIAL_INDEXED_END };
#undef ST__TRIAL_KIND_IS_INDEXED
#define ST__TRIAL_KIND(E, nm) \
  .kind = ST_TRIAL_##E, .name = #nm, .max = ST_TRIAL_MAX_##E, .indexed = ST__TRIAL_INDEXED_##E

/* main-prim's trial length of a primitive, and when the object-table collision goes off (-1:
 * never) */
int st__main_steps(const stConfig *c, int primitive);
int st__main_table_off(const stConfig *c, int primitive);

/* the fixed trial (primitive, k) into t (stage, generation, index set): posture k of the
 * primitive, its offsets from (seed, ST_RNG_TRIAL, generation, 0, t->index) - object (reach
 * trials only, thesis 2.5.1), then target (every trial, 2.5.2) -, its stage's length and table
 * removal; with drawn, the start drawn from the posture (postures.vary_starts, st__drawn_start) */
void st__fixed_trial(const stProtocol *p, stTrialSpec *t, int primitive, int k, int drawn);

/* postures.vary_starts: t's start becomes the first drawn variation of its posture that has
 * the SPEC 8 properties, the draws keyed by (seed, ST_RNG_STARTS, generation, 0, t->index),
 * common to every individual; none accepted: the fixed posture stays (start_draws 0) */
void st__drawn_start(const stProtocol *p, stTrialSpec *t);

/* the primitive scorer's scoring of a step (the default of stTrialKindDef.score) */
int st__prim_score(stPrimScorer *s, stTraceStep *ts);

/* a trial's episode and the primitive scorer, without its kind's finish hook */
stStatus st__trial_episode_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                               const stController *ctl, uint64_t seed_key, stTrialResult *r,
                               stTraceFn trace, void *ctx, char *err, size_t errsz);

/* a family of keys refused while what they shape is off: the first key of `family`
 * ("section.prefix") away from its default while `on` is 0, with the message "it shapes WHAT,
 * which SWITCH = OFF turns off (expected SWITCH ON, or the key left out)"; its index, or -1 */
int st__switched_family(const stConfig *c, int on, const char *family, const char *what,
                        const char *switch_key, const char *off, const char *on_value, char *msg,
                        size_t n);

#endif
