/* SPDX-License-Identifier: MIT
 * libselftalk: the experiment configuration.
 *
 * Configs are the experiment: every number of the protocol is a key of ST_CONFIG_KEYS below,
 * with the thesis's value as default. The one table drives the struct, the defaults, the INI
 * parser, validation, st_config_write() (the resolved config saved beside every run) and the
 * key reference (st_config_help()).
 *
 * INI files: "[section]" lines and "key = value" lines; '#' and ';' start comments. Errors
 * read "FILE:LINE: key 'section.key': problem (expected ...)". Owns nothing on the heap. */
#ifndef SELFTALK_CONFIG_H
#define SELFTALK_CONFIG_H

#include <stdio.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_CONFIG_STR_MAX 256

/* The key table. Each row: section, key, default, then
 *   INT / REAL: min, max, help     BOOL: help
 *   ENUM: choices "a|b|c" (the field holds the index), help     STR: help */
#define ST_CONFIG_KEYS(INT, REAL, BOOL, ENUM, STR)                                               \
  INT(run, seed, 1, 0, 2147483647, "run seed; keys every random stream (GA, trial offsets)")     \
  INT(run, threads, 0, 0, 1024, "evaluation threads; 0 = one per core (results do not depend on it)") \
  ENUM(network, arch, 0, "base|A|B", "network architecture: base (primitive stages), A (self talk), B (hidden linguistic memory)") \
  REAL(network, lambda, 1.5, 0.01, 100.0, "sigmoid slope: sigma(x) = 1/(1+exp(-lambda x)) (thesis eq. 2.1)") \
  REAL(network, gamma_a, 1.0, 0.0, 1000.0, "gain of the type A linguistic output units (eq. 2.13)") \
  REAL(network, gamma_b, 10.0, 0.0, 1000.0, "gain of the type B hidden-linguistic units (eq. 2.13)") \
  REAL(network, focus_scale, 20.0, 0.0, 1000.0, "focus-vector input = (focus point - palm centre) in metres times this (thesis 2.3.5)") \
  REAL(network, focus_threshold, 0.5, 0.0, 1.0, "focus output below this selects the object, else the target (thesis 2.3.2)") \
  REAL(network, linguistic_input, 10.0, 0.0, 1000.0, "value of the linguistic input of the word being given (thesis 2.3.6)") \
  REAL(network, secondary_input, 10.0, 0.0, 1000.0, "value of the secondary input move-object-to-target while given (thesis 2.9.1)") \
  INT(network, typeb_init_gene, 32768, 0, 65535, "initial gene of the type B hidden-linguistic -> hidden block (32768: v = 1/65535, near zero)") \
  INT(ga, population, 100, 2, 100000, "genotypes per generation (thesis 2.4)")                   \
  INT(ga, elites, 10, 0, 100000, "best genotypes copied unchanged into the next generation")     \
  INT(ga, parents, 20, 1, 100000, "best genotypes that breed; children are assigned round-robin") \
  REAL(ga, mutation_rate, 0.005, 0.0, 1.0, "bit-flip probability per mutable bit, primitive stages") \
  REAL(ga, mutation_rate_integrated, 0.04, 0.0, 1.0, "bit-flip probability per mutable (new) bit, integrated stage") \
  INT(ga, success_genotypes, 5, 1, 100000, "primitive stages end when this many genotypes succeed in every trial") \
  INT(ga, max_generations, 1500, 1, 10000000, "primitive stages (both together) stop after this many generations") \
  INT(ga, integrated_generations, 100, 1, 10000000, "generations of the integrated stage")

/* The configuration: one field per key, named section_key. */
#define ST__CFG_INT(s, k, d, lo, hi, h) int s##_##k;
#define ST__CFG_REAL(s, k, d, lo, hi, h) double s##_##k;
#define ST__CFG_BOOL(s, k, d, h) int s##_##k;
#define ST__CFG_ENUM(s, k, d, ch, h) int s##_##k;
#define ST__CFG_STR(s, k, d, h) char s##_##k[ST_CONFIG_STR_MAX];
typedef struct stConfig {
  ST_CONFIG_KEYS(ST__CFG_INT, ST__CFG_REAL, ST__CFG_BOOL, ST__CFG_ENUM, ST__CFG_STR)
} stConfig;
#undef ST__CFG_INT
#undef ST__CFG_REAL
#undef ST__CFG_BOOL
#undef ST__CFG_ENUM
#undef ST__CFG_STR

typedef enum stConfigType {
  ST_CFG_INT,
  ST_CFG_REAL,
  ST_CFG_BOOL,
  ST_CFG_ENUM,
  ST_CFG_STR,
  ST_CFG_TYPE_COUNT
} stConfigType;

/* Description of one key (read-only; from st_config_key()). */
typedef struct stConfigKey {
  const char *section;
  const char *name;
  stConfigType type;
  double min, max;     /* INT, REAL */
  double def_num;      /* INT, REAL, BOOL, ENUM (index) */
  const char *def_str; /* STR */
  const char *choices; /* ENUM: "a|b|c" */
  const char *help;
  size_t offset;       /* of the field in stConfig */
} stConfigKey;

/* Number of keys and key i (0 <= i < st_config_nkeys()). */
int st_config_nkeys(void);
const stConfigKey *st_config_key(int i);

/* Index of "section.key" or -1. */
int st_config_find(const char *section, const char *name);

/* Fills every field with its default (the thesis protocol). */
void st_config_default(stConfig *cfg);

/* Reads an INI file over cfg (keys the file does not name keep their value: call
 * st_config_default first). Rejects a missing file, unknown sections and keys, duplicate keys,
 * malformed or out-of-range values and inconsistent combinations, naming file and line. */
stStatus st_config_load(const char *path, stConfig *cfg, char *err, size_t errsz);

/* Applies one "section.key=value" override (the --set of every app). */
stStatus st_config_set(stConfig *cfg, const char *assignment, char *err, size_t errsz);

/* Checks ranges and cross-key consistency of a config built in code. */
stStatus st_config_validate(const stConfig *cfg, char *err, size_t errsz);

/* Writes the config as a loadable INI file, every key with its help as a comment. */
int st_config_write(FILE *f, const stConfig *cfg);

/* Writes the key reference (section, key, type, default, range, help). */
void st_config_help(FILE *f);

/* Choice name of an ENUM key's value, e.g. st_config_enum_name("network", "arch", 1) = "A". */
const char *st_config_enum_name(const char *section, const char *name, int value);

#ifdef __cplusplus
}
#endif

#endif
