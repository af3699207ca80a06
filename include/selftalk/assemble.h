/* SPDX-License-Identifier: MIT
 * libselftalk: the initial population of the integrated stage (thesis §2.4, §2.9.2; SPEC §4,
 * §10): the top genotypes of the final population of each primitive run, best first, run by
 * run, grown to the integrated network (696 genes for type A, 756 for type B). Part of
 * libselftalk-core (no simulator).
 *
 * Config keys: integrated.populations (population files, comma-separated; each item may be a
 * glob pattern, expanded in sorted order), integrated.top (10), ga.population (100),
 * network.arch (A or B), network.typeb_init_gene, run.seed. When the files give fewer than
 * ga.population genotypes the list is repeated (each copy grows its own new genes); more is
 * an error. Individual i grows its new genes from the stream (run seed, ST_RNG_GROW, 0, i). */
#ifndef SELFTALK_ASSEMBLE_H
#define SELFTALK_ASSEMBLE_H

#include "selftalk/config.h"
#include "selftalk/genome.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stAssembly {
  int nfiles;       /* population files read */
  int taken;        /* genotypes taken from them (nfiles x top) */
  int count;        /* genotypes of the population (ga.population) */
  stGenome *genome; /* count grown genotypes; genome[i] grew from taken genotype i mod taken */
} stAssembly;

/* Assembles the population. Errors name the key, the file (and line) and what was expected:
 * a pattern matching no file, a file that cannot be read, genotypes that are not 612 genes, a
 * file with fewer than `top` genotypes, more genotypes than ga.population. */
ST_API stStatus st_assemble_population(const stConfig *cfg, stAssembly *a, char *err, size_t errsz);

ST_API void st_assembly_free(stAssembly *a); /* nullable */

#ifdef __cplusplus
}
#endif

#endif
