/* SPDX-License-Identifier: MIT
 * selftalk/csv.h, selftalk/fitnesscsv.h and the numbers files of selftalk/stats.h: the writer
 * against literal lines, the reader's refusals naming FILE:LINE, the key order and the groups;
 * fitness.csv's layouts against the headers of the committed runs (evolve wrote them before
 * the table existed) and its rows against the format evolve used then. The post-evaluation
 * files' readers are checked end to end by tests/check_stats.sh. */
#include <math.h>
#include <stdlib.h>

#include "core/readers.h"
#include "selftalk/fitnesscsv.h"
#include "selftalk/stats.h"
#include "test_util.h"

typedef struct row {
  char name[ST_CSV_NAME_LEN];
  int k, v;
  int pick;
  double x;
  char note[16];
} row;

static const char *pick_name(int v) { return v == 7 ? "seven" : v == 9 ? "nine" : "?"; }
static const int PICKS[] = {7, 9};

/* v at most k: a row check, whose message the reader puts after FILE:LINE */
static int check_row(const void *p, const void *ctx, char *msg, size_t n) {
  const row *r = p;
  if (r->v <= r->k + *(const int *)ctx) return 0;
  snprintf(msg, n, "v %d above k %d", r->v, r->k);
  return 1;
}

static const stCsvColumn COLS[] = {
    ST_CSV_COL_NAME(row, name, "name"),   ST_CSV_COL_INT(row, k, "k", 0),
    ST_CSV_COL_INT(row, v, "v", -1),      ST_CSV_COL_CHOICE(row, pick, "pick", pick_name, PICKS, 2),
    ST_CSV_COL_REAL(row, x, "x"),         ST_CSV_COL_TEXT(row, note, "note"),
};
static const stCsvSchema SCHEMA = {"t.csv", COLS, 6, 4, 2, sizeof(row), check_row};

static void test_csv_write(void) {
  char buf[256];
  CU_ASSERT_EQUAL(st_csv_header_text(&SCHEMA, buf, sizeof buf), 21);
  CU_ASSERT_STRING_EQUAL(buf, "name,k,v,pick,x,note\n");
  const row r = {"a-b", 3, -1, 9, 0.1, ""};
  CU_ASSERT_EQUAL(st_csv_row_text(&SCHEMA, &r, buf, sizeof buf), 35);
  CU_ASSERT_STRING_EQUAL(buf, "a-b,3,-1,nine,0.10000000000000001,\n");
  /* cut as snprintf cuts: the whole length returned */
  CU_ASSERT_EQUAL(st_csv_row_text(&SCHEMA, &r, buf, 6), 35);
  CU_ASSERT_STRING_EQUAL(buf, "a-b,3");
  const row nan_row = {"n", 0, 0, 7, NAN, "free text"};
  char *mem = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&mem, &len);
  CU_ASSERT_EQUAL(st_csv_write_header(f, &SCHEMA), 0);
  CU_ASSERT_EQUAL(st_csv_write_row(f, &SCHEMA, &r), 0);
  CU_ASSERT_EQUAL(st_csv_write_row(f, &SCHEMA, &nan_row), 0);
  fclose(f);
  CU_ASSERT_STRING_EQUAL(mem, "name,k,v,pick,x,note\na-b,3,-1,nine,0.10000000000000001,\n"
                              "n,0,0,seven,nan,free text\n");
  free(mem);
}

/* text read with the check's slack 0; returns the status, err the message */
static stStatus parse(const char *text, stCsvRows *rows, char *err, size_t n) {
  static const int slack = 0;
  return st__csv_parse("t.csv", text, strlen(text), &SCHEMA, &slack, rows, err, n);
}

