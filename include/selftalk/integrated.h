/* SPDX-License-Identifier: MIT
 * libselftalk: the integrated stage (thesis §2.9, SPEC §10) - "move the object to the target"
 * from the evolved primitives, in the four conditions of Table 2.1.
 *
 * A condition is data (configs/integrated_*.cfg): the network type (network.arch), what even
 * and odd trials hear (integrated.words_even / _odd: none, caretaker, self talk), which
 * fitness they get (integrated.fitness_even / _odd) and whether the first generation hears the
 * caretaker everywhere with ten-fold bonuses (integrated.first_generation). st_integrated_plan
 * reads that table; nothing else asks which condition it is.
 *
 * Scoring (st_int_*) is separate from simulation: the integrated scorer is a pure function of
 * the per-step quantities, and the prediction fitness (selftalk/prediction.h) of the recorded
 * words and linguistic outputs. */
#ifndef SELFTALK_INTEGRATED_H
#define SELFTALK_INTEGRATED_H

#include "selftalk/episode.h"
#include "selftalk/prediction.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_INT_MAX_TRIALS 32 /* integrated.trials at most */

/* Fitness of a trial (Table 2.1). */
typedef enum stIntFitness { ST_FIT_INTEGRATED = 0, ST_FIT_PREDICTION, ST_FIT_COUNT } stIntFitness;

/* "integrated", "prediction". */
ST_API const char *st_int_fitness_name(stIntFitness f);

/* The stage's definition (keys integrated.*, prediction.*, network.arch). */
typedef struct stIntegratedDef {
  stNetArch arch;              /* A or B */
  stWordSource words[2];       /* even, odd trials: none, caretaker or self talk */
  stIntFitness fitness[2];     /* even, odd trials */
  int first_variant;           /* generation 0: caretaker everywhere, integrated fitness */
  double first_bonus_factor;   /* ... with bonuses times this (10) */
  int trials;                  /* 8 */
  int steps;                   /* 240 */
  int hold_steps;              /* 20 */
  int focus_bonus_steps;       /* 3 */
  int fail_end;                /* integrated.fail_end: ST_FAIL_END_PENALTY, _EXACT, _RUNOUT */
  stPredDef pred;
} stIntegratedDef;

ST_API void st_integrated_def_from_config(const stConfig *cfg, stIntegratedDef *def);

/* Main-prim's chained trials (stage.chain_trials, SPEC 12): the integrated stage's trials
 * (integrated.steps, hold_steps, focus_bonus_steps) for the base network, every trial hearing
 * the caretaker and scored by eq. 2.14, no first-generation variant. */
ST_API void st_chain_def_from_config(const stConfig *cfg, stIntegratedDef *def);

/* What trial i of a generation is: the words it hears, the fitness it gets, its bonus factor.
 * autonomous: it hears no caretaker (self talk or nothing). */
typedef struct stIntPlan {
  stWordSource words;
  stIntFitness fitness;
  double bonus_factor;
  int autonomous;
} stIntPlan;

ST_API stIntPlan st_integrated_plan(const stIntegratedDef *def, int generation, int trial);

/* ---- the integrated behaviour fitness (eq. 2.14 and §2.9.4.1), pure ---- */

/* s_i(t) = s_m / 2 + (not opened and not lifted: s_o; opened and not lifted: 1 + s_g;
 * lifted: 2) / 4 with s_o, s_g, s_m of eq. 2.10-2.12. */
ST_API double st_int_s(const stFitnessDef *def, const stQuantities *q, int opened);

/* S(t) = w f_f + (focus correct ? (1 - w) s_i : 0) (eq. 2.4): the right focus is the target
 * while the object is lifted, the object otherwise. */
ST_API double st_int_step_fitness(const stFitnessDef *def, const stQuantities *q, int opened,
                           double y_focus, double focus_threshold);

/* P(t): table touching throughout, object moving while the object is not lifted. */
ST_API double st_int_penalty(const stQuantities *q, double pen_table, double pen_moving);

