#!/usr/bin/env bash
# The thesis-figure scripts (tools/fig_*.py: Figs. 3.1, 3.3-3.12) on the hand-made fixtures of tests/fixtures/: each
# writes a valid, non-blank PNG (chunks and CRCs, the image data inflates to its size) and a
# valid SVG (XML, with the figure's labels as text), prints the numbers it drew (checked against
# values worked out by hand), draws the same SVG twice, and refuses a malformed CSV with
# FILE:LINE and what was expected, writing nothing. Also on real data: the committed seed-2
# primitive run (Fig. 3.1), a 2-generation integrated run and replay traces made here.
set -uo pipefail
CHECK=check_figures
source "$(dirname "$0")/check_lib.sh"
source "$(dirname "$0")/check_figlib.sh"
FX=tests/fixtures
FIG=$FX/figures

# ---- Fig. 3.1: the hand-made run changes stage at generation 3; its config.ini's bonus 5 x 16
# trials = 80; and the committed seed-2 run (simple-prim 0-819, main-prim from 820, 160 of 160)
draw fig3_1 fig_prim_fitness.py "$FIG/prims_run" data/evolved/prims_s2 --label "hand-made" --label "seed 2" -- \
  "hand-made" "seed 2" "main (best)" "bonus" "average" "maximum bonus" "main-prim" "generation"
has fig3_1 "fig_prim_fitness: $FIG/prims_run/fitness.csv: 6 generations, stage changes at [3], last best 70 bonus 80 of 80" \
  "fig_prim_fitness: data/evolved/prims_s2/fitness.csv: 832 generations, stage changes at [820], last best 108.752 bonus 160 of 160"
sed '5s/,5,2,/,x,2,/' "$FIG/prims_run/fitness.csv" > "$tmp/p1.csv"
refuses "fig3_1: a bad number" "$tmp/p1.csv:5: best 'x' (expected a finite number)" fig_prim_fitness.py "$tmp/p1.csv"
cut -d, -f1-4 "$FIG/prims_run/fitness.csv" > "$tmp/p2.csv"
refuses "fig3_1: missing columns" "$tmp/p2.csv:1: header without best_bonus,stage (expected a primitive run's fitness.csv" fig_prim_fitness.py "$tmp/p2.csv"
refuses "fig3_1: a missing run" "$tmp/none/fitness.csv: No such file or directory" fig_prim_fitness.py "$tmp/none"

# ---- the chain stage (tools/fig_chain.py): the hand-made chain_run.csv's best solves the 16 fixed
# trials in generations 0 and 2 (trial 13 fails in 1), grasp hand-overs 0, 1, 2 of 4 and chained
# trials 0, 2, 3 of 8; and the committed hcg_p2_s1 screen (37 generations)
draw fig_chain fig_chain.py "$FIG/chain_run.csv" data/evolved/chain_candidates/hcg_p2_s1 --label "hand-made" --label "hcg_p2_s1" -- \
  "hand-made" "hcg_p2_s1" "fixed (16)" "grasp hand-over (4)" "varied starts (8)" "chained (8)" "F_chain"
has fig_chain "fig_chain: $FIG/chain_run.csv: 3 generations, the best solved the 16 fixed trials in 2, a grasp hand-over in 2 (first 1), a chained trial in 2 (first 1, most 3 of 8)" \
  "fig_chain: data/evolved/chain_candidates/hcg_p2_s1/fitness.csv: 37 generations, the best solved the 16 fixed trials in 35, a grasp hand-over in 33 (first 3), a chained trial in 35 (first 1, most 6 of 8)"
refuses "fig_chain: a run without chained trials" "$FIG/prims_run/fitness.csv:1: header without best_c0 (expected a chain-stage run's fitness.csv" fig_chain.py "$FIG/prims_run"
sed '3s/,75.25,/,y,/' "$FIG/chain_run.csv" > "$tmp/c1.csv"
refuses "fig_chain: a bad number" "$tmp/c1.csv:3: best_F_chain 'y' (expected a finite number)" fig_chain.py "$tmp/c1.csv"
# the run's integration tests as points: integration_g3/ by hand, 3 genotypes with 25, 30 and 10
# of 40: 65 of 120, median 25; integration_all_g3/ (another test of the run) is not one of them
mkdir -p "$tmp/crun/integration_g3" "$tmp/crun/integration_all_g3"
cp "$FIG/chain_run.csv" "$tmp/crun/fitness.csv"
head -1 data/evolved/chain_s1/integration_g102/summary.csv > "$tmp/crun/integration_g3/summary.csv"
for r in "0,25" "1,30" "2,10"; do
  echo "integration,incremental,0,${r%,*},${r#*,},40,0,0,x,0.5,1,0,-1" >> "$tmp/crun/integration_g3/summary.csv"
