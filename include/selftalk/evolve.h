/* SPDX-License-Identifier: MIT
 * libselftalk: an evolution run of the primitive stages (thesis §2.4, §2.7-§2.8) or of the
 * integrated stage (§2.9, selftalk/integrated.h) - the GA, parallel evaluation (on this
 * process's threads, or anywhere through an stEvolveEvaluator: below), termination, stage
 * chaining, output files, checkpoint and resume.
 *
 * Files in the output directory:
 *   config.ini         the resolved configuration (written once)
 *   fitness.csv        one row per generation: its fitness, the best's evaluation and the
 *                      trials it solved (the columns: selftalk/fitnesscsv.h)
 *   best.genome        the best genotype of every generation, appended (SPEC §4 format)
 *   population.genome  the final population, best first, with fitness (at the end)
 *   checkpoint         the state after the last finished generation, rewritten atomically
 * A run killed at any moment and resumed (resume = 1) ends with the same files as an
 * uninterrupted one: the checkpoint records how long fitness.csv and best.genome were, and
 * resuming cuts them back to that before redoing the unfinished generation. */
#ifndef SELFTALK_EVOLVE_H
#define SELFTALK_EVOLVE_H

#include <stdio.h>

#include "selftalk/config.h"
#include "selftalk/episode.h"
#include "selftalk/integrated.h"
#include "selftalk/trial.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stEvolveEvaluator stEvolveEvaluator;

/* The threads to run on, the rule of every threaded runner and app: `requested` when > 0,
 * else run.threads when cfg (nullable: none) sets it > 0, else one per core. */
ST_API int st_thread_count(int requested, const stConfig *cfg);

typedef struct stEvolveDef {
  const stConfig *cfg;
  const char *out_dir;
  int threads;     /* evaluation threads; 0: run.threads, or one per core */
  int generations; /* > 0: the run's cap key (ga.max_generations, in the integrated stage
                      ga.integrated_generations) set to this: config.ini records it */
  int resume;      /* continue from out_dir/checkpoint when there is one */
  FILE *progress;  /* one line per generation; nullable */
  const stEvolveEvaluator *evaluator; /* nullable: evaluate on this process's threads */
} stEvolveDef;

/* Runs (or resumes) the stages cfg->stage_stages names. Refuses an unwritable directory, a
 * resume with a different configuration (run.threads and the cap aside: a run continues under
 * another cap, which its config.ini then records), or an unreadable initial population
 * (integrated: population files that cannot be assembled) before any evaluation. */
ST_API stStatus st_evolve_run(const stEvolveDef *def, char *err, size_t errsz);

/* ---- evaluating elsewhere: an individual as a task ----
 * A generation's evaluation is a list of tasks, one per individual, each answered by a
 * result. An individual's result depends only on the run's config and its task (every random
 * stream is keyed by seed, generation, individual and trial), so tasks may be evaluated in any
 * order, on any thread, process or machine running the same build: apps/evolve under mpirun
 * hands them to other MPI ranks (docs/PROTOCOL.md, "Evaluation across processes"). Both are
 * plain values (no pointers): they can be copied between processes of the same build. */

typedef struct stEvolveTask {
  int integrated;   /* 1: the integrated stage (network.arch's network, st_int_evaluate) */
  stStage stage;    /* else the primitive stage (base network, st_stage_evaluate) */
  int generation;
  int individual;   /* index in the generation: keys the dynamic solver's generator */
  stGenome genome;
  int has_rollin;   /* 1: main-prim's hand-over trials are rolled in by `rollin`
                       (stage.handover_rollin = elite, st_stage_rollin_elite) */
  stGenome rollin;  /* the generation's genotype 0, its elite (base network); carried by every
                       task so that a task is all an evaluation needs, on any thread or process */
} stEvolveTask;

typedef struct stEvolveResult {
  int individual;        /* the task's */
  stStatus status;       /* ST_OK, or why the individual could not be evaluated (err) */
  double fitness;        /* NAN unless ST_OK */
  stEvaluation eval;     /* primitive stages */
  stIntEvaluation ieval; /* integrated stage */
  char err[512];
} stEvolveResult;

/* Evaluates one task exactly as st_evolve_run's own threads do. p: st_protocol_create of the
 * run's config; idef: st_integrated_def_from_config of it; ws: the calling thread's own. */
ST_API void st_evolve_task_run(const stProtocol *p, const stIntegratedDef *idef, stWorkspace *ws,
                        const stEvolveTask *task, stEvolveResult *result);

/* Evaluates a generation somewhere else: fills results[i] for tasks[i], i < n (tasks[i] is
 * individual i; a result that failed carries its status and message); cfg is the run's. Returns non-OK (with a message)
 * only when the evaluation itself broke down, e.g. a lost process; st_evolve_run then stops
 * with that error, its files and checkpoint those of the last finished generation. */
struct stEvolveEvaluator {
  stStatus (*evaluate)(void *self, const stConfig *cfg, const stEvolveTask *tasks, int n,
                       stEvolveResult *results, char *err, size_t errsz);
  void *self;
};

#ifdef __cplusplus
}
#endif

#endif
