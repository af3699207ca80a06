/* SPDX-License-Identifier: MIT
 * libselftalk: the checkpoint of an evolution run (lib/run/evolve.c), written after every
 * generation and read by --resume; not installed.
 *
 *   # selftalk-checkpoint 1
 *   # generation 3        the next generation to evaluate (done: the generations run)
 *   # stage_idx 0         index of the current stage among the run's stages
 *   # stage_gen 3         generations done in the current stage
 *   # done 0              1: the run is complete
 *   # csv_bytes 830       length of fitness.csv at the checkpoint
 *   # best_bytes 7539     length of best.genome at the checkpoint
 *   (the population: ga.population genotypes in the genome text format)
 *
 * The reader is the one place a checkpoint is judged: every field must be there, on its line,
 * an integer in its range, consistent with the other fields, with the run's configuration and
 * with the files it describes (fitness.csv and best.genome must end, at the recorded lengths,
 * with the rows of generation - 1). A checkpoint it accepts can be resumed without losing or
 * inventing anything; any other is refused naming the file, the line and the field, before
 * anything in the run directory changes. */
#ifndef SELFTALK_CHECKPOINT_H
#define SELFTALK_CHECKPOINT_H

#include <stdio.h>

#include "selftalk/genome.h"

#define ST_CKPT_MAGIC "selftalk-checkpoint 1"

typedef struct stCheckpoint {
  int generation, stage_idx, stage_gen, done;
  long long csv_bytes, best_bytes;
  stGenomeSet pop; /* read: owned (st__checkpoint_free); not used by the writer */
} stCheckpoint;

/* What the resuming run allows (its configuration and arguments). */
typedef struct stCheckpointRun {
  int nstages;    /* stages of the run: 1, or 2 for simple-prim then main-prim */
  int population; /* ga.population: genotypes in the checkpoint */
  int ngenes;     /* genes of each genotype: 612, or the integrated network's */
  int limit;      /* generations the run may reach (--generations, ga.max_generations or
                     ga.integrated_generations) */
} stCheckpointRun;

/* Writes the header and the n genotypes of pop to f; 0, or -1 on a write error. */
int st__checkpoint_write(FILE *f, const stCheckpoint *c, const stGenome *pop, int n);

/* Parses and checks a checkpoint's text (every field and genotype; not the files). On
 * success c->pop is owned by the caller. */
stStatus st__checkpoint_parse(const char *name, const char *text, size_t len,
                              const stCheckpointRun *run, stCheckpoint *c, char *err,
                              size_t errsz);

/* Checks that csv_path and best_path are at least as long as the checkpoint says and end,
 * at those lengths, with the records of generation c->generation - 1. */
stStatus st__checkpoint_check_files(const char *name, const stCheckpoint *c, const char *csv_path,
                                    const char *best_path, char *err, size_t errsz);

/* Reads path (bounded by the size a checkpoint of this run can have), parses it and checks
 * the files; on failure nothing is left to free. */
stStatus st__checkpoint_read(const char *path, const stCheckpointRun *run, const char *csv_path,
                             const char *best_path, stCheckpoint *c, char *err, size_t errsz);

void st__checkpoint_free(stCheckpoint *c);

#endif
