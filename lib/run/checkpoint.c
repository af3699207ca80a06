/* SPDX-License-Identifier: MIT
 * The checkpoint of an evolution run: writer and the one validated reader (lib/checkpoint.h). */
#define _POSIX_C_SOURCE 200809L
#include "run/checkpoint.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/internal.h"
#include "core/readers.h"
#include "selftalk/io.h"

/* the header: fields in this order on lines 2..7 (line 1 is the magic line) */
enum { F_GENERATION, F_STAGE_IDX, F_STAGE_GEN, F_DONE, F_CSV_BYTES, F_BEST_BYTES, F_COUNT };
static const char *const FIELD[F_COUNT] = {"generation", "stage_idx", "stage_gen",
                                           "done",       "csv_bytes", "best_bytes"};
#define HEADER_LINES (1 + F_COUNT)
#define TAIL_WINDOW 8192 /* bytes read back from the end of fitness.csv / best.genome: more
                            than a row (< 2 KiB) or a best.genome record (< 4 KiB) */

int st__checkpoint_write(FILE *f, const stCheckpoint *c, const stGenome *pop, int n) {
  if (fprintf(f, "# %s\n# generation %d\n# stage_idx %d\n# stage_gen %d\n# done %d\n"
              "# csv_bytes %lld\n# best_bytes %lld\n", ST_CKPT_MAGIC, c->generation, c->stage_idx,
              c->stage_gen, c->done, c->csv_bytes, c->best_bytes) < 0)
    return -1;
  for (int i = 0; i < n; i++)
    if (st_genome_write(f, &pop[i], -1, NAN)) return -1;
  return 0;
}

void st__checkpoint_free(stCheckpoint *c) {
  if (c) st_genome_set_free(&c->pop);
}

/* ---- the header ---- */

typedef struct hparse {
  const char *name;
  const char *p, *end; /* the unread text */
  int lineno;
  char *err;
  size_t errsz;
} hparse;

/* the next line (without its newline and trailing white space) into buf; -1 at the end */
static int header_line(hparse *h, char *buf, size_t bufsz) {
  const char *line;
  size_t n;
  if (!st__text_line(&h->p, h->end, &line, &n, NULL)) return -1;
  if (n >= bufsz) n = bufsz - 1; /* a longer line cannot match: its start is enough to show */
  memcpy(buf, line, n);
  buf[n] = 0;
  while (n && isspace((unsigned char)buf[n - 1])) buf[--n] = 0;
  for (char *q = buf; *q; q++)
    if (!isprint((unsigned char)*q)) *q = '?';
  h->lineno++;
  return 0;
}

static stStatus read_magic(hparse *h) {
  char line[64];
  if (header_line(h, line, sizeof line) || strcmp(line, "# " ST_CKPT_MAGIC)) {
    st__errf(h->err, h->errsz, "%s:1: not a selftalk checkpoint (expected '# %s' as the first "
             "line)", h->name, ST_CKPT_MAGIC);
    return ST_ERR_PARSE;
  }
  return ST_OK;
}

/* a whole token as a long long; 0 on success */
static int parse_ll(const char *s, long long *v) {
  char *end;
  if (!*s || isspace((unsigned char)*s)) return -1;
  errno = 0;
  *v = strtoll(s, &end, 10);
  return *end || errno == ERANGE ? -1 : 0;
}

/* "# FIELD VALUE" on the next line, VALUE an integer */
static stStatus read_field(hparse *h, int f, long long *v) {
  char line[80];
  const int missing = header_line(h, line, sizeof line) != 0;
  const size_t n = strlen(FIELD[f]);
  if (missing || strncmp(line, "# ", 2) || strncmp(line + 2, FIELD[f], n) || line[2 + n] != ' ') {
    st__errf(h->err, h->errsz, "%s:%d: field '%s': missing (expected '# %s N' on line %d; found "
             "%s%s%s)", h->name, h->lineno + missing, FIELD[f], FIELD[f], h->lineno + missing,
             missing ? "the end of the file" : "'", missing ? "" : line, missing ? "" : "'");
    return ST_ERR_PARSE;
  }
  if (parse_ll(line + 3 + n, v)) {
    st__errf(h->err, h->errsz, "%s:%d: field '%s': '%s' is not an integer (expected '# %s N')",
             h->name, h->lineno, FIELD[f], line + 3 + n, FIELD[f]);
    return ST_ERR_PARSE;
  }
  return ST_OK;
}

