#!/usr/bin/env bash
# The scripted controller (apps/scripted, lib/episode/scripted.c) proves every primitive physically
# achievable in dynamic mode: the 16 main-prim trials (reach, open, grasp, move from each
# initial posture, scored by the library) and the 8 integrated trials (4 reach postures x 2
# targets, the caretaker's words, 12 s) must all succeed. One check per trial line, plus: the
# output has exactly 24 trial lines and the summary, the exit status agrees, the result does
# not depend on the thread count, and --trace writes a per-step CSV.
set -uo pipefail
APPDIR=${APPDIR:-apps}
CHECK=check_scripted
source "$(dirname "$0")/check_lib.sh"

"$APPDIR/scripted" --threads 2 >"$tmp/out2" 2>"$tmp/err2"
rc=$?
cat "$tmp/out2"
lines=$(grep -c '^trial ' "$tmp/out2")
if [ "$lines" = 24 ]; then ok "24 trial lines"; else ko "24 trial lines" "got $lines"; fi
while read -r line; do
  name=$(echo "$line" | awk '{print $2, $3, $4}')
  if echo "$line" | grep -qE '^trial (main-prim (reach|open|grasp|move) [0-3]|integrated move-object-to-target [0-7]) success=1 steps=[0-9]+$'; then
    ok "$name"
  else
    ko "$name" "$line"
  fi
done < <(grep '^trial ' "$tmp/out2")
if grep -qE '^scripted: 24 passed, 0 failed$' "$tmp/out2" && [ "$rc" = 0 ]; then
  ok "summary and exit status"
else
  ko "summary and exit status" "exit $rc, $(tail -1 "$tmp/out2") $(cat "$tmp/err2")"
fi

"$APPDIR/scripted" --threads 1 >"$tmp/out1" 2>&1
if cmp -s "$tmp/out1" "$tmp/out2"; then ok "same results on 1 and 2 threads"; else ko "same results on 1 and 2 threads" "$(diff "$tmp/out1" "$tmp/out2" | head -4)"; fi

if "$APPDIR/scripted" --only main_grasp_0 --trace "$tmp/trace" >/dev/null 2>&1 &&
   [ "$(wc -l <"$tmp/trace/main_grasp_0.csv")" = 81 ]; then
  ok "--trace writes one row per step"
else
  ko "--trace writes one row per step" "$(ls "$tmp/trace" 2>&1 | head -3)"
fi

# the shipped protocol's starts (configs/prims.cfg: palm-down reaches, the thumb opposed 0.9 in
# all four grasp starts, warm): every trial achievable there too; the grasp starts with partly
# flexed fingers, k = 2 and 3, are the ones the thumb's opposition changes
"$APPDIR/scripted" --config configs/prims.cfg --threads 2 >"$tmp/shipped" 2>&1
if grep -qE '^scripted: 24 passed, 0 failed$' "$tmp/shipped" &&
   grep -qE '^trial main-prim grasp 2 success=1 steps=80$' "$tmp/shipped" &&
   grep -qE '^trial main-prim grasp 3 success=1 steps=80$' "$tmp/shipped"; then
  ok "the shipped configs' trials (configs/prims.cfg): 24 of 24"
else
  ko "the shipped configs' trials (configs/prims.cfg): 24 of 24" "$(grep -v 'success=1' "$tmp/shipped" | head -4)"
fi

# --generations: the main-prim trials over several generations' trial tables; generation 0's
# are the plain run's (same success and steps), every reach trial of generations 0-2 succeeds
"$APPDIR/scripted" --only main_reach --generations 0:2 --threads 2 >"$tmp/sweep" 2>&1
rc=$?
if [ "$rc" = 0 ] && [ "$(grep -c '^sweep [0-9]' "$tmp/sweep")" = 12 ] &&
   grep -qE '^scripted: 12 passed, 0 failed$' "$tmp/sweep" &&
   [ "$(grep -cE '^sweep main-prim reach [0-3] solved=3 of 3 ' "$tmp/sweep")" = 4 ]; then
  ok "--generations 0:2: 12 reach trials, all solved"
else
  ko "--generations 0:2: 12 reach trials, all solved" "exit $rc, $(tail -3 "$tmp/sweep")"
fi
plain=$(grep '^trial main-prim reach' "$tmp/out2" | awk '{print $4, $5, $6}')
swept=$(grep '^sweep 0 main-prim reach' "$tmp/sweep" | awk '{print $5, $6, $7}')
if [ -n "$plain" ] && [ "$plain" = "$swept" ]; then
  ok "--generations: generation 0 is the plain run"
else
  ko "--generations: generation 0 is the plain run" "$plain / $swept"
fi
"$APPDIR/scripted" --only main_reach --generations 0:2 --threads 1 >"$tmp/sweep1" 2>&1
if cmp -s "$tmp/sweep" "$tmp/sweep1"; then ok "--generations: same on 1 and 2 threads"; else ko "--generations: same on 1 and 2 threads" "$(diff "$tmp/sweep" "$tmp/sweep1" | head -4)"; fi
if ! "$APPDIR/scripted" --generations 3:1 >/dev/null 2>&1; then ok "--generations 3:1 refused"; else ko "--generations 3:1 refused" "accepted"; fi

echo "check_scripted: $pass passed, $fail failed"
[ "$fail" = 0 ]
