/* SPDX-License-Identifier: MIT
 * The journal of an unfinished post-evaluation (DIR/posteval.journal): the trials done so far,
 * so that `posteval ... --resume` continues a killed test to the same files. Internal. */
#ifndef ST_POSTEVAL_JOURNAL_H
#define ST_POSTEVAL_JOURNAL_H

#include <stdint.h>

#include "selftalk/posteval.h"

#define ST_POST_JOURNAL "posteval.journal"

/* What the results depend on: the resolved configuration, the test, its words and condition,
 * and every individual (run, label, rank, generation, exclusion, genes). A journal of another
 * fingerprint belongs to another test. */
uint64_t st__post_fingerprint(const stConfig *cfg, stPostTest test, int variant,
                              const char *condition, const stPostIndividual *ind, int nind);

/* Writes the done units (done[u] != 0) of `units` atomically to `path`. */
stStatus st__post_journal_write(const char *path, uint64_t fingerprint, long units,
                                const uint8_t *done, const stPostResult *res, char *err,
                                size_t errsz);

/* Reads `path` into done[] and res[] (units entries each, zeroed first), through the bounded
 * reader (selftalk/io.h: at most what a journal of `units` holds; NUL bytes refused, naming
 * the line and column). Refuses, naming the file and line, another fingerprint or unit count,
 * a malformed or repeated line, and a result out of range; *ndone the units read. */
stStatus st__post_journal_read(const char *path, uint64_t fingerprint, long units, uint8_t *done,
                               stPostResult *res, long *ndone, char *err, size_t errsz);

#endif
