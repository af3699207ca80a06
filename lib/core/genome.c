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

const char *st_arch_name(stNetArch arch) {
  switch (arch) {
    case ST_ARCH_BASE: return "base";
    case ST_ARCH_A: return "A";
    case ST_ARCH_B: return "B";
    default: return "?";
  }
}

int st_arch_parse(const char *name) {
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

int st_genome_bit(const stGenome *g, int b) { return (g->gene[b >> 4] >> (15 - (b & 15))) & 1; }

void st_genome_flip_bit(stGenome *g, int b) {
  g->gene[b >> 4] ^= (uint16_t)(1u << (15 - (b & 15)));
}

void st_genome_random(stGenome *g, int ngenes, stRng *rng) {
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

stStatus st_genome_set_read(const char *path, int expect_genes, stGenomeSet *set, char *err,
                            size_t errsz) {
  memset(set, 0, sizeof *set);
  FILE *f = fopen(path, "r");
  if (!f) {
    st__errf(err, errsz, "%s: cannot open: %s", path, strerror(errno));
    return ST_ERR_IO;
  }
  stStatus st = ST_OK;
  int cap = 0, lineno = 0, declared = 0, pend_gen = -1;
  double pend_fit = NAN;
  char *line = NULL;
  size_t linecap = 0;
  ssize_t len;
  while ((len = getline(&line, &linecap, f)) >= 0) {
    lineno++;
    while (len > 0 && isspace((unsigned char)line[len - 1])) line[--len] = 0;
    char *p = line;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) continue;
    if (*p == '#') {
      char key[32];
      char val[64];
      if (sscanf(p + 1, " %31s %63s", key, val) == 2) {
        double v;
        if (!strcmp(key, "genes")) {
          int n;
          if (st__parse_int(val, &n) || (n != ST_GENES_BASE && n != ST_GENES_A && n != ST_GENES_B)) {
            st__errf(err, errsz, "%s:%d: '# genes %s': bad gene count (expected 612, 696 or 756)",
                     path, lineno, val);
            st = ST_ERR_PARSE;
            break;
          }
          declared = n;
        } else if (!strcmp(key, "fitness") && !st__parse_double(val, &v)) {
          pend_fit = v;
        } else if (!strcmp(key, "generation") && !st__parse_int(val, &pend_gen)) {
        }
      }
      continue;
    }
    size_t n = strlen(p);
    for (size_t c = 0; c < n; c++) {
      if (hexval((unsigned char)p[c]) < 0) {
        st__errf(err, errsz,
                 "%s:%d: genotype: non-hex character '%c' at column %zu (expected 4 lower-case "
                 "hex digits per gene)",
                 path, lineno, isprint((unsigned char)p[c]) ? p[c] : '?', c + 1 + (size_t)(p - line));
        st = ST_ERR_PARSE;
        break;
      }
    }
    if (st) break;
    if (n % 4) {
      st__errf(err, errsz,
               "%s:%d: genotype: %zu hex digits is not a whole number of genes (truncated? "
               "expected 4 hex digits per gene)",
               path, lineno, n);
      st = ST_ERR_PARSE;
      break;
    }
    int ng = (int)(n / 4);
    int want = expect_genes > 0 ? expect_genes : declared;
    if (want ? ng != want : (ng != ST_GENES_BASE && ng != ST_GENES_A && ng != ST_GENES_B)) {
      if (want)
        st__errf(err, errsz, "%s:%d: genotype: %d genes (expected %d)", path, lineno, ng, want);
      else
        st__errf(err, errsz, "%s:%d: genotype: %d genes (expected 612, 696 or 756)", path, lineno,
                 ng);
      st = ST_ERR_PARSE;
      break;
    }
    if (set_push(set, &cap)) {
      st__errf(err, errsz, "%s: out of memory", path);
      st = ST_ERR_NOMEM;
      break;
    }
    stGenome *g = &set->genome[set->count];
    memset(g, 0, sizeof *g);
    g->ngenes = ng;
    for (int i = 0; i < ng; i++) {
      const char *q = p + 4 * i;
      g->gene[i] = (uint16_t)((hexval(q[0]) << 12) | (hexval(q[1]) << 8) | (hexval(q[2]) << 4) |
                              hexval(q[3]));
    }
    set->fitness[set->count] = pend_fit;
    set->generation[set->count] = pend_gen;
    set->count++;
    pend_fit = NAN;
    pend_gen = -1;
  }
  free(line);
  if (!st && ferror(f)) {
    st__errf(err, errsz, "%s: read error", path);
    st = ST_ERR_IO;
  }
  fclose(f);
  if (!st && set->count == 0) {
    st__errf(err, errsz, "%s: no genotype in file (expected at least one line of hex genes)", path);
    st = ST_ERR_PARSE;
  }
  if (st) st_genome_set_free(set);
  return st;
}

int st_genome_write_line(FILE *f, const stGenome *g) {
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
  if (fprintf(f, "# genes %d\n", g->ngenes) < 0) return -1;
  if (generation >= 0 && fprintf(f, "# generation %d\n", generation) < 0) return -1;
  if (isfinite(fitness) && fprintf(f, "# fitness %.17g\n", fitness) < 0) return -1;
  return st_genome_write_line(f, g);
}

stStatus st_genome_set_save(const char *path, const stGenome *g, int count, const double *fitness,
                            const int *generation, char *err, size_t errsz) {
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
