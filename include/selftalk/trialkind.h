/* SPDX-License-Identifier: MIT
 * libselftalk: the kinds of trials of the primitive stages, as one table - the thesis's fixed
 * trials and the chain stage's hand-over, chained and varied trials (docs/PROTOCOL.md, "Trials
 * and fitness of the primitive stages"), each a row: its name, the key that switches it on, how
 * many trials it has in a stage's evaluation, whether they run in a generation, how a trial's
 * spec and start are made and which random streams key them, the cross-key rules of its keys,
 * its fitness.csv columns. Box2D's joint.c -> revolute_joint.c: one file per kind
 * (lib/episode/trials/NAME.c defines the row st__trial_NAME), the dispatch in
 * lib/episode/trialkind.c; the evaluation (selftalk/trial.h), fitness.csv
 * (selftalk/fitnesscsv.h), replay and the key checks go through the table.
 *
 * A new kind is its file and its line in ST_TRIAL_KINDS, appended: a kind's place gives its
 * trial indices and its fitness.csv columns, so the kinds before it keep theirs (their random
 * streams are keyed by their indices). Its row says everything above; the hooks it leaves NULL
 * take the defaults their comments give. */
#ifndef SELFTALK_TRIALKIND_H
#define SELFTALK_TRIALKIND_H

#include <stdint.h>

#include "selftalk/csv.h"
#include "selftalk/episode.h"
#include "selftalk/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The kinds, in fitness.csv's column order: X(ENUM, name, most trials, indexed). An indexed
 * kind's trials are trial indices of main-prim (st_trial_spec), the indexed kinds' ranges one
 * after another in this order: fixed 0..15, hand-over 16..27, varied 28..35; the others run as
 * a block of their own (stTrialKindDef.evaluate), after the indexed ones. */
#define ST_TRIAL_KINDS(X)                                                                        \
  X(FIXED, fixed, 16, 1)       /* the thesis's 16: primitive i / 4 from posture i % 4 */          \
  X(HANDOVER, handover, 12, 1) /* stage.handover: open, grasp, move where the chain hands over */ \
  X(CHAINED, chained, 32, 0)   /* stage.chain_trials: integrated trials, the caretaker's words */ \
  X(VARIED, varied, 8, 1)      /* postures.vary_trials = extra: open, grasp from drawn starts */

typedef enum stTrialKind {
#define ST__TRIAL_KIND_ENUM(E, name, max, indexed) ST_TRIAL_##E,
  ST_TRIAL_KINDS(ST__TRIAL_KIND_ENUM)
#undef ST__TRIAL_KIND_ENUM
  ST_TRIAL_KIND_COUNT
} stTrialKind;

/* ST_TRIAL_MAX_FIXED, ST_TRIAL_MAX_HANDOVER, ...: the most trials of each kind */
enum {
#define ST__TRIAL_KIND_MAX(E, name, max, indexed) ST_TRIAL_MAX_##E = max,
  ST_TRIAL_KINDS(ST__TRIAL_KIND_MAX)
#undef ST__TRIAL_KIND_MAX
  ST_TRIAL_KIND_MAX = 32 /* the most trials of any kind (lib/episode/trialkind.c checks it) */
};

/* main-prim's trial indices: the indexed kinds' trials */
#define ST__TRIAL_KIND_INDICES(E, name, max, indexed) +((indexed) ? (max) : 0)
#define ST_MAIN_TRIALS_MAX (0 ST_TRIAL_KINDS(ST__TRIAL_KIND_INDICES))

/* fitness.csv's column of a run's trials, one per trial ("best_t%d"): the fixed trials' in the
 * primitive stages (their row's trial_column), the integrated stage's trials in its runs
 * (selftalk/fitnesscsv.h) */
#define ST_TRIAL_COLUMN "best_t%d"

/* What the trials of one kind gave in an evaluation. */
typedef struct stKindEvaluation {
  int trials;                    /* evaluated (0: the kind is off, or does not run in the
                                    generation) */
  int successes;                 /* ... solved */
  int unstable;                  /* ... diverged */
  int count;                     /* the kind's own count (stTrialKindDef.counts): fixed, trials
                                    started from drawn postures; hand-over, roll-ins that handed
                                    over */
  double fitness;                /* the kind's own fitness term (chained: F_chain), else 0 */
  int success[ST_TRIAL_KIND_MAX]; /* trial j of the kind solved (0/1) */
} stKindEvaluation;

struct stTrialSpec;
struct stTrialResult;
struct stPrimScorer;
struct stEvaluation;

