/* SPDX-License-Identifier: MIT
 * trials.csv and summary.csv (selftalk/postcsv.h): their one column table each, the writers
 * and the validated readers. */
#include "selftalk/postcsv.h"

#include <string.h>

#include "core/internal.h"

/* ---- the columns ---- */

static const char *words_name(int v) { return st_word_source_name((stWordSource)v); }
static const char *end_name(int v) { return st_trial_end_name((stTrialEnd)v); }

/* what a post-evaluation's trials hear (st_post_words) */
static const int g_words[] = {ST_WORDS_NONE, ST_WORDS_CARETAKER, ST_WORDS_SELFTALK};
static const int g_ends[] = {ST_END_FULL, ST_END_SUCCESS, ST_END_FAILURE, ST_END_QUIET};

#define NELEMS(a) ((int)(sizeof(a) / sizeof(a)[0]))

/* both files' first columns, which name an individual (ST_POST_INDIVIDUAL_KEY) */
#define INDIVIDUAL_COLUMNS(T)                                                                 \
  ST_CSV_COL_NAME(T, test, "test"), ST_CSV_COL_NAME(T, condition, "condition"),               \
      ST_CSV_COL_INT(T, run, "run", 0), ST_CSV_COL_INT(T, individual, "individual", 0)

#define T stPostTrialRow
static const stCsvColumn g_trial_cols[] = {
    INDIVIDUAL_COLUMNS(T),
    ST_CSV_COL_INT(T, trial, "trial", 0),
    ST_CSV_COL_INT(T, type, "type", -1),
    ST_CSV_COL_INT(T, cell, "cell", -1),
    ST_CSV_COL_INT(T, posture, "posture", 0),
    ST_CSV_COL_INT(T, repetition, "repetition", 0),
    ST_CSV_COL_CHOICE(T, words, "words", words_name, g_words, NELEMS(g_words)),
    ST_CSV_COL_INT(T, success, "success", 0),
    ST_CSV_COL_INT(T, reached_step, "reached_step", -1),
    ST_CSV_COL_INT(T, open_jumped, "open_jumped", 0),
    /* written, not read (TRIAL_READ) */
    ST_CSV_COL_TEXT(T, run_label, "run_label"),
    ST_CSV_COL_TEXT(T, heard, "heard"),
    ST_CSV_COL_CHOICE(T, end, "end", end_name, g_ends, NELEMS(g_ends)),
    ST_CSV_COL_INT(T, steps_run, "steps_run", 0),
    ST_CSV_COL_REAL(T, obj_x, "obj_x"),
    ST_CSV_COL_REAL(T, obj_y, "obj_y"),
    ST_CSV_COL_REAL(T, target_x, "target_x"),
    ST_CSV_COL_REAL(T, target_y, "target_y"),
    ST_CSV_COL_REAL(T, target_z, "target_z"),
};
#undef T
#define TRIAL_READ 13 /* test .. open_jumped: what the readers need, and older files have */
#define TRIAL_KEY 5   /* an individual's trial */

#define S stPostSummaryRow
static const stCsvColumn g_summary_cols[] = {
    INDIVIDUAL_COLUMNS(S),
    ST_CSV_COL_INT(S, successes, "successes", 0),
    ST_CSV_COL_INT(S, trials, "trials", 1),
    ST_CSV_COL_INT(S, excluded, "excluded", 0),
    ST_CSV_COL_INT(S, open_jumped, "open_jumped", 0),
    /* written, not read (SUMMARY_READ) */
    ST_CSV_COL_TEXT(S, run_label, "run_label"),
    ST_CSV_COL_REAL(S, success_rate, "success_rate"),
    ST_CSV_COL_REAL(S, mean_steps, "mean_steps_to_target"),
    ST_CSV_COL_INT(S, unstable, "unstable", 0),
    ST_CSV_COL_INT(S, generation, "generation", -1),
};
#undef S
#define SUMMARY_READ 8

/* ---- the rows' checks ---- */

/* where a reader's trial tables come from (./apps/stats's options) */
#define KEYS_HINT "posteval.* keys from --config (the test's config.ini) or --set"

/* the test's name: one of posteval's (selftalk/study.h) */
static int check_test(const char *test, char *msg, size_t n) {
  if (st_post_test_parse(test) >= 0) return 0;
  snprintf(msg, n, "test '%s' (expected integration, robustness or generalisation)", test);
  return 1;
}

static int check_summary(const void *row, const void *ctx, char *msg, size_t n) {
  const stPostSummaryRow *r = row;
  (void)ctx;
  if (check_test(r->test, msg, n)) return 1;
  if (r->successes > r->trials || r->open_jumped > r->trials || r->excluded > 1) {
    snprintf(msg, n, "successes %d, open_jumped %d, excluded %d (expected successes and "
             "open_jumped <= trials (%d), excluded 0 or 1)", r->successes, r->open_jumped,
             r->excluded, r->trials);
    return 1;
  }
  if (r->excluded && r->successes) {
    snprintf(msg, n, "an excluded individual with %d successes (expected 0: it is not run)",
             r->successes);
    return 1;
  }
  return 0;
}

