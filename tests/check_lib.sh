# Helpers shared by the check_*.sh scripts. Sourced after setting CHECK to the
# script's name: a temporary directory $tmp (removed on exit), the pass / fail counters and
# ok NAME / ko NAME [DETAIL], which print "CHECK: NAME ok" or "CHECK: NAME FAILED: DETAIL".
APPDIR=${APPDIR:-apps}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { echo "$CHECK: $1 ok"; pass=$((pass + 1)); }
ko() { echo "$CHECK: $1 FAILED${2:+: $2}"; fail=$((fail + 1)); }

# the five files of two run directories are identical
same_files() { # DIR1 DIR2: the five files byte for byte, and no temporary file left in DIR2
  for f in config.ini fitness.csv best.genome population.genome checkpoint; do
    cmp -s "$1/$f" "$2/$f" || { echo "  $f differs between $1 and $2"; return 1; }
  done
  if ls "$2" | grep -q '\.tmp\.'; then echo "  temporary files left in $2: $(ls "$2")"; return 1; fi
}

# CMD fails, its stderr names NEEDLE, and no fitness.csv appeared in DIR (refused before any work)
expect() { # NAME NEEDLE DIR CMD...
  local name=$1 needle=$2 dir=$3; shift 3
  if "$@" > "$tmp/o" 2> "$tmp/e"; then ko "$name" "exit 0"; return; fi
  if grep -qF -- "$needle" "$tmp/e" && [ ! -e "$dir/fitness.csv" ]; then ok "$name"; else ko "$name" "$(cat "$tmp/e")"; fi
}
