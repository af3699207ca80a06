/* SPDX-License-Identifier: MIT
 * libselftalk: the post-evaluations of thesis §2.10 (SPEC §11) - what a researcher runs on the
 * evolved individuals after the runs:
 *   integration     the top genotypes of each primitive run, caretaker-guided trials (2.10.1);
 *   robustness      the best of the last generation of each integrated run, autonomous trials
 *                   of the four trained types (2.10.2);
 *   generalisation  the same individuals on a grid of object positions x the four reach
 *                   postures, one target (2.10.3); an individual with no autonomous success in
 *                   its last training generation scores 0 without being run; the caretaker
 *                   variant (ST-CT0, ST0) runs every individual with the caretaker's words.
 * Every trial is an episode of the one loop (selftalk/episode.h): an integrated trial from a
 * reach posture in the dynamic world, the object-table collision on, ended at the first step
 * with the object within the target radius while lifted (its success; the step is recorded),
 * or by a failure, or after its length.
 *
 * The trial tables are a pure function of the config (keys posteval.*, integrated.steps,
 * scene.*, run.seed): offsets come from the stream (run.seed, ST_RNG_POSTEVAL, test, 0, trial)
 * and the dynamic solver's generator from (run.seed, ST_RNG_POSTEVAL_SOLVER, test, 0, trial),
 * so every individual and condition sees the same trials and a result depends on nothing but
 * the individual and the trial (not on threads, nor on which individuals run together).
 *
 * Files (st_post_run): trials.csv, one row per trial run; summary.csv, one row per individual;
 * config.ini, the resolved configuration. Columns: selftalk/postcsv.h (docs/PROTOCOL.md,
 * "Post-evaluation files"). */
#ifndef SELFTALK_POSTEVAL_H
#define SELFTALK_POSTEVAL_H

#include <stdint.h>
#include <stdio.h>

#include "selftalk/integrated.h"
#include "selftalk/study.h"

