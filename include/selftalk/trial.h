/* SPDX-License-Identifier: MIT
 * libselftalk: trials of the primitive stages (thesis §2.7-§2.8, SPEC §2, §8) - which trials a
 * stage has, how one is scored (the primitive scorer of the episode loop, selftalk/episode.h),
 * and how an individual's trials combine into its fitness.
 *
 * A trial's random offsets are keyed by (seed, generation, trial index): every individual of a
 * generation sees the same trials (common random numbers). */
#ifndef SELFTALK_TRIAL_H
#define SELFTALK_TRIAL_H

#include <stdint.h>

#include "selftalk/episode.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PRIM_TRIALS 16 /* trials of a primitive stage: 4 per primitive */

/* One trial, fully specified. */
typedef struct stTrialSpec {
  stStage stage;
  int index;          /* 0..15: primitive index / 4, posture and object position index % 4 */
  int primitive;
  int k;              /* posture and object position */
  int target_index;   /* k mod 2 */
  double qhat0[ST_NDOF];
  double obj[3];
  double target[3];
  int steps;
  int table_off_step; /* main-prim grasp / move: object-table collision off from this step; -1 */
  int start_draws;    /* postures.vary_starts: the draw qhat0 is (1..postures.vary_draws); 0:
                         the fixed posture (not varied, or no draw had the SPEC 8 properties) */
} stTrialSpec;

/* Trial `index` of a stage in a generation (offsets from the counter-based generator; with
 * postures.vary_starts, open and grasp starts drawn from the stream (seed, ST_RNG_STARTS,
 * generation, 0, index), the first draw that st_posture_varied accepts). */
void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t);

/* The episode of a trial: its spec (kinematic in simple-prim, dynamic in main-prim; seed_key
 * keys the dynamic solver's generator) and its words (the primitive's word every step, no
 * secondary input). */
void st_trial_episode(const stProtocol *p, const stTrialSpec *t, uint64_t seed_key,
                      stEpisodeSpec *e, stWords *words);

typedef struct stTrialResult {
  double sum_s, sum_p; /* over all `steps` steps, including the filled remainder */
  long steps;          /* N contributed to the primitive (the trial's length) */
  long steps_run;      /* steps actually simulated */
  int success;
  int success_step;    /* first step the success condition held, -1 */
  stTrialEnd end;
  int unstable;        /* the simulation diverged */
} stTrialResult;

/* The scoring of one trial, step by step, separate from the simulation so that it can be fed
 * synthetic trajectories: st_score_begin, then st_score_step after every control step, then
 * st_score_end. */
typedef struct stTrialScore {
  stStage stage;
  int primitive;
  int steps;           /* trial length */
  int table_off_step;  /* -1: never */
  int reached_at;      /* main-prim reach: first step the reach point was reached */
  int was_in_target;   /* move: the target condition held at some step */
  int lifted;          /* lifted after the last step */
  stTrialResult r;
} stTrialScore;

void st_score_begin(stTrialScore *sc, const stTrialSpec *t);

/* Scores the state after control step `step` (0-based, consecutive): q are its quantities,
 * y_focus the focus output that chose it, penalty the sum of the penalties that apply
 * (st_penalty_mask), fell / unstable what the world reports. Writes S and P (nullable) and
 * returns the stTrialEnd that ends the trial at this step, or -1 to go on. */
int st_score_step(stTrialScore *sc, const stFitnessDef *def, int step, const stQuantities *q,
                  double y_focus, double focus_threshold, double penalty, int fell, int unstable,
                  double *S, double *P);

/* Fills the steps a premature end skipped and decides end-of-trial successes (main-prim grasp:
 * object centre above the table top; move: reached the target and still lifted). */
void st_score_end(stTrialScore *sc, const stFitnessDef *def, double obj_z, double table_top_z,
                  stTrialResult *r);

/* The primitive scorer of the episode loop: st_score_* on the episode's steps, with the
 * penalties st_penalty_mask names; the result goes to *r at the end. */
typedef struct stPrimScorer {
  const stProtocol *p;
  const stTrialSpec *t;
  stTrialScore sc;
  stTrialResult *r;
} stPrimScorer;

stScorer st_prim_scorer(stPrimScorer *s, const stProtocol *p, const stTrialSpec *t,
                        stTrialResult *r);

/* A primitive trial driven by any controller (e.g. the scripted one): st_trial_episode, the
 * primitive scorer, st_episode_run. Nullable: trace. */
stStatus st_trial_run_with(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                           const stController *ctl, uint64_t seed_key, stTrialResult *r,
                           stTraceFn trace, void *ctx, char *err, size_t errsz);

/* Runs one trial with a network. seed_key keys the dynamic solver's generator (unused in
 * kinematic mode). Nullable: trace. */
stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stNetParams *net, uint64_t seed_key, stTrialResult *r, stTraceFn trace,
                      void *ctx, char *err, size_t errsz);

/* st_trial_run with nforce outputs forced (nforce = 0: exactly st_trial_run). Forces are
 * applied in order, so a later one on the same output wins from its step on. ST_ERR_RANGE for
 * an output, value or step out of range, naming it. */
stStatus st_trial_run_forced(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                             const stNetParams *net, const stForce *force, int nforce,
                             uint64_t seed_key, stTrialResult *r, stTraceFn trace, void *ctx,
                             char *err, size_t errsz);

/* An individual's score over all trials of a stage. */
typedef struct stEvaluation {
  double fitness;              /* harmonic mean of fp over the evaluated primitives */
  double fp[ST_NPRIM];         /* F_p (0 for a primitive not evaluated) */
  int ntrials;                 /* trials evaluated: 16 unless stage.primitives names fewer */
  int successes;               /* trials succeeded */
  uint8_t success[ST_PRIM_TRIALS];
  int unstable;                /* trials that diverged */
} stEvaluation;

/* Evaluates a network on the 16 trials of a stage in a generation (only those of the
 * primitives in p->primitives; a trial keeps its index, offsets and generator key, so a subset
 * scores each trial exactly as the full set does). individual keys the dynamic solver's
 * generator. */
stStatus st_stage_evaluate(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, stEvaluation *e, char *err,
                           size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