/* the range of field f given the fields before it, and why */
static void field_range(int f, const stCheckpointRun *run, const stCheckpoint *c, long long *lo,
                        long long *hi, const char **why) {
  switch (f) {
    case F_GENERATION:
      *lo = 1, *hi = run->limit;
      *why = "the run's generation limit: --generations, ga.max_generations or "
             "ga.integrated_generations";
      break;
    case F_STAGE_IDX:
      *lo = 0, *hi = run->nstages - 1;
      *why = run->nstages == 1 ? "the run has one stage" : "the run has two stages";
      break;
    case F_STAGE_GEN:
      *lo = c->stage_idx ? 0 : c->generation;
      *hi = c->stage_idx ? c->generation - 1 : c->generation;
      *why = c->stage_idx ? "a later stage starts after generation 0"
                          : "the first stage has run every generation so far";
      break;
    case F_DONE:
      *lo = c->generation < run->limit ? 0 : 1, *hi = 1;
      *why = c->generation < run->limit ? "1: the run is complete, 0: it is not"
                                        : "a run at its generation limit is complete";
      break;
    default:
      *lo = 1, *hi = LLONG_MAX;
      *why = f == F_CSV_BYTES ? "the length of fitness.csv at the checkpoint"
                              : "the length of best.genome at the checkpoint";
  }
}

static void store_field(stCheckpoint *c, int f, long long v) {
  switch (f) {
    case F_GENERATION: c->generation = (int)v; break;
    case F_STAGE_IDX: c->stage_idx = (int)v; break;
    case F_STAGE_GEN: c->stage_gen = (int)v; break;
    case F_DONE: c->done = (int)v; break;
    case F_CSV_BYTES: c->csv_bytes = v; break;
    default: c->best_bytes = v;
  }
}

static stStatus read_header(hparse *h, const stCheckpointRun *run, stCheckpoint *c) {
  stStatus st = read_magic(h);
  for (int f = 0; f < F_COUNT && !st; f++) {
    long long v, lo, hi;
    const char *why;
    if ((st = read_field(h, f, &v))) break;
    field_range(f, run, c, &lo, &hi, &why);
    if (v < lo || v > hi) {
      st__errf(h->err, h->errsz, "%s:%d: field '%s': %lld is out of range (expected an integer "
               "in [%lld, %lld]: %s)", h->name, h->lineno, FIELD[f], v, lo, hi, why);
      st = ST_ERR_RANGE;
    }
    store_field(c, f, v);
  }
  return st;
}

/* ---- the population ---- */

static stStatus read_population(hparse *h, const stCheckpointRun *run, stCheckpoint *c) {
  stStatus st = st__genome_set_parse(h->name, h->p, (size_t)(h->end - h->p), h->lineno + 1,
                                     run->ngenes, &c->pop, h->err, h->errsz);
  if (st) return st;
  if (c->pop.count != run->population) {
    st__errf(h->err, h->errsz, "%s: field 'genotypes': %d genotypes (expected ga.population = %d)",
             h->name, c->pop.count, run->population);
    st_genome_set_free(&c->pop);
    return ST_ERR_RANGE;
  }
  return ST_OK;
}

stStatus st__checkpoint_parse(const char *name, const char *text, size_t len,
                              const stCheckpointRun *run, stCheckpoint *c, char *err,
                              size_t errsz) {
  memset(c, 0, sizeof *c);
  stStatus st = st_text_check(name, text, len, err, errsz);
  if (st) return st;
  hparse h = {name, text, text + len, 0, err, errsz};
  st = read_header(&h, run, c);
  if (!st) st = read_population(&h, run, c);
  return st;
}

/* ---- the files it describes ---- */

/* the last bytes of path before byte end (at most cap - 1, NUL-terminated); ST_OK, or a
 * message after the prefix "NAME:LINE: field 'F': " */
static stStatus read_tail(const char *path, long long end, char *buf, size_t cap, size_t *n,
                          char *msg, size_t msgsz) {
  FILE *f = fopen(path, "rb");
  struct stat sb;
  if (!f || fstat(fileno(f), &sb) != 0) {
    snprintf(msg, msgsz, "%s: cannot open: %s", path, strerror(errno));
    if (f) fclose(f);
    return ST_ERR_IO;
  }
  if (!S_ISREG(sb.st_mode) || (long long)sb.st_size < end) {
    snprintf(msg, msgsz, "%lld exceeds the length of %s (%lld bytes; expected the length it had "
             "at the checkpoint, which it keeps or exceeds)", end, path, (long long)sb.st_size);
    fclose(f);
    return ST_ERR_RANGE;
  }
  long long from = end > (long long)cap - 1 ? end - ((long long)cap - 1) : 0;
  *n = (size_t)(end - from);
  int bad = fseeko(f, (off_t)from, SEEK_SET) != 0 || fread(buf, 1, *n, f) != *n;
  fclose(f);
  buf[*n] = 0;
  if (bad) snprintf(msg, msgsz, "%s: cannot read", path);
  return bad ? ST_ERR_IO : ST_OK;
}

