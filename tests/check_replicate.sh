#!/usr/bin/env bash
# make replicate end to end (tools/replicate.mk, PRESET=tiny: 2 runs of every step, a few
# generations, tiny post-evaluations): every step's files and report.md appear; a replication
# killed in the middle of its integrated runs continues, when started again, to the same files
# as one never stopped; its cost is printed before it starts (target cost), measured once; bad
# presets, steps and inputs are refused.
set -uo pipefail
CHECK=check_replicate
. "$(dirname "$0")/check_lib.sh"
BUILD=${BUILD:-build}
REP="make --no-print-directory -s -f tools/replicate.mk PRESET=tiny THREADS=1"

# the uninterrupted replication (PROTOCOL=chain, the default: the chain stage between the
# primitive runs and the integration test)
if $REP OUT="$tmp/a" > "$tmp/a.out" 2>&1; then ok "PRESET=tiny runs every step"; else
  ko "PRESET=tiny runs every step" "$(tail -5 "$tmp/a.out")"; fi
missing=""
for f in prims-s1/population.genome prims-s2/population.genome chain-s1/population.genome \
  chain-s2/population.genome figures/fig_chain.png \
  posteval/integration/summary.csv int-stct-s1/population.genome int-ni-s2/population.genome \
  posteval/robustness-ct/summary.csv posteval/generalisation-st0/trials.csv \
  stats/table_3_1.txt stats/table_3_2.txt stats/table_3_3.txt stats/selftalk.csv \
  figures/fig3_1.png figures/fig3_3.png figures/fig3_9.svg figures/fig3_10.png \
  figures/fig3_12_stct.png figures/fig3_12_st.svg report.md; do
  [ -s "$tmp/a/$f" ] || missing="$missing $f"
done
if [ -z "$missing" ]; then ok "every step's files"; else ko "every step's files" "missing:$missing"; fi
# Fig. 3.12: the ST-CT run tools/best_run.py picks, its four types in self talk and with the caretaker
w="$tmp/a/figures/fig3_12_stct.txt"
pick=$(/usr/bin/python3 tools/best_run.py "$tmp/a/posteval/robustness-stct/summary.csv" | cut -d' ' -f1)
if [ "$(grep -c "/words-stct/self-[0-3].csv: self talk: " "$w")" = 4 ] &&
   [ "$(grep -c "/words-stct/care-[0-3].csv: caretaker: none 0-0, reach 1-" "$w")" = 4 ] &&
   [ -n "$pick" ] && grep -qF "$pick's best" "$tmp/a/figures/fig3_12_stct.svg"; then
  ok "Fig. 3.12: the best ST-CT run's four types, self talk and caretaker"
else ko "Fig. 3.12" "pick '$pick': $(cat "$w")"; fi

# report.md: every section, the thesis's numbers beside ours
r="$tmp/a/report.md"
sections=0
for h in "## Primitive stages" "## Integration test" "## Integrated stage" "## Robustness test" \
  "## Generalisation test" "## Self talk against" "## Strategies"; do grep -qF "$h" "$r" && sections=$((sections + 1)); done
if [ $sections = 7 ]; then ok "report.md has its seven sections"; else ko "report.md sections" "$sections of 7"; fi
# its strategies table: the four types of each self-talking condition, the caretaker's words from reach
if [ "$(grep -cE '^\| (ST-CT|ST) \| int-(stct|st)-s[12], generation [0-9]+ \| [0-3] \| .* \| (yes|no) \| reach' "$r")" = 8 ]; then
  ok "report.md: Fig. 3.12's words, four types of ST-CT and ST"
else ko "report.md strategies" "$(grep -A12 '## Strategies' "$r")"; fi
# which primitives it took, and the chain stage's table: both runs, 2 generations, 2 chained trials
if grep -qF 'Primitives: protocol `chain` (the default)' "$r" && grep -qF "### The chain stage" "$r" &&
   [ "$(grep -cE '^\| [12] \| 2 \| [0-9]+/16 \| [0-2]/2 \|$' "$r")" = 2 ]; then
  ok "report.md: the chain protocol named, its runs' table"
else ko "report.md, the chain protocol" "$(grep -A5 'chain stage' "$r")"; fi
# Table 3.1 as printed (data/thesis/results.json), the integrated runs of both seeds
if grep -qF "| ST-CT | - | 24 | 9.5** | 8.5** |" "$r" && grep -qF "| 581 (426, 700) |" "$r" &&
  [ "$(grep -cE '^\| (ST-CT|ST|CT|NI) \| [12] \| 2 \| [0-9.]+ \|.* [0-4]/4 \|$' "$r")" = 8 ]; then
  ok "report.md: the thesis's Table 3.1 and quartiles, our 8 integrated runs of 2 generations"
else ko "report.md content"; fi

