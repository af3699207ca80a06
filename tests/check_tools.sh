#!/usr/bin/env bash
# tools/: runs_summary.py and plot_fitness.py on hand-made fitness.csv files whose answers are
# known (which generation completes each stage, how many solved spans the plot draws), and
# grasp_probe's trace against free fall worked out by hand, run_independence's streams,
# trial_sweep and word_map against replay.
set -u
CHECK=check_tools
source "$(dirname "$0")/check_lib.sh"
t=$tmp

# the header of a run's fitness.csv (tools/csvschema.py, from the library's table)
fitness_header() { # INTEGRATED TRIALS
  python3 -c 'import sys; sys.path.insert(0, "tools"); import csvschema
print(",".join(csvschema.fitness_columns(int(sys.argv[1]), int(sys.argv[2]))))' "$1" "$2"
}

# run a: simple-prim completes at generation 2 (first row with all_success >= 5), main-prim at 5
mk() { # DIR then rows "gen stage all_success best trials16"
  local d=$1; shift
  mkdir -p "$d"
  {
    fitness_header 0 16 # a primitive run's
    while [ $# -gt 0 ]; do
      read -r g st all best tr <<<"$1"
      printf '%s,%s,%s,0,0,%s,0,%s,0,1,2,3,4' "$g" "$best" "$best" "$st" "$all"
      for k in $(seq 0 15); do printf ',%s' "${tr:$k:1}"; done
      echo
      shift
    done
  } >"$d/fitness.csv"
}
mk "$t/a" "0 simple-prim 0 10 1000000000000000" "1 simple-prim 4 20 1100000000000000" \
  "2 simple-prim 5 30 1111111111111111" "3 main-prim 0 5 1111000000000000" \
  "4 main-prim 1 6 1111111100000000" "5 main-prim 7 9 1111111111111111" "6 main-prim 9 9 1111111111111110"
mk "$t/b" "0 simple-prim 5 10 1111111111111111" "1 main-prim 2 5 0000000000000000"
mk "$t/c" "0 simple-prim 3 10 0000000000000000" "1 simple-prim 6 10 1111111111111111" \
  "2 simple-prim 6 10 1111111111111111" "3 simple-prim 6 10 1111111111111111" "4 main-prim 5 11 1111111111111111"

out=$(python3 tools/runs_summary.py "$t/a" "$t/b" "$t/c" 2>&1)
row() { echo "$out" | grep "^$1,"; }
[ "$(row "$t/a" | cut -d, -f2-5)" = "7,2,5,main-prim" ] && ok "runs_summary: run a completes at 2 and 5, 7 generations" || ko "runs_summary run a: $(row "$t/a")"
[ "$(row "$t/b" | cut -d, -f3-4)" = "0," ] && ok "runs_summary: run b has no main-prim completion" || ko "runs_summary run b: $(row "$t/b")"
[ "$(row "$t/a" | cut -d, -f8)" = "1111111111111110" ] && ok "runs_summary: final best's trials" || ko "runs_summary trials: $(row "$t/a")"
# simple-prim completions 2, 0, 1: median 1, inclusive quartiles 0.5 and 1.5
echo "$out" | grep -q "^# simple_prim_done: 3 of 3 runs, median 1 (quartiles 0.5, 1.5)" && ok "runs_summary: median and quartiles" || ko "runs_summary stats: $out"
echo "$out" | grep -q "^# main_prim_done: 2 of 3 runs, median 4.5" && ok "runs_summary: main-prim over the runs that completed it" || ko "runs_summary main: $out"

python3 tools/plot_fitness.py "$t/a/fitness.csv" -o "$t/a.svg" >/dev/null 2>&1 || ko "plot_fitness exit"
# trial spans: t0 solved 0..6 (1 span); t1 1..6 (1); t2,t3 2..6; t4..7: 2, then 4..6 -> 2 spans each;
# t8..14: 2, 5 -> 2 spans each; t15: 2, 5 -> 2 spans; total 1+1+2+4*2+7*2+2 = 28
n=$(grep -c '<rect x=' "$t/a.svg")
# 3 panel frames + 28 spans
[ "$n" = 31 ] && ok "plot_fitness: 28 solved spans and 3 panels" || ko "plot_fitness rects: $n"
[ "$(grep -c '<polyline' "$t/a.svg")" = 6 ] && ok "plot_fitness: best, mean and four F_p lines" || ko "plot_fitness lines"
grep -q '>main-prim</text>' "$t/a.svg" && ok "plot_fitness: stage change marked" || ko "plot_fitness stage mark"
python3 tools/plot_fitness.py "$t/a/fitness.csv" --from 100 >/dev/null 2>"$t/err"; rc=$?
[ $rc != 0 ] && grep -q "no generation in the requested range" "$t/err" && ok "plot_fitness: empty range refused" || ko "plot_fitness empty range rc=$rc"
printf 'gen,x\n1,2\n' >"$t/bad.csv"
python3 tools/plot_fitness.py "$t/bad.csv" >/dev/null 2>"$t/err"; rc=$?
[ $rc = 2 ] && grep -q "bad.csv:1: header without generation,best (expected the fitness.csv of ./apps/evolve" "$t/err" && ok "plot_fitness: wrong columns refused, naming the file" || ko "plot_fitness bad csv rc=$rc $(cat "$t/err")"
# a config.ini beside fitness.csv sets the completion threshold: with 6, run c's main-prim
# (at most 5 genotypes solving everything) is not complete, its simple-prim still at 1
cp -r "$t/c" "$t/c6" && printf '[ga]\n# comment\nsuccess_genotypes = 6\n' > "$t/c6/config.ini"
[ "$(python3 tools/runs_summary.py "$t/c6" | grep "^$t/c6," | cut -d, -f3-4)" = "1," ] &&
  ok "runs_summary: ga.success_genotypes of config.ini" || ko "runs_summary threshold: $(python3 tools/runs_summary.py "$t/c6")"
python3 tools/runs_summary.py "$t/nope" >/dev/null 2>"$t/err"; rc=$?
[ $rc != 0 ] && grep -q "nope/fitness.csv" "$t/err" && ok "runs_summary: missing run refused, naming the file" || ko "runs_summary missing rc=$rc"
# PNG (matplotlib, Debian's python3): a 1000-pixel-wide PNG; and without matplotlib a clear refusal
PY=${PYTHON:-/usr/bin/python3}
"$PY" tools/plot_fitness.py "$t/a/fitness.csv" -o "$t/a.png" >/dev/null 2>"$t/err"
if [ "$("$PY" -c 'import struct, sys; d = open(sys.argv[1], "rb").read(24)
print(d[:8] == b"\x89PNG\r\n\x1a\n", struct.unpack(">I", d[16:20])[0])' "$t/a.png" 2>&1)" = "True 1000" ]; then
  ok "plot_fitness: PNG written (1000 px wide)"
else
  ko "plot_fitness PNG: $(cat "$t/err")"
fi
"$PY" -c 'import runpy, sys; sys.modules["matplotlib"] = None; sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")' tools/plot_fitness.py "$t/a/fitness.csv" -o "$t/b.png" \
  >/dev/null 2>"$t/err"; rc=$?
[ $rc != 0 ] && grep -q "b.png: PNG needs matplotlib" "$t/err" && [ ! -e "$t/b.png" ] &&
  ok "plot_fitness: PNG without matplotlib refused, naming the fix" || ko "plot_fitness no matplotlib rc=$rc $(cat "$t/err")"
# run_report (the end of make run): run a completes simple-prim at 2 (rows 0-2) and main-prim at
# 5 (rows 3-5); its last best (generation 6) solves all but trial 15; the plot is drawn beside it
out=$("$PY" tools/run_report.py "$t/a" 2>&1)
if grep -qF "simple-prim: complete at generation 2 (5 genotypes solve every trial; 5 needed), after 3 generations" <<<"$out" &&
   grep -qF "main-prim: complete at generation 5 (7 genotypes solve every trial; 5 needed), after 3 generations" <<<"$out" &&
   grep -qF "(6, main-prim): fitness 9.00, solves 15/16 trials (reach 4/4, open 4/4, grasp 4/4, move 3/4)" <<<"$out" &&
   grep -qF "redraw the plot: $PY tools/plot_fitness.py $t/a/fitness.csv -o $t/a/fitness.png" <<<"$out" &&
   [ -s "$t/a/fitness.png" ]; then
  ok "run_report: stage completions, the best's successes, the plot and its command"
else
  ko "run_report: $out"
fi
# with ga.success_genotypes = 9 simple-prim never completes (at most 5) and main-prim does at 6
printf '[ga]\nsuccess_genotypes = 9\n' > "$t/a/config.ini"
out=$("$PY" tools/run_report.py "$t/a" --no-plot 2>&1)
grep -qF "simple-prim: not complete after 3 generations (at most 5 of the 9 genotypes needed" <<<"$out" &&
  grep -qF "main-prim: complete at generation 6 (9 genotypes" <<<"$out" &&
  ok "run_report: the threshold of config.ini" || ko "run_report threshold: $out"
# and how the run departs from the thesis's protocol, tier by tier (tools/keytable.py): the
# threshold is the protocol's (a real in config.ini's %.17g shown in its shortest digits); a
# seed is the run's own, not a departure; free motion is speed
printf '[run]
seed = 4
threads = 2
[ga]
success_genotypes = 9
[stage]
handover = true
[postures]
grasp_partial_oppose = 0.90000000000000002
' > "$t/a/config.ini"
out=$("$PY" tools/run_report.py "$t/a" --no-plot 2>&1)
grep -qxF "  how it departs from the thesis's protocol (config.ini, each key's default after it):" <<<"$out" &&
  grep -qxF "    protocol: ga.success_genotypes = 9 (5), postures.grasp_partial_oppose = 0.9 (0.5)" <<<"$out" &&
  grep -qxF "    extension: stage.handover = true (false)" <<<"$out" &&
  grep -qxF "    speed (the same results): run.threads = 2 (0)" <<<"$out" && ! grep -q "run.seed" <<<"$out" &&
  ok "run_report: the keys away from the thesis's protocol, by tier" || ko "run_report departures: $out"
printf '[run]
seed = 4
' > "$t/a/config.ini"
grep -qxF "  the thesis's protocol: no key away from it (config.ini)" <<<"$("$PY" tools/run_report.py "$t/a" --no-plot 2>&1)" &&
  ok "run_report: a run of the thesis's protocol says so" || ko "run_report no departure"
# which starts and solver (issue 46): a config.ini without the keys (made before them) reads with
# the thesis's defaults, position-only starts and the dense LCP; simple-prim has no solver
out=$("$PY" tools/run_report.py "$t/a" --no-plot 2>&1)
printf '[stage]\nstages = main_prim\n[postures]\nreach_palm_down = true\n[dynamics]\nlcp = schur\n' > "$t/a/config.ini"
out2=$("$PY" tools/run_report.py "$t/a" --no-plot 2>&1)
grep -qxF "  reach starts position only, palm as the arm leaves it (postures.reach_palm_down); contact none (simple-prim is kinematic)" <<<"$out" &&
  grep -qxF "  reach starts palm down (postures.reach_palm_down); contact ODE, dynamics.lcp = schur" <<<"$out2" &&
  ok "run_report: the run's reach starts and contact solver" || ko "run_report starts and solver: $out $out2"
# trial_sweep: the final best of prims_s2 on reach k=1 and grasp k=0 at the offsets of its last
# generation (831) is replay's trial (same success and sum_S); lines in (generation, genotype,
# trial) order whatever --threads; a bad --generations refused
ts="${BUILD:-build}/trial_sweep"
r2=data/evolved/prims_s2
sw=$("$ts" $r2/config.ini $r2/population.genome --trials 1,8 --generations 831:831 --count 1 2>&1)
same=1
for k in 1 8; do
  rep=$("${APPDIR:-apps}/replay" $r2/population.genome $r2/config.ini --trial $k --stage main --generation 831 --index 0 2>/dev/null |
        sed -n 's/.* success=\([01]\) .* sum_S=\([0-9.]*\) sum_P=\([0-9.]*\) .*/success=\1 .* sum_S=\2 sum_P=\3 /p')
  [ -n "$rep" ] && grep -qE "^831 0 $k $rep" <<<"$sw" || same=0
done
if [ $same = 1 ]; then ok "trial_sweep: replay's trials"; else ko "trial_sweep vs replay" "$sw"; fi
"$ts" $r2/config.ini $r2/population.genome --trials 0,1 --generations 830:831 --count 2 --threads 2 >"$t/ts2" 2>&1
"$ts" $r2/config.ini $r2/population.genome --trials 0,1 --generations 830:831 --count 2 --threads 1 >"$t/ts1" 2>&1
if [ "$(awk '{print $1, $2, $3}' "$t/ts2" | tr '\n' ' ')" = "830 0 0 830 0 1 830 1 0 830 1 1 831 0 0 831 0 1 831 1 0 831 1 1 " ] &&
   cmp -s "$t/ts1" "$t/ts2"; then
  ok "trial_sweep: order and threads"
else
  ko "trial_sweep order" "$(head -3 "$t/ts2")"
fi
# sweep_summary.py on hand-made rows: genotype 0's palm x is 0.1 + 0.5 obj x (a gain of 0.5),
# genotype 1 solves all 4 trials, genotype 0 fails trial 1
for i in 0 1; do for k in 0 1 2 3; do
  ok1=1; [ $i = 0 ] && [ $k = 1 ] && ok1=0
  x=$(awk -v k=$k 'BEGIN { printf "%.4f", 0.2 + 0.1 * k }'); px=$(awk -v x="$x" 'BEGIN { printf "%.4f", 0.1 + 0.5 * x }')
  echo "7 $i $k success=$ok1 steps=100 sum_S=50 sum_P=0 min_d_r=0.02 final_d_r=0.02 first_success_step=3 palm=$px,0.1,0.05 obj=$x,0.1,-0.045"
done; done >"$t/sweep.txt"
out=$(python3 tools/sweep_summary.py "$t/sweep.txt" 2>&1)
grep -qF "trial 1: solved in 50.0% of genotype x generation; by 1 genotypes at 7" <<<"$out" &&
  grep -qF "all listed trials: genotypes per generation 1/1/1" <<<"$out" &&
  grep -qF "palm x = 0.50 obj x +0.100" <<<"$out" &&
  ok "sweep_summary: solved counts and the reach gain" || ko "sweep_summary" "$out"
"$ts" $r2/config.ini $r2/population.genome --generations 5:2 >/dev/null 2>"$t/err"; rc=$?
[ $rc = 2 ] && grep -q "expected FIRST:LAST" "$t/err" && ok "trial_sweep: bad --generations refused" || ko "trial_sweep bad generations rc=$rc"
# grasp_probe --trace: a hand held 5 cm above the ball that never closes leaves it alone, so once
# the table collision goes off after step 39 the ball free-falls by ODE's semi-implicit Euler,
# g h^2 n (n + 1) / 2 after n sub-steps of h = 0.01 s: 0.01471 m after step 40 (n = 5), 0.05396 m
# after step 41 (n = 10), when the centre is 3.5 cm under its resting height and the trial ends
# (42 steps, not held).
gp="${BUILD:-build}/grasp_probe"
out=$("$gp" --trace 0.05,0,0,0 --close-step 80 --thumb-flex 0 --finger-flex 0 2>&1)
z() { echo "$out" | awk -v s="$1" '$1 == s && $2 == "ball" { print $5 }'; }
if awk -v r="$(z 39)" -v a="$(z 40)" -v b="$(z 41)" 'BEGIN {
     g = 9.81 * 0.01 * 0.01 / 2; d1 = r - g * 30 - a; d2 = r - g * 110 - b;
     exit !(r != "" && d1 < 2e-4 && d1 > -2e-4 && d2 < 2e-4 && d2 > -2e-4) }' &&
   echo "$out" | grep -q "^trial 0: success 0, 42 steps$"; then
  ok "grasp_probe: untouched ball free-falls from step 40 and the trial ends at 42 steps"
else
  ko "grasp_probe free fall: $(echo "$out" | sed -n '40,43p')"
fi
"$gp" --trace 0,0,2,0 >/dev/null 2>"$t/err"; rc=$?
[ $rc = 2 ] && grep -q "expected GAP,DX,OPPOSE,K" "$t/err" && ok "grasp_probe: bad --trace refused" || ko "grasp_probe bad trace rc=$rc"
# grasp_probe --hand: fingertips in the palm frame. Open hand: iKin's FK puts the index, middle,
# ring and little tips 0.074, 0.087, 0.076, 0.067 m along the fingers from the arm's end-effector
# (reference/icub_facts.md §2.3), and the palm centre sits 0.0134 m behind it (gen_icub_urdf.py).
# Thumb fully opposed, not flexed: iKin hangs it along the palm normal from near the palm
# centre (|x|, |y| < 1.5 cm); the model moves its base 3.5 cm towards the wrist (data/README.md,
# "Hand"), so it hangs 3.5 cm behind that: x in -5..-2 cm, |y| < 1.5 cm, more than 7 cm down.
out=$("$gp" --hand 0,0,0 2>&1)
tipx() { echo "$out" | awk -v f="$1" '$1 == f { print $2 }'; }
opp=$("$gp" --hand 1,0,0 2>&1 | awk '$1 == "thumb" { print $2, $3, $4 }')
if awk -v i="$(tipx index)" -v m="$(tipx middle)" -v r="$(tipx ring)" -v l="$(tipx little)" -v o="$opp" 'BEGIN {
     split(o, t, " "); e = 0.001; c = 0.0134
     d[1] = i - 0.074 - c; d[2] = m - 0.087 - c; d[3] = r - 0.076 - c; d[4] = l - 0.067 - c
     for (k = 1; k <= 4; k++) if (!(d[k] < e && d[k] > -e)) exit 1
     exit !(t[3] > 0.07 && t[1] < 0.015 - 0.035 && t[1] > -0.015 - 0.035 && t[2] < 0.015 && t[2] > -0.015) }'; then
  ok "grasp_probe --hand: open-hand tips match iKin's FK; the opposed thumb hangs 3.5 cm behind the palm centre"