done
echo "not a summary" > "$tmp/crun/integration_all_g3/summary.csv"
draw fig_chain_int fig_chain.py "$tmp/crun" --label "with tests" -- \
  "with tests" "integration test, top 10 (share of trials)" "thesis: median 25 of 40"
has fig_chain_int "fig_chain: $tmp/crun/fitness.csv: 3 generations, the best solved the 16 fixed trials in 2, a grasp hand-over in 2 (first 1), a chained trial in 2 (first 1, most 3 of 8); integration test at 3: 65 of 120, median 25 of 40"
sed -i '3s/^integration,/robustness,/' "$tmp/crun/integration_g3/summary.csv"
refuses "fig_chain: a test that is not the integration test" "$tmp/crun/integration_g3/summary.csv:3: test 'robustness' (expected an integration test's summary.csv" fig_chain.py "$tmp/crun"

# ---- Figs. 3.5-3.8: the hand-made integrated run, and a real 2-generation ST-CT run
"$APPDIR/evolve" configs/integrated_stct.cfg --set "integrated.populations=data/evolved/simple_prim_s*.genome" \
  --set integrated.top=1 --set ga.population=4 --set ga.elites=1 --set ga.parents=2 --set integrated.steps=30 \
  --generations 2 --threads 1 --out "$tmp/int" > "$tmp/int.log" 2>&1 || ko "integrated run for the figures" "$(tail -3 "$tmp/int.log")"
draw fig3_5 fig_int_fitness.py "$FIG/integrated_fitness.csv" "$tmp/int" --label "hand-made" --label "tiny ST-CT" --title "ST-CT" -- \
  "hand-made: fitness" "hand-made: bonus" "hand-made: bonus without the caretaker" "tiny ST-CT: fitness" "ST-CT"
has fig3_5 "fig_int_fitness: $FIG/integrated_fitness.csv: 4 generations, best 260, last bonus 200 (without the caretaker 80)"
grep -q "^fig_int_fitness: $tmp/int/fitness.csv: 2 generations" "$tmp/fig3_5.out" && ok "fig3_5: reads evolve's integrated fitness.csv" || ko "fig3_5 real run" "$(cat "$tmp/fig3_5.out")"
# --panel: the three runs in two panels, in order of first appearance
draw fig3_5p fig_int_fitness.py "$FIG/integrated_fitness.csv" "$tmp/int" "$FIG/integrated_fitness.csv" \
  --label "hand-made" --label "tiny" --label "again" --panel "ST-CT" --panel "NI" --panel "ST-CT" -- \
  "ST-CT" "NI" "hand-made: fitness" "tiny: fitness" "again: fitness"
has fig3_5p "fig_int_fitness: 2 panels: ST-CT (2 runs), NI (1 run)"
# --start: generation 0 (first-generation fitness, another scale) left out; past the last refused
draw fig3_5s fig_int_fitness.py "$FIG/integrated_fitness.csv" --start 2 -- "fitness"
has fig3_5s "fig_int_fitness: $FIG/integrated_fitness.csv: generations 2-3 plotted (--start 2), best 260"
refuses "fig3_5: --start past the last generation" "$FIG/integrated_fitness.csv: no generation from 4 on (its last is 3)" fig_int_fitness.py "$FIG/integrated_fitness.csv" --start 4
refuses "fig3_5: a --panel per run" "2 --panel for 1 runs (expected one per run)" fig_int_fitness.py "$FIG/integrated_fitness.csv" --panel a --panel b
sed 's/best_bonus_auto/best_auto/' "$FIG/integrated_fitness.csv" > "$tmp/i1.csv"
refuses "fig3_5: a missing column" "$tmp/i1.csv:1: header without best_bonus_auto" fig_int_fitness.py "$tmp/i1.csv"
sed '3s/,100,20,/,100,20/' "$FIG/integrated_fitness.csv" > "$tmp/i2.csv"
refuses "fig3_5: a short row" "$tmp/i2.csv:3: 16 fields (expected 17, as the header)" fig_int_fitness.py "$tmp/i2.csv"

