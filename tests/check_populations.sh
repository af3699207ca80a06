#!/usr/bin/env bash
# Every committed primitive run (data/evolved/prims_s<N>/, and the chain stage's continuations
# of them, data/evolved/chain_s<N>/; the primitive runs of the study's palm-down starts,
# pd_prims_s<N>/, and of the protocol as shipped since 2026-11-28, prims46_s<N>/; issue 46)
# holds what its fitness.csv says: the best genotype of its final population, replayed from the
# simulation with the run's own config.ini on the thesis's 16 main-prim trials (with the offsets
# of its last generation; a chain run's hand-over, varied and chained trials are not among
# them), solves all 16 (issue 12, item 4; issue 23, item 4).
# A run directory without its three files is an error; snapshots of runs still going
# (*_run/, resumable) are not finished runs and are left out.
set -uo pipefail
APPDIR=${APPDIR:-apps}
CHECK=check_populations
source "$(dirname "$0")/check_lib.sh"

runs=()
for d in data/evolved/prims_s*/ data/evolved/chain_s*/ data/evolved/pd_prims_s*/ data/evolved/prims46_s*/; do
  [ -d "$d" ] || continue
  case "$d" in *_run/) ;; *) runs+=("$d") ;; esac
done
if [ ${#runs[@]} = 0 ] || [ ! -d "${runs[0]}" ]; then
  ko "no committed primitive run in data/evolved/prims_s*/ (expected at least one)"
fi
for d in "${runs[@]}"; do
  [ -d "$d" ] || continue
  d=${d%/}
  missing=""
  for f in config.ini fitness.csv population.genome; do [ -f "$d/$f" ] || missing="$missing $f"; done
  if [ -n "$missing" ]; then ko "$d: missing$missing"; continue; fi
  last=$(tail -n 1 "$d/fitness.csv" | cut -d, -f1)
  solved=0 lines=""
  for k in $(seq 0 15); do
    out=$("$APPDIR/replay" "$d/population.genome" "$d/config.ini" --stage main --trial "$k" \
      --generation "$last" 2>&1 | grep '^trial ')
    case "$out" in *" success=1 "*) solved=$((solved + 1)) ;; *) lines="$lines t$k" ;; esac
  done
  if [ "$solved" = 16 ]; then
    ok "$d: the final best replays 16/16 main-prim trials (generation $last)"
  else
    ko "$d: the final best replays $solved/16 (failed:$lines)"
  fi
done
echo "check_populations: $pass passed, $fail failed"
[ "$fail" = 0 ]