/* One trial's outcome. */
typedef struct stIntTrialResult {
  double sum_s, sum_p;   /* over the full length (a premature end fills the remainder) */
  long steps;            /* the full length N (240) */
  long steps_run;        /* steps simulated */
  int reached_step;      /* first step with the object within the target radius while lifted */
  int success;           /* moved to the target: within the radius at some step and still
                            lifted at the end (main-prim move's condition; the move bonus) */
  int focus_bonus;       /* lifted with the focus on the target for focus_bonus_steps */
  int opened;            /* the open success condition held at some step */
  int furthest_word;     /* the furthest primitive (ST_PRIM_*) whose word was heard, -1 none:
                            with the caretaker's words, how far its chain got */
  stTrialEnd end;        /* failure: the object fell (integrated.fail_end = penalty), the world
                            diverged, or (exact) nothing left could change the result */
  int unstable;
} stIntTrialResult;

/* What a trial reports besides its reach, bonuses and success, which an exact early end
 * (integrated.fail_end = exact, st_int_score_settle) must leave as running out would: */
enum {
  ST_INT_KEEP_POINTS = 1u, /* max(0, sum S - sum P): the integrated fitness's trials */
  ST_INT_KEEP_RECORD = 2u, /* the words and outputs of a prediction trial (they count once its
                              object reached the target) */
  ST_INT_KEEP_WORDS = 4u   /* the words heard (posteval's heard): self talk can still change */
};

/* The scorer's state; st_int_score_begin, st_int_score_step after every step, st_int_score_end. */
typedef struct stIntScore {
  const stFitnessDef *fd;
  double focus_threshold;
  int steps, hold_steps, focus_bonus_steps;
  int focus_run;         /* consecutive steps lifted with the focus on the target */
  int was_in_target;
  int lifted;
  int fail_end;          /* ST_FAIL_END_* (def->fail_end) */
  unsigned keep;         /* ST_INT_KEEP_* (the caller's, after st_int_score_begin) */
  double fill_p;         /* failure: P of every remaining step */
  stIntTrialResult r;
} stIntScore;

ST_API void st_int_score_begin(stIntScore *sc, const stFitnessDef *fd, double focus_threshold,
                        const stIntegratedDef *def);

/* Scores the state after step `step`: writes S, P (nullable) and returns the stTrialEnd that
 * ends the trial here (success: within the target radius while lifted more than hold_steps
 * steps ago and still lifted; failure: the world diverged, or the object fell with
 * integrated.fail_end = penalty), or -1. */
ST_API int st_int_score_step(stIntScore *sc, int step, const stQuantities *q, double y_focus,
                      double pen_table, double pen_moving, int fell, int unstable, double *S,
                      double *P);

/* integrated.fail_end = exact, after st_int_score_step returned -1: ST_END_FAILURE when no
 * remaining step can change what the trial reports, else -1. That needs the object out of the
 * robot's reach for good (out_of_reach: no touch, so never lifted again: no reach, bonus or
 * success, and d_r stays above fitness.success_dist: no "opened", no caretaker switch) and, as
 * sc->keep asks, points certain to be clamped to 0 (each remaining step adds S <= w + (1 - w) / 2
 * - pen_moving_floor, or -fitness.fail_penalty should the world diverge), a prediction record
 * that does not count (no reach yet), words that cannot change (words_fixed: not self talk). */
ST_API int st_int_score_settle(stIntScore *sc, int out_of_reach, double pen_moving_floor,
                        int words_fixed);

/* Fills the remainder (success: S = 1; failure: P = fitness.fail_penalty per step, or, ended by
 * st_int_score_settle, the object-moving penalty every remaining step is certain to pay). */
ST_API void st_int_score_end(stIntScore *sc, stIntTrialResult *r);

/* A trial's bonus: (focus bonus + move bonus) x bonus x factor. */
ST_API double st_int_trial_bonus(const stIntTrialResult *r, double bonus, double factor);

/* A trial's share before normalisation: max(0, sum S - sum P) (the penalty cap). */
ST_API double st_int_trial_points(const stIntTrialResult *r);

/* ---- an individual's fitness over its trials ---- */

typedef struct stIntEvaluation {
  double fitness;              /* F = F_int + F_pred */
  double f_int;                /* integrated part: B + (scale / N) sum max(0, sum S - sum P) */
  double f_pred;               /* prediction part (eq. 2.24) */
  double bonus;                /* all bonus points in F (integrated bonuses and B_pred) */
  double bonus_auto;           /* integrated bonuses earned in autonomous trials */
  int ntrials;
  int successes;               /* trials whose object was moved to the target */
  uint8_t success[ST_INT_MAX_TRIALS];
  int unstable;
  double progress;             /* mean over the trials of max(0, furthest_word) (0..3) */
} stIntEvaluation;