/* ctx: the tests' trial tables, stPostDef[ST_POST_NTESTS] */
static int check_trial(const void *row, const void *ctx, char *msg, size_t n) {
  const stPostTrialRow *r = row;
  if (r->success > 1 || r->open_jumped > 1) { /* type, cell, posture: the trial table's, below */
    snprintf(msg, n, "success %d, open_jumped %d (expected 0 or 1)", r->success, r->open_jumped);
    return 1;
  }
  if (r->success && r->reached_step < 0) {
    snprintf(msg, n, "success 1 with reached_step -1 (expected the step the object reached the "
             "target)");
    return 1;
  }
  if (!r->success && r->reached_step >= 0) {
    snprintf(msg, n, "success 0 with reached_step %d (expected -1: a failed trial never reached "
             "the target)", r->reached_step);
    return 1;
  }
  if (check_test(r->test, msg, n)) return 1;
  const stPostDef *d = &((const stPostDef *)ctx)[st_post_test_parse(r->test)];
  if (r->trial >= d->trials) {
    snprintf(msg, n, "trial %d (expected 0..%d: the %s test has %d trials; " KEYS_HINT ")",
             r->trial, d->trials - 1, r->test, d->trials);
    return 1;
  }
  stPostTrial l;
  st_post_trial_layout(d, r->trial, &l);
  if (r->type != l.type || r->cell != l.cell || r->posture != l.posture || r->repetition != l.repetition) {
    snprintf(msg, n, "trial %d with type %d, cell %d, posture %d, repetition %d (expected type "
             "%d, cell %d, posture %d, repetition %d: the %s test's trial table; " KEYS_HINT ")",
             r->trial, r->type, r->cell, r->posture, r->repetition, l.type, l.cell, l.posture,
             l.repetition, r->test);
    return 1;
  }
  return 0;
}

static const stCsvSchema g_trials = {"trials.csv", g_trial_cols, NELEMS(g_trial_cols), TRIAL_READ,
                                     TRIAL_KEY, sizeof(stPostTrialRow), check_trial};
static const stCsvSchema g_summary = {"summary.csv", g_summary_cols, NELEMS(g_summary_cols),
                                      SUMMARY_READ, ST_POST_INDIVIDUAL_KEY,
                                      sizeof(stPostSummaryRow), check_summary};

const stCsvSchema *st_post_trials_schema(void) { return &g_trials; }
const stCsvSchema *st_post_summary_schema(void) { return &g_summary; }

/* ---- writing ---- */

/* what every row of an individual says */
static void labels_of(const stPostLabels *L, const stPostIndividual *ind, char *test,
                      char *condition, int *run, int *individual, char *label) {
  ST_ASSERT(strlen(L->condition) < ST_POST_LABEL_MAX);
  st__strlcpy(test, L->test, ST_CSV_NAME_LEN);
  st__strlcpy(condition, L->condition, ST_POST_LABEL_MAX);
  *run = ind->run;
  *individual = ind->rank;
  st__strlcpy(label, ind->run_label, sizeof ind->run_label);
}

int st_post_write_trials(FILE *f, const stPostLabels *L, const stPostIndividual *ind, int nind,
                         const stPostTrial *t, int ntrials, const stPostResult *r) {
  ST_ASSERT(f && L && nind >= 0 && ntrials >= 0);
  ST_ASSERT(nind == 0 || (ind && t && r));
  st_csv_write_header(f, &g_trials);
  for (int i = 0; i < nind; i++) {
    if (ind[i].excluded) continue;
    stPostTrialRow w;
    memset(&w, 0, sizeof w);
    labels_of(L, &ind[i], w.test, w.condition, &w.run, &w.individual, w.run_label);
    w.words = (int)L->words;
    for (int k = 0; k < ntrials; k++) {
      const stPostResult *x = &r[(size_t)i * (size_t)ntrials + (size_t)k];
      const stPostTrial *y = &t[k];
      w.trial = y->index, w.type = y->type, w.cell = y->cell, w.posture = y->posture;
      w.repetition = y->repetition;
      w.success = x->success, w.reached_step = x->reached_step, w.open_jumped = x->open_jumped;
      memcpy(w.heard, x->heard, sizeof w.heard);
      w.end = x->end, w.steps_run = x->steps_run;
      w.obj_x = y->obj[0], w.obj_y = y->obj[1];
      w.target_x = y->target_pos[0], w.target_y = y->target_pos[1], w.target_z = y->target_pos[2];
      st_csv_write_row(f, &g_trials, &w);
    }
  }
  return ferror(f) ? -1 : 0;
}

int st_post_write_summary(FILE *f, const stPostLabels *L, const stPostIndividual *ind, int nind,
                          int ntrials, const stPostResult *r) {
  ST_ASSERT(f && L && nind >= 0 && ntrials >= 0);
  ST_ASSERT(nind == 0 || (ind && r));
  st_csv_write_header(f, &g_summary);
  for (int i = 0; i < nind; i++) {
    stPostSummary s;
    st_post_summarise(&r[(size_t)i * (size_t)ntrials], ntrials, ind[i].excluded, &s);
    stPostSummaryRow w;
    memset(&w, 0, sizeof w);
    labels_of(L, &ind[i], w.test, w.condition, &w.run, &w.individual, w.run_label);
    w.successes = s.successes, w.trials = s.trials, w.excluded = ind[i].excluded;
    w.open_jumped = s.open_jumps;
    w.success_rate = (double)s.successes / s.trials;
    w.mean_steps = s.mean_steps;
    w.unstable = s.unstable, w.generation = ind[i].generation;
    st_csv_write_row(f, &g_summary, &w);
  }
  return ferror(f) ? -1 : 0;
}

/* ---- reading ---- */

stStatus st_post_read_summary(const char *path, stCsvRows *rows, char *err, size_t errsz) {
  ST_ASSERT(path && rows);
  return st_csv_read(path, &g_summary, NULL, rows, err, errsz);
}

stStatus st_post_read_trials(const char *path, const stPostDef defs[ST_POST_NTESTS],
                             stCsvRows *rows, char *err, size_t errsz) {
  ST_ASSERT(defs);
  return st_csv_read(path, &g_trials, defs, rows, err, errsz);
}
