#!/usr/bin/env bash
# Every committed primitive run (data/evolved/prims_s<N>/, and the chain stage's continuations
# of them, data/evolved/chain_s<N>/; the primitive runs of the study's palm-down starts,
# pd_prims_s<N>/, and of the protocol as shipped since 2026-11-28, prims46_s<N>/ and their chain
# stages chain46_s<N>/; issue 46) holds what its fitness.csv says: the best genotype of its
# final population, replayed from the simulation with the run's own config.ini on the thesis's
# 16 main-prim trials (with the offsets of its last generation; a chain run's hand-over, varied
# and chained trials are not among them), solves all 16, or, when the best by fitness is not
# among a completed stage's solvers, the final population holds as many genotypes solving all 16
# as fitness.csv records (issue 12, item 4; issue 23, item 4).
# A run directory without its three files is an error; snapshots of runs still going
# (*_run/, resumable) are not finished runs and are left out.
set -uo pipefail
APPDIR=${APPDIR:-apps}
BUILD=${BUILD:-build}
CHECK=check_populations
source "$(dirname "$0")/check_lib.sh"

runs=()
for d in data/evolved/prims_s*/ data/evolved/chain_s*/ data/evolved/pd_prims_s*/ data/evolved/prims46_s*/ data/evolved/chain46_s*/; do
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
    continue
  fi
  # A stage completes when ga.success_genotypes genotypes of a generation solve all 16, and the
  # best by fitness need not be one of them (prims46_s2: its best solves 15, fitness.csv's
  # best_successes). Then the final population must hold the all_success genotypes its last row
  # records, replayed together by build/trial_sweep (one process, seconds).
  recorded=$(python3 -c 'import csv, sys; r = list(csv.DictReader(open(sys.argv[1])))[-1]
print(r["all_success"], r["best_successes"])' "$d/fitness.csv")
  want=${recorded% *} best=${recorded#* }
  have=$("$BUILD/trial_sweep" "$d/config.ini" "$d/population.genome" --generations "$last:$last" |
    awk '{ split($4, a, "="); s[$2] += a[2] } END { n = 0; for (g in s) if (s[g] == 16) n++; print n }')
  if [ "$best" = "$solved" ] && [ "$want" -gt 0 ] && [ "$have" = "$want" ]; then
    ok "$d: its final best replays $solved/16, as fitness.csv says, and $have genotypes of the final population all 16 (generation $last)"
  else
    ko "$d: the final best replays $solved/16 (failed:$lines; fitness.csv: $best), $have genotypes all 16 (fitness.csv: $want)"
  fi
done
echo "check_populations: $pass passed, $fail failed"
[ "$fail" = 0 ]
