/* SPDX-License-Identifier: MIT
 * score: a fitness function of the library on data from a file, so that it can be checked
 * against an independent implementation.
 *
 *   score prediction FILE [--per-trial] [--config FILE] [--set section.key=value]...
 *
 * prediction: the prediction fitness (eq. 2.15-2.24, selftalk/prediction.h). FILE has one row
 * per step, "step,word,o_reach,o_open,o_grasp,o_move": the step (0, 1, 2, ... within a trial),
 * the caretaker's word given at that step (0-3 reach, open, grasp, move; -1 none) and the four
 * linguistic outputs of the network at that step (finite, within +-ST_PRED_OUTPUT_MAX); within a
 * trial the words never go back (the caretaker's order, words jumped aside). Trials
 * are separated by blank lines; lines starting with '#' are skipped, and so is a header line
 * starting with "step" before the first row (a later one is refused). No field may be empty. Every trial is treated
 * as one whose object reached the target. Prints
 *   F_step=... F_switch=... B_pred=... F_pred=...
 * (%.17g): F_step and F_switch averaged over the trials, B_pred summed, F_pred = B_pred +
 * (1/T) sum (F_step / 3 + 2 F_switch / 3) with T the number of trials. --per-trial first prints
 * "trial I F_step=... F_switch=... B_pred=..." for each. Errors name FILE:LINE; exit 2. FILE is
 * read through the library's bounded reader (at most 64 MiB, no NUL bytes). */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/prediction.h"

static const char *prog = "score";

/* the trials of a file, rows appended in order */
typedef struct table {
  int n, cap;
  int *word;
  double (*o)[ST_PRED_NWORDS];
  int ntrials, tcap;
  int *start; /* first row of each trial */
  int *len;
} table;

static void *xrealloc(void *p, int n, size_t size) {
  void *q = realloc(p, size * (size_t)n);
  if (!q) app_die(prog, "out of memory");
  return q;
}

static void add_row(table *t, int word, const double *o) {
  if (t->n == t->cap) {
    t->cap = t->cap ? 2 * t->cap : 256;
    t->word = xrealloc(t->word, t->cap, sizeof *t->word);
    t->o = xrealloc(t->o, t->cap, sizeof *t->o);
  }
  t->word[t->n] = word;
  memcpy(t->o[t->n], o, sizeof t->o[t->n]);
  t->n++;
  t->len[t->ntrials - 1]++;
}

static void start_trial(table *t) {
  if (t->ntrials == t->tcap) {
    t->tcap = t->tcap ? 2 * t->tcap : 16;
    t->start = xrealloc(t->start, t->tcap, sizeof *t->start);
    t->len = xrealloc(t->len, t->tcap, sizeof *t->len);
  }
  t->start[t->ntrials] = t->n;
  t->len[t->ntrials] = 0;
  t->ntrials++;
}

#define COLUMNS "step,word,o_reach,o_open,o_grasp,o_move"

/* one row "step,word,o0,o1,o2,o3" of the current trial, or dies naming the line */
static void parse_row(const char *path, int lineno, char *line, int expect_step, table *t) {
  char *field[6];
  int nf = 0;
  for (char *f = line;; nf++) { /* every comma separates two fields: none may be empty */
    char *c = strchr(f, ',');
    if (c) *c = 0;
    while (isspace((unsigned char)*f)) f++;
    for (size_t n = strlen(f); n > 0 && isspace((unsigned char)f[n - 1]);) f[--n] = 0;
    if (!*f)
      app_die(prog, "%s:%d: field %d is empty (expected 6 fields: " COLUMNS ")", path, lineno,
              nf + 1);
    if (nf < 6) field[nf] = f;
    if (!c) break;
    f = c + 1;
  }
  if (++nf != 6) app_die(prog, "%s:%d: %d fields (expected 6: " COLUMNS ")", path, lineno, nf);
  char *end;
  errno = 0;
  const long step = strtol(field[0], &end, 10);
  if (end == field[0] || *end || errno || step != expect_step)
    app_die(prog, "%s:%d: step '%s' (expected %d: steps count 0, 1, 2, ... within a trial)", path,
            lineno, field[0], expect_step);
  const long word = strtol(field[1], &end, 10);
  if (end == field[1] || *end || word < -1 || word > 3)
    app_die(prog, "%s:%d: word '%s' (expected -1 for none or 0-3: reach, open, grasp, move)",
            path, lineno, field[1]);
  /* the caretaker gives reach, open, grasp, move in order, jumping some, never going back */
  const int prev = expect_step > 0 ? t->word[t->n - 1] : -1;
  if (word < prev)
    app_die(prog, "%s:%d: word %ld after %d (expected the caretaker's words in order, never "
            "back: -1 none, then 0-3 reach, open, grasp, move)", path, lineno, word, prev);
  double o[ST_PRED_NWORDS];
  for (int m = 0; m < ST_PRED_NWORDS; m++) {
    errno = 0;
    o[m] = strtod(field[2 + m], &end);
    if (end == field[2 + m] || *end)
      app_die(prog, "%s:%d: output %d '%s' is not a number", path, lineno, m, field[2 + m]);
    /* the prediction's own bound (selftalk/prediction.h): every difference stays finite */
    if (errno == ERANGE || !(fabs(o[m]) <= ST_PRED_OUTPUT_MAX))
      app_die(prog, "%s:%d: output %d '%s' (expected a finite number within +-%g: the "
              "network's linguistic outputs are in [0, 1])", path, lineno, m, field[2 + m],
              ST_PRED_OUTPUT_MAX);
  }
  add_row(t, (int)word, o);
}

