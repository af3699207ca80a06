/* SPDX-License-Identifier: MIT
 * libselftalk: the statistics of the post-evaluation files (thesis §3, docs/PROTOCOL.md,
 * "Post-evaluation files, statistics and figures"), what ./apps/stats prints, over the rows of
 * selftalk/postcsv.h's readers and the core's selftalk/stats.h. Nothing here runs a trial.
 *
 * Conditions: the thesis's order first (ST-CT, ST, CT, NI, ST-CT0, ST0), the others in the
 * order they first come in the file. A condition NAME0 is the caretaker variant of NAME (the
 * same individuals hearing the caretaker's words): Table 3.2 compares it with NAME only. */
#ifndef SELFTALK_POSTSTATS_H
#define SELFTALK_POSTSTATS_H

#include "selftalk/postcsv.h"
#include "selftalk/stats.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_POST_MAX_NAMES 32 /* tests, or conditions of a test, in a file */
#define ST_POST_MAX_REPS 1000 /* repetitions of a trial read (stPostTrialRow.repetition) */

/* Distinct tests or conditions; the names point into the rows they come from. */
typedef struct stPostNames {
  const char *name[ST_POST_MAX_NAMES];
  int n;
} stPostNames;

/* The index of name, or -1. */
ST_API int st_post_names_index(const stPostNames *names, const char *name);

/* The tests of a file's rows (summary or trials: their test column), in file order. ST_ERR_RANGE
 * beyond ST_POST_MAX_NAMES. */
ST_API stStatus st_post_tests(const stCsvRows *rows, stPostNames *tests, char *err, size_t errsz);

/* The test to use: want when the file has it; without want, the file's only test; else NULL. */
ST_API const char *st_post_pick_test(const stPostNames *tests, const char *want);

/* Table 3.2's pairs: conditions i and j (i != j) are compared when one is the other's caretaker
 * variant, or when neither is a variant. */
ST_API int st_post_compared(const stPostNames *conds, int i, int j);

/* ---- summary.csv: Tables 3.1, 3.2, A.1, A.2 ---- */

/* The samples of one test: per condition, its individuals' success percentages (100 successes
 * / trials) and open_jumped, in file order. */
typedef struct stPostSamples {
  const char *test;
  stPostNames conds;
  double *pct[ST_POST_MAX_NAMES];
  double *jumped[ST_POST_MAX_NAMES];
  int n[ST_POST_MAX_NAMES];
} stPostSamples;

/* The samples of `test` in the rows of st_post_read_summary (which must outlive them).
 * ST_ERR_RANGE beyond ST_POST_MAX_NAMES conditions, ST_ERR_NOMEM. */
ST_API stStatus st_post_samples(const stCsvRows *summary, const char *test, stPostSamples *s, char *err,
                         size_t errsz);
ST_API void st_post_samples_free(stPostSamples *s);

/* ---- trials.csv: Fig. 3.11, Table 3.3 ---- */

/* One individual with self talk (condition NAME) and with the caretaker's words (NAME0). */
typedef struct stPostComparison {
  char condition[ST_CSV_NAME_LEN]; /* NAME: need not be in the file (all excluded) */
  const char *variant;             /* NAME0, into the rows */
  int run, individual;
  int excluded;                    /* no rows in NAME: scores 0 in every repetition */
  int trials[2], successes[2];     /* [0] self talk (NAME), [1] caretaker (NAME0) */
  double steps[2];                 /* sum of reached_step + 1 over the successes */
  stMwuResult mwu;                 /* the per-repetition success percentages, [0] against [1] */
  const char *better;              /* "selftalk", "caretaker" (p <= alpha), else "none" */
} stPostComparison;

typedef struct stPostComparisons {
  stPostComparison *c;
  int n;
} stPostComparisons;

/* Every individual of every condition NAME0 of `test` in the rows of st_post_read_trials
 * against its rows in NAME: conditions in their order, individuals in the order of their first
 * row (O(n log n)). name: the file, for messages. ST_ERR_ARG when the test has no NAME0 (or an
 * mwu error, "FILE: NAME against NAME0, run R individual I: ..."), ST_ERR_RANGE (a repetition
 * ST_POST_MAX_REPS or more), ST_ERR_NOMEM. */
ST_API stStatus st_post_compare(const stCsvRows *trials, const char *name, const char *test,
                         const stMwuDef *mwu, double alpha, stPostComparisons *out, char *err,
                         size_t errsz);
ST_API void st_post_comparisons_free(stPostComparisons *c);

#ifdef __cplusplus
}
#endif

#endif