# ---- Fig. 3.3 from the integration rows of the fixture (the robustness row skipped).
# incremental successes 25 30 20 28 35 10 -> sorted 10 20 25 28 30 35: median (25 + 28) / 2 =
# 26.5, quartiles (h = 1.25, 3.75) 20 + 0.25 x 5 = 21.25 and 28 + 0.75 x 2 = 29.5; bins of 5
# (35-40 closed): 10-14 one, 20-24 one, 25-29 two, 30-34 one, 35-40 one. nonincremental 23 24
# 10 40 -> 10 23 24 40: median 23.5, quartiles 10 + 0.75 x 13 = 19.75 and 24 + 0.25 x 16 = 28.
# open_jumped, all ten: 12 20 21 25 30 30 33 35 35 40: median 30, quartiles (h = 2.25, 6.75)
# 21 + 0.25 x 4 = 22 and 33 + 0.75 x 2 = 34.5
draw fig3_3 fig_integration.py "$FIG/integration_summary.csv" -- \
  "integration test" "successful trials (of 40)" "individuals" "incremental (n = 6, median 26.5)" \
  "nonincremental (n = 4, median 23.5)" "35-40"
has fig3_3 "fig_integration: incremental: successes n=6 median=26.5 q1=21.25 q3=29.5 min=10 max=35" \
  "fig_integration: incremental: individuals per bin 0-4:0 5-9:0 10-14:1 15-19:0 20-24:1 25-29:2 30-34:1 35-40:1" \
  "fig_integration: nonincremental: successes n=4 median=23.5 q1=19.75 q3=28 min=10 max=40" \
  "fig_integration: nonincremental: individuals per bin 0-4:0 5-9:0 10-14:1 15-19:0 20-24:2 25-29:0 30-34:0 35-40:1" \
  "fig_integration: open jumped, all: n=10 median=30 q1=22 q3=34.5 min=12 max=40"
"$PY" tools/fig_integration.py "$FIG/integration_summary.csv" --bin 20 -o "$tmp/f33.svg" > "$tmp/f33.out" 2>&1 &&
  grep -qxF "fig_integration: incremental: individuals per bin 0-19:1 20-40:5" "$tmp/f33.out" &&
  ok "fig3_3: --bin 20 (two bins, the second closed)" || ko "fig3_3 --bin" "$(cat "$tmp/f33.out")"
# two protocols side by side: the incremental rows twice, each file labelled (6 each, as above)
grep -v ',nonincremental,' "$FIG/integration_summary.csv" > "$tmp/inc.csv"
"$PY" tools/fig_integration.py "$tmp/inc.csv" "$tmp/inc.csv" --label thesis chain -o "$tmp/f33b.svg" > "$tmp/f33b.out" 2>&1 &&
  grep -qxF "fig_integration: thesis: successes n=6 median=26.5 q1=21.25 q3=29.5 min=10 max=35" "$tmp/f33b.out" &&
  grep -qxF "fig_integration: chain: successes n=6 median=26.5 q1=21.25 q3=29.5 min=10 max=35" "$tmp/f33b.out" &&
  grep -qF "chain (n = 6, median 26.5)" "$tmp/f33b.svg" &&
  ok "fig3_3: two summaries, --label per file" || ko "fig3_3 --label" "$(cat "$tmp/f33b.out")"
