#!/usr/bin/env bash
# Fault injection where evolve writes (issue 17): a full disk, an output directory that becomes
# read-only mid-run, a failing sync, a failing rename. Each time the run must stop with a clear
# message and a non-zero exit, leave no temporary file, and its last checkpoint must resume to
# the files of an uninterrupted run of the same config and seed, byte for byte.
# As root with mount(2) (a small tmpfs), the disk is really full and the directory really
# read-only; otherwise tests/faults/fault_shim.c (LD_PRELOAD) makes the calls fail as they would.
set -uo pipefail
CHECK=check_faults
source "$(dirname "$0")/check_lib.sh"
BUILD=${BUILD:-build}
EV="$APPDIR/evolve"
SHIM="$PWD/$BUILD/fault_shim.so"
mounts=()
trap 'for m in "${mounts[@]}"; do umount "$m" 2> /dev/null; done; rm -rf "$tmp"' EXIT
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0 # the shim before libasan

G=20
args=(configs/simple_prim.cfg --seed 2 --generations $G --threads 1 --set ga.population=20
      --set ga.elites=2 --set ga.parents=5)
"$EV" "${args[@]}" --out "$tmp/ref" > "$tmp/ref.log" 2>&1 || ko "uninterrupted run" "$(tail -2 "$tmp/ref.log")"

# a tmpfs of SIZE at DIR; 1 if this process cannot mount one
tmpfs() { # DIR SIZE
  mkdir -p "$1" && mount -t tmpfs -o "size=$2" tmpfs "$1" 2> /dev/null || return 1
  mounts+=("$1")
}
can_mount=0 # ST_FAULTS_NO_MOUNT=1 takes the paths of a machine without mount(2)
[ "${ST_FAULTS_NO_MOUNT:-0}" = 1 ] || { tmpfs "$tmp/probe" 64k && can_mount=1; }

# stopped NAME DIR RC NEEDLE: the faulted run in DIR exited RC with stderr $tmp/e; it must have
# stopped mid-run with NEEDLE in its message and no temporary file left; then a resume in DIR
# (the fault gone) must end with the uninterrupted run's files
stopped() {
  local name=$1 dir=$2 rc=$3 needle=$4 rows
  rows=$(($(wc -l 2> /dev/null < "$dir/fitness.csv" || echo 1) - 1))
  if [ "$rc" = 0 ]; then ko "$name: stops" "exit 0 ($rows generations)"; return; fi
  if ! grep -qF -- "$needle" "$tmp/e"; then ko "$name: stops" "expected '$needle' in: $(cat "$tmp/e")"; return; fi
  if [ "$rows" -lt 1 ] || [ "$rows" -ge $G ]; then ko "$name: stops mid-run" "$rows generations written"; return; fi
  if ls "$dir" | grep -q '\.tmp\.'; then ko "$name: no temporary file left" "$(ls "$dir")"; return; fi
  ok "$name: stops after $rows generations, exit $rc: $(sed 's/^evolve: //' "$tmp/e")"
  if "$EV" "${args[@]}" --out "$dir" --resume > "$tmp/r.log" 2>&1 && same_files "$tmp/ref" "$dir"; then
    ok "$name: the last checkpoint resumes to the uninterrupted run's files"
  else
    ko "$name: resume" "$(tail -2 "$tmp/r.log")"
  fi
}

# run_bg DIR [ENV...]: the run in the background, its pid in $pid
run_bg() {
  local dir=$1; shift
  env "$@" "$EV" "${args[@]}" --out "$dir" > /dev/null 2> "$tmp/e" &
  pid=$!
}

# waits until the run holds after its first checkpoint (the shim's ST_FAULT_HOLD: $tmp/hold);
# release lets it go on
wait_held() { # DIR
  wait_for 900 "$pid" test -e "$1/checkpoint"
}
release() { rm -f "$tmp/hold"; }

