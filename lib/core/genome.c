/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/internal.h"
#include "selftalk/genome.h"
#include "selftalk/io.h"
#include "core/readers.h"

const char *st_arch_name(stNetArch arch) {
  switch (arch) {
    case ST_ARCH_BASE: return "base";
    case ST_ARCH_A: return "A";
    case ST_ARCH_B: return "B";
    default: return "?";
  }
}

int st_arch_parse(const char *name) {
  ST_ASSERT(name);
  if (!strcasecmp(name, "base")) return ST_ARCH_BASE;
  if (!strcasecmp(name, "A")) return ST_ARCH_A;
  if (!strcasecmp(name, "B")) return ST_ARCH_B;
  return -1;
}

int st_arch_ngenes(stNetArch arch) {
  static const int n[ST_ARCH_COUNT] = {ST_GENES_BASE, ST_GENES_A, ST_GENES_B};
  return (int)arch >= 0 && arch < ST_ARCH_COUNT ? n[arch] : 0;
}

double st_gene_value(uint16_t u) { return -1.0 + 2.0 * (double)u / 65535.0; }

int st_genome_bit(const stGenome *g, int b) {
  ST_ASSERT(g && b >= 0 && b < 16 * g->ngenes);
  return (g->gene[b >> 4] >> (15 - (b & 15))) & 1;
}

void st_genome_flip_bit(stGenome *g, int b) {
  ST_ASSERT(g && b >= 0 && b < 16 * g->ngenes);
  g->gene[b >> 4] ^= (uint16_t)(1u << (15 - (b & 15)));
}

void st_genome_random(stGenome *g, int ngenes, stRng *rng) {
  ST_ASSERT(g && rng);
  ST_ASSERT(ngenes >= 0 && ngenes <= ST_GENOME_MAX_GENES);
  memset(g, 0, sizeof *g);
  g->ngenes = ngenes;
  /* four genes per draw: every bit is an independent fair coin */
  for (int i = 0; i < ngenes; i += 4) {
    uint64_t r = st_rng_u64(rng);
    for (int k = 0; k < 4 && i + k < ngenes; k++) g->gene[i + k] = (uint16_t)(r >> (16 * k));
  }
}

stStatus st_genome_grow(const stGenome *in, stNetArch arch, uint16_t typeb_init, stRng *rng,
                        stGenome *out, char *err, size_t errsz) {
  ST_ASSERT(in && rng && out);
  if (in->ngenes != ST_GENES_BASE) {
    st__errf(err, errsz, "genotype has %d genes (expected %d to grow)", in->ngenes, ST_GENES_BASE);
    return ST_ERR_ARG;
  }
  if (arch != ST_ARCH_A && arch != ST_ARCH_B) {
    st__errf(err, errsz, "cannot grow to architecture '%s' (expected A or B)", st_arch_name(arch));
    return ST_ERR_ARG;
  }
  stGenome fresh;
  st_genome_random(&fresh, ST_GENES_A - ST_GENES_BASE, rng);
  stGenome g = *in;
  g.ngenes = st_arch_ngenes(arch);
  memcpy(g.gene + ST_GENES_BASE, fresh.gene, sizeof(uint16_t) * (ST_GENES_A - ST_GENES_BASE));
  /* type B: hidden-linguistic -> hidden starts near zero so it cannot disturb the primitives */
  for (int i = ST_GENES_A; i < g.ngenes; i++) g.gene[i] = typeb_init;
  *out = g;
  return ST_OK;
}

void st_genome_mask_new_genes(uint8_t *mask, int ngenes) {
  ST_ASSERT(mask && ngenes >= 0);
  for (int i = 0; i < ST_GENOME_MAX_GENES; i++) mask[i] = (uint8_t)(i >= ST_GENES_BASE && i < ngenes);
}

/* ---- text format ---- */

static int hexval(int c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10; /* tolerated on read; written lower-case */
  return -1;
}

void st_genome_set_free(stGenomeSet *set) {
  if (!set) return;
  free(set->genome);
  free(set->fitness);
  free(set->generation);
  memset(set, 0, sizeof *set);
}

static int set_push(stGenomeSet *s, int *cap) {
  if (s->count < *cap) return 0;
  int nc = *cap ? *cap * 2 : 16;
  stGenome *g = realloc(s->genome, sizeof *g * (size_t)nc);
  if (!g) return -1;
  s->genome = g;
  double *f = realloc(s->fitness, sizeof *f * (size_t)nc);
  if (!f) return -1;
  s->fitness = f;
  int *gen = realloc(s->generation, sizeof *gen * (size_t)nc);
  if (!gen) return -1;
  s->generation = gen;
  *cap = nc;
  return 0;
}

