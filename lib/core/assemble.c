/* SPDX-License-Identifier: MIT
 * The integrated stage's initial population (selftalk/assemble.h). */
#define _POSIX_C_SOURCE 200809L
#include "selftalk/assemble.h"

#include <glob.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"

#define MAX_FILES 1024

typedef struct fileList {
  int n;
  char *path[MAX_FILES];
} fileList;

static void list_free(fileList *l) {
  for (int i = 0; i < l->n; i++) free(l->path[i]);
  l->n = 0;
}

static stStatus list_add(fileList *l, const char *path, char *err, size_t errsz) {
  if (l->n == MAX_FILES)
    return st__errf(err, errsz, "key 'integrated.populations': more than %d files", MAX_FILES),
           ST_ERR_RANGE;
  const size_t n = strlen(path) + 1;
  if (!(l->path[l->n] = malloc(n))) return ST_ERR_NOMEM;
  memcpy(l->path[l->n++], path, n);
  return ST_OK;
}

/* one item of the list: a literal path, or a glob pattern that must match something */
static stStatus expand_item(fileList *l, const char *item, char *err, size_t errsz) {
  if (!strpbrk(item, "*?[")) return list_add(l, item, err, errsz);
  glob_t g;
  memset(&g, 0, sizeof g);
  if (glob(item, 0, NULL, &g) != 0 || g.gl_pathc == 0) {
    globfree(&g);
    return st__errf(err, errsz, "key 'integrated.populations': '%s' matches no file (expected "
                    "primitive-stage population files)", item), ST_ERR_IO;
  }
  stStatus st = ST_OK;
  for (size_t i = 0; i < g.gl_pathc && !st; i++) st = list_add(l, g.gl_pathv[i], err, errsz);
  globfree(&g);
  return st;
}

/* the comma-separated items of integrated.populations, patterns expanded */
static stStatus expand_list(const char *spec, fileList *l, char *err, size_t errsz) {
  char item[ST_CONFIG_STR_MAX];
  const int n = st__list_count(spec);
  for (int i = 0; i < (n ? n : 1); i++) { /* "": one empty item */
    const char *at = spec;
    size_t len = 0;
    if (n) st__list_item(spec, i, &at, &len);
    if (len == 0 || len >= sizeof item)
      return st__errf(err, errsz, "key 'integrated.populations': '%s': an empty or overlong item "
                      "(expected FILE[,FILE]...)", spec), ST_ERR_PARSE;
    memcpy(item, at, len);
    item[len] = 0;
    stStatus st = expand_item(l, item, err, errsz);
    if (st) return st;
  }
  return ST_OK;
}

/* the first `top` genotypes of every file, file by file */
static stStatus take_tops(const fileList *l, int top, stGenome *taken, char *err, size_t errsz) {
  for (int f = 0; f < l->n; f++) {
    stGenomeSet set;
    stStatus st = st_genome_set_read(l->path[f], ST_GENES_BASE, &set, err, errsz);
    if (st) {
      st__err_key(err, errsz, "integrated.populations");
      return st;
    }
    if (set.count < top) {
      st__errf(err, errsz, "key 'integrated.populations': %s has %d genotypes (expected at least "
               "integrated.top = %d)", l->path[f], set.count, top);
      st_genome_set_free(&set);
      return ST_ERR_ARG;
    }
    memcpy(taken + (size_t)f * (size_t)top, set.genome, sizeof *taken * (size_t)top);
    st_genome_set_free(&set);
  }
  return ST_OK;
}

/* every individual grows its own new genes from (seed, grow, individual) */
static stStatus grow_all(const stConfig *c, const stGenome *taken, int ntaken, stAssembly *a,
                         char *err, size_t errsz) {
  for (int i = 0; i < a->count; i++) {
    stRng rng = st_rng_keyed(st_config_rng_seed(c), ST_RNG_GROW, 0, (uint64_t)i, 0);
    stStatus st = st_genome_grow(&taken[i % ntaken], (stNetArch)c->network_arch,
                                 (uint16_t)c->network_typeb_init_gene, &rng, &a->genome[i], err,
                                 errsz);
    if (st) return st;
  }
  return ST_OK;
}

stStatus st_assemble_population(const stConfig *c, stAssembly *a, char *err, size_t errsz) {
  ST_ASSERT(c && a);
  memset(a, 0, sizeof *a);
  fileList l;
  l.n = 0;
  stStatus st = expand_list(c->integrated_populations, &l, err, errsz);
  const int top = c->integrated_top;
  if (!st && (long)l.n * top > c->ga_population) {
    st__errf(err, errsz, "key 'integrated.populations': %d files x integrated.top %d = %ld "
             "genotypes (expected at most ga.population = %d)", l.n, top, (long)l.n * top,
             c->ga_population);
    st = ST_ERR_RANGE;
  }
  stGenome *taken = st ? NULL : malloc(sizeof *taken * (size_t)(l.n * top));
  a->genome = st ? NULL : malloc(sizeof *a->genome * (size_t)c->ga_population);
  if (!st && (!taken || !a->genome)) {
    st__errf(err, errsz, "assembly: out of memory");
    st = ST_ERR_NOMEM;
  }
  if (!st) st = take_tops(&l, top, taken, err, errsz);
  if (!st) {
    a->nfiles = l.n;
    a->taken = l.n * top;
    a->count = c->ga_population;
    st = grow_all(c, taken, a->taken, a, err, errsz);
  }
  free(taken);
  list_free(&l);
  if (st) st_assembly_free(a);
  return st;
}

void st_assembly_free(stAssembly *a) {
  if (!a) return;
  free(a->genome);
  memset(a, 0, sizeof *a);
}
