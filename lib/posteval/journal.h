/* SPDX-License-Identifier: MIT
 * The journal of an unfinished post-evaluation (DIR/posteval.journal): the trials done so far,
 * so that `posteval ... --resume` continues a killed test to the same files. Internal. */
#ifndef ST_POSTEVAL_JOURNAL_H
#define ST_POSTEVAL_JOURNAL_H

#include <stdint.h>

#include "selftalk/posteval.h"

#define ST_POST_JOURNAL "posteval.journal"

/* What the results depend on: the configuration's keys away from their defaults, the robot
 * model read from robot.urdf and its meshes (every value the importer took; nullable: none),
 * the test, its words and condition, and every individual (run, label, rank, generation,
 * exclusion, genes). A journal of another fingerprint belongs to another test. */
uint64_t st__post_fingerprint(const stConfig *cfg, const stModel *model, stPostTest test,
                              int variant, const char *condition, const stPostIndividual *ind,
                              int nind);

/* Writes the done units (done[u] != 0) of `units` atomically to `path`. */
stStatus st__post_journal_write(const char *path, uint64_t fingerprint, long units,
                                const uint8_t *done, const stPostResult *res, char *err,
                                size_t errsz);

/* Reads `path` into done[] and res[] (units entries each, zeroed first), through the bounded
 * reader (selftalk/io.h: at most what a journal of `units` holds; NUL bytes refused, naming
 * the line and column). Refuses, naming the file and line, another fingerprint or unit count,
 * a malformed or repeated line, a result out of range, and a line no trial of `steps` steps
 * gives (an end posteval never writes, more steps than the trial has, success, step and end
 * that disagree, unstable with end full, open_jumped that disagrees with the words heard);
 * *ndone the units read. */
stStatus st__post_journal_read(const char *path, uint64_t fingerprint, long units, int steps,
                               uint8_t *done, stPostResult *res, long *ndone, char *err,
                               size_t errsz);

/* The parser of st__post_journal_read on text in memory (name: what messages call it; NUL
 * bytes refused): the fuzz target's entry point. */
stStatus st__post_journal_parse(const char *name, const char *text, size_t len,
                                uint64_t fingerprint, long units, int steps, uint8_t *done,
                                stPostResult *res, long *ndone, char *err, size_t errsz);

/* open_jumped of a trial that heard `heard` (letters r o g m): grasp or move but never open.
 * The one rule posteval's scorer and the journal's reader apply. */
int st__post_open_jumped(const char *heard);

#endif
