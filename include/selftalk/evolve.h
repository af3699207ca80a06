/* SPDX-License-Identifier: MIT
 * libselftalk: an evolution run of the primitive stages (thesis §2.4, §2.7-§2.8) or of the
 * integrated stage (§2.9, selftalk/integrated.h) - the GA, parallel evaluation, termination,
 * stage chaining, output files, checkpoint and resume.
 *
 * Files in the output directory:
 *   config.ini         the resolved configuration (written once)
 *   fitness.csv        one row per generation: generation,best,mean,worst,best_bonus,stage,...
 *                      (integrated: generation,best,mean,worst,best_F_int,best_F_pred,
 *                      best_bonus,best_bonus_auto,best_successes,best_t0,...)
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

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stEvolveDef {
  const stConfig *cfg;
  const char *out_dir;
  int threads;     /* evaluation threads; 0: run.threads, or one per core */
  int generations; /* > 0: stop after this many generations in all (else ga.max_generations) */
  int resume;      /* continue from out_dir/checkpoint when there is one */
  FILE *progress;  /* one line per generation; nullable */
} stEvolveDef;

/* Runs (or resumes) the stages cfg->stage_stages names. Refuses an unwritable directory, a
 * resume with a different configuration, or an unreadable initial population (integrated:
 * population files that cannot be assembled) before any evaluation. */
stStatus st_evolve_run(const stEvolveDef *def, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
