#!/usr/bin/env bash
# make replicate end to end (tools/replicate.mk, PRESET=tiny: 2 runs of every step, a few
# generations, tiny post-evaluations): every step's files and report.md appear; a replication
# killed in the middle of its integrated runs continues, when started again, to the same files
# as one never stopped; bad presets and steps are refused.
set -uo pipefail
CHECK=check_replicate
. "$(dirname "$0")/check_lib.sh"
REP="make --no-print-directory -s -f tools/replicate.mk PRESET=tiny THREADS=1"

# the uninterrupted replication
if $REP OUT="$tmp/a" > "$tmp/a.out" 2>&1; then ok "PRESET=tiny runs every step"; else
  ko "PRESET=tiny runs every step" "$(tail -5 "$tmp/a.out")"; fi
missing=""
for f in prims-s1/population.genome prims-s2/population.genome \
  posteval/integration/summary.csv int-stct-s1/population.genome int-ni-s2/population.genome \
  posteval/robustness-ct/summary.csv posteval/generalisation-st0/trials.csv \
  stats/table_3_1.txt stats/table_3_2.txt stats/table_3_3.txt stats/selftalk.csv \
  figures/fig3_1.png figures/fig3_3.png figures/fig3_9.svg figures/fig3_10.png report.md; do
  [ -s "$tmp/a/$f" ] || missing="$missing $f"
done
if [ -z "$missing" ]; then ok "every step's files"; else ko "every step's files" "missing:$missing"; fi

# report.md: every section, the thesis's numbers beside ours
r="$tmp/a/report.md"
sections=0
for h in "## Primitive stages" "## Integration test" "## Integrated stage" "## Robustness test" \
  "## Generalisation test" "## Self talk against"; do grep -qF "$h" "$r" && sections=$((sections + 1)); done
if [ $sections = 6 ]; then ok "report.md has its six sections"; else ko "report.md sections" "$sections of 6"; fi
# Table 3.1 as printed (data/thesis/results.json), the integrated runs of both seeds
if grep -qF "| ST-CT | - | 24 | 9.5** | 8.5** |" "$r" && grep -qF "| 581 (426, 700) |" "$r" &&
  [ "$(grep -cE '^\| (ST-CT|ST|CT|NI) \| [12] \| 2 \| [0-9.]+ \|.* [0-4]/4 \|$' "$r")" = 8 ]; then
  ok "report.md: the thesis's Table 3.1 and quartiles, our 8 integrated runs of 2 generations"
else ko "report.md content"; fi

# killed while its integrated runs evolve, then started again: the same files
setsid $REP OUT="$tmp/b" > "$tmp/b.out" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -e "$tmp/b/int-stct-s1/checkpoint" ] && break
  kill -0 $pid 2> /dev/null || break
  sleep 0.1
done
kill -TERM -- -$pid 2> /dev/null
wait $pid 2> /dev/null
if [ -e "$tmp/b/int-stct-s1/checkpoint" ] && [ ! -e "$tmp/b/report.md" ]; then
  ok "killed during the integrated runs"
else ko "killed during the integrated runs" "report exists or no integrated checkpoint"; fi
if $REP OUT="$tmp/b" > "$tmp/b2.out" 2>&1; then ok "started again, it completes"; else
  ko "started again, it completes" "$(tail -5 "$tmp/b2.out")"; fi
# files name their directory (config.ini's integrated.populations, report.md): compared with it
# replaced; pictures are left out (matplotlib's PNG is not byte-stable)
diffs=$(cd "$tmp/a" && find . -type f ! -name '*.log' ! -name '*.png' ! -name '*.svg' | sort |
  while read -r f; do
    cmp -s <(sed "s|$tmp/a|OUT|g" "$f") <(sed "s|$tmp/b|OUT|g" "$tmp/b/$f" 2> /dev/null) || echo "$f"
  done)
