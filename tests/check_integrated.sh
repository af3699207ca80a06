#!/usr/bin/env bash
# The integrated stage end to end: ./apps/score prediction on hand-worked files; the four
# condition configs run (a tiny population, short trials), resume to identical files and give
# the same files on 1 and 2 threads; frozen genes never change; replay of an integrated
# individual; bad integrated configs refused before any work.
set -uo pipefail
CHECK=check_integrated
source "$(dirname "$0")/check_lib.sh"

# ---- score prediction: the perfect predictor and the late switch of tests/test_prediction.c,
# as two trials of one file (values worked out by hand there: F_step 100 and 80, F_switch
# 25 (1 + 3 (0.5 S8 + 0.5)) and 25 (3 + 0.5 S4 + 0.08), B_pred 40 and 30, S8 = 1/(1 + e^-0.8),
# S4 = 1/(1 + e^-0.4)); T = 2
cat > "$tmp/pred.csv" <<'CSV'
step,word,o_reach,o_open,o_grasp,o_move
# the perfect predictor: the outputs at t name the word of t + 1
0,-1,0.9,0.1,0.1,0.1
1,0,0.9,0.1,0.1,0.1
2,0,0.1,0.9,0.1,0.1
3,1,0.1,0.9,0.1,0.1
4,1,0.1,0.1,0.9,0.1
5,2,0.1,0.1,0.9,0.1
6,2,0.1,0.1,0.1,0.9
7,3,0.1,0.1,0.1,0.9

0,-1,0.8,0.2,0.1,0.1
1,0,0.8,0.2,0.1,0.1
2,0,0.7,0.5,0.1,0.1
3,1,0.2,0.8,0.1,0.1
4,1,0.2,0.8,0.1,0.1
CSV
if "$APPDIR/score" prediction "$tmp/pred.csv" --per-trial > "$tmp/pred.out" 2>&1 &&
   python3 - "$tmp/pred.out" <<'PY'
import math, re, sys
S8, S4 = 1 / (1 + math.exp(-0.8)), 1 / (1 + math.exp(-0.4))
fs = [100.0, 80.0]
fw = [25 * (1 + 3 * (0.5 * S8 + 0.5)), 25 * (3 + 0.5 * S4 + 0.08)]
b = [40.0, 30.0]
want = {"F_step": sum(fs) / 2, "F_switch": sum(fw) / 2, "B_pred": sum(b),
        "F_pred": sum(b) + sum(x / 3 + 2 * y / 3 for x, y in zip(fs, fw)) / 2}
lines = open(sys.argv[1]).read().splitlines()
got = dict(re.findall(r"(\w+)=(\S+)", lines[-1]))
per = [dict(re.findall(r"(\w+)=(\S+)", l)) for l in lines[:-1]]
ok = all(abs(float(got[k]) - v) < 1e-9 for k, v in want.items()) and len(per) == 2
ok = ok and all(abs(float(per[i]["F_switch"]) - fw[i]) < 1e-9 for i in range(2))
ok = ok and re.fullmatch(r"F_step=\S+ F_switch=\S+ B_pred=\S+ F_pred=\S+", lines[-1]) is not None
print("score:", lines[-1], "want", want)
sys.exit(0 if ok else 1)
PY
then ok "score prediction agrees with the hand-worked values (2 trials, per trial and total)"
else ko "score prediction" "$(cat "$tmp/pred.out")"; fi

