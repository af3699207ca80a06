/* SPDX-License-Identifier: MIT
 * libselftalk: the one sense-think-act-score loop. Every trial of the library - primitive
 * trials (thesis §2.7-§2.8), integrated trials (§2.9), the scripted runner, post-evaluations -
 * is an episode:
 *   a spec       what the world starts as and how long it runs (posture, object, target,
 *                length, when the object-table collision goes off, kinematic or dynamic);
 *   a controller what drives the robot (an evolved network, the scripted controller, any
 *                stController);
 *   a word source what the robot hears (nothing, one fixed word, the caretaker, self talk)
 *                plus the secondary input "move-object-to-target";
 *   a scorer     what the steps are worth (primitive, integrated, integrated with the record
 *                the prediction fitness needs); scoring never touches the simulator.
 *
 * Owns: stProtocol, the immutable run-level data (config, robot, scene, postures) that every
 * thread reads; per-thread state lives in stWorkspace. */
#ifndef SELFTALK_EPISODE_H
#define SELFTALK_EPISODE_H

#include <stdint.h>

#include "selftalk/fitness.h"
#include "selftalk/net.h"
#include "selftalk/postures.h"
#include "selftalk/world.h"

#ifdef __cplusplus
extern "C" {
#endif

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
  /* integrated.fail_end = exact or runout: the lowest the robot's geometry and its palm frame
   * reach (st_robot_lowest_z, joint ranges widened by dynamics.limit_tolerance_deg); -inf with
   * penalty, so that nothing is ever out of reach */
  double reach_geom_z, reach_palm_z;
} stProtocol;

/* What the margin of an out-of-reach object covers: ODE's contact correction, which can lift
 * the object a little above its energy bound, and the dynamic joints' separation (m). */
#define ST_REACH_MARGIN 0.02

/* Loads the robot, computes the 16 postures. */
ST_API stStatus st_protocol_create(const stConfig *cfg, stProtocol **protocol, char *err, size_t errsz);
ST_API void st_protocol_destroy(stProtocol *protocol); /* nullable */

/* Per-thread scratch: the worlds of each mode, created on first use, and the trial table of
 * the last generation evaluated (selftalk/trial.h), built once for all its individuals. */
typedef struct stWorkspace {
  stWorld *kin;
  stWorld *dyn;
  struct stTrialTable *trials;
} stWorkspace;

ST_API void st_workspace_free(stWorkspace *ws);

/* ---- the spec ---- */

typedef struct stEpisodeSpec {
  int dynamic;              /* 1: dynamic world (ODE), 0: kinematic */
  double qhat0[ST_NDOF];    /* initial posture */
  double obj[3];            /* object centre */
  double target[3];
  int steps;                /* length (control steps); a scorer may end the episode earlier */
  int table_off_step;       /* object-table collision off from this step on; -1: never.
                               With ST_WORDS_HANDOVER: counted from the hand-over step */
  uint64_t seed_key;        /* the dynamic solver's generator (st_world_set_seed) */
} stEpisodeSpec;

/* ---- the word source ---- */

/* What the robot hears on its linguistic inputs 21-24. */
typedef enum stWordSource {
  ST_WORDS_NONE = 0,  /* nothing */
  ST_WORDS_FIXED,     /* one word every step (primitive trials) */
  ST_WORDS_CARETAKER, /* the caretaker of thesis §2.9.3, sensing the state before each action */
  ST_WORDS_SELFTALK,  /* the label the controller produced at the previous step; none at step 0 */
  ST_WORDS_HANDOVER,  /* the caretaker until its word reaches `word` (said, or jumped past), then
                         `word` every step: a primitive's trial from the state the chain hands
                         over in (main-prim's hand-over trials, stage.handover) */
  ST_WORDS_COUNT
} stWordSource;

/* "none", "fixed", "caretaker", "selftalk", "handover". */
ST_API const char *st_word_source_name(stWordSource source);

/* 1 for the sources whose words someone else gives (fixed, caretaker, hand-over), 0 for none
 * and self talk. */
ST_API int st_word_source_given(stWordSource source);

typedef struct stWords {
  stWordSource source;
  int word;         /* ST_WORDS_FIXED, ST_WORDS_HANDOVER: the primitive named (ST_PRIM_*) */
  double scale;     /* input value of the word heard (network.linguistic_input, 10) */
  double secondary; /* secondary input "move-object-to-target" every step (0 in primitive
                       trials, network.secondary_input in integrated ones) */
} stWords;

/* ---- the controller ---- */

/* What drives the robot. act() gets the state and the inputs of this step and writes
 * noutputs values (at least 13: 12 desired normalised DOF positions, then the focus output;
 * networks of type A and B add their 4 linguistic values). */
typedef struct stController {
  void (*reset)(void *self, const stEpisodeSpec *e); /* nullable */
  void (*act)(void *self, const stWorld *w, const stQuantities *q, const double *in, int step,
              double *out);
  int ninputs;  /* network inputs to prepare (25 or 26) */
  void *self;
  int noutputs; /* outputs act() writes; 0 means 13 */
  int talks;    /* 1: outputs 13-16 are linguistic outputs (type A) whose argmax is the label
                   the controller produces each step (self talk) */
  /* nullable: told before each act() what the robot hears this step (the words' source, the
   * word, -1 none) and, with hand-over words, the step it was handed over at (-1 before) */
  void (*hear)(void *self, stWordSource source, int word, int handover);
} stController;

