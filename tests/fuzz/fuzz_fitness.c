/* SPDX-License-Identifier: MIT
 * Fuzz target: the reader of a generation's trials in an integrated run's fitness.csv
 * (st__fitness_csv_successes_parse, lib/run/fitnesscsv_parse.h: the exclusion rule of the
 * generalisation test, and every posteval of an integrated run, read it). Asked for generation 0
 * with room for 8 trials. Property: an accepted file gives 1..8 trials, each 0 or 1, the same
 * when asked again; and, read again here independently, the accepted text has generation and
 * best_t0 columns and every row a generation above the previous one and best_t0 0 or 1. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "run/fitnesscsv_parse.h"

/* field k of a line (up to its end or a CR): *f and its length; 0 when the line has no field k */
static int field(const char *line, size_t len, int k, const char **f, size_t *n) {
  size_t i = 0;
  for (int c = 0; c < k; c++) {
    while (i < len && line[i] != ',' && line[i] != '\r') i++;
    if (i >= len || line[i] != ',') return 0;
    i++;
  }
  size_t j = i;
  while (j < len && line[j] != ',' && line[j] != '\r') j++;
  *f = line + i, *n = j - i;
  return 1;
}

static int is(const char *f, size_t n, const char *s) { return n == strlen(s) && !memcmp(f, s, n); }

/* the accepted text again, independently: the header's generation and best_t0 columns, and in
 * every row a generation above the last one and best_t0 0 or 1 */
static void recheck(const char *t, size_t size) {
  int gcol = -1, tcol = -1, lineno = 0;
  long prev = -1;
  const char *f;
  size_t n;
  for (size_t p = 0; p < size;) {
    const char *nl = memchr(t + p, '\n', size - p);
    const size_t len = nl ? (size_t)(nl - (t + p)) : size - p;
    const char *line = t + p;
    p += len + 1;
    if (lineno++ == 0) {
      for (int k = 0; k < 256 && field(line, len, k, &f, &n); k++) {
        if (is(f, n, "generation") && gcol < 0) gcol = k;
        if (is(f, n, "best_t0") && tcol < 0) tcol = k;
      }
      if (gcol < 0 || tcol < 0) abort();
      continue;
    }
    if (!field(line, len, gcol, &f, &n) || n == 0 || n > 10) abort();
    long gv = 0;
    for (size_t i = 0; i < n; i++) {
      if (f[i] < '0' || f[i] > '9') abort();
      gv = 10 * gv + (f[i] - '0');
    }
    if (gv <= prev) abort();
    prev = gv;
    if (!field(line, len, tcol, &f, &n) || !(is(f, n, "0") || is(f, n, "1"))) abort();
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  uint8_t s[8], again[8];
  int n = -1, n2 = -1;
  char err[512];
  if (st__fitness_csv_successes_parse("fuzz.csv", (const char *)data, size, 0, s, 8, &n, err,
                                      sizeof err))
    return 0;
  if (n < 1 || n > 8) abort();
  for (int i = 0; i < n; i++)
    if (s[i] > 1) abort();
  if (st__fitness_csv_successes_parse("fuzz.csv", (const char *)data, size, 0, again, 8, &n2, err,
                                      sizeof err) ||
      n2 != n || memcmp(s, again, (size_t)n))
    abort();
  if (memchr(data, 0, size)) abort(); /* NUL bytes are refused */
  recheck((const char *)data, size);
  return 0;
}