printf '0,-1,0.9,0.1,0.1,0.1\n2,0,0.9,0.1,0.1,0.1\n' > "$tmp/bad1.csv"
printf '0,-1,0.9,0.1,0.1,0.1\n1,7,0.9,0.1,0.1,0.1\n' > "$tmp/bad2.csv"
printf '0,-1,0.9,0.1,0.1\n' > "$tmp/bad3.csv"
printf '0,-1,0.9,0.1,0.1,0.1\n1,0,0.9,0.1,0.1,0.1\n2,-1,0.9,0.1,0.1,0.1\n' > "$tmp/bad4.csv"
# the caretaker's words never go back (issue 48: grasp after move was scored)
printf '0,-1,0.9,0.1,0.1,0.1\n1,0,0.9,0.1,0.1,0.1\n2,3,0.9,0.1,0.1,0.1\n3,2,0.9,0.1,0.1,0.1\n\n0,-1,0.9,0.1,0.1,0.1\n1,1,0.9,0.1,0.1,0.1\n' > "$tmp/bad10.csv"
"$APPDIR/score" prediction "$tmp/bad1.csv" > /dev/null 2> "$tmp/e1"; r1=$?
"$APPDIR/score" prediction "$tmp/bad2.csv" > /dev/null 2> "$tmp/e2"; r2=$?
"$APPDIR/score" prediction "$tmp/bad3.csv" > /dev/null 2> "$tmp/e3"; r3=$?
"$APPDIR/score" prediction "$tmp/bad4.csv" > /dev/null 2> "$tmp/e4"; r4=$?
"$APPDIR/score" integrated "$tmp/pred.csv" > /dev/null 2> "$tmp/e5"; r5=$?
"$APPDIR/score" prediction "$tmp/bad10.csv" > /dev/null 2> "$tmp/e10"; r10=$?
if [ $r1 = 2 ] && grep -q "bad1.csv:2: step '2' (expected 1" "$tmp/e1" &&
   [ $r2 = 2 ] && grep -q "bad2.csv:2: word '7' (expected -1 for none or 0-3" "$tmp/e2" &&
   [ $r3 = 2 ] && grep -q "bad3.csv:1: 5 fields (expected 6" "$tmp/e3" &&
   [ $r4 = 2 ] && grep -q "bad4.csv:3: word -1 after 0 (expected the caretaker's words in order, never back" "$tmp/e4" &&
   [ $r5 = 2 ] && grep -q "'integrated': unknown fitness (expected prediction)" "$tmp/e5" &&
   [ $r10 = 2 ] && grep -q "bad10.csv:4: word 2 after 3 (expected the caretaker's words in order, never back" "$tmp/e10"; then
  ok "score refuses bad rows naming FILE:LINE (words going back too), and unknown fitness functions"
else
  ko "score refusals" "$(cat "$tmp"/e[1-5] "$tmp/e10")"
fi
# rows with an empty field (strtok took ",," for one comma), a second header line (skipped
# anywhere before), finite outputs whose differences overflow (1 - (h1 - o) = -inf)
printf '0,-1,0.9,,0.1,0.1,0.1\n1,0,0.9,0.1,0.1,0.1\n' > "$tmp/bad6.csv"
printf 'step,word,o_reach,o_open,o_grasp,o_move\n0,-1,0.9,0.1,0.1,0.1\n1,0,0.9,0.1,0.1,0.1\nstep,word,o_reach,o_open,o_grasp,o_move\n2,0,0.9,0.1,0.1,0.1\n' > "$tmp/bad7.csv"
printf '0,-1,1e308,-1e308,0.1,0.1\n1,1,1e308,-1e308,0.1,0.1\n2,1,1e308,-1e308,0.1,0.1\n' > "$tmp/bad8.csv"
printf '0,-1,0.9,0.1,0.1,0.1,\n1,0,0.9,0.1,0.1,0.1\n' > "$tmp/bad9.csv"
"$APPDIR/score" prediction "$tmp/bad6.csv" > /dev/null 2> "$tmp/e6"; r6=$?
"$APPDIR/score" prediction "$tmp/bad7.csv" > /dev/null 2> "$tmp/e7"; r7=$?
"$APPDIR/score" prediction "$tmp/bad8.csv" > "$tmp/o8" 2> "$tmp/e8"; r8=$?
"$APPDIR/score" prediction "$tmp/bad9.csv" > /dev/null 2> "$tmp/e9"; r9=$?
if [ $r6 = 2 ] && grep -q "bad6.csv:1: field 4 is empty (expected 6 fields: step,word," "$tmp/e6" &&
   [ $r7 = 2 ] && grep -q "bad7.csv:4: a header line after the first line" "$tmp/e7" &&
   [ $r8 = 2 ] && grep -q "bad8.csv:1: output 0 '1e308' (expected a finite number within +-1e+06" "$tmp/e8" &&
   [ $r9 = 2 ] && grep -q "bad9.csv:1: field 7 is empty" "$tmp/e9" && [ ! -s "$tmp/o8" ]; then
  ok "score refuses empty fields, a second header and outputs whose differences overflow, naming FILE:LINE"
else
  ko "score: empty fields, second header, overflow" "$r6 $r7 $r8 $r9 $(cat "$tmp"/e[6-9] "$tmp/o8")"
fi

# ---- evolve: the four conditions, tiny (4 genotypes: the best of each simple-prim population
# in data/evolved; 30-step trials), 2 generations: the first generation's variant, then the
# condition's own trials
EV="$APPDIR/evolve"
# the committed simple-prim populations stand in for primitive runs (as many as there are)
npop=$(ls data/evolved/simple_prim_s*.genome | wc -l)
tiny=(--set "integrated.populations=data/evolved/simple_prim_s*.genome" --set integrated.top=1
      --set ga.population=4 --set ga.elites=1 --set ga.parents=2 --set integrated.steps=30)
