# Helpers shared by the check_*.sh scripts that run evolve (sourced; they define tmp, ok, ko).

# the five files of two run directories are identical
same_files() { # DIR1 DIR2
  for f in config.ini fitness.csv best.genome population.genome checkpoint; do
    cmp -s "$1/$f" "$2/$f" || { echo "  $f differs between $1 and $2"; return 1; }
  done
}

# CMD fails, its stderr names NEEDLE, and no fitness.csv appeared in DIR (refused before any work)
expect() { # NAME NEEDLE DIR CMD...
  local name=$1 needle=$2 dir=$3; shift 3
  if "$@" > "$tmp/o" 2> "$tmp/e"; then ko "$name" "exit 0"; return; fi
  if grep -qF -- "$needle" "$tmp/e" && [ ! -e "$dir/fitness.csv" ]; then ok "$name"; else ko "$name" "$(cat "$tmp/e")"; fi
}
