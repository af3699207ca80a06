/* SPDX-License-Identifier: MIT
 * Fuzz target: the checkpoint reader (lib/run/checkpoint.h). An input is a checkpoint, then
 * optionally "\n#--- fitness.csv\n" and that file's bytes, then "\n#--- best.genome\n" and
 * that file's (the seed, tests/fuzz/seeds/checkpoint, is a short run's three files so joined):
 * the two files are written to a private directory and checked against the checkpoint as
 * --resume does. The run: simple-prim then main-prim, 2 genotypes of 612 genes, 1500
 * generations. Property: an accepted checkpoint's fields are in the ranges the header
 * promises, and the files are at least as long as it records. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "run/checkpoint.h"
#include "core/readers.h"

static const stCheckpointRun RUN = {2, 2, 612, 1500};
static const char SEP_CSV[] = "\n#--- fitness.csv\n", SEP_BEST[] = "\n#--- best.genome\n";
static char g_csv[256], g_best[256];

static const char *find(const char *s, size_t n, const char *what) {
  const size_t w = strlen(what);
  for (size_t i = 0; i + w <= n; i++)
    if (!memcmp(s + i, what, w)) return s + i;
  return NULL;
}

static void write_file(const char *path, const char *s, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(s, 1, n, f) != n || fclose(f)) abort();
}

static char g_dir[200];

static void cleanup(void) {
  remove(g_csv);
  remove(g_best);
  rmdir(g_dir);
}

static void setup(void) {
  if (g_csv[0]) return;
  char *dir = g_dir;
  snprintf(dir, sizeof g_dir, "%s/selftalk-fuzz-%ld", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp",
           (long)getpid());
  mkdir(dir, 0700);
  snprintf(g_csv, sizeof g_csv, "%s/fitness.csv", dir);
  snprintf(g_best, sizeof g_best, "%s/best.genome", dir);
  atexit(cleanup);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  setup();
  const char *s = (const char *)data, *end = s + size;
  const char *csv = find(s, size, SEP_CSV);
  const char *best = csv ? find(csv, (size_t)(end - csv), SEP_BEST) : NULL;
  const char *ck_end = csv ? csv : end;
  stCheckpoint c;
  char err[2048];
  if (st__checkpoint_parse("fuzz/checkpoint", s, (size_t)(ck_end - s), &RUN, &c, err, sizeof err))
    return 0;
  if (!(c.generation >= 1 && c.generation <= RUN.limit && c.stage_idx >= 0 && c.stage_idx < RUN.nstages &&
        c.stage_gen >= 0 && c.stage_gen <= c.generation && (c.done == 0 || c.done == 1) &&
        c.csv_bytes >= 1 && c.best_bytes >= 1 && c.pop.count == RUN.population))
    abort();
  const char *csv0 = csv ? csv + sizeof SEP_CSV - 1 : end, *csv1 = best ? best : end;
  const char *best0 = best ? best + sizeof SEP_BEST - 1 : end;
  write_file(g_csv, csv0, csv0 < csv1 ? (size_t)(csv1 - csv0) : 0);
  write_file(g_best, best0, (size_t)(end - best0));
  if (!st__checkpoint_check_files("fuzz/checkpoint", &c, g_csv, g_best, err, sizeof err)) {
    struct stat a, b;
    if (stat(g_csv, &a) || stat(g_best, &b) || a.st_size < c.csv_bytes || b.st_size < c.best_bytes)
      abort();
  }
  st__checkpoint_free(&c);
  return 0;
}
