/* SPDX-License-Identifier: MIT
 * The checkpoint reader (lib/run/checkpoint.h): every finding of issue 17 refused, naming the file,
 * the line and the field. Expected ranges are derived here from the run the checkpoint belongs
 * to (2 stages, 3 genotypes of 612 genes, a limit of 8 generations). */
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "run/checkpoint.h"
#include "test_util.h"

static const stCheckpointRun RUN = {2, 3, 612, 8};

/* a checkpoint's text: the header lines given, then n genotypes of 612 genes */
static char *ckpt_text(const char *header, int n) {
  const size_t line = 4 * 612 + 1;
  char *s = malloc(strlen(header) + (size_t)n * (line + 16) + 1), *p = s;
  p += sprintf(p, "%s", header);
  for (int i = 0; i < n; i++) {
    p += sprintf(p, "# genes 612\n");
    for (int g = 0; g < 612; g++) p += sprintf(p, "%04x", (unsigned)(g * 7 + i) & 0xffff);
    *p++ = '\n';
  }
  *p = 0;
  return s;
}

#define HEADER(gen, idx, sg, done, csv, best)                                                    \
  "# selftalk-checkpoint 1\n# generation " gen "\n# stage_idx " idx "\n# stage_gen " sg         \
  "\n# done " done "\n# csv_bytes " csv "\n# best_bytes " best "\n"

/* parses header + n genotypes; asserts the status and the message */
static void expect_parse(const char *header, int n, stStatus want, const char *needle) {
  char *text = ckpt_text(header, n), err[512] = "";
  stCheckpoint c;
  stStatus st = st__checkpoint_parse("run/checkpoint", text, strlen(text), &RUN, &c, err, sizeof err);
  if (st != want) fprintf(stderr, "\n  status %d, expected %d: %s\n", st, want, err);
  CU_ASSERT_EQUAL(st, want);
  if (needle) ST_ASSERT_CONTAINS(err, needle);
  if (!st) st__checkpoint_free(&c);
  free(text);
}

static void test_ckpt_valid(void) {
  char *text = ckpt_text(HEADER("5", "1", "2", "0", "830", "7539"), 3), err[256];
  stCheckpoint c;
  CU_ASSERT_EQUAL_FATAL(st__checkpoint_parse("ck", text, strlen(text), &RUN, &c, err, sizeof err), ST_OK);
  CU_ASSERT(c.generation == 5 && c.stage_idx == 1 && c.stage_gen == 2 && c.done == 0);
  CU_ASSERT(c.csv_bytes == 830 && c.best_bytes == 7539);
  CU_ASSERT_EQUAL(c.pop.count, 3);
  CU_ASSERT_EQUAL(c.pop.genome[2].gene[1], 9); /* 1 * 7 + 2 */
  st__checkpoint_free(&c);
  free(text);
  /* the writer's text reads back as the same fields */
  stGenome pop[3];
  for (int i = 0; i < 3; i++) {
    pop[i].ngenes = 612;
    for (int g = 0; g < 612; g++) pop[i].gene[g] = (uint16_t)(g + i);
  }
  stCheckpoint w = {8, 0, 8, 1, 12, 34, {0, NULL, NULL, NULL}};
  char *buf;
  size_t len;
  FILE *f = open_memstream(&buf, &len);
  CU_ASSERT_EQUAL(st__checkpoint_write(f, &w, pop, 3), 0);
  fclose(f);
  CU_ASSERT_EQUAL_FATAL(st__checkpoint_parse("ck", buf, len, &RUN, &c, err, sizeof err), ST_OK);
  CU_ASSERT(c.generation == 8 && c.stage_idx == 0 && c.stage_gen == 8 && c.done == 1);
  CU_ASSERT(c.csv_bytes == 12 && c.best_bytes == 34 && c.pop.count == 3);
  CU_ASSERT_EQUAL(c.pop.genome[1].gene[611], 612);
  st__checkpoint_free(&c);
  free(buf);
}

