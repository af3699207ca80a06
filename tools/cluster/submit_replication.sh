#!/usr/bin/env bash
# Submits a whole replication (replication.sbatch): the primitive runs as one job array, then
# the integrated runs as another that starts when every primitive run has succeeded.
#
#   tools/cluster/submit_replication.sh [SBATCH_ARGS...]     e.g. --partition=long
#
# SEEDS (default 10) and CONDITIONS (default "stct st ct ni") choose the runs; DRY_RUN=1 prints
# the sbatch commands. If a primitive run fails (e.g. reaches the time limit), the integrated
# array never starts: submit this again; finished runs are skipped, unfinished ones resume.
set -euo pipefail
cd "$(dirname "$0")/../.."
seeds=${SEEDS:-10}
read -r -a conds <<< "${CONDITIONS:-stct st ct ni}"
script=tools/cluster/replication.sbatch
sb=(sbatch --parsable --export=ALL "$@")
if [ -n "${DRY_RUN:-}" ]; then
  echo "${sb[*]} --array=0-$((seeds - 1)) $script prims"
  echo "${sb[*]} --array=0-$((seeds * ${#conds[@]} - 1)) --dependency=afterok:PRIMS_JOB $script integrated"
  exit 0
fi
prims=$("${sb[@]}" --array=0-$((seeds - 1)) "$script" prims)
integ=$("${sb[@]}" --array=0-$((seeds * ${#conds[@]} - 1)) --dependency=afterok:"${prims%%;*}" \
  "$script" integrated)
echo "submitted: primitive runs $prims, integrated runs $integ (after $prims succeeds)"