# the robustness test by trial type: each run's successes per type (tiny: 4 trials, one each),
# counted again here from the trials files
bytype=$(awk -F, 'FNR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
  { k = $h["condition"] "|" $h["run_label"]; n[k, $h["type"]] += $h["success"]; m[k, $h["type"]]++; seen[k] = 1 }
  END { for (k in seen) { split(k, c, "|"); all = "yes"; line = "| " c[1] " | " c[2]
    for (t = 0; t < 4; t++) { line = line " | " n[k, t] + 0 "/" m[k, t] + 0; if (!n[k, t]) all = "no" }
    print line " | " all " |" } }' "$tmp"/a/posteval/robustness-{stct,st,ct,ni}/trials.csv | sort)
if [ "$(echo "$bytype" | wc -l)" = 8 ] && [ "$(echo "$bytype" | grep -c '/1 |')" = 8 ] &&
   [ "$(grep -E '^\| (ST-CT|ST|CT|NI) \| int-[a-z]+-s[0-9]+ \| [0-9]+/' "$r" | sort)" = "$bytype" ] &&
   grep -qE "^\| ST-CT \| 9 \| $(echo "$bytype" | grep -c '^| ST-CT .* yes |$') \|$" "$r"; then
  ok "report.md: the robustness test by trial type, each run (by hand), the thesis's ST-CT count"
else ko "report.md by trial type" "$(grep -A14 '### By trial type' "$r")"; fi

# and on trials whose successes are set by hand: ST-CT seed 1 succeeds in types 0 and 3, seed 2
# in type 2, ST seed 1 in all four, the rest in none
mkdir -p "$tmp/ty"
for c in stct st ct ni; do
  mkdir -p "$tmp/ty/robustness-$c"
  awk -F, -v OFS=, 'FNR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; print; next }
    { l = $h["run_label"]; t = $h["type"]
      $h["success"] = (l == "int-stct-s1" && (t == 0 || t == 3)) || (l == "int-stct-s2" && t == 2) ||
        l == "int-st-s1"; print }' "$tmp/a/posteval/robustness-$c/trials.csv" > "$tmp/ty/robustness-$c/trials.csv"
done
/usr/bin/python3 tools/replicate_report.py "$tmp/ty" --types > "$tmp/ty.md" 2> "$tmp/e"
if grep -qxF "| ST-CT | int-stct-s1 | 1/1 | 0/1 | 0/1 | 1/1 | no |" "$tmp/ty.md" &&
   grep -qxF "| ST-CT | int-stct-s2 | 0/1 | 0/1 | 1/1 | 0/1 | no |" "$tmp/ty.md" &&
   grep -qxF "| ST | int-st-s1 | 1/1 | 1/1 | 1/1 | 1/1 | yes |" "$tmp/ty.md" &&
   grep -qxF "| NI | int-ni-s2 | 0/1 | 0/1 | 0/1 | 0/1 | no |" "$tmp/ty.md" &&
   grep -qxF "| ST-CT | 9 | 0 |" "$tmp/ty.md" && grep -qxF "| ST | - | 1 |" "$tmp/ty.md" &&
   [ "$(grep -c ' | no |$\| | yes |$' "$tmp/ty.md")" = 8 ]; then
  ok "replicate_report.py --types: successes set by hand, counted by type"
else ko "replicate_report.py --types" "$(cat "$tmp/ty.md" "$tmp/e")"; fi

# the thesis's counts of §3.2 (learned, all autonomous, first generation): on a copy whose
# integrated fitness.csv and robustness summary are set by hand. PRESET=tiny runs 4 trials, so
# ST's autonomous bonus is at most 4 trials x 2 bonuses x 10 = 80 and ST-CT's (2 self-talk
# trials) 40. ST: s1 80 in both generations (all autonomous, first 0), s2 80 in generation 0
# only (first 0, not at the end), robustness 3 and 0 successes: learned 1 of 2; ST-CT: s1 40 in
# generation 1 (first 1, all autonomous), s2 39.9 (never), robustness 0 and 0
cp -r "$tmp/a" "$tmp/h"
python3 - "$tmp/h" << 'PYEOF'
import csv, sys
out = sys.argv[1]
def setcol(path, col, values):
    rows = list(csv.DictReader(open(path)))
    for r, v in zip(rows, values):
        r[col] = v
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader(); w.writerows(rows)
setcol(out + "/int-st-s1/fitness.csv", "best_bonus_auto", ["80", "80"])
setcol(out + "/int-st-s2/fitness.csv", "best_bonus_auto", ["80", "0"])
setcol(out + "/int-stct-s1/fitness.csv", "best_bonus_auto", ["0", "40"])
setcol(out + "/int-stct-s2/fitness.csv", "best_bonus_auto", ["0", "39.9"])
path = out + "/summary/robustness.csv"
rows = list(csv.DictReader(open(path)))
for r in rows:
    r["successes"] = {"int-st-s1": "3"}.get(r["run_label"].rstrip("/"), "0")
with open(path, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader(); w.writerows(rows)
PYEOF
if python3 tools/replicate_report.py "$tmp/h" --preset tiny --runs 2 -o "$tmp/h.md" &&
   grep -qxF "| ST | 2 | 8 | 1 of 2 tested | 7 | 1 | 3-40 | 0 (0-0), 2 runs |" "$tmp/h.md" &&
   grep -qxF "| ST-CT | 2 | 9 | 0 of 2 tested | 9 | 1 | - | 1 (1-1), 1 runs |" "$tmp/h.md" &&
   grep -qxF "| NI | 2 | 5 | 0 of 2 tested | 0 | 0 | - | - |" "$tmp/h.md"; then
  ok "report.md: the thesis's counts of 3.2 beside ours (by hand)"
else ko "report.md, the counts of 3.2" "$(grep -A8 'as the thesis counts' "$tmp/h.md")"; fi

# interim: the robustness test of the integrated runs complete so far, on a copy with three of
# them unfinished (ST seed 2, NI both): the other five, each with the same trials and successes
# as the study's own robustness step gave it
cp -r "$tmp/a" "$tmp/i" && rm -rf "$tmp/i/interim" &&
  rm "$tmp/i/int-st-s2/population.genome" "$tmp/i/int-ni-s1/population.genome" "$tmp/i/int-ni-s2/population.genome"
rows() { # SUMMARY.csv...: run_label,condition,successes,trials per row, sorted
  awk -F, 'FNR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
    { print $h["run_label"] "," $h["condition"] "," $h["successes"] "," $h["trials"] }' "$@" | sort; }
st1() { # TRIALS.csv: ST seed 1's trials, all but the run index (its place among the runs given)
  awk -F, 'FNR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
    $h["run_label"] == "int-st-s1" { $h["run"] = ""; print }' "$1"; }
want=$(rows "$tmp"/a/posteval/robustness-{stct,st,ct}/summary.csv | grep -v '^int-st-s2,')
if $REP interim OUT="$tmp/i" > "$tmp/in.out" 2> "$tmp/in.err" &&
   grep -qF "(stct 2 st 1 ct 2)" "$tmp/in.out" && [ "$(rows "$tmp/i/interim/robustness.csv")" = "$want" ] &&
   [ "$(echo "$want" | wc -l)" = 5 ] && [ ! -e "$tmp/i/interim.tmp" ] &&
   grep -qF "| ST-CT | - |" "$tmp/i/interim/table_3_1.txt" && ! grep -q "| NI |" "$tmp/i/interim/table_3_1.txt" &&
   [ "$(grep -cE '^\| (ST-CT|ST|CT) \| int-' "$tmp/i/interim/types.md")" = 5 ] &&
   [ "$(st1 "$tmp/a/posteval/robustness-st/trials.csv")" = "$(st1 "$tmp/i/interim/robustness-st/trials.csv")" ] &&
   [ "$(st1 "$tmp/a/posteval/robustness-st/trials.csv" | wc -l)" = 4 ]; then
  ok "interim: the complete runs' robustness, as the study's step gives it, Table 3.1 of them"
else ko "interim" "$(cat "$tmp/in.out" "$tmp/in.err")"; fi
rm "$tmp"/i/int-*/population.genome
if $REP interim OUT="$tmp/i" > /dev/null 2> "$tmp/e"; then ko "interim with no complete run" "exit 0"
elif grep -qF "interim: no integrated run in $tmp/i is complete yet" "$tmp/e" && [ -d "$tmp/i/interim" ]; then
  ok "interim with no complete run is refused, the last interim kept"
else ko "interim with no complete run" "$(cat "$tmp/e")"; fi

# killed while its integrated runs evolve, then started again: the same files
# (an event, not a deadline: on a busy machine the primitive runs before it take minutes)
setsid $REP OUT="$tmp/b" > "$tmp/b.out" 2>&1 &
pid=$!
wait_for 1800 $pid test -e "$tmp/b/int-stct-s1/checkpoint"
kill -TERM -- -$pid 2> /dev/null
wait $pid 2> /dev/null
if [ -e "$tmp/b/int-stct-s1/checkpoint" ] && [ ! -e "$tmp/b/report.md" ]; then
  ok "killed during the integrated runs"
else ko "killed during the integrated runs" "report exists or no integrated checkpoint"; fi
# through a snapshot (target snapshot: checkpoints first) and a restore into a fresh OUT: what
# resumes below is the restored copy, which must give the uninterrupted replication's files
nck=$(find "$tmp/b" -name checkpoint | wc -l)
if $REP snapshot OUT="$tmp/b" SNAPSHOT="$tmp/bsnap" > "$tmp/bs.out" 2>&1 && mv "$tmp/b" "$tmp/b.orig" &&
   $REP restore OUT="$tmp/b" SNAPSHOT="$tmp/bsnap" >> "$tmp/bs.out" 2>&1 &&
   diff -r -x '*.tmp' -x '*.tmp.[0-9]*' "$tmp/b.orig" "$tmp/b" > /dev/null && [ "$nck" -ge 5 ] &&
   grep -q "checkpoints" "$tmp/bs.out" && [ -z "$(find "$tmp/bsnap" -name '*.tmp')" ]; then
  ok "snapshot and restore: the killed replication copied whole ($nck checkpoints), no temporary file"
else ko "snapshot and restore" "$(cat "$tmp/bs.out")"; fi
$REP restore OUT="$tmp/b" SNAPSHOT="$tmp/bsnap" > /dev/null 2> "$tmp/e"
e1=$?
$REP snapshot OUT="$tmp/b" > /dev/null 2> "$tmp/e2"
if [ $e1 != 0 ] && grep -q "restore: $tmp/b exists (restoring over it would overwrite newer files)" "$tmp/e" &&
   grep -q "snapshot: SNAPSHOT=DIR expected" "$tmp/e2"; then
  ok "restore over an existing OUT, or without SNAPSHOT, is refused"
else ko "snapshot refusals" "$(cat "$tmp/e" "$tmp/e2")"; fi
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
# (the wrapper waits until the test removes its hold file: no deadline for the test to meet)
case $APPDIR in /*) apps=$APPDIR ;; *) apps=$PWD/$APPDIR ;; esac
printf '#!/bin/sh\n"%s/evolve" "$@" || exit $?\ntouch "%s/finished"\nwhile [ -e "%s/hold" ]; do sleep 0.1; done\n' \
  "$apps" "$tmp" "$tmp" > "$tmp/slow"
chmod +x "$tmp/slow"
touch "$tmp/hold"
setsid $REP OUT="$tmp/d" EVOLVE="$tmp/slow" "$tmp/d/prims-s1/population.genome" > "$tmp/d.out" 2>&1 &
pid=$!
wait_for 1800 $pid test -e "$tmp/finished"
kill -TERM -- -$pid 2> /dev/null
wait $pid 2> /dev/null
rm -f "$tmp/hold"
if [ -e "$tmp/finished" ] && [ -s "$tmp/d/prims-s1/population.genome" ] &&
   $REP OUT="$tmp/d" "$tmp/d/prims-s1/population.genome" > /dev/null 2>&1 &&
   cmp -s "$tmp/d/prims-s1/population.genome" "$tmp/a/prims-s1/population.genome"; then
  ok "stopped after a run's last checkpoint: its population.genome kept"
else ko "stopped after a run's last checkpoint" "$(cat "$tmp/d.out")"; fi

# PROTOCOL=chain: each primitive run continued by the chain stage (configs/chain_prim.cfg) from
# its population, the same seed, and the integration test on those runs
if $REP OUT="$tmp/a" chain > "$tmp/ch.out" 2>&1 &&
   grep -q "^chain_trials = 2$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^handover = true$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^init_population = $tmp/a/prims-s2/population.genome$" "$tmp/a/chain-s2/config.ini" &&
   grep -q "^seed = 2$" "$tmp/a/chain-s2/config.ini" && [ -s "$tmp/a/chain-s1/population.genome" ] &&
   [ "$(head -1 "$tmp/a/chain-s1/fitness.csv" | grep -o 'best_c[0-9]*' | wc -l)" = 2 ] &&
   [ "$(head -1 "$tmp/a/chain-s1/fitness.csv" | grep -o 'best_h[0-9][0-9]*' | wc -l)" = 12 ]; then
  ok "PROTOCOL=chain: the chain stage from each primitive run"
else ko "PROTOCOL=chain" "$(tail -3 "$tmp/ch.out")"; fi
# (make's output read whole before grep: with pipefail, grep -q leaving early fails the pipe)
dry() { $REP -n "$@" 2> /dev/null; }
out=$(dry OUT="$tmp/a" "$tmp/a/posteval/integration/summary.csv")
if [ "$($REP jobs STEP=chain OUT=x | wc -l)" = 2 ] &&
   grep -q "posteval integration .*chain-s1/population.genome" <<< "$out"; then
  ok "PROTOCOL=chain: the integration test takes the chain runs"
else ko "PROTOCOL=chain integration"; fi
# PROTOCOL=thesis: no chain stage; the integration test and the report take the primitive runs
out=$(dry OUT="$tmp/t" PROTOCOL=thesis "$tmp/t/posteval/integration/summary.csv")
if grep "posteval integration" <<< "$out" | grep -q "prims-s1/population.genome .*prims-s2/population.genome" &&
   ! grep -q "chain" <<< "$out" &&
   python3 tools/replicate_report.py "$tmp/a" --preset tiny --runs 2 --protocol thesis -o "$tmp/rt.md" &&
   grep -qF 'Primitives: protocol `thesis`' "$tmp/rt.md" && ! grep -qF "### The chain stage" "$tmp/rt.md"; then
  ok "PROTOCOL=thesis: the primitive runs alone, and the report says so"
else ko "PROTOCOL=thesis"; fi
# a report of the chain protocol from a directory without its chain runs is refused
mkdir -p "$tmp/nochain/prims-s1" && cp "$tmp/a/prims-s1/"{fitness.csv,config.ini} "$tmp/nochain/prims-s1/"
if ! python3 tools/replicate_report.py "$tmp/nochain" --protocol chain -o "$tmp/nc.md" 2> "$tmp/e" &&
   grep -q "$tmp/nochain: no chain-s\*/fitness.csv (expected the chain runs of --protocol chain)" "$tmp/e" &&
   [ ! -e "$tmp/nc.md" ]; then
  ok "report.md of the chain protocol without chain runs is refused"
else ko "report without chain runs" "$(cat "$tmp/e")"; fi
# the chain stage's figure (tools/fig_chain.py) from the chain runs, only with PROTOCOL=chain
out=$(dry OUT="$tmp/f" PROTOCOL=chain "$tmp/f/figures/.done")
out0=$(dry OUT="$tmp/f" PROTOCOL=thesis "$tmp/f/figures/.done")
if grep -qF "tools/fig_chain.py $tmp/f/chain-s1 $tmp/f/chain-s2 -o '$tmp/f/figures/fig_chain.png'" <<< "$out" &&
   grep -q "tools/fig_int_fitness.py" <<< "$out0" && ! grep -q fig_chain <<< "$out0"; then
  ok "PROTOCOL=chain: the chain stage's figure from the chain runs"
else ko "PROTOCOL=chain figure"; fi
# the study from primitive runs that exist (PRIM_RUNS, CHAIN_RUNS: here OUT a's, as a user gives
# the committed ones): nothing is evolved or written for them, RUNS counts the integrated runs,
# and the report names them and reads their fitness.csv
given="PRIM_RUNS='$tmp/a/prims-s1 $tmp/a/prims-s2/' CHAIN_RUNS='$tmp/a/chain-s1 $tmp/a/chain-s2'"
sums() { (cd "$tmp/a" && find prims-s1 prims-s2 chain-s1 chain-s2 -type f | sort | xargs md5sum); }
sums > "$tmp/g.before"
if eval "$REP OUT='$tmp/g' RUNS=1 $given" > "$tmp/g.out" 2>&1 &&
   [ -s "$tmp/g/report.md" ] && [ -s "$tmp/g/int-ni-s1/population.genome" ] &&
   [ ! -e "$tmp/g/int-ni-s2" ] && [ -z "$(ls -d "$tmp/g/prims-s"* "$tmp/g/chain-s"* 2> /dev/null)" ] &&
   grep -qx "populations = $tmp/a/chain-s1/population.genome,$tmp/a/chain-s2/population.genome" \
     "$tmp/g/int-stct-s1/config.ini" &&
   [ "$(cut -d, -f9 "$tmp/g/posteval/integration/summary.csv" | sort -u | tr '\n' ' ')" = "chain-s1 chain-s2 run_label " ] &&
   sums | cmp -s - "$tmp/g.before"; then
  ok "PRIM_RUNS, CHAIN_RUNS: the integrated runs from the given runs, which stay untouched"
else ko "PRIM_RUNS, CHAIN_RUNS" "$(tail -5 "$tmp/g.out")"; fi
r="$tmp/g/report.md"
if grep -qF "The primitive runs were given (\`PRIM_RUNS\`, \`CHAIN_RUNS\`), not run here: \`$tmp/a/prims-s1\`" "$r" &&
   [ "$(grep -cE '^\| [12] \| 2 \| [0-9]+/16 \| [0-2]/2 \|$' "$r")" = 2 ] &&
   [ "$(grep -cE '^\| [12] \| (-|[0-9]+) \| (-|[0-9]+) \| (-|[0-9]+) \| 2 \| [0-9]+/16 \|$' "$r")" = 2 ] &&
   [ "$(grep -cE '^\| (ST-CT|ST|CT|NI) \| 1 \| 2 \|' "$r")" = 4 ]; then
  ok "PRIM_RUNS: the report names the given runs and reads their primitive and chain stages"
else ko "PRIM_RUNS report" "$(sed -n 1,40p "$r")"; fi
e1=$($REP -n OUT="$tmp/g" CHAIN_RUNS="$tmp/a/chain-s1" 2>&1)
e2=$($REP -n OUT="$tmp/g" PRIM_RUNS="$tmp/a/prims-s1 $tmp/a/prims-s2" CHAIN_RUNS="$tmp/a/chain-s1" 2>&1)
e3=$($REP -n OUT="$tmp/g" PROTOCOL=thesis PRIM_RUNS="$tmp/a/prims-s1" CHAIN_RUNS="$tmp/a/chain-s1" 2>&1)
e4=$($REP -n OUT="$tmp/g" PRIM_RUNS="$tmp/a/prims-s1" CHAIN_RUNS="$tmp/nowhere" 2>&1)
if grep -q "CHAIN_RUNS without PRIM_RUNS" <<< "$e1" &&
   grep -q "PRIM_RUNS has 2 and CHAIN_RUNS 1 directories: expected one chain run per primitive run" <<< "$e2" &&
   grep -q "CHAIN_RUNS with PROTOCOL=thesis, which has no chain stage" <<< "$e3" &&
   grep -q "no such file: $tmp/nowhere/fitness.csv $tmp/nowhere/population.genome" <<< "$e4"; then
  ok "PRIM_RUNS, CHAIN_RUNS: a missing or unpaired run is refused"
else ko "PRIM_RUNS refusals" "$e1 $e2 $e3 $e4"; fi
$REP OUT="$tmp/c" PROTOCOL=mine > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PROTOCOL=mine: expected chain or thesis" "$tmp/e"; then
  ok "an unknown protocol is refused"; else ko "unknown protocol" "$(cat "$tmp/e")"; fi

# the cost, before anything runs (target cost, tools/replicate_cost.py): a row per step, a
# total row and a last line, from costs measured once (OUT/cost/costs.csv) and taken from there the second time
COST="$REP EVAL_COST=$BUILD/eval_cost COST_SAMPLE=1"
rows='^prims: simple-prim |^prims: main-prim |^integration test |^integrated (ST-CT|ST|CT|NI) |^robustness |^generalisation |^stats, figures, report |^total '
if $COST cost OUT="$tmp/p" PROTOCOL=thesis > "$tmp/p.out" 2> "$tmp/p.err" &&
   [ "$(grep -cE "$rows" "$tmp/p.out")" = 12 ] && grep -q "^Expected: .* core-hours, .* hours on 1 thread; at most" "$tmp/p.out" &&
   grep -q "measuring what one evaluation costs" "$tmp/p.err" && grep -q "measured now on host" "$tmp/p.out" &&
   [ "$(grep -c "^$(hostname)," "$tmp/p/cost/costs.csv")" = 17 ]; then
  ok "cost: a row per step and a total, 17 kinds measured"
else ko "cost" "$(cat "$tmp/p.err"; head -20 "$tmp/p.out")"; fi
cp "$tmp/p/cost/costs.csv" "$tmp/costs1.csv"
if $COST cost OUT="$tmp/p" PROTOCOL=thesis > "$tmp/p2.out" 2> "$tmp/p.err" && [ ! -s "$tmp/p.err" ] &&
   grep -q "measured earlier on host" "$tmp/p2.out" && cmp -s "$tmp/p/cost/costs.csv" "$tmp/costs1.csv" &&
   [ "$(grep -cE "$rows" "$tmp/p2.out")" = 12 ]; then
  ok "cost: the second time from OUT/cost/costs.csv, nothing measured"
else ko "cost, cached" "$(cat "$tmp/p.err")"; fi
if $COST cost OUT="$tmp/p" PROTOCOL=thesis REMEASURE=1 > "$tmp/p3.out" 2> "$tmp/p.err" &&
   grep -q "measured now on host" "$tmp/p3.out" && [ "$(grep -c "^$(hostname)," "$tmp/p/cost/costs.csv")" = 17 ]; then
  ok "cost: REMEASURE=1 measures again"
else ko "cost, REMEASURE=1" "$(cat "$tmp/p.err")"; fi
if $COST cost OUT="$tmp/p" > "$tmp/p4.out" 2> "$tmp/p.err" &&
   [ "$(grep -cE "$rows|^chain: replace " "$tmp/p4.out")" = 13 ] &&
   grep -q "chain replace individual .* of data/evolved/chain_candidates" "$tmp/p4.out" &&
   ! grep -q "^chain: extra\|chain extra individual" "$tmp/p4.out"; then
  # the tiny preset's 2 generations are all within the first 60, which replace
  ok "cost: PROTOCOL=chain has the chain stage's row (tiny: 2 generations, all replacing)"
else ko "cost, PROTOCOL=chain" "$(cat "$tmp/p.err")"; fi
# make replicate prints it before its first job
make -n --no-print-directory replicate-only PRESET=tiny OUT="$tmp/n" BUILD="$BUILD" APPDIR="$APPDIR" > "$tmp/n.out" 2> /dev/null
if [ "$(grep -oE "tools/replicate_cost.py|evolve configs/" "$tmp/n.out" | sed -n 1p)" = tools/replicate_cost.py ]; then
  ok "make replicate prices the study before its first job"
else ko "make replicate prices first"; fi
# the arithmetic, with costs given (--assume), by hand: full preset, 10 runs of 100 individuals;
# prims 10 x 100 x (484 x 0.002 + 97 x 0.5) = 49468 s, at most 10 x 100 x 1500 x 0.5 = 750000 s;
# integrated 4 x 10 x 100 x 100 x 0.6 = 240000 s; tests 10 x 10 x 40 x 0.05 + 4 x 10 x 40 x 0.1 +
# 6 x 10 x 7 x 7 x 4 x 10 x 0.1 = 12120 s: 83.77 core-hours (at most 278.37); on 2 threads half
# of it; on 64, a generation of 100 takes 2 rounds (50 at a time): 289468 / 50 + 12120 / 64 s =
# 1.66 h (at most 990000 / 50 + 12120 / 64 s = 5.55 h); the chain stage (configs/chain_prim.cfg's
# budget, 150 generations, the first 60 replacing): 10 x 100 x 60 x 0.5 = 30000 s = 8.3
# core-hours (4.2 h on 2 threads), then 10 x 100 x 90 x 1 = 90000 s = 25 core-hours (12.5 h)
assume=(--assume simple-prim=0.002 --assume main-prim=0.5 --assume integration=0.05
  --assume 'integrated-*=0.6' --assume 'robustness-*=0.1' --assume 'generalisation-*=0.1' --assume chain-replace=0.5 --assume chain=1)
price() { python3 tools/replicate_cost.py --preset full --runs 10 --out "$tmp/q" --eval-cost "$BUILD/eval_cost" "${assume[@]}" "$@"; }
if price --protocol thesis --threads 2 > "$tmp/q.out" 2>&1 &&
   grep -qx "Expected: 83.8 core-hours, 41.9 hours on 2 threads; at most 278 core-hours, 139 hours." "$tmp/q.out" &&
   [ "$(tail -1 "$tmp/q.out")" = "total 83.8 core-hours (expected; at most 278), 41.9 hours on 2 threads" ] &&
   grep -qE "^prims: main-prim +10 +0.5 +97 +97,000 +13.5 +6.7 +\| +1500 +208 +104$" "$tmp/q.out" &&
   grep -qE "^generalisation +6 +0.1 +- +117,600 +3.3 +1.6 +\| +- +3.3 +1.6$" "$tmp/q.out" &&
   price --protocol thesis --threads 64 > "$tmp/q64.out" &&
   grep -qx "Expected: 83.8 core-hours, 1.7 hours on 64 threads; at most 278 core-hours, 5.6 hours." "$tmp/q64.out" &&
   price --protocol chain --threads 2 > "$tmp/qc.out" &&
   grep -qE "^chain: replace +10 +0.5 +60 +60,000 +8.3 +4.2 +\| +60 +8.3 +4.2$" "$tmp/qc.out" &&
   grep -qE "^chain: extra +10 +1 +90 +90,000 +25.0 +12.5 +\| +90 +25.0 +12.5$" "$tmp/qc.out" &&
   [ ! -e "$tmp/q/cost/costs.csv" ]; then
  ok "cost: the arithmetic (costs given, numbers by hand; 2 and 64 threads, PROTOCOL=chain)"
else ko "cost arithmetic" "$(cat "$tmp/q.out" "$tmp/q64.out" "$tmp/qc.out" 2> /dev/null)"; fi
# given primitive runs (PRIM_RUNS, 4 of them) and RUNS=5 integrated runs: no prims or chain rows;
# by hand: the integration test 4 x 10 x 40 = 1,600 trials; each condition 5 x 100 x 100 x 0.6 s
# = 8.3 core-hours; robustness 4 x 5 x 40 = 800 trials; generalisation 6 x 5 x 1960 = 58,800
# trials x 0.1 s = 1.6; total 4 x 8.33 + 0.022 + 0.022 + 1.63 = 35.0
if price --protocol chain --threads 2 --given-runs 4 --runs 5 > "$tmp/qg.out" 2>&1 &&
   ! grep -qE "^(prims|chain):" "$tmp/qg.out" &&
   grep -qE "^integration test +1 +0.05 +- +1,600 " "$tmp/qg.out" &&
   grep -qE "^integrated NI +5 +0.6 +100 +50,000 +8.3 +4.2 " "$tmp/qg.out" &&
   grep -qE "^robustness +4 +0.1 +- +800 " "$tmp/qg.out" &&
   grep -qE "^generalisation +6 +0.1 +- +58,800 +1.6 " "$tmp/qg.out" &&
   grep -qx "Expected: 35.0 core-hours, 17.5 hours on 2 threads; at most 35.0 core-hours, 17.5 hours." "$tmp/qg.out" &&
   grep -q "^prims, chain: given (PRIM_RUNS, CHAIN_RUNS, 4 runs), nothing to run.$" "$tmp/qg.out"; then
  ok "cost: given primitive runs priced as nothing to run, the tests on their count (by hand)"
else ko "cost, given runs" "$(cat "$tmp/qg.out")"; fi
# status: what OUT's files say is done and left, at the same prices (given runs, RUNS=2): ST-CT
# seed 1 done (population.genome: done whatever its generations, 60 here), ST seed 1 at 30 generations (checkpoint), one robustness
# summary written. By hand: ST-CT 1 run x 100 x 100 x 0.6 s = 1.67 core-hours; ST (70 + 100) x
# 60 s = 2.83; CT and NI 200 x 60 s = 3.33 each; the integration test 1,600 x 0.05 s = 0.022;
# robustness 3 jobs x 80 trials x 0.1 s = 0.0067; generalisation 6 x 3,920 x 0.1 s = 0.65;
# total 11.85 core-hours, 5.9 hours on 2 threads
mkdir -p "$tmp/s/int-stct-s1" "$tmp/s/int-st-s1" "$tmp/s/posteval/robustness-ct"
{ echo generation,best; seq 0 59 | sed 's/$/,1/'; } > "$tmp/s/int-stct-s1/fitness.csv"
: > "$tmp/s/int-stct-s1/population.genome"
{ echo generation,best; seq 0 29 | sed 's/$/,1/'; } > "$tmp/s/int-st-s1/fitness.csv"
: > "$tmp/s/int-st-s1/checkpoint"; : > "$tmp/s/posteval/robustness-ct/summary.csv"
pstat() { python3 tools/replicate_cost.py --preset full --protocol chain --runs 2 --given-runs 4 \
  --threads 2 --out "$tmp/s" --eval-cost "$BUILD/eval_cost" "${assume[@]}" --status "$@"; }
if pstat > "$tmp/st.out" 2>&1 &&
   grep -qE "^integrated ST-CT +2 +1 +0 +60 of 200 +1.7 +0.83 " "$tmp/st.out" &&
   grep -qE "^integrated ST +2 +0 +1 +30 of 200 +2.8 +1.4 " "$tmp/st.out" &&
   grep -qE "^integrated NI +2 +0 +0 +0 of 200 +3.3 +1.7 " "$tmp/st.out" &&
   grep -qE "^robustness +4 +1 +0 +- +0.0067 " "$tmp/st.out" &&
   grep -qx "Left: 11.8 core-hours, 5.9 hours on 2 threads; at most 11.8 core-hours, 5.9 hours." "$tmp/st.out" &&
   grep -qx "Running: int-st-s1 (integrated ST, generation 30 of 100)." "$tmp/st.out"; then
  ok "status: the jobs done and running, what is left (by hand)"
else ko "status" "$(cat "$tmp/st.out")"; fi
mkdir -p "$tmp/s/int-ct-s1"; printf 'gen,best\n0,1\n' > "$tmp/s/int-ct-s1/fitness.csv"
if ! pstat > /dev/null 2> "$tmp/e" && grep -q "int-ct-s1/fitness.csv:1: header without generation (expected the fitness.csv of ./apps/evolve" "$tmp/e"; then
  ok "status: a fitness.csv without its generation column is refused, FILE:LINE"
else ko "status, bad fitness.csv" "$(cat "$tmp/e")"; fi

# SET: every evolve and posteval command carries each setting, after the step's own arguments
$REP -n all OUT="$tmp/sd" RUNS=1 SET='postures.reach_palm_down=1 integrated.fail_end=exact' > "$tmp/sd.out" 2>&1
tr '\n' ' ' < "$tmp/sd.out" | sed 's/\\ */ /g' | grep -o "apps/\(evolve\|posteval\) [^>]*" > "$tmp/sd.cmds"
if [ "$(grep -c . "$tmp/sd.cmds")" -ge 6 ] &&
   [ "$(grep -c -- "--set postures.reach_palm_down=1 --set integrated.fail_end=exact" "$tmp/sd.cmds")" = "$(grep -c . "$tmp/sd.cmds")" ] &&
   ! $REP -n all OUT="$tmp/sd" SET='postures.reach_palm_down' > /dev/null 2> "$tmp/e" &&
   grep -q "SET: 'postures.reach_palm_down': expected section.key=value" "$tmp/e"; then
  ok "SET: every evolve and posteval command carries it; a setting without = is refused"
else ko "SET" "$(cat "$tmp/sd.cmds" "$tmp/e")"; fi

# refused: a population that is not there, arguments it cannot price, a bad RUNS
$COST cost OUT="$tmp/p" COST_PRIM_POP=nowhere.genome > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "nowhere.genome (COST_PRIM_POP): no such file" "$tmp/e"; then
  ok "cost: a missing population is refused"; else ko "cost, missing population" "$(cat "$tmp/e")"; fi
$COST cost OUT="$tmp/p" PRIM_ARGS="--threads 3" > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PRIM_ARGS: '--threads 3' cannot be priced" "$tmp/e"; then
  ok "cost: step arguments it cannot price are refused"; else ko "cost, bad PRIM_ARGS" "$(cat "$tmp/e")"; fi
$COST cost OUT="$tmp/p" RUNS=two > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "RUNS=two: expected an integer >= 1" "$tmp/e"; then
  ok "cost: a bad RUNS is refused"; else ko "cost, RUNS=two" "$(cat "$tmp/e")"; fi
$COST cost OUT="$tmp/p" PRESET=huge > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PRESET=huge: expected full, small or tiny" "$tmp/e"; then
  ok "cost: an unknown preset is refused"; else ko "cost, unknown preset" "$(cat "$tmp/e")"; fi

# refusals
$REP OUT="$tmp/c" PRESET=huge > /dev/null 2> "$tmp/e"
if [ $? != 0 ] && grep -q "PRESET=huge: expected full, small or tiny" "$tmp/e"; then
  ok "an unknown preset is refused"; else ko "unknown preset" "$(cat "$tmp/e")"; fi
if ! $REP jobs STEP=everything > /dev/null 2> "$tmp/e" && grep -q "STEP=prims" "$tmp/e"; then
  ok "an unknown step is refused"; else ko "unknown step"; fi
# seed by seed (a replication stopped part way has every condition): ST-CT, ST, CT, NI of seed 1 first
jobs=$($REP jobs STEP=integrated OUT=x)
if [ "$(wc -l <<< "$jobs")" = 8 ] && [ "$(sed -n 4,5p <<< "$jobs" | tr '\n' ' ')" = \
  "x/int-ni-s1/population.genome x/int-stct-s2/population.genome " ]; then
  ok "jobs STEP=integrated lists 4 conditions x 2 runs, seed by seed"; else ko "jobs STEP=integrated" "$jobs"; fi

# the makefiles run the apps of the build under test (APPDIR, as tests/run_all.sh exports it:
# make asan's tests run build-asan/apps), never ./apps of another build
apps_run=""
for mk in "replicate.mk OUT=$tmp/n $tmp/n/prims-s1/population.genome" "order_screen.mk OUT=$tmp/n" \
  "screen.mk OUT=$tmp/n"; do
  set -- $mk
  apps_run="$apps_run $(make --no-print-directory -s -n -f "tools/$1" PRESET=tiny THREADS=1 APPDIR=/no/such \
    "${@:2}" 2>&1 | grep -o '[^ ]*/evolve ' | head -1)"
done
if [ "$apps_run" = " /no/such/evolve  /no/such/evolve  /no/such/evolve " ]; then
  ok "replicate.mk, order_screen.mk and screen.mk run APPDIR's apps"
else ko "APPDIR's apps" "the makefiles ran:$apps_run"; fi

echo "$CHECK: $pass passed, $fail failed"
[ $fail = 0 ]