/* Combines n trials (bonus: fitness.bonus, scale: fitness.scale): plan[i], result[i] and, for
 * prediction trials, pred[i] (only read where plan[i].fitness is prediction; nullable when
 * none is). */
ST_API void st_int_combine(double bonus, double scale, const stIntPlan *plan,
                    const stIntTrialResult *result, const stPredScore *pred, int n,
                    stIntEvaluation *e);

/* ---- trials in the simulator ---- */

/* The episode of an integrated trial: reach posture k, object position k, target t (0, 1, or
 * ST_TARGET_GENERAL), offsets drawn from rng (nullable: none; object x/y, then target x/y/z),
 * def->steps long, dynamic, the object-table collision on throughout. */
ST_API void st_int_episode(const stProtocol *p, const stIntegratedDef *def, int k, int t, stRng *rng,
                    uint64_t seed_key, stEpisodeSpec *e);

/* Integrated trial i's type k (reach posture and object position k, target k mod 2):
 * i mod 4, or with integrated.trial_order = pairs (i div 2) mod 4 (SPEC 13). */
ST_API int st_int_trial_type(const stProtocol *p, int i);

/* Trial i of a generation for an individual: type k = st_int_trial_type(p, i), target k mod 2,
 * offsets keyed by (seed, generation, trial) - common to every individual - and the solver's
 * generator by (seed, generation, individual, trial). */
ST_API void st_int_trial(const stProtocol *p, const stIntegratedDef *def, int generation, int individual,
                  int i, stEpisodeSpec *e);

/* The words of a source: scale network.linguistic_input, the secondary input throughout. */
ST_API stWords st_int_words(const stProtocol *p, stWordSource source);

/* Where the integrated scorer keeps the record the prediction fitness needs (nullable
 * buffers: no record): the word heard and the four linguistic outputs of each step. */
typedef struct stIntRecord {
  int cap;
  int n;
  int *word;
  double (*o)[ST_PRED_NWORDS];
} stIntRecord;

/* The integrated scorer of the episode loop; the result goes to *r at the end, the record to
 * rec (nullable). */
typedef struct stIntScorer {
  const stProtocol *p;
  const stIntegratedDef *def;
  unsigned keep;         /* ST_INT_KEEP_*: st_int_scorer sets POINTS, or RECORD with a record */
  stIntScore sc;
  stIntTrialResult *r;
  stIntRecord *rec;
} stIntScorer;

ST_API stScorer st_int_scorer(stIntScorer *s, const stProtocol *p, const stIntegratedDef *def,
                       stIntTrialResult *r, stIntRecord *rec);

/* Evaluates a network (type def->arch) on the trials of a generation. */
ST_API stStatus st_int_evaluate(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                         int generation, int individual, const stNetParams *net,
                         stIntEvaluation *e, char *err, size_t errsz);

/* Trial i of a generation with a network: the plan, the result and (prediction trials) the
 * prediction score of the trial's words and outputs, whether or not its object reached the
 * target (st_int_combine decides whether it counts); zero for other trials. Nullable: trace,
 * pred. */
ST_API stStatus st_int_trial_run(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                          int generation, int individual, int i, const stNetParams *net,
                          stIntPlan *plan, stIntTrialResult *r, stPredScore *pred,
                          stTraceFn trace, void *ctx, char *err, size_t errsz);

/* An integrated episode e driven by any controller (what st_int_trial_run does with a
 * network's): the words of plan->words, the integrated scorer, and, when plan->fitness is
 * ST_FIT_PREDICTION and pred is given, the prediction score of the words and the controller's
 * linguistic outputs (zero otherwise). Nullable: trace, pred. */
ST_API stStatus st_int_run_with(const stProtocol *p, const stIntegratedDef *def, stWorkspace *ws,
                         const stEpisodeSpec *e, const stController *ctl, const stIntPlan *plan,
                         stIntTrialResult *r, stPredScore *pred, stTraceFn trace, void *ctx,
                         char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
