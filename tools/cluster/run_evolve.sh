#!/usr/bin/env bash
# Runs (or continues) one evolution run inside a SLURM allocation; the sbatch scripts beside
# this file call it. With one task it runs apps/evolve on the task's cores (--threads
# $SLURM_CPUS_PER_TASK); with several, under mpirun: rank 0 runs the GA and writes the files,
# the others evaluate (README, "Running on a cluster"). Always with --resume: a requeued or
# resubmitted job continues the run, a finished run only says so.
#
#   run_evolve.sh CONFIG SEED OUT
#
# Environment: EVOLVE (default ./apps/evolve), EVOLVE_ARGS (more arguments, e.g.
# "--set ga.max_generations=500"), MPIRUN (default mpirun), MPIRUN_ARGS (more mpirun
# arguments), DRY_RUN=1 (print the command instead of running it).
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: run_evolve.sh CONFIG SEED OUT" >&2
  exit 2
fi
config=$1 seed=$2 out=$3
threads=${SLURM_CPUS_PER_TASK:-1}
ntasks=${SLURM_NTASKS:-1}
read -r -a extra <<< "${EVOLVE_ARGS:-}"
cmd=("${EVOLVE:-./apps/evolve}" "$config" --seed "$seed" --threads "$threads" --out "$out" --resume
     ${extra[@]+"${extra[@]}"})
if [ "$ntasks" -gt 1 ]; then
  # one rank more than the allocation's tasks: rank 0 only hands out work and writes the files
  # (it sleeps while it waits: well under 1% of a core), so it shares a core with a worker;
  # no binding, so that each worker's threads spread over its cores
  read -r -a margs <<< "${MPIRUN_ARGS:-}"
  cmd=("${MPIRUN:-mpirun}" -n $((ntasks + 1)) --oversubscribe --bind-to none
       ${margs[@]+"${margs[@]}"} "${cmd[@]}")
fi
if [ -n "${DRY_RUN:-}" ]; then
  echo "${cmd[*]}"
  exit 0
fi
mkdir -p "$(dirname "$out")"
echo "run_evolve: $(date -u +%FT%TZ) on ${SLURM_JOB_NODELIST:-$(hostname)}: ${cmd[*]}"
exec "${cmd[@]}"