else
  ko "grasp_probe --hand: $out / thumb opposed: $opp"
fi
"$gp" --hand 1,2,0 >/dev/null 2>"$t/err"; rc=$?
[ $rc = 2 ] && grep -q "expected OPPOSE,THUMB,FINGERS, each in 0..1" "$t/err" && ok "grasp_probe: bad --hand refused" || ko "grasp_probe bad hand rc=$rc"
# grasp_probe --basin: the default hand holds the ball in at least 10 % of the 720 closings
# (issue 12's target; 84 when measured, data/README.md §3b) and every hold has its line
OMP_NUM_THREADS=2 "$gp" --basin > "$t/basin2" 2>&1
if awk '/^basin held=/ { split($2, h, "="); split($3, n, "="); held = h[2]; total = n[2] }
        /^held trial / { lines++ }
        END { exit !(total == 720 && held >= 72 && lines == held) }' "$t/basin2"; then
  ok "grasp_probe --basin: $(tail -1 "$t/basin2") (>= 10 %)"
else
  ko "grasp_probe --basin: $(tail -1 "$t/basin2")"
fi
# screen_report.py: a hand-made screen whose row is known: 3 generations at 40 s (elapsed
# 0:02:00 after generation 2), the last row's 15 fixed and 2 hand-over trials solved, three
# genotypes with 3, 0 and 0 successes of 4 trials (median 0, one genotype >= 1), heard rogm 3,
# ro 9, open jumped in 1; with no words 0 of 12
s="$t/screen/handover-pop-s1"
mkdir -p "$s/integration" "$s/integration-nowords"
{
  printf 'generation,best,mean,worst'
  for k in $(seq 0 15); do printf ',best_t%d' "$k"; done
  printf ',best_handovers'; for k in $(seq 0 11); do printf ',best_h%d' "$k"; done; echo
  for g in 0 1 2; do
    printf '%d,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,0,9,1,1,0,0,0,0,0,0,0,0,0,0\n' "$g"
  done
} > "$s/fitness.csv"
printf 'gen    2 main-prim best 1 | 0.03 gen/s elapsed 0:02:00 left <= 0:00:00\n' > "$s/progress.log"
for d in integration integration-nowords; do
  w=$([ $d = integration ] && echo 3 || echo 0)
  { echo "test,run,individual,successes,trials"; echo "integration,0,0,$w,4"
    echo "integration,0,1,0,4"; echo "integration,0,2,0,4"; } > "$s/$d/summary.csv"
  { echo "heard,open_jumped,success"
    for h in rogm rogm rogm ro ro ro ro ro ro ro ro ro; do echo "$h,0,0"; done; } > "$s/$d/trials.csv"