/* the start of the last line of buf[0..n), which ends with '\n' */
static const char *last_line(const char *buf, size_t n) {
  const char *p = buf + n - 1;
  while (p > buf && p[-1] != '\n') p--;
  return p;
}

/* fitness.csv ends at csv_bytes with the row of generation - 1 (its first column:
 * selftalk/fitnesscsv.h) */
static int csv_ends_right(const char *buf, size_t n, int gen, char *msg, size_t msgsz) {
  char want[24];
  snprintf(want, sizeof want, "%d,", gen);
  const char *row = n && buf[n - 1] == '\n' ? last_line(buf, n) : NULL;
  if (row && !strncmp(row, want, strlen(want))) return 1;
  snprintf(msg, msgsz, "fitness.csv does not end there with the row of generation %d (found "
           "'%.24s...')", gen, row ? row : buf + (n > 24 ? n - 24 : 0));
  return 0;
}

/* best.genome ends at best_bytes with the record ("# generation G", ..., the genotype line)
 * of generation - 1 */
static int best_ends_right(const char *buf, size_t n, int gen, char *msg, size_t msgsz) {
  const char *line = n && buf[n - 1] == '\n' ? last_line(buf, n) : NULL;
  int hex = line && *line != '\n';
  for (const char *q = line; hex && *q != '\n'; q++) hex = isxdigit((unsigned char)*q) != 0;
  long found = -1;
  for (const char *q = strstr(buf, "# generation "); q; q = strstr(q + 1, "# generation "))
    if (q == buf || q[-1] == '\n') found = strtol(q + 13, NULL, 10);
  if (hex && found == gen) return 1;
  if (!hex)
    snprintf(msg, msgsz, "best.genome does not end there with a genotype line (expected the "
             "record of generation %d to end there)", gen);
  else if (found < 0)
    snprintf(msg, msgsz, "best.genome has no '# generation' line in the %d bytes before it "
             "(expected the record of generation %d)", TAIL_WINDOW, gen);
  else
    snprintf(msg, msgsz, "best.genome's record ending there is of generation %ld (expected %d)",
             found, gen);
  return 0;
}

static stStatus check_file(const char *name, int f, const char *path, long long end, int gen,
                           char *err, size_t errsz) {
  char buf[TAIL_WINDOW + 1], msg[512];
  size_t n = 0;
  stStatus st = read_tail(path, end, buf, sizeof buf, &n, msg, sizeof msg);
  if (!st && memchr(buf, 0, n)) {
    snprintf(msg, sizeof msg, "%s has a NUL byte before byte %lld (expected text)", path, end);
    st = ST_ERR_PARSE;
  }
  if (!st && !(f == F_CSV_BYTES ? csv_ends_right(buf, n, gen, msg, sizeof msg)
                                : best_ends_right(buf, n, gen, msg, sizeof msg)))
    st = ST_ERR_RANGE;
  if (st) st__errf(err, errsz, "%s:%d: field '%s': %s", name, 2 + f, FIELD[f], msg);
  return st;
}

stStatus st__checkpoint_check_files(const char *name, const stCheckpoint *c, const char *csv_path,
                                    const char *best_path, char *err, size_t errsz) {
  stStatus st = check_file(name, F_CSV_BYTES, csv_path, c->csv_bytes, c->generation - 1, err, errsz);
  if (!st)
    st = check_file(name, F_BEST_BYTES, best_path, c->best_bytes, c->generation - 1, err, errsz);
  return st;
}

stStatus st__checkpoint_read(const char *path, const stCheckpointRun *run, const char *csv_path,
                             const char *best_path, stCheckpoint *c, char *err, size_t errsz) {
  memset(c, 0, sizeof *c);
  /* a checkpoint holds the header and the population: nothing larger is one */
  const size_t max = (size_t)run->population * (size_t)(4 * run->ngenes + 64) + 4096;
  char *text;
  size_t len;
  stStatus st = st_file_read(path, max, &text, &len, err, errsz);
  if (st) return st;
  st = st__checkpoint_parse(path, text, len, run, c, err, errsz);
  free(text);
  if (!st) st = st__checkpoint_check_files(path, c, csv_path, best_path, err, errsz);
  if (st) st__checkpoint_free(c);
  return st;
}