# two runs' tests pooled under one --label: posteval's run_label tells them apart (each is run 0)
awk '/^#/ { print; next } !h { print $0 ",run_label"; h = 1; next } { print $0 ",chain_s1" }' "$tmp/inc.csv" > "$tmp/inc1.csv"
awk '/^#/ { print; next } !h { print $0 ",run_label"; h = 1; next } { print $0 ",chain_s2" }' "$tmp/inc.csv" > "$tmp/inc2.csv"
"$PY" tools/fig_integration.py "$tmp/inc1.csv" "$tmp/inc2.csv" --label chain chain -o "$tmp/f33c.svg" > "$tmp/f33c.out" 2>&1 &&
  grep -qxF "fig_integration: chain: successes n=12 median=26.5 q1=20 q3=30 min=10 max=35" "$tmp/f33c.out" &&
  ok "fig3_3: two runs pooled under one --label (run_label)" || ko "fig3_3 pooled" "$(cat "$tmp/f33c.out")"
refuses "fig3_3: one run's test twice under one label" "$tmp/inc1.csv:4: chain run 0 (chain_s1) individual 0 is also at $tmp/inc1.csv:4" fig_integration.py "$tmp/inc1.csv" "$tmp/inc1.csv" --label chain chain
refuses "fig3_3: one individual in two files" "$tmp/inc.csv:4: incremental run 0 individual 0 is also at $tmp/inc.csv:4" fig_integration.py "$tmp/inc.csv" "$tmp/inc.csv"
refuses "fig3_3: a label short" "--label: 1 names for 2 summaries (expected one per file)" fig_integration.py "$tmp/inc.csv" "$tmp/inc.csv" --label thesis
refuses "fig3_3: a label for two conditions" "$FIG/integration_summary.csv: conditions incremental, nonincremental (expected one with --label)" fig_integration.py "$FIG/integration_summary.csv" --label x
sed '5s/,30,40,0,20$/,30,36,0,20/' "$FIG/integration_summary.csv" > "$tmp/g1.csv"
refuses "fig3_3: another trial count" "$tmp/g1.csv:5: 36 trials (expected 40, as line 4" fig_integration.py "$tmp/g1.csv"
sed '5s/,30,40,0,20$/,41,40,0,20/' "$FIG/integration_summary.csv" > "$tmp/g2.csv"
refuses "fig3_3: successes > trials" "$tmp/g2.csv:5: successes 41 of 40 trials" fig_integration.py "$tmp/g2.csv"
sed '5s/,30,40,0,20$/,30,40,1,20/' "$FIG/integration_summary.csv" > "$tmp/g3.csv"
refuses "fig3_3: an excluded individual" "$tmp/g3.csv:5: excluded 1 (expected 0" fig_integration.py "$tmp/g3.csv"
sed '5s/^integration,incremental,0,1,/integration,incremental,0,0,/' "$FIG/integration_summary.csv" > "$tmp/g4.csv"
refuses "fig3_3: an individual twice" "$tmp/g4.csv:5: incremental run 0 individual 0 again (expected one row per individual; first at line 4)" fig_integration.py "$tmp/g4.csv"
sed '5s/,20$/,x/' "$FIG/integration_summary.csv" > "$tmp/g5.csv"
refuses "fig3_3: a bad number" "$tmp/g5.csv:5: open_jumped 'x' (expected an integer)" fig_integration.py "$tmp/g5.csv"
grep -v '^integration' "$FIG/integration_summary.csv" > "$tmp/g6.csv"
refuses "fig3_3: no integration rows" "$tmp/g6.csv: no rows of test 'integration'" fig_integration.py "$tmp/g6.csv"
refuses "fig3_3: a bad --bin" "--bin 41: expected 1..40" fig_integration.py "$FIG/integration_summary.csv" --bin 41

# ---- Figs. 3.4 and 3.9 from the summary fixture (Tables A.1 and A.2): robustness ST-CT 95 95
# 87.5 100 67.5 90 92.5 97.5 0 97.5 -> sorted 0 67.5 87.5 90 92.5 95 95 97.5 97.5 100: median
# 93.75, quartiles (h = 2.25, 6.75) 88.125 and 96.875; NI: five 0, 32.5 32.5 60 62.5 75 -> median
# (0 + 32.5) / 2 = 16.25, quartiles 0 and 32.5 + 0.75 (60 - 32.5) = 53.125
draw fig3_4 fig_boxplot.py "$FX/posteval/summary.csv" --test robustness -- "ST-CT" "ST" "CT" "NI" "robustness test"
has fig3_4 "fig_boxplot: robustness ST-CT: n=10 median=93.75 q1=88.125 q3=96.875 min=0 max=100" \
  "fig_boxplot: robustness NI: n=10 median=16.25 q1=0 q3=53.125 min=0 max=75"
