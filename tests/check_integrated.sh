#!/usr/bin/env bash
# The integrated stage end to end: ./apps/score prediction on hand-worked files; the four
# condition configs run (a tiny population, short trials), resume to identical files and give
# the same files on 1 and 2 threads; frozen genes never change; replay of an integrated
# individual; bad integrated configs refused before any work.
set -uo pipefail
APPDIR=${APPDIR:-apps}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { echo "check_integrated: $1 ok"; pass=$((pass + 1)); }
ko() { echo "check_integrated: $1 FAILED${2:+: $2}"; fail=$((fail + 1)); }

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
"$APPDIR/score" prediction "$tmp/bad1.csv" > /dev/null 2> "$tmp/e1"; r1=$?
"$APPDIR/score" prediction "$tmp/bad2.csv" > /dev/null 2> "$tmp/e2"; r2=$?
"$APPDIR/score" prediction "$tmp/bad3.csv" > /dev/null 2> "$tmp/e3"; r3=$?
"$APPDIR/score" prediction "$tmp/bad4.csv" > /dev/null 2> "$tmp/e4"; r4=$?
"$APPDIR/score" integrated "$tmp/pred.csv" > /dev/null 2> "$tmp/e5"; r5=$?
if [ $r1 = 2 ] && grep -q "bad1.csv:2: step '2' (expected 1" "$tmp/e1" &&
   [ $r2 = 2 ] && grep -q "bad2.csv:2: word '7' (expected -1 for none or 0-3" "$tmp/e2" &&
   [ $r3 = 2 ] && grep -q "bad3.csv:1: 5 fields (expected 6" "$tmp/e3" &&
   [ $r4 = 2 ] && grep -q "trial 0: prediction: step 2: no word" "$tmp/e4" &&
   [ $r5 = 2 ] && grep -q "'integrated': unknown fitness (expected prediction)" "$tmp/e5"; then
  ok "score refuses bad rows naming FILE:LINE, and unknown fitness functions"
else
  ko "score refusals" "$(cat "$tmp"/e[1-5])"
fi

echo "check_integrated: $pass passed, $fail failed"
[ "$fail" = 0 ]
