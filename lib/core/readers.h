/* SPDX-License-Identifier: MIT
 * libselftalk: the readers' in-memory entry points; not installed. Each file reader is
 * st_file_read (selftalk/io.h: bounded) followed by one of these, so the unit tests and the
 * fuzz targets (tests/fuzz/) reach exactly the code that reads files. `name` is what messages
 * call the text (the file's path); `text` need not be NUL-terminated, and a NUL byte in it is
 * refused (st_text_check). The URDF importer's entry point, st__model_parse_urdf, is the model
 * layer's: lib/model/model_internal.h. */
#ifndef SELFTALK_READERS_H
#define SELFTALK_READERS_H

#include <stddef.h>

#include "selftalk/config.h"
#include "selftalk/csv.h"
#include "selftalk/genome.h"

#ifdef __cplusplus
extern "C" {
#endif

/* st_config_load's parser: INI text over cfg. */
stStatus st__config_parse(const char *name, const char *text, size_t len, stConfig *cfg,
                          char *err, size_t errsz);

/* st_genome_set_read's parser; first_line is the file line of text's first line (messages). */
stStatus st__genome_set_parse(const char *name, const char *text, size_t len, int first_line,
                              int expect_genes, stGenomeSet *set, char *err, size_t errsz);

/* st_csv_read's parser: the rows of a results file (ctx: the schema's check's). */
stStatus st__csv_parse(const char *name, const char *text, size_t len, const stCsvSchema *schema,
                       const void *ctx, stCsvRows *rows, char *err, size_t errsz);

/* st_numbers_read's parser: *x (freed with free()) and *n >= 1 on success, NULL and 0 else. */
stStatus st__numbers_parse(const char *name, const char *text, size_t len, double **x, int *n,
                           char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