draw fig3_9 fig_boxplot.py "$FX/posteval/summary.csv" --test generalisation -- "ST-CT0" "ST0"
grep -c "^fig_boxplot: generalisation " "$tmp/fig3_9.out" | grep -qx 6 && ok "fig3_9: six conditions" || ko "fig3_9" "$(cat "$tmp/fig3_9.out")"
sed '12s/,40,0,0$/,20,0,0/' "$FX/posteval/summary.csv" > "$tmp/b1.csv"  # ST-CT run 0: 38 of 40
refuses "fig3_4: successes > trials" "$tmp/b1.csv:12: successes 38 of 20 trials (expected 0 <= successes <= trials" fig_boxplot.py "$tmp/b1.csv" --test robustness
refuses "fig3_4: an unknown test" "no rows of test 'robust' (tests in the file: integration, robustness, generalisation)" fig_boxplot.py "$FX/posteval/summary.csv" --test robust

# ---- Fig. 3.10 from the trials fixture: ST-CT run 0 succeeds in 25 cells x 5 repetitions + 4
# extra = 129 of 245; ST0 shows run 1 (ST has no rows: excluded), 5 cells x 5 = 25 of 245
draw fig3_10 fig_success_maps.py "$FX/posteval/trials.csv" -- "ST-CT (run 0)" "CT (run 0)" "NI (run 0)" "ST0 (run 1)"
has fig3_10 "fig_success_maps: ST-CT run 0 individual 0: 129 of 245 trials (52.65 %), cells with trials 49" \
  "fig_success_maps: ST0 run 1 individual 0: 25 of 245 trials (10.2 %), cells with trials 49" \
  "fig_success_maps: NI run 0 individual 0: 1 of 49 trials (2.041 %), cells with trials 49"
awk -F, -v OFS=, 'NR == 7 { $7 = 49 } 1' "$FX/posteval/trials.csv" > "$tmp/m1.csv"
refuses "fig3_10: a cell off the grid" "$tmp/m1.csv:7: cell 49, success 0 (expected a cell 0..48 and success 0 or 1" fig_success_maps.py "$tmp/m1.csv"
refuses "fig3_10: a bad --pick" "--pick 'ST-CT': expected CONDITION:RUN" fig_success_maps.py "$FX/posteval/trials.csv" --pick ST-CT

# ---- Fig. 3.11 from ./apps/stats selftalk (the committed fixture is its output on trials.csv)
"$APPDIR/stats" selftalk "$FX/posteval/trials.csv" | cmp -s - "$FIG/selftalk.csv" &&
  ok "fig3_11: the fixture is ./apps/stats selftalk's output" || ko "fig3_11 fixture" "stats selftalk output differs from $FIG/selftalk.csv"
draw fig3_11 fig_selftalk.py "$FIG/selftalk.csv" -- "self talk (ST-CT)" "caretaker (ST-CT0)" "self talk (ST)"
has fig3_11 "fig_selftalk: ST-CT: 1 individuals, better with self talk 1, with the caretaker 0" \
  "fig_selftalk: ST: 1 individuals, better with self talk 0, with the caretaker 1"
sed '2s/,selftalk,/,maybe,/' "$FIG/selftalk.csv" > "$tmp/s1.csv"
refuses "fig3_11: a bad 'better'" "$tmp/s1.csv:2: better 'maybe' (expected selftalk, caretaker or none)" fig_selftalk.py "$tmp/s1.csv"

# ---- Fig. 3.12 from traces: hand-made (self talk reach 0-3, grasp 4-7, move 8-11; the
# caretaker silent at 0, then reach, open, grasp, move), and real replays of the tiny run
draw fig3_12 fig_words.py "$FIG/trace_selftalk.csv+$FIG/trace_caretaker.csv" "$FIG/trace_selftalk.csv" --label "type 0" --label "self talk only" -- \
  "type 0" "self talk only" "self talk" "caretaker" "reach" "move" "time (s)"
has fig3_12 "fig_words: $FIG/trace_selftalk.csv: self talk: reach 0-3, grasp 4-7, move 8-11" \
  "fig_words: $FIG/trace_caretaker.csv: caretaker: none 0-0, reach 1-4, open 5-5, grasp 6-8, move 9-11"
