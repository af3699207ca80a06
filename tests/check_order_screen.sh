#!/usr/bin/env bash
# tools/order_screen.mk end to end, tiny (issue 47 item 2): ST-CT under both trial orders for 2
# generations of a small population, the robustness test on 4 trials, the table; the pairs run's
# config.ini records its order and its trials' types follow it (replay); a run resumed after it is
# complete is left as it was; a bad order is refused.
set -uo pipefail
APPDIR=${APPDIR:-apps}
CHECK=check_order_screen
source "$(dirname "$0")/check_lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ARGS=(SEEDS=1 CONDS=stct GENS=2 OUT="$tmp/os" POP=data/evolved/chain_s1/population.genome
  EVOLVE_ARGS='--set ga.population=6 --set ga.elites=1 --set ga.parents=2 --set integrated.trials=4 --set integrated.steps=20 --set integrated.top=6'
  ROB_ARGS='--set posteval.robustness_trials=4 --set integrated.steps=20')
if make -s -f tools/order_screen.mk "${ARGS[@]}" > "$tmp/out" 2> "$tmp/err"; then
  ok "two runs and their tests"
else
  ko "the screen failed: $(tail -3 "$tmp/err")"
fi
grep -q '^| stct-mod4-s1 | 2 | [0-4] |' "$tmp/out" && grep -q '^| stct-pairs-s1 | 2 | [0-4] |' "$tmp/out" &&
  grep -q '^stct pairs: robustness median' "$tmp/out" && ok "the table has both runs" ||
  ko "table: $(cat "$tmp/out")"
grep -q '^trial_order = pairs' "$tmp/os/stct-pairs-s1/config.ini" &&
  grep -q '^trial_order = mod4' "$tmp/os/stct-mod4-s1/config.ini" && ok "each run records its order" ||
  ko "config.ini without its trial_order"
# trial 1's type: 1 under mod4, 0 under pairs (i div 2)
t1=$("$APPDIR/replay" "$tmp/os/stct-pairs-s1/best.genome" "$tmp/os/stct-pairs-s1/config.ini" --trial 1 2>&1 | grep '^trial ')
case "$t1" in *" k=0 "*) ok "pairs: trial 1 has type 0" ;; *) ko "pairs: trial 1: $t1" ;; esac
sum=$(cat "$tmp/os"/*/fitness.csv | sha256sum)
make -s -f tools/order_screen.mk "${ARGS[@]}" > /dev/null 2>&1
[ "$(cat "$tmp/os"/*/fitness.csv | sha256sum)" = "$sum" ] && ok "a second make leaves complete runs as they were" ||
  ko "a second make changed fitness.csv"
if make -s -f tools/order_screen.mk ORDERS=sideways OUT="$tmp/x" > /dev/null 2> "$tmp/err"; then
  ko "ORDERS=sideways accepted"
else
  grep -q "expected orders among mod4 pairs" "$tmp/err" && ok "a bad order refused" || ko "$(cat "$tmp/err")"
fi
echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