done
sed -i '2s/,0,0$/,1,0/' "$s/integration/trials.csv"
out=$(python3 tools/screen_report.py "$s" 2>&1)
if grep -qF '| `handover-pop-s1` | 3 | 40 s | 15/16, hand-over 2/12 | 3 of 12 | 0 | 1 of 3 | `ro` 9, `rogm` 3 | 1 | 0 of 12 |' <<<"$out"; then
  ok "screen_report: the row of a hand-made screen"
else
  ko "screen_report: $out"
fi
# a screen with varied trials: before postures.vary_replace_generations (5 here) the varied
# columns are 0 because the drawn starts replace open's and grasp's, which the row says; from
# it, the varied trials solved (3 of 8 in the hand-made last row)
v="$t/screen/sched-pop-s1"
mkdir -p "$v"
{ printf 'generation,best,mean,worst'; for k in $(seq 0 15); do printf ',best_t%d' "$k"; done
  for k in $(seq 0 7); do printf ',best_v%d' "$k"; done; echo
  for g in 0 1 2; do printf '%d,1,1,1' "$g"; for k in $(seq 0 15); do printf ',1'; done
    for k in $(seq 0 7); do printf ',%d' $((g == 2 && k < 3)); done; echo; done; } > "$v/fitness.csv"
printf '[postures]\nvary_replace_generations = 5\n' > "$v/config.ini"
out5=$(python3 tools/screen_report.py "$v" 2>&1)
sed -i 's/= 5$/= 2/' "$v/config.ini"
out2=$(python3 tools/screen_report.py "$v" 2>&1)
if grep -qF '| 16/16, varied: replacing (open and grasp from drawn starts) |' <<<"$out5" &&
   grep -qF '| 16/16, varied 3/8 |' <<<"$out2"; then
  ok "screen_report: varied trials, and the generations the drawn starts replace"
