#!/usr/bin/env bash
# tools/replicate.mk's directories and tools/snapshot.sh (issue 48), on a made-up replication
# (no run needed: seconds). OUT that make cannot quote in its targets (white space, ',', ':') or
# an empty OUT is refused before anything runs (an unquoted `rm -rf` once removed runs/replicate
# for OUT='runs/replicate copy'); SNAPSHOT may be any name (quoted through make). snapshot and
# restore copy any file name (spaces, a newline, a leading '-', quotes), leave temporary files
# out, and refuse OUT and SNAPSHOT equal or nested and a snapshot over a run that is ahead of it
# (OUT and SNAPSHOT swapped), changing nothing; a restore that fails half way leaves no OUT, so
# the same restore can simply be run again.
set -uo pipefail
CHECK=check_snapshot
. "$(dirname "$0")/check_lib.sh"
REP="make --no-print-directory -s -f tools/replicate.mk PRESET=tiny THREADS=1"

# ---- OUT that make cannot quote -----------------------------------------------------------
mkdir -p "$tmp/r/replicate/int-stct-s1" && echo keep > "$tmp/r/replicate/sentinel" &&
  touch "$tmp/r/replicate/int-stct-s1/population.genome"
refused() { # NAME NEEDLE MAKE-ARGS...: exit 2, NEEDLE on stderr, the sentinel run untouched
  local name=$1 needle=$2; shift 2
  $REP "$@" > "$tmp/o" 2> "$tmp/e"; local rc=$?
  if [ $rc = 2 ] && grep -qF -- "$needle" "$tmp/e" && [ "$(cat "$tmp/r/replicate/sentinel" 2> /dev/null)" = keep ]; then
    ok "$name"
  else ko "$name" "rc=$rc $(cat "$tmp/e" "$tmp/o" | head -5); sentinel: $(ls "$tmp/r/replicate" 2>&1)"; fi
}
refused "interim OUT='.../replicate copy': refused, .../replicate kept" \
  "OUT='$tmp/r/replicate copy': a name with white space, which make cannot quote" interim OUT="$tmp/r/replicate copy"
refused "restore OUT= (empty): refused" "OUT is empty: expected the replication's directory" \
  restore OUT= SNAPSHOT="$tmp/r/replicate"
refused "OUT with a ',': refused (it would split the list of populations)" "OUT: '$tmp/r/a,b' holds ','" OUT="$tmp/r/a,b"
refused "PRIM_RUNS with a ':': refused" "PRIM_RUNS: '$tmp/r/x:y' holds ':'" OUT="$tmp/r/replicate" PRIM_RUNS="$tmp/r/x:y"

# ---- a replication to copy: two runs' checkpoints and files, a journal, odd names, temporaries
L=$tmp/live
mkdir -p "$L/prims-s1" "$L/int-stct-s1" "$L/posteval/robustness-st" "$L/odd"
ckpt() { printf '# selftalk-checkpoint 1\n# generation %s\n# stage_idx 0\n' "$2" > "$1"; }
ckpt "$L/prims-s1/checkpoint" 5
ckpt "$L/int-stct-s1/checkpoint" 12
seq 1 12 > "$L/int-stct-s1/fitness.csv"
printf '# journal\n1,a\n2,b\n' > "$L/posteval/robustness-st/posteval.journal"
for n in 'a b' '-n' $'new\nline' $'trailing\n' 'star*' "quote'\"" 'back\slash' ' lead'; do
  printf '%s\n' "$n" > "$L/odd/$n"
done
touch "$L/int-stct-s1/fitness.csv.tmp.4242" "$L/int-stct-s1/x.tmp"
Q="$tmp/my snap's \"copy\""
S=$tmp/snap
for s in "$Q" "$S"; do
  if $REP snapshot OUT="$L" SNAPSHOT="$s" > "$tmp/o" 2> "$tmp/e" &&
     diff -r -x '*.tmp' -x '*.tmp.[0-9]*' "$L" "$s" > "$tmp/d" 2>&1 &&
     [ -z "$(find "$s" -name '*.tmp*')" ] && [ "$(find "$s/odd" -type f -printf x | wc -c)" = 8 ] &&
     grep -qF "snapshot.sh: $L -> $s: 2 checkpoints, 12 files" "$tmp/o"; then
    ok "snapshot to '${s#"$tmp"/}': every odd file name, no temporary file"
  else ko "snapshot to '${s#"$tmp"/}'" "$(cat "$tmp/o" "$tmp/e" "$tmp/d")"; fi
done

# the live run goes on; a snapshot with OUT and SNAPSHOT swapped would put the older copy over it
ckpt "$L/int-stct-s1/checkpoint" 14
seq 1 14 > "$L/int-stct-s1/fitness.csv"
cp -a "$L" "$tmp/live.before"
same_live() { diff -r "$tmp/live.before" "$L" > /dev/null 2>&1; }
if ! $REP snapshot OUT="$S" SNAPSHOT="$L" > "$tmp/o" 2> "$tmp/e" &&
   grep -qF "$L/int-stct-s1/checkpoint is at generation 14, $S/int-stct-s1/checkpoint at 12: copying $S to $L would put an older run over a newer one (OUT and SNAPSHOT swapped?); nothing copied" "$tmp/e" &&
   same_live; then
  ok "snapshot with OUT and SNAPSHOT swapped: refused, the live run's newer checkpoint untouched"