#ifdef __cplusplus
extern "C" {
#endif

/* stPostTest, its names: selftalk/study.h */
/* The test's reader bit of the key table (ST_CONFIG_INTEGRATION_TEST, ...). */
ST_API unsigned st_post_test_reader(stPostTest test);

/* A test's variant: its own words, or other words in the same trials. */
typedef enum stPostVariant {
  ST_POST_OWN_WORDS = 0, /* the test's words */
  ST_POST_CARETAKER = 1, /* generalisation: the caretaker's words (ST-CT0, ST0) */
  ST_POST_NO_WORDS = 2   /* integration: no words (SPEC 12: chains of primitives that stay
                            word-driven should rarely succeed without them) */
} stPostVariant;

/* What sets a test apart, one row per test (lib/posteval/posteval.c), read wherever tests are
 * treated differently. A new test is its name (selftalk/study.h), a row, and its reader bit
 * and keys in the config's key table. */
typedef struct stPostTestInfo {
  unsigned reader;        /* the config keys' reader bit (ST_CONFIG_*_TEST) */
  int grid;               /* trials: 1, the generalisation grid (cells x postures x
                             repetitions, the one target ST_TARGET_GENERAL); 0, the integrated
                             stage's four types with fresh offsets, posteval.<test>_trials */
  int own_caretaker;      /* its own words are the caretaker's; 0: the condition's autonomous
                             words (st_post_words) */
  stPostVariant variant;  /* the variant it has besides its own words (ST_POST_OWN_WORDS:
                             none) */
  int populations;        /* inputs: primitive runs' populations (posteval.integration_top
                             each), the condition named by their kind; 0: integrated runs, the
                             condition named by its Table 2.1 row (st_post_condition) */
  int excludes;           /* with its own words, a run whose autonomous training trials never
                             succeeded is left out (st_post_excluded) */
  int (*trials)(const stConfig *cfg); /* trials per individual */
  int (*steps)(const stConfig *cfg);  /* trial length */
} stPostTestInfo;

/* The row of a test; NULL for no test. */
ST_API const stPostTestInfo *st_post_test_info(stPostTest test);

/* A test's trial table (keys posteval.*, integrated.steps, run.seed). */
typedef struct stPostDef {
  stPostTest test;
  int trials;        /* trials per individual */
  int steps;         /* trial length (integrated.steps; generalisation_steps) */
  int cells;         /* generalisation: grid cells along x and along y */
  double cell_size;  /* m */
  double center[2];  /* grid centre: scene.object_center_x/y */
  double offset;     /* generalisation: object offset on x and y around the cell centre */
  int repetitions;   /* generalisation: trials per cell and posture */
  uint64_t seed;     /* run.seed */
} stPostDef;

ST_API void st_post_def_from_config(const stConfig *cfg, stPostTest test, stPostDef *def);

/* One row of a trial table. */
typedef struct stPostTrial {
  int index;         /* 0 .. trials-1 */
  int type;          /* integration, robustness: k = index mod 4; generalisation: -1 */
  int cell;          /* generalisation: cell row * cells + column; -1 */
  int posture;       /* reach posture (integration, robustness: = type) */
  int repetition;    /* integration, robustness: index / 4; generalisation: 0 .. repetitions-1 */
  int target;        /* 0, 1 (k mod 2) or ST_TARGET_GENERAL */
  double obj[3];     /* object centre at the start */
  double target_pos[3];
  int steps;
  uint64_t solver_key;
} stPostTrial;

/* Trial i of the table. Integration and robustness: type k = i mod 4, reach posture k, object
 * position k + uniform x/y offset (scene.object_offset), target k mod 2 + uniform x/y/z offset
 * (scene.target_offset), drawn in that order as in the integrated stage. Generalisation:
 * i = (cell x postures + posture) x repetitions + repetition; the object at the cell centre +
 * uniform x/y offset (posteval.generalisation_offset), the generalisation target without
 * offset. */
ST_API void st_post_trial(const stPostDef *def, const stScene *scene, int i, stPostTrial *trial);

/* What st_post_trial fills without the scene: index, type, cell, posture, repetition, target,
 * steps (the positions 0). The one layout of the trial tables: ./apps/stats checks the rows of
 * a trials.csv against it. */
ST_API void st_post_trial_layout(const stPostDef *def, int i, stPostTrial *trial);

/* Centre (x, y) of cell c = row * cells + column, the row along x (0 nearest the robot), the
 * column along y (0 the most negative y, the robot's right): centre + ((row, column) -
 * (cells - 1) / 2) cell_size. */
ST_API void st_post_cell_center(const stPostDef *def, int cell, double xy[2]);

/* The episode of a trial: dynamic, from reach posture trial->posture, the object-table
 * collision on throughout. */
ST_API void st_post_episode(const stProtocol *p, const stPostTrial *trial, stEpisodeSpec *e);

/* What the trials of a test hear: integration, and the generalisation test's caretaker variant,
 * the caretaker; robustness and generalisation the condition's autonomous words
 * (integrated.words_odd, else words_even, whichever is not the caretaker: self talk for ST-CT
 * and ST, none for CT and NI); the integration test's no-words variant, none. ST_ERR_ARG when
 * the condition has no autonomous trials or a variant is asked of another test. */
ST_API stStatus st_post_words(const stIntegratedDef *idef, stPostTest test, stPostVariant variant,
                       stWordSource *words, char *err, size_t errsz);

/* The condition's label: robustness and generalisation, the row of Table 2.1 the config's
 * network.arch and integrated.words_* / fitness_* / first_generation match ("ST-CT", "ST",
 * "CT", "NI"; "custom" for none), with "0" appended for the caretaker variant ("ST-CT0");
 * integration, the primitive runs' kind (thesis 3.1): "incremental" (stage.stages prims, or
 * main_prim from stage.init_population) or "nonincremental" (main_prim from random genotypes),
 * with "-nowords" appended for the no-words variant. */
ST_API void st_post_condition(const stConfig *cfg, stPostTest test, stPostVariant variant, char *buf,
                       size_t n);

/* The exclusion rule of the generalisation test (thesis 2.10.3, SPEC §11): 1 when none of the
 * trials that were autonomous (st_integrated_plan: no caretaker) in the training generation
 * `generation` succeeded; success[i] is trial i's (fitness.csv best_t<i>), n trials. */
ST_API int st_post_excluded(const stIntegratedDef *idef, int generation, const uint8_t *success, int n);

/* ---- one trial ---- */

#define ST_POST_HEARD_MAX 48 /* letters of stPostResult.heard before it is cut ('+') */

typedef struct stPostResult {
  int success;       /* the object was within the target radius while lifted */
  int reached_step;  /* the first such step (0-based), -1 */
  int steps_run;     /* steps simulated: reached_step + 1 after a success */
  int end;           /* stTrialEnd: ST_END_SUCCESS at reached_step, ST_END_FAILURE, ST_END_FULL */
  int unstable;      /* the simulation gave up (a failure) */
  int open_jumped;  /* heard grasp or move but never open (the caretaker jumped open) */
  char heard[ST_POST_HEARD_MAX + 2]; /* the words heard in order, repeats collapsed, as r, o,
                                        g, m; '+' ends a sequence cut at ST_POST_HEARD_MAX */
} stPostResult;

/* Runs one trial of a controller (an evolved network: st_net_controller; the scripted one)
 * hearing `words`, with the secondary input network.secondary_input when it has 26 inputs.
 * Nullable: trace (called after every step, as st_episode_run's; replay --posteval). */
ST_API stStatus st_post_run_trial(const stProtocol *p, const stIntegratedDef *idef, stWorkspace *ws,
                           const stPostTrial *trial, const stController *ctl, stWordSource words,
                           stPostResult *r, stTraceFn trace, void *ctx, char *err, size_t errsz);

/* ---- individuals ---- */

typedef struct stPostIndividual {
  int run;           /* the run's number: its input's position (0-based) on the command line */
  char run_label[128]; /* the run's label: its directory's name */
  char path[512];    /* the file the genotype came from */
  int rank;          /* its index in that file (0 = the best); the best of a run: 0 */
  int generation;    /* robustness, generalisation: the last generation; integration: -1 */
  int excluded;      /* generalisation: scores 0 without being run */
  stGenome genome;
} stPostIndividual;

/* The run label of a path: a directory's own name; a file's directory's name, or the file's
 * name without its extension when the directory is ".". */
ST_API void st_post_run_label(const char *path, char *buf, size_t n);

/* Integration: the first `top` genotypes (ngenes genes) of a population file, or of a
 * primitive run directory's population.genome (finished run), else its checkpoint (a run
 * still going: its first genotypes are the elites, best first). out holds top entries. */
ST_API stStatus st_post_load_population(const char *path, int top, int ngenes, stPostIndividual *out,
                                 char *err, size_t errsz);

/* Robustness, generalisation: the best of the last generation of an integrated run directory
 * (the last record of best.genome, its "# generation G"), checked against the directory's
 * config.ini (the same network.arch and integrated.words_* / fitness_* / first_generation as
 * cfg) and fitness.csv (a row for G). excluded is set by the exclusion rule when `exclusion`
 * is 1, from that row's best_t<i> columns. */
ST_API stStatus st_post_load_run(const char *dir, const stConfig *cfg, int exclusion,
                          stPostIndividual *out, char *err, size_t errsz);

/* ---- results ---- */

typedef struct stPostSummary {
  int successes;
  int trials;            /* trials of the test (an excluded individual scores 0 of them) */
  int open_jumps;        /* trials with open_jumped */
  int unstable;          /* trials the simulation gave up on */
  double mean_steps;     /* mean of reached_step + 1 over the successes; NAN without any */
} stPostSummary;

/* Summary of one individual's n results (excluded: none run, n = the test's trials). */
ST_API void st_post_summarise(const stPostResult *r, int n, int excluded, stPostSummary *s);

/* What every row of a run's files says besides the individual and the trial. */
typedef struct stPostLabels {
  const char *test;       /* st_post_test_name */
  const char *condition;  /* st_post_condition, or the user's */
  stWordSource words;
} stPostLabels;

/* The files' writers and readers: selftalk/postcsv.h. */

/* ---- a whole test ---- */

typedef struct stPostRunDef {
  const stConfig *cfg;       /* the configuration: the config file, then the --set options */
  const stConfig *file_cfg;  /* the config file alone (nullable: the defaults); the --set
                                options must name keys the test reads */
  stPostTest test;
  const char *const *inputs; /* integration: population files or primitive run directories;
                                else integrated run directories */
  int ninputs;
  stPostVariant variant;     /* the test's words, or its caretaker (generalisation) or no-words
                                (integration) variant */
  const char *condition;     /* nullable: st_post_condition */
  const char *out_dir;
  int threads;               /* 0: run.threads, else one per core */
  FILE *progress;            /* nullable: progress lines (trials done, speed, time left) */
  int resume;                /* 1: continue from out_dir/posteval.journal when there is one */
  double journal_seconds;    /* the journal is written this often: 0 the default
                                (ST_POST_JOURNAL_SECONDS), < 0 after every trial */
} stPostRunDef;

#define ST_POST_JOURNAL_SECONDS 30.0

/* Loads the individuals, runs every trial of every individual (OpenMP over trials; the files
 * are the same whatever the number of threads), writes the files atomically. The trials done
 * are journalled in out_dir/posteval.journal (kept when the test ends: a record of it); with
 * resume a killed test continues from there to the same files, without resume a directory
 * with a journal is refused. Refuses keys the
 * test does not read (in the config file: unless the run's stages read them), inputs that
 * cannot be read, and an unwritable directory before any trial. */
ST_API stStatus st_post_run(const stPostRunDef *def, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