else
  ko "screen_report varied: $out5 $out2"
fi
python3 tools/screen_report.py "$t/nope" >/dev/null 2>"$t/err"; rc=$?
[ $rc = 2 ] && grep -q "screen_report: $t/nope/fitness.csv" "$t/err" && ok "screen_report: a missing screen named" || ko "screen_report missing rc=$rc $(cat "$t/err")"
# tools/runconfig.py, the tools' one reader of a run's config.ini: a key in its own section
# (not another section's key of the same name), the default without the file or the key, and a
# value it cannot convert named with FILE:LINE
r="$t/rc"; mkdir -p "$r"
printf '[stage]\nsuccess_genotypes = 7\n[ga]\n; note\nsuccess_genotypes = 3  # three\n[fitness]\nbonus = x\n' > "$r/config.ini"
if out=$(python3 - "$r" "$t/none" <<'PY'
import sys
sys.path.insert(0, "tools")
import runconfig
got = [runconfig.value(sys.argv[1], "ga", "success_genotypes", 5, int),
       runconfig.value(sys.argv[2], "ga", "success_genotypes", 5, int),
       runconfig.value(sys.argv[1], "ga", "population", 100, int)]
try:
    runconfig.value(sys.argv[1], "fitness", "bonus", 10.0, float)
    err = "accepted"
except ValueError as e:
    err = str(e)
print(got, err)
sys.exit(0 if got == [3, 5, 100] and err == sys.argv[1] + "/config.ini:7: fitness.bonus 'x' (expected a number)" else 1)
PY
); then ok "runconfig: a key of a run's config.ini ($out)"; else ko "runconfig" "$out"; fi
# ---- tools/csvschema.py and tools/keytable.py: the library's column tables and key table as
# the tools take them, generated from the C tables: each committed file is what its tools/*.c
# prints
generated() { # NAME WHAT: tools/NAME.py against build/NAME's output
  local gen="${BUILD:-build}/$1"
  if "$gen" > "$t/$1.py" && cmp -s "$t/$1.py" "tools/$1.py"; then
    ok "tools/$1.py is what $2 give ($gen)"
  else
    ko "tools/$1.py differs from $2: regenerate it with $gen > tools/$1.py" \
      "$(diff "$t/$1.py" "tools/$1.py" | head -20)"
  fi
}
generated csvschema "the library's tables"
generated keytable "the library's key table (its tiers and defaults)"
gen="${BUILD:-build}/csvschema"
# its defaults read as config.ini writes them: a run of the shipped simple-prim config departs in
# its --set keys, its --generations (the cap key, issue 48), the shipped grasp starts' thumb (our
# reading, protocol tier), the shipped palm-down starts and keyed streams (extensions) alone
"${APPDIR:-apps}/evolve" configs/simple_prim.cfg --generations 1 --set ga.population=2 \
  --set ga.elites=1 --set ga.parents=1 --set ga.success_genotypes=1 --out "$t/kt" > /dev/null 2>&1
