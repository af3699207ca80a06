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
#include "selftalk/trialkind.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PRIM_TRIALS (ST_NPRIM * ST_NPOSTURE) /* trials of a primitive stage: 16 */

/* One trial, fully specified. */
typedef struct stTrialSpec {
  stStage stage;
  int index;          /* the trial index of the stage (selftalk/trialkind.h: the indexed kinds'
                         ranges one after another) */
  stTrialKind kind;   /* st_trial_kind(index) */
  int j;              /* trial j of its kind: index - st_trial_kind_first(kind) */
  int generation;
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
  int rollin_steps;   /* hand-over trials (qhat0 reach posture k, the object with the reach
                         trials' offset): the caretaker's chain runs, unscored, until it hands
                         over to `primitive`, which must happen before this step; the primitive
                         is then scored for `steps` steps as its own trial (table_off_step
                         counted from the hand-over). 0 for other trials */
} stTrialSpec;

/* Trial `index` of a stage in a generation (offsets from the counter-based generator; with
 * postures.vary_starts, open and grasp starts drawn from the stream (seed, ST_RNG_STARTS,
 * generation, 0, index), the first draw that st_posture_varied accepts). Main-prim indices
 * 16..27 are the hand-over trials (offsets from (seed, ST_RNG_HANDOVER, generation, 0,
 * index - 16): object, then target), built whatever stage.handover says; 28..35 the varied
 * trials, open and grasp k as trials 4 + (index - 28) with their own offsets and always a drawn
 * start (the fixed one when no draw is accepted), built whatever postures.vary_trials says; with
 * vary_trials = extra the fixed trials keep their fixed starts. */
ST_API void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t);

/* A stage's trials in one generation, built once and read by every individual's evaluation
 * (st_stage_evaluate keeps the last one in its workspace): each is keyed by (seed, generation,
 * trial) alone, and with postures.vary_starts a start costs inverse-kinematics draws. */
typedef struct stTrialTable {
  stConfig cfg;          /* the protocol's config it was built for (a copy: compared whole) */
  stStage stage;
  int generation;
  int n;                 /* st_stage_trials */
  stTrialSpec t[ST_MAIN_TRIALS_MAX]; /* st_trial_spec of each trial whose primitive
                                        p->primitives evaluates; the others zero */
} stTrialTable;

ST_API void st_trial_table(const stProtocol *p, stStage stage, int generation, stTrialTable *table);

/* The trial a hand-over trial falls back to when its roll-in did not hand over: the fixed
 * main-prim trial of its primitive and posture, from the fixed posture (never a drawn start,
 * even in generations that replace), with the hand-over trial's target and index. */
ST_API void st_handover_fallback(const stProtocol *p, const stTrialSpec *handover, stTrialSpec *t);

/* The key of the dynamic solver's generator for trial `index` of a generation run by
 * `individual` (its kind's seed_key: fixed and varied trials ST_RNG_TRIAL, hand-over trials
 * ST_RNG_HANDOVER_SOLVER). With stage.handover_rollin = elite a hand-over trial takes individual
 * 0's key (the elite's) whoever runs it, so that every individual's roll-in is the elite's, bit
 * for bit. */
ST_API uint64_t st_trial_seed_key(const stProtocol *p, int generation, int individual, int index);

/* The trial indices of a stage: up to the last indexed kind it has trials of (16; in main-prim
 * 28 with stage.handover, 36 with postures.vary_trials = extra; st_stage_trial_active says which
 * of them run). */
ST_API int st_stage_trials(const stProtocol *p, stStage stage);

/* 1 when the open and grasp fixed trials of `generation` start from drawn postures instead of
 * theirs: postures.vary_starts with vary_trials = replace, or with extra in the first
 * postures.vary_replace_generations generations (the varied kind's rule,
 * lib/episode/trials/varied.c). */
ST_API int st_vary_replacing(const stConfig *cfg, int generation);

/* 1 when an evaluation of `stage` in `generation` runs trial `index` (< st_stage_trials): its
 * primitive is one p->primitives evaluates, and its kind runs then (st_trial_kind_runs). */
ST_API int st_stage_trial_active(const stProtocol *p, stStage stage, int generation, int index);

/* The primitive of trial `index` of a stage. */
ST_API int st_trial_primitive(int index);

/* The episode of a trial: its spec (kinematic in simple-prim, dynamic in main-prim; seed_key
 * keys the dynamic solver's generator) and its words (the primitive's word every step, no
 * secondary input). */
ST_API void st_trial_episode(const stProtocol *p, const stTrialSpec *t, uint64_t seed_key,
                      stEpisodeSpec *e, stWords *words);