/* A row of the table (read-only). */
typedef struct stTrialKindDef {
  stTrialKind kind;
  const char *name;        /* ST_TRIAL_KINDS's: "fixed", "handover", "chained", "varied" */
  const char *title;       /* for people: "hand-over trials" */
  const char *switch_key;  /* "section.key" that switches the kind on; NULL: always on */
  int max;                 /* the most trials (ST_TRIAL_KINDS's) */
  int indexed;             /* ST_TRIAL_KINDS's */
  stRngStream offsets;     /* the streams of its trials' offsets, (generation, 0, trial), */
  stRngStream starts;      /* drawn starts (0: none), the same, */
  stRngStream solver;      /* and dynamic solver generators, (generation, individual, trial) */
  /* trials in an evaluation of `stage` (0: none): fitness.csv has their columns */
  int (*count)(const stConfig *cfg, stStage stage);
  /* nullable (always): 1 when the kind's trials run in `generation` */
  int (*active)(const stConfig *cfg, int generation);
  /* indexed kinds: the primitive of trial j (ST_PRIM_*); its spec, into t whose stage,
   * generation, index, kind and j are set and the rest zero; its solver's key */
  int (*primitive)(int j);
  void (*spec)(const stProtocol *p, struct stTrialSpec *t);
  uint64_t (*seed_key)(const stProtocol *p, int generation, int individual, int j);
  /* nullable (st__prim_score): scores a step of one of its trials */
  int (*score)(struct stPrimScorer *s, stTraceStep *ts);
  /* nullable (nothing): after a trial's episode ran, what the kind does with it (hand-over:
   * the fallback of a chain that did not hand over) */
  stStatus (*finish)(const stProtocol *p, stWorkspace *ws, const struct stTrialSpec *t,
                     const stController *ctl, uint64_t seed_key, struct stTrialResult *r,
                     stTraceFn trace, void *ctx, char *err, size_t errsz);
  /* nullable (0): 1 when a trial counts in stKindEvaluation.count */
  int (*counts)(const struct stTrialSpec *t, const struct stTrialResult *r);
  /* block kinds: its trials for an individual, into r */
  stStatus (*evaluate)(const stProtocol *p, stWorkspace *ws, int generation, int individual,
                       const stNetParams *net, stKindEvaluation *r, char *err, size_t errsz);
  /* nullable (none): its term of the individual's fitness, appended to the harmonic mean's
   * terms[*n] or added to *added after it */
  void (*fitness)(const stProtocol *p, const struct stEvaluation *e, double *terms, int *n,
                  double *added);
  /* nullable (nothing): what evolve's progress line says of an evaluation's trials of the kind
   * (" (hand-over 3/12, 8 handed over)"), into buf as snprintf does; called in a run whose
   * fitness.csv has the kind's columns */
  int (*note)(const struct stEvaluation *e, char *buf, size_t n);
  /* the keys that shape it, refused while switch_key is at its default (off): those of
   * `family` ("section.prefix": the section's keys whose names start with prefix), and what
   * they shape, for the message ("the drawn starts"); NULL: none */
  const char *family;
  const char *shapes;
  /* nullable: its cross-key rules; the index of the key blamed (st_config_find) with msg
   * "problem (expected ...)", or -1 */
  int (*check)(const stConfig *cfg, char *msg, size_t n);
  /* fitness.csv: a column over stKindEvaluation before the per-trial ones (name NULL: none),
   * then one column per trial, "success[j]" named by the printf format trial_column */
  stCsvColumn column;
  const char *trial_column;
} stTrialKindDef;

/* Row k (k < ST_TRIAL_KIND_COUNT). */
ST_API const stTrialKindDef *st_trial_kind_def(stTrialKind k);

/* The kind of main-prim trial index (0 <= index < ST_MAIN_TRIALS_MAX) and its first index. */
ST_API stTrialKind st_trial_kind(int index);
ST_API int st_trial_kind_first(stTrialKind k);

/* The trials of kind k in an evaluation of stage (0: none; its count hook). */
ST_API int st_trial_kind_count(const stConfig *cfg, stStage stage, stTrialKind k);

/* 1 when kind k's trials run in an evaluation of stage in generation: it has trials there and
 * its active hook says so. */
ST_API int st_trial_kind_runs(const stConfig *cfg, stStage stage, int generation, stTrialKind k);

/* The kinds' cross-key rules (their check hooks, and each family's keys refused while the kind
 * is off), in table order: ST_ERR_RANGE with "key 'section.key': problem (expected ...)",
 * prefixed "PATH:LINE: " when the key is set on that line of the config file `path` (nullable:
 * a config built in code or with --set options). Every evolution run and protocol checks
 * them (st_evolve_run, st_protocol_create); a program reading a config file checks them after
 * st_config_load to name the line. */
ST_API stStatus st_trial_kinds_check(const stConfig *cfg, const char *path, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