if [ -z "$diffs" ]; then ok "the resumed replication's files equal the uninterrupted one's"; else
  ko "resumed replication" "differ: $(echo $diffs)"; fi

# stopped after a run finished but before make saw it end (a wrapper that pauses after evolve):
# make must not delete the run's population.genome, which a resume of the finished run does
# not write again
printf '#!/bin/sh\n"%s/apps/evolve" "$@" || exit $?\ntouch "%s/finished"\nsleep 30\n' "$PWD" "$tmp" > "$tmp/slow"
chmod +x "$tmp/slow"
setsid $REP OUT="$tmp/d" EVOLVE="$tmp/slow" "$tmp/d/prims-s1/population.genome" > "$tmp/d.out" 2>&1 &
pid=$!
for _ in $(seq 1 600); do [ -e "$tmp/finished" ] && break; sleep 0.1; done
kill -TERM -- -$pid 2> /dev/null
wait $pid 2> /dev/null
if [ -e "$tmp/finished" ] && [ -s "$tmp/d/prims-s1/population.genome" ] &&
   $REP OUT="$tmp/d" "$tmp/d/prims-s1/population.genome" > /dev/null 2>&1 &&
   cmp -s "$tmp/d/prims-s1/population.genome" "$tmp/a/prims-s1/population.genome"; then
  ok "stopped after a run's last checkpoint: its population.genome kept"
else ko "stopped after a run's last checkpoint" "$(cat "$tmp/d.out")"; fi

# PROTOCOL=chain: each primitive run continued by the chain stage (configs/chain_prim.cfg) from
# its population, the same seed, and the integration test on those runs
if $REP OUT="$tmp/a" PROTOCOL=chain chain > "$tmp/ch.out" 2>&1 &&
   grep -q "^chain_trials = 2$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^handover = true$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^init_population = $tmp/a/prims-s2/population.genome$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^seed = 2$" "$tmp/a/chain-s2/config.ini" && [ -s "$tmp/a/chain-s1/population.genome" ] &&
   [ "$(head -1 "$tmp/a/chain-s1/fitness.csv" | grep -o 'best_c[0-9]*' | wc -l)" = 2 ] &&
   [ "$(head -1 "$tmp/a/chain-s1/fitness.csv" | grep -o 'best_h[0-9][0-9]*' | wc -l)" = 12 ]; then
  ok "PROTOCOL=chain: the chain stage from each primitive run"
else ko "PROTOCOL=chain" "$(tail -3 "$tmp/ch.out")"; fi
if [ "$($REP jobs STEP=chain OUT=x PROTOCOL=chain | wc -l)" = 2 ] &&
   $REP -n OUT="$tmp/a" PROTOCOL=chain "$tmp/a/posteval/integration/summary.csv" 2> /dev/null |
   grep -q "posteval integration .*chain-s1/population.genome"; then
  ok "PROTOCOL=chain: the integration test takes the chain runs"
else ko "PROTOCOL=chain integration"; fi
$REP OUT="$tmp/c" PROTOCOL=mine > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PROTOCOL=mine: expected chain or thesis" "$tmp/e"; then
  ok "an unknown protocol is refused"; else ko "unknown protocol" "$(cat "$tmp/e")"; fi

# refusals
$REP OUT="$tmp/c" PRESET=huge > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PRESET=huge: expected full, small or tiny" "$tmp/e"; then
  ok "an unknown preset is refused"; else ko "unknown preset" "$(cat "$tmp/e")"; fi
if ! $REP jobs STEP=everything > /dev/null 2> "$tmp/e" && grep -q "STEP=prims" "$tmp/e"; then
  ok "an unknown step is refused"; else ko "unknown step"; fi
if [ "$($REP jobs STEP=integrated OUT=x | wc -l)" = 8 ]; then ok "jobs STEP=integrated lists 4 conditions x 2 runs"; else
  ko "jobs STEP=integrated"; fi

echo "$CHECK: $pass passed, $fail failed"
[ $fail = 0 ]
