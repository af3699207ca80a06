#!/usr/bin/env bash
# Submits a whole replication (replication.sbatch): the primitive runs as one job array, the
# chain stage's runs as another that starts when every primitive run has succeeded
# (PROTOCOL=chain, the default; PROTOCOL=thesis: none), then the integrated runs after those.
#
#   tools/cluster/submit_replication.sh [SBATCH_ARGS...]     e.g. --partition=long
#
# SEEDS (default 10) and CONDITIONS (default "stct st ct ni") choose the runs; DRY_RUN=1 prints
# the sbatch commands. If a run fails (e.g. reaches the time limit), the arrays after it never
# start: submit this again; finished runs are skipped, unfinished ones resume.
set -euo pipefail
cd "$(dirname "$0")/../.."
seeds=${SEEDS:-10}
read -r -a conds <<< "${CONDITIONS:-stct st ct ni}"
script=tools/cluster/replication.sbatch
sb=(sbatch --parsable --export=ALL "$@")
protocol=${PROTOCOL:-chain}
case $protocol in
  chain|thesis) ;;
  *) echo "submit_replication: PROTOCOL=$protocol: expected chain or thesis" >&2; exit 2 ;;
esac
if [ -n "${DRY_RUN:-}" ]; then
  echo "${sb[*]} --array=0-$((seeds - 1)) $script prims"
  last=PRIMS_JOB
  if [ "$protocol" = chain ]; then
    echo "${sb[*]} --array=0-$((seeds - 1)) --dependency=afterok:PRIMS_JOB $script chain"
    last=CHAIN_JOB
  fi
  echo "${sb[*]} --array=0-$((seeds * ${#conds[@]} - 1)) --dependency=afterok:$last $script integrated"
  exit 0
fi
prims=$("${sb[@]}" --array=0-$((seeds - 1)) "$script" prims)
last=$prims
if [ "$protocol" = chain ]; then
  last=$("${sb[@]}" --array=0-$((seeds - 1)) --dependency=afterok:"${prims%%;*}" "$script" chain)
  echo "submitted: primitive runs $prims, chain-stage runs $last (after $prims succeeds)"
fi
integ=$("${sb[@]}" --array=0-$((seeds * ${#conds[@]} - 1)) --dependency=afterok:"${last%%;*}" \
  "$script" integrated)
echo "submitted: integrated runs $integ (after $last succeeds)"
