/* SPDX-License-Identifier: MIT
 * evolve across MPI ranks (issue 16; docs/PROTOCOL.md, "Evaluation across processes"):
 *
 *   mpirun -n N ./apps/evolve CONFIG ...
 *
 * Rank 0 parses the arguments, runs the GA, writes every file and the checkpoint; ranks
 * 1..N-1 evaluate individuals (each on its own OpenMP threads), handed out one at a time as
 * evaluation slots free up. The files are bit-identical to a --threads 1 run for any N.
 * Built with MPI when the Makefile finds mpicc (ST_WITH_MPI); without it, or when this
 * process was not started by an MPI launcher, every function below does nothing and evolve
 * runs exactly as it always did. */
#ifndef SELFTALK_EVOLVE_MPI_H
#define SELFTALK_EVOLVE_MPI_H

#include <stdio.h>

#include "selftalk/evolve.h"

typedef enum appMpiRole {
  APP_MPI_NONE = 0,    /* no MPI: a plain process */
  APP_MPI_COORDINATOR, /* rank 0 of an MPI job (the only rank of a 1-rank job) */
  APP_MPI_WORKER       /* any other rank */
} appMpiRole;

/* 1 when this evolve was built with MPI. */
int app_mpi_built(void);

/* Joins the MPI job when an MPI launcher started this process: MPI_Init, and on rank 0 the
 * handlers that release the other ranks at exit and explain an abort by the launcher. */
appMpiRole app_mpi_start(int *argc, char ***argv);

/* A worker rank's life: serves rank 0 until it says stop. Returns the exit status. */
int app_mpi_serve(void);

/* Rank 0: the evaluator that spreads tasks over the other ranks; NULL when there are none
 * (a plain process or a 1-rank job: evolve evaluates on its own threads). threads: evolve's
 * --threads (0: not given; each rank then uses run.threads or its cores); out_dir for the
 * messages; progress (nullable) gets the set-up line and the closing statistics. */
const stEvolveEvaluator *app_mpi_evaluator(int threads, const char *out_dir, FILE *progress);

#endif