if [ -d "$tmp/int" ]; then
  "$APPDIR/replay" "$tmp/int/best.genome" "$tmp/int/config.ini" --trial 1 --out "$tmp/r_self.csv" > /dev/null 2>&1
  "$APPDIR/replay" "$tmp/int/best.genome" "$tmp/int/config.ini" --trial 1 --set integrated.words_odd=caretaker --out "$tmp/r_care.csv" > /dev/null 2>&1
  draw fig3_12_replay fig_words.py "$tmp/r_self.csv+$tmp/r_care.csv" -- "self talk" "caretaker"
  grep -q "r_care.csv: caretaker: none 0-0, reach 1-" "$tmp/fig3_12_replay.out" && grep -q "r_self.csv: self talk: " "$tmp/fig3_12_replay.out" &&
    ok "fig3_12: reads ./apps/replay's traces" || ko "fig3_12 replay" "$(cat "$tmp/fig3_12_replay.out")"
fi
sed '6d' "$FIG/trace_selftalk.csv" > "$tmp/w1.csv"
refuses "fig3_12: a missing step" "$tmp/w1.csv:6: step 5 (expected 4: one row per step)" fig_words.py "$tmp/w1.csv"
printf 'step,caretaker_word,selftalk_label\n0,-1,0\n1,-1,\0000\n' > "$tmp/w2.csv"
refuses "fig3_12: a NUL byte" "$tmp/w2.csv:3: NUL byte" fig_words.py "$tmp/w2.csv"
printf 'step,caretaker_word,selftalk_label\n0,-1,7\n' > "$tmp/w3.csv"
refuses "fig3_12: a word out of range" "$tmp/w3.csv:2: selftalk_label 7 (expected -1 for none or 0-3" fig_words.py "$tmp/w3.csv"
: > "$tmp/w4.csv"
refuses "fig3_12: an empty file" "$tmp/w4.csv:1: empty (expected an ./apps/replay trace" fig_words.py "$tmp/w4.csv"

# tools/best_run.py (Fig. 3.12's individual): the most successes; a tie goes to the lower run
cat > "$tmp/b.csv" <<'CSV'
test,condition,run,individual,successes,trials,excluded,open_jumped,run_label,success_rate,mean_steps_to_target,unstable,generation
robustness,ST-CT,2,0,37,40,0,0,int-stct-s3,0.925,90,0,99
robustness,ST-CT,0,0,30,40,0,0,int-stct-s1,0.75,90,0,99
robustness,ST-CT,1,0,37,40,0,0,int-stct-s2,0.925,90,0,98
robustness,ST,0,0,39,40,0,0,int-st-s1,0.975,90,0,99
CSV
[ "$("$PY" tools/best_run.py "$tmp/b.csv" --condition ST-CT 2>&1)" = "int-stct-s2 0 98" ] &&
  [ "$("$PY" tools/best_run.py "$tmp/b.csv" --condition ST 2>&1)" = "int-st-s1 0 99" ] &&
  ok "best_run: the most successes, ties the lower run" || ko "best_run" "$("$PY" tools/best_run.py "$tmp/b.csv" --condition ST-CT 2>&1)"
"$PY" tools/best_run.py "$tmp/b.csv" > /dev/null 2> "$tmp/err" && ko "best_run: two conditions" ||
  { grep -qF "$tmp/b.csv: conditions ST, ST-CT (expected one: give --condition)" "$tmp/err" && ok "best_run: two conditions refused" || ko "best_run: two conditions" "$(cat "$tmp/err")"; }
refuses "an unknown output format" "$tmp/x.pdf: unknown output format (expected a name ending in .png or .svg)" fig_words.py "$FIG/trace_selftalk.csv" -o "$tmp/x.pdf"

# ---- the same data gives the same SVG
"$PY" tools/fig_boxplot.py "$FX/posteval/summary.csv" --test robustness -o "$tmp/again.svg" > /dev/null 2>&1
cmp -s "$tmp/fig3_4.svg" "$tmp/again.svg" && ok "the same data draws the same SVG" || ko "SVG not reproducible"

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
