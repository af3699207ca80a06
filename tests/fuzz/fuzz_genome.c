/* SPDX-License-Identifier: MIT
 * Fuzz target: the genome reader (st_genome_set_read's parser, lib/core/readers.h). Property: the
 * genotypes of a text it accepts are written back by st_genome_write and read back the same. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/readers.h"

/* the first byte picks the gene count asked for: any, or one architecture's */
static int expect_of(const uint8_t *data, size_t size) {
  static const int expect[4] = {0, ST_GENES_BASE, ST_GENES_A, ST_GENES_B};
  return size ? expect[data[0] & 3] : 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  stGenomeSet set, back;
  char err[1024];
  const int expect = expect_of(data, size);
  if (st__genome_set_parse("fuzz.genome", (const char *)data, size, 1, expect, &set, err, sizeof err))
    return 0;
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f) abort();
  for (int i = 0; i < set.count; i++)
    if (st_genome_write(f, &set.genome[i], set.generation[i], set.fitness[i])) abort();
  if (fclose(f)) abort();
  if (st__genome_set_parse("written.genome", text, len, 1, expect, &back, err, sizeof err)) {
    fprintf(stderr, "accepted genotypes do not read back: %s\n", err);
    abort();
  }
  if (back.count != set.count) abort();
  for (int i = 0; i < set.count; i++) {
    const stGenome *a = &set.genome[i], *b = &back.genome[i];
    if (a->ngenes != b->ngenes || memcmp(a->gene, b->gene, sizeof a->gene[0] * (size_t)a->ngenes) ||
        back.generation[i] != set.generation[i] ||
        !(back.fitness[i] == set.fitness[i] || (isnan(back.fitness[i]) && isnan(set.fitness[i])))) {
      fprintf(stderr, "genotype %d reads back as another\n", i);
      abort();
    }
  }
  st_genome_set_free(&set);
  st_genome_set_free(&back);
  free(text);
  return 0;
}