static void test_csv_read(void) {
  stCsvRows rs;
  char err[512] = "";
  /* comments, blank lines, surrounding blanks, further columns ignored; the key order */
  const char *text = "# made by hand\nname,k,v,pick,more\n\n b,2,1,seven \na,5,5,nine,x\nb,1,0,nine\r\n"
                     "a,1,-1,seven\n";
  CU_ASSERT_EQUAL_FATAL(parse(text, &rs, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(rs.n, 4);
  const row *r = st_csv_row(&rs, 0);
  CU_ASSERT(!strcmp(r->name, "b") && r->k == 2 && r->v == 1 && r->pick == 7 && r->x == 0.0);
  CU_ASSERT_EQUAL(rs.line[0], 4);
  static const int want[] = {3, 1, 2, 0}; /* a 1, a 5, b 1, b 2 */
  for (int k = 0; k < 4; k++) CU_ASSERT_EQUAL(rs.order[k], want[k]);
  stCsvGroup *g;
  int ng;
  CU_ASSERT_EQUAL_FATAL(st_csv_groups(&rs, 1, &g, &ng, err, sizeof err), ST_OK);
  CU_ASSERT(ng == 2 && g[0].start == 0 && g[0].end == 2 && g[0].first == 1 && g[1].first == 0);
  const row want_b = {"b", 0, 0, 0, 0.0, ""}, want_c = {"c", 0, 0, 0, 0.0, ""};
  CU_ASSERT_PTR_EQUAL(st_csv_group_find(&rs, 1, g, ng, &want_b), &g[1]);
  CU_ASSERT_PTR_NULL(st_csv_group_find(&rs, 1, g, ng, &want_c));
  free(g);
  st_csv_rows_free(&rs);
  /* refusals: FILE:LINE and what was expected */
  static const struct {
    const char *text, *msg;
  } bad[] = {
      {"", "t.csv:0: no header (expected the header name,k,v,pick, further columns ignored)"},
      {"# c\nname,k\n", "t.csv:2: not the header (expected the header name,k,v,pick"},
      {"name,k,v,pick\n", "t.csv: no rows after the header"},
      {"name,k,v,pick\na,1,1\n", "t.csv:2: 3 fields (expected at least 4: name,k,v,pick)"},
      {"name,k,v,pick\n\"a\",1,1,nine\n", "t.csv:2: a quoted field (expected plain comma-separated values)"},
      {"name,k,v,pick\n,1,1,nine\n", "t.csv:2: name '' (expected a name of 1..31 characters without blanks or |)"},
      {"name,k,v,pick\na b,1,1,nine\n", "t.csv:2: name 'a b' (expected a name"},
      {"name,k,v,pick\na,-1,1,nine\n", "t.csv:2: k '-1' (expected an integer >= 0)"},
      {"name,k,v,pick\na,1,,nine\n", "t.csv:2: v '' (expected an integer >= -1)"},
      {"name,k,v,pick\na,1,1,eight\n", "t.csv:2: pick 'eight' (expected seven or nine)"},
      {"name,k,v,pick\na,1,2,nine\n", "t.csv:2: v 2 above k 1"},
      {"name,k,v,pick\na,1,1,nine\nname,k,v,pick\n", "t.csv:3: k 'k' (expected an integer >= 0)"},
      {"name,k,v,pick\na,1,1,nine\nb,1,1,nine\n\na,1,0,seven\n",
       "t.csv:5: name a k 1 twice (first at line 2; expected each once)"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    err[0] = 0;
    CU_ASSERT_EQUAL(parse(bad[i].text, &rs, err, sizeof err), ST_ERR_PARSE);
    ST_ASSERT_CONTAINS(err, bad[i].msg);
    CU_ASSERT(rs.n == 0 && rs.data == NULL);
  }
  /* a NUL byte, as every reader */
  CU_ASSERT_EQUAL(st__csv_parse("t.csv", "name,k,v,pick\na\0", 16, &SCHEMA, NULL, &rs, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "t.csv:2: NUL byte at column 2 (expected a text file)");
  /* the file reader: the same, and the file's own errors */
  char path[256];
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".csv", "name,k,v,pick\nz,4,4,seven\n"));
  static const int slack = 0;
  CU_ASSERT_EQUAL_FATAL(st_csv_read(path, &SCHEMA, &slack, &rs, err, sizeof err), ST_OK);
  CU_ASSERT(rs.n == 1 && ((const row *)st_csv_sorted(&rs, 0))->k == 4);
  st_csv_rows_free(&rs);
  CU_ASSERT_EQUAL(st_csv_read("/nonexistent/t.csv", &SCHEMA, &slack, &rs, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "/nonexistent/t.csv: cannot open");
}

static void test_numbers(void) {
  double *x;
  int n;
  char err[256] = "";
  const char *ok = "# n\n 1.5 \n\n-2\n1e3\r\n";
  CU_ASSERT_EQUAL_FATAL(st__numbers_parse("n.txt", ok, strlen(ok), &x, &n, err, sizeof err), ST_OK);
  CU_ASSERT(n == 3 && x[0] == 1.5 && x[1] == -2.0 && x[2] == 1000.0);
  free(x);
  static const struct {
    const char *text, *msg;
  } bad[] = {{"1\n2 3\n", "n.txt:2: '2 3' is not a number (expected one number per line)"},
             {"inf\n", "n.txt:1: 'inf' is not finite (expected a finite number)"},
             {"1e999\n", "n.txt:1: '1e999' is not finite"},
             {"# none\n\n", "n.txt: no numbers (expected one number per line; blank lines and # comments are skipped)"}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    CU_ASSERT_EQUAL(st__numbers_parse("n.txt", bad[i].text, strlen(bad[i].text), &x, &n, err, sizeof err), ST_ERR_PARSE);
    ST_ASSERT_CONTAINS(err, bad[i].msg);
    CU_ASSERT(x == NULL && n == 0);
  }
}

/* the first line of a file, with its newline */
static void first_line(const char *path, char *buf, size_t n) {
  FILE *f = fopen(path, "r");
  CU_ASSERT_PTR_NOT_NULL_FATAL(f);
  CU_ASSERT_PTR_NOT_NULL(fgets(buf, (int)n, f));
  fclose(f);
}

/* a layout: the integrated stage's with `trials` trials, or the primitive stages' with the 16
 * fixed trials and the other kinds' counts */
static stFitnessLayout layout(int integrated, int trials, int handover, int chained, int varied) {
  stFitnessLayout l;
  memset(&l, 0, sizeof l);
  l.integrated = integrated;
  l.trials = integrated ? trials : 0;
  l.kind_trials[ST_TRIAL_FIXED] = integrated ? 0 : trials;
  l.kind_trials[ST_TRIAL_HANDOVER] = handover;
  l.kind_trials[ST_TRIAL_CHAINED] = chained;
  l.kind_trials[ST_TRIAL_VARIED] = varied;
  return l;
}

/* every layout's header as evolve wrote it in the committed runs, the primitive stages' trials
 * from the kinds' rows (selftalk/trialkind.h). With test_fitness_csv_rows, a pin of the format
 * (as tests/golden/golden.sha256 of evolve's output): a column added to the table or a kind
 * changes them, on purpose */
static void test_fitness_csv_layouts(void) {
  const int H = ST_TRIAL_MAX_HANDOVER, V = ST_TRIAL_MAX_VARIED;
  const struct {
    stFitnessLayout l;
    const char *run;
  } cases[] = {
      {layout(0, ST_PRIM_TRIALS, 0, 0, 0), "data/evolved/prims_s2/fitness.csv"},
      {layout(1, 8, 0, 0, 0), "data/evolved/unchained/int_stct_s1/fitness.csv"},
      {layout(0, ST_PRIM_TRIALS, 0, 8, 0), "data/evolved/chain_candidates/chain_gated_p2_s1/fitness.csv"},
      {layout(0, ST_PRIM_TRIALS, H, 0, 0), "data/evolved/chain_candidates/handover_p2_s1/fitness.csv"},
      {layout(0, ST_PRIM_TRIALS, H, 8, 0), "data/evolved/chain_candidates/hcg_p2_s1/fitness.csv"},
      {layout(0, ST_PRIM_TRIALS, H, 8, V), "data/evolved/chain_s1/fitness.csv"}, /* every kind */
      {layout(1, 8, H, 8, V), "data/evolved/unchained/int_ct_s1/fitness.csv"}, /* integrated: no kinds */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    stFitnessCsv c;
    st_fitness_csv(&cases[i].l, &c);
    char got[4096], want[4096];
    st_csv_header_text(&c.schema, got, sizeof got);
    first_line(cases[i].run, want, sizeof want);
    if (strcmp(got, want)) fprintf(stderr, "\n  %s:\n  got  %s  want %s", cases[i].run, got, want);
    CU_ASSERT_STRING_EQUAL(got, want);
  }
}

/* rows as evolve formatted them before the table (lib/run/evolve.c's csv_row) */
static void test_fitness_csv_rows(void) {
  stFitnessRow w;
  memset(&w, 0, sizeof w);
  w.generation = 12, w.best = 101.25, w.mean = 1.0 / 3.0, w.worst = -0.5, w.f_int = 90.1;
  w.f_pred = 0.7, w.bonus = 80, w.bonus_auto = 40, w.successes = 5;
  for (int t = 0; t < 8; t++) w.success[t] = t % 3 == 0;
  char got[4096], want[4096];
  int k = snprintf(want, sizeof want, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d", w.generation,
                   w.best, w.mean, w.worst, w.f_int, w.f_pred, w.bonus, w.bonus_auto, w.successes);
  for (int t = 0; t < 8; t++) k += snprintf(want + k, sizeof want - (size_t)k, ",%d", w.success[t]);
  snprintf(want + k, sizeof want - (size_t)k, "\n");
  stFitnessCsv c;
  const stFitnessLayout integrated = layout(1, 8, 0, 0, 0);
  st_fitness_csv(&integrated, &c);
  st_csv_row_text(&c.schema, &w, got, sizeof got);
  CU_ASSERT_STRING_EQUAL(got, want);
  /* a main-prim row with hand-over and chained trials */
  stKindEvaluation *fixed = &w.kind[ST_TRIAL_FIXED], *ho = &w.kind[ST_TRIAL_HANDOVER];
  stKindEvaluation *chained = &w.kind[ST_TRIAL_CHAINED], *varied = &w.kind[ST_TRIAL_VARIED];
  snprintf(w.stage, sizeof w.stage, "main-prim");
  w.stage_generation = 4, w.all_success = 2, ho->count = 3, chained->fitness = 12.5;
  for (int p = 0; p < ST_NPRIM; p++) w.f_prim[p] = 0.1 * (p + 1);
  for (int t = 0; t < ST_PRIM_TRIALS; t++) fixed->success[t] = t % 2;
  ho->success[1] = chained->success[2] = 1;
  k = snprintf(want, sizeof want, "%d,%.17g,%.17g,%.17g,%.17g,%s,%d,%d,%d,%.17g,%.17g,%.17g,%.17g",
               w.generation, w.best, w.mean, w.worst, w.bonus, w.stage, w.stage_generation,
               w.all_success, w.successes, w.f_prim[0], w.f_prim[1], w.f_prim[2], w.f_prim[3]);
  for (int t = 0; t < ST_PRIM_TRIALS; t++) k += snprintf(want + k, sizeof want - (size_t)k, ",%d", fixed->success[t]);
  k += snprintf(want + k, sizeof want - (size_t)k, ",%d", ho->count);
  for (int t = 0; t < ST_TRIAL_MAX_HANDOVER; t++)
    k += snprintf(want + k, sizeof want - (size_t)k, ",%d", ho->success[t]);
  k += snprintf(want + k, sizeof want - (size_t)k, ",%.17g", chained->fitness);
  for (int t = 0; t < 3; t++) k += snprintf(want + k, sizeof want - (size_t)k, ",%d", chained->success[t]);
  snprintf(want + k, sizeof want - (size_t)k, "\n");
  const stFitnessLayout main_prim = layout(0, ST_PRIM_TRIALS, ST_TRIAL_MAX_HANDOVER, 3, 0);
  st_fitness_csv(&main_prim, &c);
  st_csv_row_text(&c.schema, &w, got, sizeof got);
  CU_ASSERT_STRING_EQUAL(got, want);
  /* and with its varied trials: best_v0..7 last */
  varied->success[0] = varied->success[6] = 1;
  k = (int)strlen(want) - 1;
  for (int t = 0; t < ST_TRIAL_MAX_VARIED; t++)
    k += snprintf(want + k, sizeof want - (size_t)k, ",%d", varied->success[t]);
  snprintf(want + k, sizeof want - (size_t)k, "\n");
  const stFitnessLayout main_varied = layout(0, ST_PRIM_TRIALS, ST_TRIAL_MAX_HANDOVER, 3, ST_TRIAL_MAX_VARIED);
  st_fitness_csv(&main_varied, &c);
  st_csv_row_text(&c.schema, &w, got, sizeof got);
  CU_ASSERT_STRING_EQUAL(got, want);
  CU_ASSERT_EQUAL(c.schema.ncols, 13 + ST_PRIM_TRIALS + 1 + ST_TRIAL_MAX_HANDOVER + 1 + 3 + 8);
}

/* the kinds' columns are their rows': each kind's own column and its per-trial column, named
 * by the row, in the table's order after the primitive stages' own columns */
static void test_fitness_csv_kind_rows(void) {
  stFitnessLayout l = layout(0, ST_PRIM_TRIALS, 0, 0, 0);
  int n0;
  const stFitnessColumn *common = st_fitness_columns(&n0);
  int primitive = 0;
  for (int i = 0; i < n0; i++) primitive += (common[i].stages & ST_FITNESS_PRIMITIVE) != 0;
  stFitnessCsv c;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) l.kind_trials[k] = st_trial_kind_def((stTrialKind)k)->max;
  st_fitness_csv(&l, &c);
  int at = primitive;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    CU_ASSERT_EQUAL(d->kind, (stTrialKind)k);
    if (d->column.name) CU_ASSERT_STRING_EQUAL(c.col[at++].name, d->column.name);
    for (int t = 0; t < d->max; t++, at++) {
      char want[32];
      snprintf(want, sizeof want, d->trial_column, t);
      CU_ASSERT_STRING_EQUAL(c.col[at].name, want);
    }
  }
  CU_ASSERT_EQUAL(at, c.schema.ncols);
  /* the fixed trials' column is the runs' trial column, which the reader finds */
  CU_ASSERT_STRING_EQUAL(st_trial_kind_def(ST_TRIAL_FIXED)->trial_column, ST_TRIAL_COLUMN);
}

/* the trials of a generation, the columns found by name */
static void test_fitness_csv_successes(void) {
  uint8_t s[ST_INT_MAX_TRIALS];
  int n = 0;
  char err[512] = "";
  CU_ASSERT_EQUAL_FATAL(st_fitness_csv_successes("data/evolved/unchained/int_stct_s1/fitness.csv", 0, s,
                                                 ST_INT_MAX_TRIALS, &n, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(n, 8);
  char path[256];
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".csv", "x,best_t0,generation,best_t1\n1,0,3,1\n"));
  CU_ASSERT_EQUAL_FATAL(st_fitness_csv_successes(path, 3, s, 4, &n, err, sizeof err), ST_OK);
  CU_ASSERT(n == 2 && s[0] == 0 && s[1] == 1);
  CU_ASSERT_EQUAL(st_fitness_csv_successes(path, 4, s, 4, &n, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, ": no row for generation 4, the last of best.genome");
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".csv", "generation,best\n0,1\n"));
  CU_ASSERT_EQUAL(st_fitness_csv_successes(path, 0, s, 4, &n, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, ":1: no generation and best_t0 columns (expected the fitness.csv of an integrated run)");
  /* issue 48: strict. A trial's value other than 0 or 1 was read as a success, the first of two
   * rows of a generation taken; each refused naming FILE:LINE, whichever generation is asked */
  static const struct {
    const char *text, *why;
  } bad[] = {
      {"generation,best_t0,best_t1\n0,1,0\n1,,1\n", ":3: best_t0 '' (expected 0 or 1: the trial failed or succeeded)"},
      {"generation,best_t0,best_t1\n0,1,x\n", ":2: best_t1 'x' (expected 0 or 1"},
      {"generation,best_t0,best_t1\n0,1,2\n", ":2: best_t1 '2' (expected 0 or 1"},
      {"generation,best_t0,best_t1\n0,1,1\n1,0,0\n1,1,1\n", ":4: generation 1 after 1 (expected one row per generation, in increasing order)"},
      {"generation,best_t0,best_t1\n1,1,1\n0,0,0\n", ":3: generation 0 after 1"},
      {"generation,best_t0,best_t1\n0,1,1\n1,0\n", ":3: 2 fields (expected 3, as the header)"},
      {"generation,best_t0,best_t1\n0,1,1,1\n", ":2: 4 fields (expected 3, as the header)"},
      {"generation,best_t0,best_t1\n-1,1,1\n", ":2: generation '-1' (expected an integer >= 0 as evolve writes it)"},
      {"generation,best_t0,best_t1\n0,1,1\n01,1,1\n", ":3: generation '01' (expected an integer >= 0"},
      {"generation,best_t0,best_t1\n 0,1,1\n", ":2: generation ' 0' (expected an integer >= 0"},
      {"generation,best_t0,best_t0\n0,1,1\n", ":1: column 'best_t0' twice (expected each column once)"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".csv", bad[i].text));
    err[0] = 0;
    CU_ASSERT_EQUAL(st_fitness_csv_successes(path, 0, s, 4, &n, err, sizeof err), ST_ERR_PARSE);
    ST_ASSERT_CONTAINS(err, path);
    ST_ASSERT_CONTAINS(err, bad[i].why);
  }
}

void st_suite_csv(void) {
  ST_ADD_SUITE("csv");
  ST_ADD_TEST(test_csv_write);
  ST_ADD_TEST(test_csv_read);
  ST_ADD_TEST(test_numbers);
  ST_ADD_TEST(test_fitness_csv_layouts);
  ST_ADD_TEST(test_fitness_csv_rows);
  ST_ADD_TEST(test_fitness_csv_kind_rows);
  ST_ADD_TEST(test_fitness_csv_successes);
}
