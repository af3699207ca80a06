/* SPDX-License-Identifier: MIT
 * libselftalk: trials of the primitive stages (thesis §2.7-§2.8, SPEC §2, §8) - which trials a
 * stage has, how one runs (sense, think, act, score), and how an individual's trials combine
 * into its fitness.
 *
 * Owns: stProtocol, the immutable run-level data (config, robot, scene, the 16 postures) that
 * every thread reads; per-thread state lives in stWorkspace. A trial's random offsets are
 * keyed by (seed, generation, trial index): every individual of a generation sees the same
 * trials (common random numbers). */
#ifndef SELFTALK_TRIAL_H
#define SELFTALK_TRIAL_H

#include <stdint.h>

#include "selftalk/fitness.h"
#include "selftalk/net.h"
#include "selftalk/postures.h"
#include "selftalk/world.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PRIM_TRIALS 16 /* trials of a primitive stage: 4 per primitive */

/* Everything a run reads and never changes. */
typedef struct stProtocol {
  stConfig cfg;
  stRobot *robot; /* owned */
  stScene scene;
  stSensorDef sensor;
  stFitnessDef fitness;
  stNetDef net;
  double posture[ST_NPRIM][ST_NPOSTURE][ST_NDOF];
  unsigned primitives; /* stage.primitives: bit p set = primitive p's trials are evaluated */
} stProtocol;

/* Loads the robot, computes the 16 postures. */
stStatus st_protocol_create(const stConfig *cfg, stProtocol **protocol, char *err, size_t errsz);
void st_protocol_destroy(stProtocol *protocol); /* nullable */

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
  double ling[ST_NET_NLING]; /* the caretaker's word, one-hot x linguistic_input */
} stTrialSpec;

/* Trial `index` of a stage in a generation (offsets from the counter-based generator). */
void st_trial_spec(const stProtocol *p, stStage stage, int generation, int index, stTrialSpec *t);

/* How a trial ended. */
typedef enum stTrialEnd {
  ST_END_FULL = 0,  /* ran its full length */
  ST_END_SUCCESS,   /* reach held for reach_hold_steps: S = 1 for the remaining steps */
  ST_END_FAILURE,   /* object fell (or the simulation diverged): P = fail_penalty after */
  ST_END_QUIET      /* grasp: object fell after the table was removed: nothing after */
} stTrialEnd;

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

/* One step as seen by a trace (apps/replay). */
typedef struct stTraceStep {
  int step;
  const stWorld *world;
  const stQuantities *q;
  const double *in;  /* network inputs of this step */
  const double *out; /* network outputs of this step */
  int focus_target;  /* focus chosen by this step's output */
  double S, P;
  int success_now;
  int event;         /* stTrialEnd when the trial ends at this step, else -1 */
} stTraceStep;

typedef void (*stTraceFn)(void *ctx, const stTraceStep *step);

/* Per-thread scratch: the worlds of each mode, created on first use. */
typedef struct stWorkspace {
  stWorld *kin;
  stWorld *dyn;
} stWorkspace;

void st_workspace_free(stWorkspace *ws);

/* What drives the robot in a trial: the evolved network, or any other controller (e.g. the
 * scripted one of apps/scripted). act() gets the state and the network inputs of this step and
 * writes at least 13 outputs: 12 desired normalised DOF positions, then the focus output. */
typedef struct stController {
  void (*reset)(void *self, const stTrialSpec *t); /* nullable */
  void (*act)(void *self, const stWorld *w, const stQuantities *q, const double *in, int step,
              double *out);
  int ninputs; /* network inputs to prepare (25 or 26) */
  void *self;
} stController;

/* Runs one trial with any controller; see st_trial_run. */
stStatus st_trial_run_controller(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                                 const stController *ctl, uint64_t seed_key, stTrialResult *r,
                                 stTraceFn trace, void *ctx, char *err, size_t errsz);

/* Runs one trial with a network. seed_key keys the dynamic solver's generator (unused in
 * kinematic mode). Nullable: trace. */
stStatus st_trial_run(const stProtocol *p, stWorkspace *ws, const stTrialSpec *t,
                      const stNetParams *net, uint64_t seed_key, stTrialResult *r, stTraceFn trace,
                      void *ctx, char *err, size_t errsz);

/* One network output forced to a value from a step on, whatever the network says: override
 * and lesion analyses of an evolved individual (apps/replay --force). The forced value is
 * what the robot and the scoring see, exactly as if the network had produced it. */
typedef struct stForce {
  int output;     /* 0..ST_NET_OUT_FOCUS: 12 desired normalised DOF positions, then focus */
  double value;   /* 0..1 */
  int from_step;  /* >= 0 */
} stForce;

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