for c in stct st ct ni; do
  "$EV" configs/integrated_$c.cfg "${tiny[@]}" --generations 2 --threads 1 --out "$tmp/$c" > "$tmp/$c.log" 2>&1
  genes=696; [ $c = ct ] || [ $c = ni ] && genes=756
  if [ "$(grep -c '^gen    [01] integrated best ' "$tmp/$c.log")" = 2 ] &&
     grep -q "from the top 1 of $npop population files: $npop genotypes" "$tmp/$c.log" &&
     [ "$(head -1 "$tmp/$c/fitness.csv")" = "$(python3 -c 'import sys; sys.path.insert(0, "tools")
import csvschema; print(",".join(csvschema.fitness_columns(True, 8)))')" ] &&
     [ "$(wc -l < "$tmp/$c/fitness.csv")" = 3 ] && [ "$(grep -c '^# stage integrated' "$tmp/$c/best.genome")" = 2 ] &&
     [ "$(grep -v '^#' "$tmp/$c/population.genome" | awk -v n=$((4 * genes)) 'length($0) == n' | wc -l)" = 4 ]; then
    ok "configs/integrated_$c.cfg runs: progress lines, fitness.csv columns, best.genome, population.genome of $genes genes"
  else
    ko "integrated_$c run" "$(tail -3 "$tmp/$c.log")"
  fi
done

# the base part (genes 0-611) of every genotype ever written is one of those it started from
if python3 - "$tmp" "$npop" <<'PY'
import glob, sys
starts = set()
for f in sorted(glob.glob("data/evolved/simple_prim_s*.genome")):
    starts.add(next(l.strip() for l in open(f) if l.strip() and not l.startswith("#"))[:4 * 612])
bad = 0
for c in ("stct", "st", "ct", "ni"):
    for name in ("population.genome", "best.genome", "checkpoint"):
        for line in open(f"{sys.argv[1]}/{c}/{name}"):
            if line.strip() and not line.startswith("#"):
                bad += line.strip()[:4 * 612] not in starts
print("genotypes whose frozen genes changed:", bad)
sys.exit(1 if bad or len(starts) != int(sys.argv[2]) else 0)
PY
then ok "frozen genes never change (every genotype's first 612 genes are an initial genotype's)"
else ko "frozen genes"; fi

"$EV" configs/integrated_stct.cfg "${tiny[@]}" --generations 2 --threads 2 --out "$tmp/stct2" > /dev/null 2>&1
"$EV" configs/integrated_ct.cfg "${tiny[@]}" --generations 2 --threads 2 --out "$tmp/ct2" > /dev/null 2>&1
if same_files "$tmp/stct" "$tmp/stct2" && same_files "$tmp/ct" "$tmp/ct2"; then
  ok "1 and 2 threads give bit-identical files (ST-CT, CT)"
else ko "thread independence"; fi

# killed, resumed (twice): the files of the uninterrupted run
"$EV" configs/integrated_stct.cfg "${tiny[@]}" --generations 3 --threads 1 --out "$tmp/full" > /dev/null 2>&1
# (killed at the run's own events, however busy the machine: after generation 0's record, then
# the resumed run after generation 1's)
"$EV" configs/integrated_stct.cfg "${tiny[@]}" --generations 3 --threads 1 --out "$tmp/k" > /dev/null 2>&1 &
pid=$!; wait_for 600 $pid has_lines "$tmp/k/fitness.csv" 2; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
"$EV" configs/integrated_stct.cfg "${tiny[@]}" --generations 3 --threads 2 --out "$tmp/k" --resume > /dev/null 2>&1 &
pid=$!; wait_for 600 $pid has_lines "$tmp/k/fitness.csv" 3; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
"$EV" configs/integrated_stct.cfg "${tiny[@]}" --generations 3 --threads 1 --out "$tmp/k" --resume > "$tmp/k.log" 2>&1
if same_files "$tmp/full" "$tmp/k"; then ok "killed twice and resumed: identical files"
else ko "resume" "$(tail -2 "$tmp/k.log")"; fi

# replay: the best of the last generation, trial by trial, gives back its fitness (F_int over
# the odd trials + F_pred over the even ones, recombined here from the per-trial summaries) and
# its successes; its trace of a caretaker trial, fed to score, gives replay's prediction score
for k in 0 1 2 3 4 5 6 7; do
  "$APPDIR/replay" "$tmp/stct/population.genome" "$tmp/stct/config.ini" --trial $k --generation 1 \
    --out "$tmp/trace$k.csv"
done > "$tmp/replay.txt" 2> "$tmp/replay.err"
if python3 - "$tmp/replay.txt" "$tmp/stct/fitness.csv" "$tmp/trace0.csv" "$tmp/trace1.csv" <<'PY'
import csv, re, sys
rows = [dict(re.findall(r"(\w+)=(\S+)", l)) for l in open(sys.argv[1])]
bonus = points = steps = 0.0
b_pred = parts = 0.0; T = 0
for r in rows:
    if r["fitness"] == "integrated":
        bonus += float(r["bonus"]); points += float(r["points"]); steps += int(r["steps"].split("/")[1])
    else:
        T += 1
        if r["reached"] == "1":
            b_pred += float(r["B_pred"]); parts += float(r["F_step"]) / 3 + 2 * float(r["F_switch"]) / 3
F = bonus + 100 * points / steps + b_pred + parts / T
best = list(csv.DictReader(open(sys.argv[2])))[-1]
succ = [r["success"] for r in rows] == [best["best_t%d" % i] for i in range(8)]
words = [r["words"] for r in rows] == ["caretaker", "selftalk"] * 4
t0, t1 = list(csv.DictReader(open(sys.argv[3]))), list(csv.DictReader(open(sys.argv[4])))
# caretaker trial: silent at step 0, then reach; self-talk trial: hears its previous label
care = t0[0]["caretaker_word"] == "-1" and t0[1]["caretaker_word"] == "0" and t0[0]["lo_reach"] != ""
heard = all(float(t1[i]["ling_" + ["reach", "open", "grasp", "move"][int(t1[i - 1]["selftalk_label"])]]) == 10
            for i in range(1, len(t1)))
ok = abs(F - float(best["best"])) < 1e-9 * max(1, abs(F)) and succ and words and care and heard and t1[0]["hl_0"] == ""
print("replay F %.12g vs csv %s; successes %s; words %s; caretaker %s; self talk heard %s" %
      (F, best["best"], succ, words, care, heard))
sys.exit(0 if ok else 1)
PY
then ok "replay of the best reproduces its fitness and successes; trace words, labels and linguistic outputs"
else ko "replay integrated" "$(cat "$tmp/replay.err" | tail -2)"; fi
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
         { print $c["step"] "," $c["caretaker_word"] "," $c["lo_reach"] "," $c["lo_open"] "," $c["lo_grasp"] "," $c["lo_move"] }' \
  "$tmp/trace0.csv" > "$tmp/words0.csv"
"$APPDIR/score" prediction "$tmp/words0.csv" > "$tmp/score0.txt" 2>&1
if python3 - "$tmp/score0.txt" "$tmp/replay.txt" <<'PY'
import re, sys
got = dict(re.findall(r"(\w+)=(\S+)", open(sys.argv[1]).read()))
want = dict(re.findall(r"(\w+)=(\S+)", open(sys.argv[2]).readline()))
ok = all(float(got[k]) == float(want[k]) for k in ("F_step", "F_switch", "B_pred"))
print("score", got, "replay", {k: want[k] for k in ("F_step", "F_switch", "B_pred")})
sys.exit(0 if ok else 1)
PY
then ok "score prediction of replay's trace equals replay's prediction score, bit for bit"
else ko "trace -> score" "$(cat "$tmp/score0.txt")"; fi

# bad integrated input, refused before any work
expect "population files that do not exist refused" "'runs/none-s*/population.genome' matches no file" "$tmp/b1" \
  "$EV" configs/integrated_ni.cfg --out "$tmp/b1" --set "integrated.populations=runs/none-s*/population.genome"
expect "self talk with a type B network refused" "key 'integrated.words_even': self talk needs linguistic outputs" "$tmp/b2" \
  "$EV" configs/integrated_ct.cfg --out "$tmp/b2" --set integrated.words_even=selftalk
expect "too many genotypes refused" "$npop files x integrated.top 10 = $((10 * npop)) genotypes (expected at most ga.population = 4)" "$tmp/b3" \
  "$EV" configs/integrated_st.cfg "${tiny[@]}" --set integrated.top=10 --out "$tmp/b3"

echo "check_integrated: $pass passed, $fail failed"
[ "$fail" = 0 ]
