#!/usr/bin/env bash
# Golden results, as Box2D's determinism test: the SHA-256 of three results, every real printed
# with %.17g (it reads back bit for bit, and text does not depend on the machine's byte order or
# struct layout), against tests/golden/golden.sha256:
#   kinematic  one simple-prim trial (kinematic world) of a fixed genotype, step by step
#   dynamic    one main-prim trial (ODE world) of a fixed genotype, step by step
#   evolution  fitness.csv of 3 generations of simple-prim, seed 1 (GA, trials, scoring)
# These three keep the keys' defaults, under which the older committed runs were made (reach
# starts position only, the dense LCP, the thumb at 0.5 in the grasp starts k = 2, 3,
# run.rng_seed plain), whatever the shipped configs say; two more take the shipped configs as
# they are (palm-down reach starts, dynamics.lcp = warm, grasp_partial_oppose 0.9, run.rng_seed
# apart; SPEC 13, docs/PROTOCOL.md):
#   dynamic_shipped    the dynamic trial of configs/main_prim.cfg as shipped (warm contact)
#   evolution_shipped  3 generations of configs/simple_prim.cfg as shipped (palm-down reaches)
# A change of code, compiler, flags, libm or ODE that moves any of them by one bit is caught;
# runs made on machines whose hashes agree can be pooled.
#
#   bash tests/check_golden.sh                  check every result (make test runs this)
#   bash tests/check_golden.sh --update [NAME]  rewrite the hash of NAME (default: all) after a
#                                               change meant to move results; or
#                                               make golden-update [GOLDEN=NAME]
# Commit tests/golden/golden.sha256 with the change that moved the results and say why. The
# results of the last run are kept in $BUILD/golden/ to compare (e.g. with a build of the
# previous commit) when a hash moves unexpectedly.
set -uo pipefail
APPDIR=${APPDIR:-apps}
BUILD=${BUILD:-build}
FILE=tests/golden/golden.sha256
NAMES="kinematic dynamic evolution dynamic_shipped evolution_shipped"
# the keys' defaults where the shipped configs set others (kinematic results), and the LCP's
OLDER_KEYS="--set postures.reach_palm_down=false --set postures.grasp_partial_oppose=0.5 --set run.rng_seed=plain"
THESIS_KEYS="$OLDER_KEYS --set dynamics.lcp=dense"
out="$BUILD/golden"
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# produce NAME: writes $out/NAME.csv; the commands are the definition of each golden result
produce() {
  case $1 in
    kinematic)
      "$APPDIR/replay" tests/golden/simple_prim.genome configs/simple_prim.cfg --trial 9 \
        --generation 0 --exact $OLDER_KEYS --out "$out/kinematic.csv" > /dev/null ;;
    dynamic)
      "$APPDIR/replay" tests/golden/main_prim.genome configs/main_prim.cfg --trial 12 \
        --generation 0 --exact $THESIS_KEYS --out "$out/dynamic.csv" > /dev/null ;;
    evolution)
      "$APPDIR/evolve" configs/simple_prim.cfg --seed 1 --generations 3 --threads 2 \
        $OLDER_KEYS --out "$tmp/evolution" > /dev/null && cp "$tmp/evolution/fitness.csv" "$out/evolution.csv" ;;
    dynamic_shipped)
      "$APPDIR/replay" tests/golden/main_prim.genome configs/main_prim.cfg --trial 12 \
        --generation 0 --exact --out "$out/dynamic_shipped.csv" > /dev/null ;;
    evolution_shipped)
      "$APPDIR/evolve" configs/simple_prim.cfg --seed 1 --generations 3 --threads 2 \
        --out "$tmp/evolution_shipped" > /dev/null &&
        cp "$tmp/evolution_shipped/fitness.csv" "$out/evolution_shipped.csv" ;;
    *) echo "check_golden: unknown result '$1' (expected one of: $NAMES)" >&2; return 2 ;;
  esac
}

hash_of() { sha256sum "$out/$1.csv" | cut -d' ' -f1; }
expected() { awk -v n="$1" '$1 !~ /^#/ && $2 == n { print $1 }' "$FILE"; }

if [ "${1:-}" = --update ]; then
  shift
  names=${*:-$NAMES}
  cp "$FILE" "$tmp/new"
  for n in $names; do
    produce "$n" 2> "$tmp/err" || { echo "check_golden: $n: $(cat "$tmp/err")" >&2; exit 1; }
    h=$(hash_of "$n") old=$(expected "$n")
    if [ -n "$old" ]; then
      awk -v n="$n" -v h="$h" '$1 !~ /^#/ && $2 == n { $0 = h "  " n } { print }' "$tmp/new" > "$tmp/next"
      mv "$tmp/next" "$tmp/new"
    else
      echo "$h  $n" >> "$tmp/new"
    fi
    [ "$h" = "$old" ] && echo "check_golden: $n unchanged ($h)" || echo "check_golden: $n ${old:-(none)} -> $h"
  done
  mv "$tmp/new" "$FILE"
  echo "check_golden: $FILE updated; commit it with the change that moved the results"
  exit 0
fi

pass=0 fail=0
for n in $NAMES; do
  want=$(expected "$n")
  if ! produce "$n" 2> "$tmp/err"; then
    echo "check_golden: $n FAILED: $(cat "$tmp/err")"; fail=$((fail + 1)); continue
  fi
  got=$(hash_of "$n")
  if [ -n "$want" ] && [ "$got" = "$want" ]; then
    echo "check_golden: $n ok"; pass=$((pass + 1))
  else
    echo "check_golden: $n FAILED: sha256 $got, expected ${want:-(none in $FILE)}; the result"
    echo "  ($out/$n.csv) moved. If a change was meant to move it: make golden-update GOLDEN=$n"
    fail=$((fail + 1))
  fi
done
echo "check_golden: $pass passed, $fail failed"
[ "$fail" = 0 ]
