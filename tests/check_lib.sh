# Helpers shared by the check_*.sh scripts. Sourced after setting CHECK to the
# script's name: a temporary directory $tmp (removed on exit), the pass / fail counters and
# ok NAME / ko NAME [DETAIL], which print "CHECK: NAME ok" or "CHECK: NAME FAILED: DETAIL".
APPDIR=${APPDIR:-apps}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { echo "$CHECK: $1 ok"; pass=$((pass + 1)); }
ko() { echo "$CHECK: $1 FAILED${2:+: $2}"; fail=$((fail + 1)); }

# waits for an event, not a deadline (issue 48: a busy machine made fixed waits race): polls
# until CMD succeeds (0), or PID has ended and CMD still fails (1), or TIMEOUT seconds have
# passed (2: generous, only so that a hang fails the check instead of the suite)
wait_for() { # TIMEOUT PID CMD...
  local timeout=$1 pid=$2 end=$((SECONDS + $1)); shift 2
  while ! "$@"; do
    if ! kill -0 "$pid" 2> /dev/null; then "$@"; return $(($? ? 1 : 0)); fi
    [ $SECONDS -ge $end ] && { echo "wait_for: ${timeout}s passed waiting for: $*" >&2; return 2; }
    sleep 0.1
  done
}

# FILE exists and has at least N lines (a run's fitness.csv: its header and N - 1 generations;
# written whole, by rename, so never read half way)
has_lines() { # FILE N
  [ -e "$1" ] && [ "$(wc -l < "$1")" -ge "$2" ]
}

# the lines of FILE, 0 when it does not exist
lines_of() { # FILE
  if [ -e "$1" ]; then wc -l < "$1"; else echo 0; fi
}

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
