/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>

#include "selftalk/genome.h"
#include "test_util.h"

static char *hex_line(int ngenes, const char *fill) {
  char *s = malloc((size_t)ngenes * 4 + 2);
  for (int i = 0; i < ngenes; i++) memcpy(s + 4 * i, fill, 4);
  s[4 * ngenes] = '\n';
  s[4 * ngenes + 1] = 0;
  return s;
}

static void test_genome_roundtrip(void) {
  stGenome g[3];
  stRng rng = st_rng_keyed(1, ST_RNG_USER, 0, 0, 0);
  st_genome_random(&g[0], 612, &rng);
  st_genome_random(&g[1], 696, &rng);
  st_genome_random(&g[2], 756, &rng);
  g[0].gene[0] = 0x0000;
  g[0].gene[611] = 0xffff;
  double fit[3] = {12.5, NAN, -3.25};
  int gen[3] = {7, -1, 1499};
  char dir[256], path[300], err[256];
  st_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/pop.genome", dir);
  CU_ASSERT_EQUAL_FATAL(st_genome_set_save(path, g, 3, fit, gen, err, sizeof err), ST_OK);
  stGenomeSet set;
  CU_ASSERT_EQUAL_FATAL(st_genome_set_read(path, 0, &set, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(set.count, 3);
  for (int i = 0; i < 3; i++) {
    CU_ASSERT_EQUAL(set.genome[i].ngenes, g[i].ngenes);
    CU_ASSERT_EQUAL(memcmp(set.genome[i].gene, g[i].gene, 2 * (size_t)g[i].ngenes), 0);
    CU_ASSERT_EQUAL(set.generation[i], gen[i]);
  }
  CU_ASSERT_DOUBLE_EQUAL(set.fitness[0], 12.5, 0.0);
  CU_ASSERT(isnan(set.fitness[1]));
  CU_ASSERT_DOUBLE_EQUAL(set.fitness[2], -3.25, 0.0);
  st_genome_set_free(&set);
  /* the writer's format: lower-case hex, the first gene of g[0] is "0000" */
  FILE *f = fopen(path, "r");
  char line[4000];
  int found = 0;
  while (fgets(line, sizeof line, f))
    if (line[0] != '#') {
      found = !strncmp(line, "0000", 4);
      break;
    }
  fclose(f);
  CU_ASSERT(found);
  /* no temporary file is left beside the target */
  char cmd[600];
  snprintf(cmd, sizeof cmd, "ls '%s' | grep -q tmp", dir);
  CU_ASSERT_NOT_EQUAL(system(cmd), 0);
}

static void expect_reject(const char *text, int expect_genes, const char *needle) {
  char path[256], err[512];
  st_test_write_tmp(path, sizeof path, ".genome", text);
  stGenomeSet set;
  stStatus st = st_genome_set_read(path, expect_genes, &set, err, sizeof err);
  CU_ASSERT_NOT_EQUAL(st, ST_OK);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, needle);
}

static void test_genome_reject(void) {
  char *ok = hex_line(612, "8000");
  /* truncated: the last gene lost two digits */
  char *trunc = hex_line(612, "1234");
  trunc[612 * 4 - 2] = '\n';
  trunc[612 * 4 - 1] = 0;
  char buf[4000];
  snprintf(buf, sizeof buf, "# genes 612\n%s", trunc);
  expect_reject(buf, 0, ":2: genotype: 2446 hex digits is not a whole number of genes");
  /* wrong length */
  char *short_line = hex_line(600, "0001");
  expect_reject(short_line, 0, ":1: genotype: 600 genes (expected 612, 696 or 756)");
  /* right length for another architecture than the one asked for */
  expect_reject(ok, 696, ":1: genotype: 612 genes (expected 696)");
  /* declared count disagrees */
  snprintf(buf, sizeof buf, "# genes 756\n%s", ok);
  expect_reject(buf, 0, ":2: genotype: 612 genes (expected 756)");
  /* non-hex */
  char *bad = hex_line(612, "abcd");
  bad[17] = 'g';
  snprintf(buf, sizeof buf, "# comment\n\n%s", bad);
  expect_reject(buf, 0, ":3: genotype: non-hex character 'g' at column 18");
  expect_reject("# only comments\n", 0, "no genotype");
  expect_reject("# genes 7\n", 0, ":1: '# genes 7': bad gene count");
  stGenomeSet set;
  char err[256];
  CU_ASSERT_EQUAL(st_genome_set_read("/nonexistent/x.genome", 0, &set, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "/nonexistent/x.genome: cannot open");
  free(ok);
  free(trunc);
  free(short_line);
  free(bad);
}

/* issue 17: a valid genotype line followed by a NUL byte and junk was read as the line alone
 * (strlen after getline); metadata the reader uses must parse; a file that never ends is
 * refused at the size limit */
static void test_genome_hostile_files(void) {
  char *line = hex_line(612, "8000"), path[256], err[512];
  const size_t n = strlen(line);
  char *text = malloc(n + 16);
  memcpy(text, line, n - 1);         /* the line without its newline */
  memcpy(text + n - 1, "\0junk\n", 6); /* NUL at column 2449 of line 1 */
  stGenomeSet set;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".genome", text, n + 5));
  CU_ASSERT_EQUAL(st_genome_set_read(path, 0, &set, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, ":1: NUL byte at column 2449 (expected a text file)");
  CU_ASSERT_EQUAL(set.count, 0);
  char buf[4000];
  snprintf(buf, sizeof buf, "# fitness 1.5x\n%s", line);
  expect_reject(buf, 0, ":1: '# fitness 1.5x': not a number (expected a finite number)");
  snprintf(buf, sizeof buf, "# generation -2\n%s", line);
  expect_reject(buf, 0, ":1: '# generation -2': not a generation (expected an integer >= 0)");
  CU_ASSERT_EQUAL(st_genome_set_read("/dev/zero", 0, &set, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "/dev/zero: larger than 64 MiB");
  free(text);
  free(line);
}

static void test_genome_grow(void) {
  stGenome base, a, b, a2;
  stRng rng = st_rng_keyed(2, ST_RNG_USER, 0, 0, 0);
  st_genome_random(&base, 612, &rng);
  char err[256];
  stRng g1 = st_rng_keyed(2, ST_RNG_GROW, 0, 5, 0), g2 = g1, g3 = g1;
  CU_ASSERT_EQUAL(st_genome_grow(&base, ST_ARCH_A, 32768, &g1, &a, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_genome_grow(&base, ST_ARCH_B, 32768, &g2, &b, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(a.ngenes, 696);
  CU_ASSERT_EQUAL(b.ngenes, 756);
  CU_ASSERT_EQUAL(memcmp(a.gene, base.gene, 612 * 2), 0);
  CU_ASSERT_EQUAL(memcmp(b.gene, a.gene, 696 * 2), 0); /* same stream, same new genes */
  for (int i = 696; i < 756; i++) CU_ASSERT_EQUAL(b.gene[i], 32768);
  /* the new block is random: over 84 x 16 bits about half are set */
  int ones = 0;
  for (int bit = 612 * 16; bit < 696 * 16; bit++) ones += st_genome_bit(&a, bit);
  CU_ASSERT(ones > 672 - 5 * 18 && ones < 672 + 5 * 18); /* binomial(1344, .5): sd 18.3 */
  /* another individual's stream gives other new genes */
  stRng other = st_rng_keyed(2, ST_RNG_GROW, 0, 6, 0);
  st_genome_grow(&base, ST_ARCH_A, 32768, &other, &a2, err, sizeof err);
  CU_ASSERT_NOT_EQUAL(memcmp(a2.gene + 612, a.gene + 612, 84 * 2), 0);
  CU_ASSERT_EQUAL(st_genome_grow(&base, ST_ARCH_BASE, 32768, &g3, &a2, err, sizeof err), ST_ERR_ARG);
  CU_ASSERT_EQUAL(st_genome_grow(&a, ST_ARCH_B, 32768, &g3, &a2, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "696 genes (expected 612");
  uint8_t mask[ST_GENOME_MAX_GENES];
  st_genome_mask_new_genes(mask, 756);
  CU_ASSERT(mask[611] == 0 && mask[612] == 1 && mask[755] == 1);
  st_genome_mask_new_genes(mask, 696);
  CU_ASSERT(mask[695] == 1 && mask[696] == 0);
}

static void test_arch_names(void) {
  CU_ASSERT_EQUAL(st_arch_parse("base"), ST_ARCH_BASE);
  CU_ASSERT_EQUAL(st_arch_parse("a"), ST_ARCH_A);
  CU_ASSERT_EQUAL(st_arch_parse("B"), ST_ARCH_B);
  CU_ASSERT_EQUAL(st_arch_parse("C"), -1);
  CU_ASSERT_STRING_EQUAL(st_arch_name(ST_ARCH_B), "B");
}

void st_suite_genome(void) {
  ST_ADD_SUITE("genome");
  ST_ADD_TEST(test_genome_roundtrip);
  ST_ADD_TEST(test_genome_reject);
  ST_ADD_TEST(test_genome_hostile_files);
  ST_ADD_TEST(test_genome_grow);
  ST_ADD_TEST(test_arch_names);
}