# ---- a full disk
if [ $can_mount = 1 ]; then
  # 160 KiB: config.ini, a 50 KiB checkpoint and its next version fit, plus some generations of
  # best.genome (2.5 KiB each); then a write fails with ENOSPC
  tmpfs "$tmp/full" 160k
  "$EV" "${args[@]}" --out "$tmp/full/run" > /dev/null 2> "$tmp/e"; rc=$?
  mount -o remount,size=8m "$tmp/full" # space freed
  stopped "full disk (tmpfs)" "$tmp/full/run" $rc "No space left on device"
fi
# a full disk noticed when the data is synced (the 12th fsync: mid-run)
run_bg "$tmp/sync" LD_PRELOAD="$SHIM" ST_FAULT_FSYNC_AT=12; wait $pid; rc=$?
stopped "fsync fails (ENOSPC)" "$tmp/sync" $rc "cannot write: No space left on device"

# ---- the output directory becomes read-only mid-run
# the run holds after its first checkpoint (the shim: no file open, no temporary file waiting)
# until the directory is read-only: mid-run on any machine, however fast or busy (issue 48)
held=(LD_PRELOAD="$SHIM" ST_FAULT_HOLD="$tmp/hold")
if [ $can_mount = 1 ]; then
  tmpfs "$tmp/ro" 8m
  touch "$tmp/hold"
  run_bg "$tmp/ro/run" "${held[@]}"
  wait_held "$tmp/ro/run"
  # the remount waits for a moment no file is open for writing (the held run has none open)
  remount_ro() { mount -o remount,ro "$tmp/ro" 2> /dev/null; }
  wait_for 600 $pid remount_ro
  release
  wait $pid; rc=$?
  mount -o remount,rw "$tmp/ro"
  stopped "read-only directory mid-run (tmpfs remounted)" "$tmp/ro/run" $rc "Read-only file system"
elif [ "$(id -u)" != 0 ]; then
  mkdir -p "$tmp/ro"
  touch "$tmp/hold"
  run_bg "$tmp/ro" "${held[@]}"
  wait_held "$tmp/ro"
  chmod a-w "$tmp/ro"
  release
  wait $pid; rc=$?
  chmod u+w "$tmp/ro"
  stopped "read-only directory mid-run (chmod)" "$tmp/ro" $rc "Permission denied"
else # root without mount: permissions do not stop root
  run_bg "$tmp/ro" LD_PRELOAD="$SHIM" ST_FAULT_FOPEN_AT=12; wait $pid; rc=$?
  stopped "read-only directory mid-run (shim)" "$tmp/ro" $rc "Read-only file system"
fi

# ---- the atomic replace fails (the 6th rename: config.ini, then checkpoints)
run_bg "$tmp/rename" LD_PRELOAD="$SHIM" ST_FAULT_RENAME_AT=6; wait $pid; rc=$?
stopped "rename fails" "$tmp/rename" $rc "/checkpoint: cannot write: renaming $tmp/rename/checkpoint.tmp."
# at the end: population.genome's rename fails, the checkpoint before it stays done 0
# (renames of a run: config.ini, the checkpoints of generations 0..G-2, population.genome, the last
# checkpoint)
run_bg "$tmp/last" LD_PRELOAD="$SHIM" ST_FAULT_RENAME_AT=$((1 + G)); wait $pid; rc=$?
if [ $rc != 0 ] && grep -qF "population.genome: cannot write: renaming" "$tmp/e" &&
   grep -q '^# done 0$' "$tmp/last/checkpoint" && [ ! -e "$tmp/last/population.genome" ]; then
  ok "rename of population.genome fails at the end: exit $rc, the checkpoint still done 0"
  "$EV" "${args[@]}" --out "$tmp/last" --resume > "$tmp/r.log" 2>&1 && same_files "$tmp/ref" "$tmp/last" &&
    ok "... and it resumes to the uninterrupted run's files" || ko "last rename: resume" "$(tail -2 "$tmp/r.log")"
else
  ko "rename of population.genome" "rc $rc: $(cat "$tmp/e")"
fi

echo "check_faults: $pass passed, $fail failed"
[ "$fail" = 0 ]
