#!/usr/bin/env bash
# Smoke test of make compare's harness (tools/compare/compare.c), tiny and fast: MuJoCo's import
# of the URDF passes the model checks (frames to 1e-6 m, masses), a 1-round, 3-step run prints
# the three scenarios and the closing line in its documented form, the scene it writes loads
# again in MuJoCo, and a bad argument is refused. The speed figures themselves are make
# compare's (docs/PROTOCOL.md, "Speed"; docs/notebook/speed.md, "Against MuJoCo"), not checked
# here.
set -uo pipefail
BUILD=${BUILD:-build}
CHECK=check_compare
source "$(dirname "$0")/check_lib.sh"
bin="$BUILD/compare"

if "$bin" --check-only --xml "$tmp/xml" >"$tmp/o" 2>"$tmp/e" &&
   grep -qE '^model: MuJoCo 2\.2\.2 imported .*: 18 moving bodies \(the library.s: 18\), 18 hinges' "$tmp/o"; then
  ok "model checks pass (18 bodies, 18 hinges)"
else
  ko "model checks pass (18 bodies, 18 hinges)" "$(cat "$tmp/o" "$tmp/e")"
fi
dp=$(sed -nE 's/.*max \|dp\| ([0-9.e+-]+) m.*/\1/p' "$tmp/o")
dm=$(sed -nE 's/.*max \|dm\| ([0-9.e+-]+) kg.*/\1/p' "$tmp/o")
if python3 -c "import sys; sys.exit(not (float('$dp') <= 1e-9 and float('$dm') <= 1e-12))" 2>/dev/null; then
  ok "frames and masses equal (|dp| $dp m, |dm| $dm kg)"
else
  ko "frames and masses equal" "dp=$dp dm=$dm"
fi
pairs=$(grep -c '<pair ' "$tmp/xml/scene.xml" 2>/dev/null)
nopairs=$(grep -c '<pair ' "$tmp/xml/scene_notable.xml" 2>/dev/null)
if [ "${pairs:-0}" -gt 0 ] && [ "$pairs" = $((nopairs + 2)) ] && grep -q 'noslip_iterations="3"' "$tmp/xml/scene.xml"; then
  ok "scene written: $pairs pairs, 2 more than without the object's table pairs"
else
  ko "scene written" "pairs=$pairs nopairs=$nopairs"
fi

"$bin" --rounds 1 --steps 3 --set 'dynamics.lcp=warm' >"$tmp/run" 2>"$tmp/e"
rc=$?
cat "$tmp/run"
for s in free press held; do
  if grep -qE "^scenario=$s libselftalk=[0-9]+ mujoco=[0-9]+ ratio=[0-9.]+ kept=4/4 mujoco_kept=[0-4]/4 " "$tmp/run"; then
    ok "$s: rates, ratio, every ball kept by the library"
  else
    ko "$s" "$(grep "scenario=$s" "$tmp/run") $(cat "$tmp/e")"
  fi
done
if [ "$rc" = 0 ] && tail -1 "$tmp/run" | grep -qE '^compare: press [0-9.]+ held [0-9.]+ free [0-9.]+ \(libselftalk / MuJoCo, per CPU-second, same run\)$'; then
  ok "closing line"
else
  ko "closing line" "exit $rc: $(tail -1 "$tmp/run")"
fi

if "$bin" --rounds 0 >/dev/null 2>&1; then ko "--rounds 0 refused" "exit 0"; else ok "--rounds 0 refused"; fi
if "$bin" --set dynamics.lcp=nope --check-only >/dev/null 2>"$tmp/e" || ! grep -q 'dynamics.lcp' "$tmp/e"; then
  ko "a bad --set refused, named" "$(cat "$tmp/e")"
else
  ok "a bad --set refused, named"
fi

echo "check_compare: $pass passed, $fail failed"
[ "$fail" = 0 ]