/* issue 17: no header field was range-checked */
static void test_ckpt_ranges(void) {
  /* stage_idx 5, -1 and 2 indexed stStage[2] out of bounds; 100000000 segfaulted */
  const char *idx[] = {"5", "-1", "2", "100000000"};
  for (int i = 0; i < 4; i++) {
    char h[512], want[128];
    snprintf(h, sizeof h, HEADER("5", "%s", "2", "0", "830", "7539"), idx[i]);
    snprintf(want, sizeof want, "run/checkpoint:3: field 'stage_idx': %s is out of range (expected "
             "an integer in [0, 1]: the run has two stages)", idx[i]);
    expect_parse(h, 3, ST_ERR_RANGE, want);
  }
  /* one header each: generation, stage_idx, stage_gen, done, csv_bytes, best_bytes; the status
   * and a part of the message that names the line and the field */
  static const struct {
    const char *f[6];
    stStatus st;
    const char *want;
  } cases[] = {
      /* generation 2147483647 overflowed gen + 1; 2^32 + 1 wrapped to 1 in the long -> int cast */
      {{"2147483647", "0", "2147483647", "0", "1", "1"}, ST_ERR_RANGE,
       "run/checkpoint:2: field 'generation': 2147483647 is out of range (expected an integer in "
       "[1, 8]: the run's generation limit"},
      {{"4294967297", "0", "1", "0", "1", "1"}, ST_ERR_RANGE,
       ":2: field 'generation': 4294967297 is out of range"},
      {{"99999999999999999999", "0", "1", "0", "1", "1"}, ST_ERR_PARSE,
       ":2: field 'generation': '99999999999999999999' is not an integer"},
      {{"0", "0", "0", "0", "1", "1"}, ST_ERR_RANGE,
       ":2: field 'generation': 0 is out of range (expected an integer in [1, 8]"},
      /* any non-zero done meant "complete" */
      {{"5", "0", "5", "2", "830", "7539"}, ST_ERR_RANGE,
       ":5: field 'done': 2 is out of range (expected an integer in [0, 1]"},
      {{"5", "0", "5", "-1", "830", "7539"}, ST_ERR_RANGE, ":5: field 'done'"},
      /* at the limit a run is complete: done 0 there would run a generation past it */
      {{"8", "0", "8", "0", "830", "7539"}, ST_ERR_RANGE,
       ":5: field 'done': 0 is out of range (expected an integer in [1, 1]: a run at its "
       "generation limit is complete)"},
      /* stage_gen against the stage: the first stage ran every generation, a later one fewer */
      {{"5", "0", "4", "0", "830", "7539"}, ST_ERR_RANGE,
       ":4: field 'stage_gen': 4 is out of range (expected an integer in [5, 5]"},
      {{"5", "1", "5", "0", "830", "7539"}, ST_ERR_RANGE,
       ":4: field 'stage_gen': 5 is out of range (expected an integer in [0, 4]"},
      {{"5", "1", "2", "0", "0", "7539"}, ST_ERR_RANGE, ":6: field 'csv_bytes': 0 is out of range"},
      {{"5", "1", "2", "0", "830", "-7"}, ST_ERR_RANGE, ":7: field 'best_bytes': -7 is out of range"},
      {{"5", "1", "2", "0", "830", "75x"}, ST_ERR_PARSE,
       ":7: field 'best_bytes': '75x' is not an integer"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char h[512];
    const char *const *f = cases[i].f;
    snprintf(h, sizeof h, HEADER("%s", "%s", "%s", "%s", "%s", "%s"), f[0], f[1], f[2], f[3], f[4], f[5]);
    expect_parse(h, 3, cases[i].st, cases[i].want);
  }
}

/* every field required, on its line: a missing one silently became 0 (cutting fitness.csv and
 * best.genome to nothing, or writing generation 0 again) */
static void test_ckpt_missing(void) {
  expect_parse("# selftalk-checkpoint 1\n# generation 5\n# stage_idx 0\n# stage_gen 5\n# done 0\n"
               "# best_bytes 7539\n", 3, ST_ERR_PARSE,
               "run/checkpoint:6: field 'csv_bytes': missing (expected '# csv_bytes N' on line 6; "
               "found '# best_bytes 7539')");
  expect_parse("# selftalk-checkpoint 1\n# generation 5\n# stage_idx 0\n# stage_gen 5\n# done 0\n"
               "# csv_bytes 830\n", 3, ST_ERR_PARSE,
               ":7: field 'best_bytes': missing (expected '# best_bytes N' on line 7; found '# genes 612')");
  expect_parse("# selftalk-checkpoint 1\n# stage_idx 0\n", 0, ST_ERR_PARSE,
               ":2: field 'generation': missing (expected '# generation N' on line 2");
  expect_parse("# selftalk-checkpoint 1\n# generation 5\n", 0, ST_ERR_PARSE,
               ":3: field 'stage_idx': missing (expected '# stage_idx N' on line 3; found the end "
               "of the file)");
  /* the file type was a strstr anywhere in the comments */
  expect_parse("# not a selftalk-checkpoint 1 at all\n", 3, ST_ERR_PARSE,
               "run/checkpoint:1: not a selftalk checkpoint (expected '# selftalk-checkpoint 1' as "
               "the first line)");
  expect_parse("", 0, ST_ERR_PARSE, "run/checkpoint:1: not a selftalk checkpoint");
}

/* the population: ga.population genotypes of the run's network; resuming with too few blamed
 * "initial population" */
static void test_ckpt_population(void) {
  expect_parse(HEADER("5", "0", "5", "0", "830", "7539"), 2, ST_ERR_RANGE,
               "run/checkpoint: field 'genotypes': 2 genotypes (expected ga.population = 3)");
  expect_parse(HEADER("5", "0", "5", "0", "830", "7539"), 4, ST_ERR_RANGE,
               "field 'genotypes': 4 genotypes (expected ga.population = 3)");
  expect_parse(HEADER("5", "0", "5", "0", "830", "7539") "# genes 700\n", 0, ST_ERR_PARSE,
               "run/checkpoint:8: '# genes 700': bad gene count");
  expect_parse(HEADER("5", "0", "5", "0", "830", "7539") "0123\n", 0, ST_ERR_PARSE,
               "run/checkpoint:8: genotype: 1 genes (expected 612)");
  char *text = ckpt_text(HEADER("5", "0", "5", "0", "830", "7539"), 3), err[256];
  /* a NUL byte in the last genotype (line 13: 2448 digits and a newline), 100 bytes before the
   * end of the text: 0-based 2349 in its line, column 2350 */
  text[strlen(text) - 100] = 0;
  stCheckpoint c;
  size_t len = strlen(text) + 1 + 99;
  CU_ASSERT_EQUAL(st__checkpoint_parse("ck", text, len, &RUN, &c, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "ck:13: NUL byte at column 2350");
  free(text);
}

/* the files the checkpoint describes: csv_bytes beyond fitness.csv made truncate() pad it with
 * NUL bytes and the run exit 0 */
static void test_ckpt_files(void) {
  char dir[256], csv[300], best[300], err[512];
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  snprintf(csv, sizeof csv, "%s/fitness.csv", dir);
  snprintf(best, sizeof best, "%s/best.genome", dir);
  /* fitness.csv: header 16 bytes, row 0 (8), row 1 (8), part of the row of the unfinished
   * generation 2 (5): 37 bytes */
  FILE *f = fopen(csv, "w");
  fputs("generation,best\n0,1.5,x\n1,2.5,y\n2,9.9", f);
  fclose(f);
  f = fopen(best, "w");
  fputs("# generation 0\n# fitness 1.5\nabcd\n# generation 1\n# fitness 2.5\n0123\n# gener", f);
  fclose(f);
  /* best.genome: records of 15 + 14 + 5 bytes: generation 0 ends at 34, generation 1 at 68 */
  /* generation 2 next: fitness.csv ends at 32 with row 1, best.genome at 68 with its record */
  stCheckpoint c = {2, 0, 2, 0, 32, 68, {0, NULL, NULL, NULL}};
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_OK);
  c.csv_bytes = 100;
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_RANGE);
  char want[600];
  snprintf(want, sizeof want, "ck:6: field 'csv_bytes': 100 exceeds the length of %s (37 bytes; "
           "expected the length it had at the checkpoint", csv);
  ST_ASSERT_CONTAINS(err, want);
  c.csv_bytes = 24; /* ends with row 0: a checkpoint of generation 1, not 2 */
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ck:6: field 'csv_bytes': fitness.csv does not end there with the row of "
                          "generation 1 (found '0,1.5,x");
  c.csv_bytes = 30; /* in the middle of a row */
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_RANGE);
  c.csv_bytes = 32;
  c.best_bytes = 34; /* the record of generation 0 */
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ck:7: field 'best_bytes': best.genome's record ending there is of "
                          "generation 0 (expected 1)");
  c.best_bytes = 66; /* the genotype line cut */
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ck:7: field 'best_bytes': best.genome does not end there with a "
                          "genotype line");
  c.best_bytes = 68;
  remove(csv);
  CU_ASSERT_EQUAL(st__checkpoint_check_files("ck", &c, csv, best, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "ck:6: field 'csv_bytes': ");
  ST_ASSERT_CONTAINS(err, "fitness.csv: cannot open: No such file or directory");
}

void st_suite_checkpoint(void) {
  ST_ADD_SUITE("checkpoint");
  ST_ADD_TEST(test_ckpt_valid);
  ST_ADD_TEST(test_ckpt_ranges);
  ST_ADD_TEST(test_ckpt_missing);
  ST_ADD_TEST(test_ckpt_population);
  ST_ADD_TEST(test_ckpt_files);
}