typedef struct stTrialResult {
  double sum_s, sum_p; /* over all `steps` steps, including the filled remainder */
  long steps;          /* N contributed to the primitive (the trial's length) */
  long steps_run;      /* steps actually simulated */
  int success;
  int success_step;    /* first step the success condition held, -1 */
  stTrialEnd end;
  int unstable;        /* the simulation diverged */
  int handover_step;   /* hand-over trials: the step of the chain the primitive took over at;
                          -1: the roll-in did not hand over, and the trial either ran from the
                          fixed posture (stage.handover_fallback, st_handover_fallback) or
                          scored nothing (S = P = 0 over its length, end ST_END_QUIET, no step
                          run). -1 for other trials */
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

ST_API void st_score_begin(stTrialScore *sc, const stTrialSpec *t);

/* Scores the state after control step `step` (0-based, consecutive): q are its quantities,
 * y_focus the focus output that chose it, penalty the sum of the penalties that apply
 * (st_penalty_mask), fell / unstable what the world reports. Writes S and P (nullable) and
 * returns the stTrialEnd that ends the trial at this step, or -1 to go on. */
ST_API int st_score_step(stTrialScore *sc, const stFitnessDef *def, int step, const stQuantities *q,
                  double y_focus, double focus_threshold, double penalty, int fell, int unstable,
                  double *S, double *P);

/* Fills the steps a premature end skipped and decides end-of-trial successes (main-prim grasp:
 * object centre above the table top; move: reached the target and still lifted). */
ST_API void st_score_end(stTrialScore *sc, const stFitnessDef *def, double obj_z, double table_top_z,
                  stTrialResult *r);

/* The primitive scorer of the episode loop: st_score_* on the episode's steps, with the
 * penalties st_penalty_mask names; the result goes to *r at the end. */
typedef struct stPrimScorer {
  const stProtocol *p;
  const stTrialSpec *t;
  stTrialScore sc;
  stTrialResult *r;
} stPrimScorer;

ST_API stScorer st_prim_scorer(stPrimScorer *s, const stProtocol *p, const stTrialSpec *t,
                        stTrialResult *r);

/* Runs one trial: st_trial_episode, the primitive scorer (its kind's score hook), st_episode_run
 * with ctl (any controller: a network's, st_net_controller, with forced outputs or not; one
 * composed with a roll-in, st_rollin_controller; the scripted one), then its kind's finish hook
 * (a hand-over trial whose roll-in did not hand over scores nothing, or with
 * stage.handover_fallback runs its fallback next: the trace sees the roll-in's steps, then the
 * fallback's from step 0). seed_key keys the dynamic solver's generator (unused in kinematic
 * mode). Nullable: trace. */
ST_API stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stController *ctl, uint64_t seed_key, stTrialResult *r,
                      stTraceFn trace, void *ctx, char *err, size_t errsz);

/* An individual's score over all trials of a stage. */
typedef struct stEvaluation {
  double fitness;              /* harmonic mean of fp over the evaluated primitives, with the
                                  kinds' terms (stTrialKindDef.fitness: F_chain) */
  double fp[ST_NPRIM];         /* F_p (0 for a primitive not evaluated) */
  int ntrials;                 /* trials evaluated, every kind's: 16 unless stage.primitives
                                  names fewer, and main-prim's hand-over, varied and chained */
  int successes;               /* ... succeeded */
  int unstable;                /* ... diverged */
  stKindEvaluation kind[ST_TRIAL_KIND_COUNT]; /* each kind's (selftalk/trialkind.h) */
} stEvaluation;

/* Evaluates a network on the trials of a stage in a generation: the indexed kinds' trials in
 * index order (only those of the primitives in p->primitives; a trial keeps its index, offsets
 * and generator key, so a subset scores each trial exactly as the full set does), each counting
 * in its primitive's F_p as one more trial (eq. 2.3: its bonus, its S - P over its length);
 * then the block kinds (stage.chain_trials chained trials, st_chain_def: the integrated stage's
 * trials with the caretaker's words), whose terms join the fitness (their fitness hooks).
 * individual keys the dynamic solver's generator. rollin: the base network of the
 * generation's elite (genotype 0), which acts main-prim's hand-over trials' roll-ins
 * (st_rollin_controller) exactly when st_stage_rollin_elite says so; NULL otherwise.
 * ST_ERR_ARG naming stage.handover_rollin when rollin is missing where it is needed or given
 * where it is not, or the networks cannot take over from each other (not base networks). */
ST_API stStatus st_stage_evaluate(const stProtocol *p, stWorkspace *ws, stStage stage, int generation,
                           int individual, const stNetParams *net, const stNetParams *rollin,
                           stEvaluation *e, char *err, size_t errsz);

/* 1 when an evaluation counts towards ga.success_genotypes (the primitive stages' completion):
 * it solved every trial it was evaluated on, or, with stage.chain_complete = fixed_chained and
 * chained trials, its fixed trials from their fixed starts (none drawn) and its chained trials
 * (the hand-over and varied trials train the chain; the fixed ones are the thesis's, the
 * chained ones the integration test's). */
ST_API int st_evaluation_completes(const stConfig *cfg, const stEvaluation *e);

/* 1 when an evaluation of `stage` has hand-over trials rolled in by the elite (main-prim,
 * stage.handover, stage.handover_rollin = elite): st_stage_evaluate then needs the elite's
 * network. */
ST_API int st_stage_rollin_elite(const stProtocol *p, stStage stage);

#ifdef __cplusplus
}
#endif

#endif