/* the genome text parser: one line at a time, no NUL-terminated copy of the text needed */
typedef struct gparse {
  const char *name;
  int lineno, expect, declared, pend_gen, cap;
  size_t col0; /* columns before the trimmed line (messages count from the line's start) */
  double pend_fit;
  stGenomeSet *set;
  char *err;
  size_t errsz;
} gparse;

/* the next line of [*p, end) without surrounding white space (*col0 columns dropped before
 * it); 0 at the end of the text */
static int next_line(const char **p, const char *end, const char **s, size_t *n, size_t *col0) {
  const char *line;
  size_t len;
  if (!st__text_line(p, end, &line, &len, NULL)) return 0;
  const char *b = line, *e = line + len;
  while (b < e && isspace((unsigned char)*b)) b++;
  while (e > b && isspace((unsigned char)e[-1])) e--;
  *s = b;
  *n = (size_t)(e - b);
  *col0 = (size_t)(b - line);
  return 1;
}

/* the value of a "# key value" line as a C string; -1 if it is too long to be a number */
static int meta_value(const char *v, size_t n, char *buf, size_t bufsz) {
  while (n && isspace((unsigned char)*v)) v++, n--;
  if (n >= bufsz) return -1;
  memcpy(buf, v, n);
  buf[n] = 0;
  return 0;
}

/* "# genes N", "# fitness F", "# generation G"; any other '#' line is a comment */
static stStatus parse_meta(gparse *g, const char *s, size_t n) {
  size_t k = 1;
  while (k < n && isspace((unsigned char)s[k])) k++;
  const char *key = s + k;
  size_t klen = 0;
  while (k + klen < n && !isspace((unsigned char)key[klen])) klen++;
  char val[64];
  int bad = meta_value(key + klen, n - k - klen, val, sizeof val);
  if (klen == 5 && !memcmp(key, "genes", 5)) {
    int v;
    if (bad || st__parse_int(val, &v) || (v != ST_GENES_BASE && v != ST_GENES_A && v != ST_GENES_B)) {
      st__errf(g->err, g->errsz, "%s:%d: '# genes %.20s': bad gene count (expected 612, 696 or 756)",
               g->name, g->lineno, bad ? "..." : val);
      return ST_ERR_PARSE;
    }
    g->declared = v;
  } else if (klen == 7 && !memcmp(key, "fitness", 7)) {
    if (bad || st__parse_double(val, &g->pend_fit)) {
      st__errf(g->err, g->errsz, "%s:%d: '# fitness %.20s': not a number (expected a finite number)",
               g->name, g->lineno, bad ? "..." : val);
      return ST_ERR_PARSE;
    }
  } else if (klen == 10 && !memcmp(key, "generation", 10)) {
    if (bad || st__parse_int(val, &g->pend_gen) || g->pend_gen < 0) {
      st__errf(g->err, g->errsz, "%s:%d: '# generation %.20s': not a generation (expected an "
               "integer >= 0)", g->name, g->lineno, bad ? "..." : val);
      return ST_ERR_PARSE;
    }
  }
  return ST_OK;
}

/* a genotype line's length and characters */
static stStatus check_hex(const gparse *g, const char *s, size_t n, int *ngenes) {
  for (size_t c = 0; c < n; c++)
    if (hexval((unsigned char)s[c]) < 0) {
      st__errf(g->err, g->errsz,
               "%s:%d: genotype: non-hex character '%c' at column %zu (expected 4 lower-case hex "
               "digits per gene)",
               g->name, g->lineno, isprint((unsigned char)s[c]) ? s[c] : '?', g->col0 + c + 1);
      return ST_ERR_PARSE;
    }
  if (n % 4) {
    st__errf(g->err, g->errsz, "%s:%d: genotype: %zu hex digits is not a whole number of genes "
             "(truncated? expected 4 hex digits per gene)", g->name, g->lineno, n);
    return ST_ERR_PARSE;
  }
  const size_t ng = n / 4;
  const int want = g->expect > 0 ? g->expect : g->declared;
  if (want ? ng != (size_t)want : (ng != ST_GENES_BASE && ng != ST_GENES_A && ng != ST_GENES_B)) {
    if (want)
      st__errf(g->err, g->errsz, "%s:%d: genotype: %zu genes (expected %d)", g->name, g->lineno,
               ng, want);
    else
      st__errf(g->err, g->errsz, "%s:%d: genotype: %zu genes (expected 612, 696 or 756)", g->name,
               g->lineno, ng);
    return ST_ERR_PARSE;
  }
  *ngenes = (int)ng;
  return ST_OK;
}

