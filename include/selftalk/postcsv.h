/* SPDX-License-Identifier: MIT
 * libselftalk: the post-evaluation's files, trials.csv and summary.csv (docs/PROTOCOL.md,
 * "Post-evaluation files"): each one row struct and one column table (selftalk/csv.h) that
 * posteval's writers and the validated readers (./apps/stats, selftalk/poststats.h) go through.
 * A new column is a field of the row, a line of its table (lib/posteval/postcsv.c) and where
 * the writer fills it; tools/csvschema.py is generated from the tables (tools/csvschema.c).
 *
 * Read, besides selftalk/csv.h's rules, each row is refused (naming FILE:LINE) when: its test
 * is not one of posteval's three; summary: successes or open_jumped above trials, excluded
 * other than 0 or 1, an excluded individual with successes; trials: success or open_jumped
 * other than 0 or 1, a success without a reached_step or a failure with one, a trial number
 * outside its test's table or a row whose type, cell, posture, repetition are not that
 * trial's (st_post_trial_layout of the tests' stPostDef); an individual (summary) or a trial
 * (trials) given twice. Only the columns older files have are read (the first 8 of summary.csv,
 * 13 of trials.csv); the others are written, and ignored on reading. */
#ifndef SELFTALK_POSTCSV_H
#define SELFTALK_POSTCSV_H

#include <stdio.h>

#include "selftalk/csv.h"
#include "selftalk/posteval.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_POST_LABEL_MAX 64 /* a condition's label, with its NUL */

/* The columns of both files that name an individual, their first four: test, condition, run,
 * individual (a trials file's rows grouped by them are its individuals). */
#define ST_POST_INDIVIDUAL_KEY 4

/* trials.csv: one row per trial run. */
typedef struct stPostTrialRow {
  char test[ST_CSV_NAME_LEN];        /* st_post_test_name */
  char condition[ST_POST_LABEL_MAX]; /* st_post_condition, or the user's */
  int run;                           /* the input's position (stPostIndividual.run) */
  int individual;                    /* its rank in the input (stPostIndividual.rank) */
  int trial, type, cell, posture, repetition; /* stPostTrial's index, type, ... */
  int words;                         /* stWordSource: none, caretaker or selftalk */
  int success, reached_step, open_jumped; /* stPostResult's */
  char run_label[128];               /* stPostIndividual.run_label */
  char heard[ST_POST_HEARD_MAX + 2];
  int end;                           /* stTrialEnd */
  int steps_run;
  double obj_x, obj_y, target_x, target_y, target_z;
} stPostTrialRow;

/* summary.csv: one row per individual (st_post_summarise of its results). */
typedef struct stPostSummaryRow {
  char test[ST_CSV_NAME_LEN];
  char condition[ST_POST_LABEL_MAX];
  int run, individual;
  int successes, trials, excluded, open_jumped;
  char run_label[128];
  double success_rate;        /* successes / trials */
  double mean_steps;          /* mean_steps_to_target: stPostSummary.mean_steps, NAN (nan) */
  int unstable, generation;
} stPostSummaryRow;

/* The files' column tables. */
ST_API const stCsvSchema *st_post_trials_schema(void);
ST_API const stCsvSchema *st_post_summary_schema(void);

/* trials.csv: a header, then one row per trial run, individual by individual in order, trial
 * by trial; r[i * ntrials + t] is individual i's trial t; excluded individuals have no rows.
 * labels->condition has fewer than ST_POST_LABEL_MAX characters. Returns 0, or -1 on a write
 * error. */
ST_API int st_post_write_trials(FILE *f, const stPostLabels *labels, const stPostIndividual *ind,
                         int nind, const stPostTrial *trials, int ntrials, const stPostResult *r);

/* summary.csv: a header, then one row per individual (st_post_summarise of its results). */
ST_API int st_post_write_summary(FILE *f, const stPostLabels *labels, const stPostIndividual *ind,
                          int nind, int ntrials, const stPostResult *r);

/* The rows (stPostSummaryRow) of a summary file, checked (st_csv_read's errors). */
ST_API stStatus st_post_read_summary(const char *path, stCsvRows *rows, char *err, size_t errsz);

/* The rows (stPostTrialRow) of a trials file, each checked against its test's trial table in
 * defs (st_post_def_from_config of each test: the posteval.* keys the file was made with). */
ST_API stStatus st_post_read_trials(const char *path, const stPostDef defs[ST_POST_NTESTS],
                             stCsvRows *rows, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