/* One network output forced to a value from a step on, whatever the network says: override
 * and lesion analyses of an evolved individual (apps/replay --force). The forced value is
 * what the robot and the scoring see, exactly as if the network had produced it. */
typedef struct stForce {
  int output;     /* 0..ST_NET_OUT_FOCUS: 12 desired normalised DOF positions, then focus */
  double value;   /* 0..1 */
  int from_step;  /* >= 0 */
} stForce;

/* An evolved network as a controller (state for one episode at a time). */
typedef struct stNetController {
  const stNetParams *net;
  stNetState state;
  const stForce *force;
  int nforce;
} stNetController;

/* The controller of a network: ninputs and noutputs of its architecture, talks for type A.
 * Nullable: force (nforce 0). c must outlive the returned controller. */
ST_API stController st_net_controller(stNetController *c, const stNetParams *net, const stForce *force,
                               int nforce);

/* Two controllers as one, for main-prim's hand-over trials under stage.handover_rollin = elite
 * (docs/PROTOCOL.md): `rollin` acts while hand-over words have not handed over yet, `then` from
 * the hand-over step on and in any other episode (a hand-over trial's fallback); both are reset
 * at the start of an episode, only the one acting is stepped. So `then`'s first step is the
 * hand-over step, with no state from the steps before: exact only for controllers without
 * memory (the base network: its outputs at t depend on its inputs at t alone), which the
 * caller ensures; what can be seen is checked: ST_ERR_ARG unless both have the base network's
 * 25 inputs and 13 outputs and neither talks. Both must outlive c, and c the composed *out. */
typedef struct stRollinController {
  stController rollin, then;
  int rolling; /* the roll-in acts this step */
} stRollinController;

ST_API stStatus st_rollin_controller(stRollinController *c, const stController *rollin,
                              const stController *then, stController *out, char *err,
                              size_t errsz);

/* Checks forced outputs: ST_ERR_RANGE naming an output, value or step out of range. */
ST_API stStatus st_force_check(const stForce *force, int nforce, char *err, size_t errsz);

/* ---- one step, as the scorer and a trace see it ---- */

typedef struct stTraceStep {
  int step;
  const stWorld *world;     /* the state after the step's action */
  const stQuantities *q;    /* its fitness quantities */
  const double *in;         /* network inputs of this step */
  const double *out;        /* controller outputs of this step (nout values) */
  int nout;
  int focus_target;         /* focus chosen by this step's output */
  stWordSource source;      /* where the word heard came from */
  int word;                 /* word heard this step (ST_PRIM_*), -1 none */
  int handover;             /* ST_WORDS_HANDOVER: the step the word was handed over at, -1
                               before (and for other sources) */
  int label;                /* label produced this step (talking controllers), -1 */
  double pen_table;         /* penalties of the state: table touching, */
  double pen_object;        /* object touching, */
  double pen_moving;        /* object moving (SPEC §6) */
  int fell, unstable;       /* what the world reports */
  int out_of_reach;         /* the object can never again touch the robot, nor come within
                               fitness.success_dist of its palm's reach point (d_r), whatever
                               the controller does: its energy bound (st_world_object_ceiling)
                               plus ST_REACH_MARGIN stays below the protocol's reach_*_z; 0
                               with integrated.fail_end = penalty */
  double pen_moving_floor;  /* the least object-moving penalty any later step can have while
                               the object is not lifted: fitness.move_max once its energy
                               bound keeps it move_max x move_scale below its start, else 0 */
  /* filled by the scorer */
  double S, P;
  int success_now;
  int event;                /* stTrialEnd when the episode ends at this step, else -1 */
} stTraceStep;

typedef void (*stTraceFn)(void *ctx, const stTraceStep *step);

/* ---- the scorer ---- */

/* How a trial ended. */
typedef enum stTrialEnd {
  ST_END_FULL = 0,  /* ran its full length */
  ST_END_SUCCESS,   /* ended early by success: S = 1 for the remaining steps */
  ST_END_FAILURE,   /* object fell (or the simulation diverged): P = fail_penalty after */
  ST_END_QUIET      /* main-prim grasp: object fell after the table was removed: nothing after */
} stTrialEnd;

/* "full", "success", "failure", "quiet" (posteval's trials.csv, replay's lines); "?" for
 * anything else. */
ST_API const char *st_trial_end_name(stTrialEnd end);

/* step() fills S, P and success_now of the record and returns the stTrialEnd that ends the
 * episode at this step, or -1 to go on; end() sees the final state. */
typedef struct stScorer {
  void (*begin)(void *self);                            /* nullable */
  int (*step)(void *self, stTraceStep *s);
  void (*end)(void *self, const stWorld *w);            /* nullable */
  void *self;
} stScorer;

/* Runs one episode: reset the world and the controller, then for each step: the word source
 * speaks (on the state before the action; the controller hears it), sense, think, act, score
 * the state the action produced. Nullable: trace. ST_ERR_ARG when self talk is asked of a
 * controller that does not talk, or the controller's outputs do not fit. */
ST_API stStatus st_episode_run(const stProtocol *p, stWorkspace *ws, const stEpisodeSpec *e,
                        const stController *ctl, const stWords *words, const stScorer *scorer,
                        stTraceFn trace, void *ctx, char *err, size_t errsz);

/* The label of four linguistic values: their argmax (ties: lowest index). */
ST_API int st_episode_label(const double *ling4);

#ifdef __cplusplus
}
#endif

#endif