else ko "swapped snapshot" "$(cat "$tmp/e")"; fi
ckpt "$L/int-stct-s1/checkpoint" 12 && cp -a "$tmp/live.before/int-stct-s1/fitness.csv" "$L/int-stct-s1/"
printf '3,c\n' >> "$L/posteval/robustness-st/posteval.journal"
if ! $REP snapshot OUT="$S" SNAPSHOT="$L" > "$tmp/o" 2> "$tmp/e" &&
   grep -qF "$L/posteval/robustness-st/posteval.journal holds 4 lines, $S/posteval/robustness-st/posteval.journal 3" "$tmp/e"; then
  ok "snapshot over a post-evaluation further on (a longer journal): refused"
else ko "swapped snapshot, journal" "$(cat "$tmp/e")"; fi
# the live run ahead of the snapshot: a second snapshot brings the snapshot up to it
if $REP snapshot OUT="$L" SNAPSHOT="$S" > "$tmp/o" 2> "$tmp/e" &&
   diff -r -x '*.tmp' -x '*.tmp.[0-9]*' "$L" "$S" > /dev/null; then
  ok "snapshot again: the snapshot brought up to the live run"
else ko "snapshot again" "$(cat "$tmp/e")"; fi

# equal or nested
nested() { # NAME NEEDLE OUT SNAPSHOT
  cp -a "$L" "$tmp/live.before2" 2> /dev/null
  $REP snapshot OUT="$3" SNAPSHOT="$4" > "$tmp/o" 2> "$tmp/e"; local rc=$?
  if [ $rc = 2 ] && grep -qF -- "$2" "$tmp/e" && [ ! -e "$L/snap" ] && diff -r "$tmp/live.before2" "$L" > /dev/null; then
    ok "$1"; else ko "$1" "rc=$rc $(cat "$tmp/e")"; fi
  rm -rf "$tmp/live.before2"
}
nested "snapshot into OUT itself: refused" "$L is $L or inside it: a copy into itself" "$L" "$L"
nested "snapshot into a directory inside OUT: refused" "$L/snap is $L or inside it" "$L" "$L/snap"
nested "snapshot into a directory holding OUT: refused" "$L is inside $tmp/live/..: a copy into itself" "$L" "$tmp/live/.."

# restore: whole, any name; over an existing OUT refused; a failed restore leaves nothing
if $REP restore OUT="$tmp/restored" SNAPSHOT="$S" > "$tmp/o" 2> "$tmp/e" &&
   diff -r "$S" "$tmp/restored" > "$tmp/d" 2>&1 && [ -z "$(ls -d "$tmp"/restored.restore.* 2> /dev/null)" ]; then
  ok "restore: the snapshot whole, odd names included"
else ko "restore" "$(cat "$tmp/e" "$tmp/d")"; fi
if ! $REP restore OUT="$tmp/restored" SNAPSHOT="$S" > /dev/null 2> "$tmp/e" &&
   grep -qF "restore: $tmp/restored exists (restoring over it would overwrite newer files)" "$tmp/e"; then
  ok "restore over an existing OUT: refused"
else ko "restore over OUT" "$(cat "$tmp/e")"; fi
# cp fails on its third file (a full disk, a file that cannot be read)
mkdir -p "$tmp/bin"
printf '#!/bin/sh\nn=$(($(cat "%s/count" 2> /dev/null || echo 0) + 1))\necho $n > "%s/count"\n[ $n -lt 3 ] || { echo "cp: failing on purpose" >&2; exit 1; }\nexec /bin/cp "$@"\n' \
  "$tmp" "$tmp" > "$tmp/bin/cp"
chmod +x "$tmp/bin/cp"
PATH="$tmp/bin:$PATH" $REP restore OUT="$tmp/restored2" SNAPSHOT="$S" > /dev/null 2> "$tmp/e"; rc=$?
if [ $rc != 0 ] && [ "$(cat "$tmp/count")" -ge 3 ] && [ ! -e "$tmp/restored2" ] &&
   [ -z "$(ls -d "$tmp"/restored2.restore.* 2> /dev/null)" ] &&
   $REP restore OUT="$tmp/restored2" SNAPSHOT="$S" > /dev/null 2>> "$tmp/e" && diff -r "$S" "$tmp/restored2" > /dev/null; then
  ok "a restore failing half way leaves no OUT and no copy; run again, it restores whole"
else ko "failed restore" "rc=$rc count=$(cat "$tmp/count" 2>&1) $(ls -d "$tmp"/restored2* 2>&1) $(cat "$tmp/e")"; fi
if ! sh tools/snapshot.sh --restore "$S" '' 2> "$tmp/e" && grep -qF "an empty directory name" "$tmp/e" &&
   ! sh tools/snapshot.sh "$L" / 2> "$tmp/e2" && grep -qF "/: the root directory" "$tmp/e2"; then
  ok "snapshot.sh: an empty name or / refused"
else ko "snapshot.sh refusals" "$(cat "$tmp/e" "$tmp/e2")"; fi

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