if [ "$(python3 -c 'import sys; sys.path.insert(0, "tools"); import keytable
print(keytable.departures(sys.argv[1]))' "$t/kt/config.ini")" = "[('protocol', 'ga.population', '2', '100'), ('protocol', 'ga.elites', '1', '10'), ('protocol', 'ga.parents', '1', '20'), ('protocol', 'ga.success_genotypes', '1', '5'), ('protocol', 'ga.max_generations', '1', '1500'), ('protocol', 'postures.grasp_partial_oppose', '0.90000000000000002', '0.5'), ('extension', 'run.rng_seed', 'apart', 'plain'), ('extension', 'postures.reach_palm_down', 'true', 'false')]" ]; then
  ok "keytable.departures: a run's config.ini away from the defaults in its --set keys and the shipped starts"
else
  ko "keytable.departures" "$(python3 -c 'import sys; sys.path.insert(0, "tools"); import keytable
print(keytable.departures(sys.argv[1]))' "$t/kt/config.ini")"
fi
# its fitness.csv layouts are the library's (st_fitness_csv), primitive and integrated, with and
# without each kind of trials (none, one, the most of it)
if out=$(python3 - "$gen" <<'PY'
import itertools, subprocess, sys
sys.path.insert(0, "tools")
import csvschema
bad = []
others = [k for k in csvschema.TRIAL_KINDS if k != "fixed"]
counts = [sorted({0, 1, m}) for m in (csvschema.TRIAL_KINDS[k] for k in others)]
layouts = [(i, t, dict(zip(others, c))) for i in (0, 1) for t in (0, 1, 8, 16)
           for c in itertools.product(*counts)]
for i, t, kinds in layouts:
    arg = ["%s=%d" % kv for kv in kinds.items()]
    lib = subprocess.run([sys.argv[1], "--fitness-header", str(i), str(t)] + arg,
                         capture_output=True, text=True, check=True).stdout.rstrip("\n").split(",")
    if csvschema.fitness_columns(i, t, kinds) != lib:
        bad.append("%s" % ((i, t, kinds),))
print("%d layouts" % len(layouts), *bad)
sys.exit(1 if bad else 0)
PY
); then ok "csvschema.fitness_columns: the library's layouts ($out)"; else ko "csvschema fitness layouts" "$out"; fi
# every tool that reads a results file takes its column names from csvschema.pick, and every
# name it picks is one of the library's: a column renamed or dropped in C fails here
if out=$(python3 - tools/*.py <<'PY'
import ast, sys
sys.path.insert(0, "tools")
import csvschema
bad, seen = [], 0
for path in sys.argv[1:]:
    if path.endswith("csvschema.py"):
        continue
    src = open(path).read()
    tree = ast.parse(src)
    picks = [n for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
             and n.func.attr == "pick" and getattr(n.func.value, "id", "") == "csvschema"]
    reads = any(f in src for f in ("fitness.csv", "summary.csv", "trials.csv"))
    if reads and not picks:
        bad.append(path + ": names a results file but takes no column from csvschema.pick")
    for call in picks:
        seen += 1
        table = getattr(csvschema, call.args[0].attr)
        for a in call.args[1:]:
            if isinstance(a, ast.Starred):  # a generated list of names: evaluated as the tool does
                names = list(eval(compile(ast.Expression(a.value), path, "eval"), {"PRIMS": ["reach", "open", "grasp", "move"]}))
            else:
                names = [a.value]
            bad += ["%s:%d: '%s' is no column of %s" % (path, call.lineno, n, call.args[0].attr)
                    for n in names if n not in table]
print("%d picks" % seen, *bad)
sys.exit(1 if bad or seen < 10 else 0)
PY
); then ok "tools: every column name picked is the library's ($out)"; else ko "tools' column names" "$out"; fi

# ---- malformed input (issue 48): every Python tool says FILE:LINE: and what it expected, exit 2,
# never a traceback. First the cases the issue names, then the sweep over every tool.
PYT=${PYTHON:-/usr/bin/python3}
refused() { # NAME NEEDLE CMD...: exit 2, NEEDLE on stderr, no traceback
  local name=$1 needle=$2; shift 2
  "$@" > "$t/o" 2> "$t/e"; local rc=$?
  if [ $rc = 2 ] && grep -qF -- "$needle" "$t/e" && ! grep -q Traceback "$t/e"; then ok "$name"
  else ko "$name" "rc=$rc $(head -c 600 "$t/e")"; fi
}
mkdir -p "$t/nan" "$t/dup"
sed '4s/^2,30,/2,nan,/' "$t/a/fitness.csv" > "$t/nan/fitness.csv"
sed '3p' "$t/a/fitness.csv" > "$t/dup/fitness.csv"   # generation 1 twice
for tool in plot_fitness runs_summary run_report; do
  arg() { [ $tool = plot_fitness ] && echo "$1/fitness.csv" || echo "$1"; }
  refused "$tool: a nan fitness refused" "$t/nan/fitness.csv:4: best 'nan' (expected a finite number)" \
    "$PYT" tools/$tool.py "$(arg "$t/nan")" $([ $tool = run_report ] && echo --no-plot)
  refused "$tool: a generation given twice refused" "$t/dup/fitness.csv:4: generation 1 again (first at line 3" \
    "$PYT" tools/$tool.py "$(arg "$t/dup")" $([ $tool = run_report ] && echo --no-plot)
done
# replicate.mk cost (tools/replicate_cost.py) on a bad cache of measured costs: a row of this
# host and build without its count (was KeyError: 'n'), a nan cost (was "nan core-hours"), and
# --assume nan; a stand-in for build/eval_cost that prints its plan at once
printf '#!/bin/sh\necho individual,cpu_s\necho "# plan: population=10 generations=10 replace_generations=0 trials=4 individuals=2"\n' > "$t/eval_cost"
chmod +x "$t/eval_cost"
build=$(sha256sum "$t/eval_cost" | cut -c1-12) host=$(hostname)
mkdir -p "$t/rep/cost"
cost() { "$PYT" tools/replicate_cost.py --preset tiny --protocol thesis --runs 1 --out "$t/rep" --eval-cost "$t/eval_cost" "$@"; }
key="configs/prims.cfg --population data/evolved/prims_s2/population.genome --count 1"
printf 'host,build,kind,args,mean_cpu_s,min_cpu_s,max_cpu_s,measured\n%s,%s,prims,%s,0.5,0.4,0.6,now\n' "$host" "$build" "$key" > "$t/rep/cost/costs.csv"
refused "replicate cost: a cache without its count column refused" \
  "$t/rep/cost/costs.csv:1: header without n (expected the measured costs replicate cost keeps" cost
printf 'host,build,kind,args,n,mean_cpu_s,min_cpu_s,max_cpu_s,measured\n%s,%s,prims,%s,1,nan,0.4,0.6,now\n' "$host" "$build" "$key" > "$t/rep/cost/costs.csv"
refused "replicate cost: a nan cost in the cache refused" "$t/rep/cost/costs.csv:2: mean_cpu_s 'nan' (expected a finite number > 0)" cost
rm "$t/rep/cost/costs.csv"
refused "replicate cost: --assume nan refused" "--assume *=nan: expected KIND=SECONDS, a finite number > 0" cost --assume '*=nan'
if cost --assume '*=0.5' > "$t/o" 2> "$t/e" && grep -qE '^total [0-9.]+ core-hours' "$t/o" && ! grep -qi nan "$t/o"; then
  ok "replicate cost: with costs assumed, a total in core-hours ($(tail -1 "$t/o"))"
else ko "replicate cost, assumed" "$(cat "$t/e"; tail -3 "$t/o")"; fi
# tools/mpi_model.py reads a replication's own costs.csv: the model kind by kind
if "$PYT" tools/mpi_model.py data/evolved/study/cost/costs.csv --slots 1,2 --samples 3 > "$t/o" 2> "$t/e" &&
   [ "$(grep -c '^# data/evolved/study/cost/costs.csv: .* s an evaluation, every individual at it$' "$t/o")" = \
     "$(($(grep -vc '^host,' data/evolved/study/cost/costs.csv)))" ]; then
  ok "mpi_model: a replication's costs.csv, kind by kind"
else ko "mpi_model on costs.csv" "$(cat "$t/e"; head -3 "$t/o")"; fi
# the sweep: every tool, ~1500 malformed inputs (tests/tools_sweep.py)
if "$PYT" tests/tools_sweep.py "$t/sweep" > "$t/sweep.out" 2>&1; then
  ok "malformed CSVs: $(tail -1 "$t/sweep.out" | sed 's/^tools_sweep: //'): exit 2 with FILE:LINE, no traceback"
else ko "malformed CSVs" "$(head -c 3000 "$t/sweep.out")"; fi
# run_independence streams (issue 47): the integrated runs' draws across seeds 1-5 of the
# palm-down study, as the library keys them: with run.rng_seed = plain (the default, the key of
# the runs committed before study46b) two keys meet, seed 4's and seed 5's generation-0 offsets
# and new genes; with apart none
ri="${BUILD:-build}/run_independence"
cfg=data/evolved/study_palm_down/int-stct-s1/config.ini
if out=$("$ri" streams "$cfg" 2>&1) &&
   grep -q "identical: 0 of 8000" <<<"$out" && grep -q "shared between two: 2 of 449050" <<<"$out" &&
   grep -q "seed 4 stream 5 (0, 0, 0) = seed 5 stream 4 (0, 0, 0)" <<<"$out" &&
   out2=$("$ri" streams "$cfg" run.rng_seed=apart 2>&1) &&
   grep -q "repeated: 0 of 2970" <<<"$out2" && grep -q "shared between two: 0 of 449050" <<<"$out2"; then
  ok "run_independence: no offsets shared by two seeds; plain keys meet twice (seeds 4, 5), apart never"
else
  ko "run_independence streams" "$out ${out2:-}"
fi

# word_map: the palm-down study's ST seed 1, trial 0 of generation 99, is replay's trial (its
# success, steps, and at every step the label said, from replay's trace, and heard the step after);
# among the labels it would have said, the one for the word really heard is the one said (the
# copied state steps as the real one); a primitive stage's config refused
wm="${BUILD:-build}/word_map"
st1=data/evolved/study_palm_down/int-st-s1
"$wm" $st1/config.ini $st1/best.genome --trial 0 --steps > "$t/wm" 2>&1
"${APPDIR:-apps}/replay" $st1/best.genome $st1/config.ini --trial 0 --out "$t/wm.csv" > "$t/wm.rep" 2>&1
if "$PY" - "$t/wm" "$t/wm.csv" "$t/wm.rep" <<'PY'
import csv, re, sys
wm = open(sys.argv[1]).read().splitlines()
tr = list(csv.DictReader(open(sys.argv[2])))
rep = open(sys.argv[3]).read()
head = re.match(r"genotype \d+ of \S+, trial 0 of generation 99 \(words selftalk\): success (\d), (\d+) steps$", wm[0])
want = re.search(r"success=(\d) steps=(\d+)/", rep)
assert head and want and head.groups() == want.groups(), (wm[0], want)
L = "-rogm"
steps = [l.split() for l in wm if l.startswith("step ")]
assert len(steps) == len(tr) == int(want.group(2)), (len(steps), len(tr))
prev = "-"  # self talk: the label said at t is heard at t + 1, nothing at step 0
for f, row in zip(steps, tr):
    heard, said, would = f[3], f[5], f[7:]
    assert heard == prev, (f, prev)
    assert said == L[int(row["selftalk_label"]) + 1], (f, row["selftalk_label"])
    prev = said
    assert would[L.index(heard)] == said, f
PY
then ok "word_map: replay's trial, and the label for the word heard is the one said"
else ko "word_map vs replay" "$(head -3 "$t/wm")"; fi
if ! "$wm" configs/prims.cfg $st1/best.genome > /dev/null 2> "$t/wm.err" &&
   grep -qF "configs/prims.cfg: expected an integrated stage's config with a talking network" "$t/wm.err"; then
  ok "word_map: a primitive stage's config refused"
else ko "word_map refusal" "$(cat "$t/wm.err")"; fi

echo "check_tools: $pass passed, $fail failed"
[ "$fail" = 0 ]