static void read_table(const char *path, table *t) {
  char *text = app_read_text(prog, path, NULL);
  int lineno = 0, in_trial = 0, content = 0;
  /* lines one by one; strtok_r would skip empty lines, which end trials */
  for (char *line = text, *next; line; line = next) {
    next = strchr(line, '\n');
    if (next) *next++ = 0;
    if (!next && !*line) break; /* after the last newline */
    lineno++;
    size_t len = strlen(line);
    while (len > 0 && isspace((unsigned char)line[len - 1])) line[--len] = 0;
    char *p = line;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) {
      in_trial = 0; /* a blank line ends a trial */
      continue;
    }
    if (*p == '#') continue;
    if (!strncmp(p, "step", 4)) { /* the header: the first line that is not a comment only */
      if (content)
        app_die(prog, "%s:%d: a header line after the first line (expected rows of numbers: "
                "the header " COLUMNS " comes first, once)", path, lineno);
      content = 1;
      continue;
    }
    content = 1;
    if (!in_trial) start_trial(t), in_trial = 1;
    parse_row(path, lineno, p, t->len[t->ntrials - 1], t);
  }
  free(text);
  if (!t->ntrials) app_die(prog, "%s: no rows (expected " COLUMNS ")", path);
}

static int prediction(const char *path, int per_trial, const stConfig *cfg) {
  table t;
  memset(&t, 0, sizeof t);
  read_table(path, &t);
  stPredDef def;
  st_pred_def_from_config(cfg, &def);
  stPredScore *s = calloc((size_t)t.ntrials, sizeof *s);
  int *counts = calloc((size_t)t.ntrials, sizeof *counts);
  if (!s || !counts) app_die(prog, "out of memory");
  double f_step = 0.0, f_switch = 0.0;
  for (int i = 0; i < t.ntrials; i++) {
    const stPredTrial tr = {t.len[i], t.word + t.start[i],
                            (const double(*)[ST_PRED_NWORDS])(t.o + t.start[i])};
    char err[512];
    if (st_pred_trial(&def, &tr, &s[i], err, sizeof err)) app_die(prog, "%s: trial %d: %s", path, i, err);
    counts[i] = 1;
    f_step += s[i].f_step / t.ntrials;
    f_switch += s[i].f_switch / t.ntrials;
    if (per_trial)
      printf("trial %d F_step=%.17g F_switch=%.17g B_pred=%.17g\n", i, s[i].f_step, s[i].f_switch,
             s[i].b_pred);
  }
  double b = 0.0;
  const double f_pred = st_pred_fitness(s, counts, t.ntrials, &b);
  printf("F_step=%.17g F_switch=%.17g B_pred=%.17g F_pred=%.17g\n", f_step, f_switch, b, f_pred);
  free(s);
  free(counts);
  free(t.word);
  free(t.o);
  free(t.start);
  free(t.len);
  return 0;
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *what = NULL, *file = NULL;
  int per_trial = 0;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--per-trial")) per_trial = 1;
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      printf("usage: score prediction FILE [--per-trial] [--config FILE] [--set section.key=value]...\n");
      return 0;
    } else if (a[0] == '-' && a[1]) app_die(prog, "unknown option '%s'", a);
    else if (!what) what = a;
    else if (!file) file = a;
    else app_die(prog, "unexpected argument '%s'", a);
  }
  if (!what || !file) app_die(prog, "usage: score prediction FILE [--per-trial] [--set section.key=value]...");
  if (strcmp(what, "prediction")) app_die(prog, "'%s': unknown fitness (expected prediction)", what);
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  return prediction(file, per_trial, &cfg);
}