static stStatus parse_genotype(gparse *g, const char *s, size_t n) {
  int ng;
  stStatus st = check_hex(g, s, n, &ng);
  if (st) return st;
  if (set_push(g->set, &g->cap)) {
    st__errf(g->err, g->errsz, "%s: out of memory", g->name);
    return ST_ERR_NOMEM;
  }
  stGenome *gen = &g->set->genome[g->set->count];
  memset(gen, 0, sizeof *gen);
  gen->ngenes = ng;
  for (int i = 0; i < ng; i++) {
    const char *q = s + 4 * i;
    gen->gene[i] = (uint16_t)((hexval(q[0]) << 12) | (hexval(q[1]) << 8) | (hexval(q[2]) << 4) |
                              hexval(q[3]));
  }
  g->set->fitness[g->set->count] = g->pend_fit;
  g->set->generation[g->set->count] = g->pend_gen;
  g->set->count++;
  g->pend_fit = NAN;
  g->pend_gen = -1;
  return ST_OK;
}

stStatus st__genome_set_parse(const char *name, const char *text, size_t len, int first_line,
                              int expect_genes, stGenomeSet *set, char *err, size_t errsz) {
  memset(set, 0, sizeof *set);
  stStatus st = st_text_check(name, text, len, err, errsz);
  if (st) return st;
  gparse g = {name, first_line - 1, expect_genes, 0, -1, 0, 0, NAN, set, err, errsz};
  const char *p = text, *s;
  size_t n;
  while (!st && next_line(&p, text + len, &s, &n, &g.col0)) {
    g.lineno++;
    if (n) st = *s == '#' ? parse_meta(&g, s, n) : parse_genotype(&g, s, n);
  }
  if (!st && set->count == 0) {
    st__errf(err, errsz, "%s: no genotype in file (expected at least one line of hex genes)", name);
    st = ST_ERR_PARSE;
  }
  if (st) st_genome_set_free(set);
  return st;
}

stStatus st_genome_set_read(const char *path, int expect_genes, stGenomeSet *set, char *err,
                            size_t errsz) {
  ST_ASSERT(path && set);
  memset(set, 0, sizeof *set);
  char *text;
  size_t len;
  stStatus st = st_file_read(path, ST_FILE_MAX, &text, &len, err, errsz);
  if (st) return st;
  st = st__genome_set_parse(path, text, len, 1, expect_genes, set, err, errsz);
  free(text);
  return st;
}

int st_genome_write_line(FILE *f, const stGenome *g) {
  ST_ASSERT(f && g);
  static const char hex[] = "0123456789abcdef";
  char buf[4 * ST_GENOME_MAX_GENES + 2];
  for (int i = 0; i < g->ngenes; i++) {
    unsigned u = g->gene[i];
    buf[4 * i] = hex[(u >> 12) & 15];
    buf[4 * i + 1] = hex[(u >> 8) & 15];
    buf[4 * i + 2] = hex[(u >> 4) & 15];
    buf[4 * i + 3] = hex[u & 15];
  }
  buf[4 * g->ngenes] = '\n';
  size_t n = (size_t)(4 * g->ngenes + 1);
  return fwrite(buf, 1, n, f) == n ? 0 : -1;
}

int st_genome_write(FILE *f, const stGenome *g, int generation, double fitness) {
  ST_ASSERT(f && g);
  if (fprintf(f, "# genes %d\n", g->ngenes) < 0) return -1;
  if (generation >= 0 && fprintf(f, "# generation %d\n", generation) < 0) return -1;
  if (isfinite(fitness) && fprintf(f, "# fitness %.17g\n", fitness) < 0) return -1;
  return st_genome_write_line(f, g);
}

stStatus st_genome_set_save(const char *path, const stGenome *g, int count, const double *fitness,
                            const int *generation, char *err, size_t errsz) {
  ST_ASSERT(path && count >= 0 && (g || count == 0));
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, path, err, errsz);
  if (st) return st;
  fprintf(af.f, "# selftalk genome file, %d genotypes\n", count);
  for (int i = 0; i < count; i++) {
    if (st_genome_write(af.f, &g[i], generation ? generation[i] : -1,
                        fitness ? fitness[i] : NAN)) {
      st_atomic_abort(&af);
      st__errf(err, errsz, "%s: write error", path);
      return ST_ERR_IO;
    }
  }
  return st_atomic_commit(&af, err, errsz);
}
