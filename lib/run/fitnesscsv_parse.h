/* SPDX-License-Identifier: MIT
 * libselftalk: the in-memory entry point of the reader of a generation's trials in fitness.csv
 * (selftalk/fitnesscsv.h: st_fitness_csv_successes, the exclusion rule's reader), for the unit
 * tests and tests/fuzz/fuzz_fitness.c; not installed. */
#ifndef SELFTALK_FITNESSCSV_PARSE_H
#define SELFTALK_FITNESSCSV_PARSE_H

#include <stdint.h>

#include "selftalk/base.h"

/* st_fitness_csv_successes on a text in memory (name: what messages call it; NUL bytes
 * refused as the file's reader refuses them). */
stStatus st__fitness_csv_successes_parse(const char *name, const char *text, size_t len,
                                         int generation, uint8_t *success, int max, int *n,
                                         char *err, size_t errsz);

#endif
