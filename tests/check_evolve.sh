#!/usr/bin/env bash
# apps/evolve end to end: thread-count independence, SIGKILL + --resume giving identical files,
# and bad input refused before any work.
set -uo pipefail
APPDIR=${APPDIR:-apps}
EV="$APPDIR/evolve"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { echo "check_evolve: $1 ok"; pass=$((pass + 1)); }
ko() { echo "check_evolve: $1 FAILED${2:+: $2}"; fail=$((fail + 1)); }
same_files() { # DIR1 DIR2
  for f in config.ini fitness.csv best.genome population.genome checkpoint; do
    cmp -s "$1/$f" "$2/$f" || { echo "  $f differs between $1 and $2"; return 1; }
  done
}
cfg=configs/simple_prim.cfg
G=8

"$EV" $cfg --seed 11 --generations $G --threads 1 --out "$tmp/t1" > "$tmp/t1.log" 2>&1
"$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/t2" > "$tmp/t2.log" 2>&1
if [ "$(grep -c '^gen ' "$tmp/t1.log")" = $G ] && [ "$(wc -l < "$tmp/t1/fitness.csv")" = $((G + 1)) ] &&
   head -1 "$tmp/t1/fitness.csv" | grep -q '^generation,best,mean,worst,best_bonus,' &&
   [ "$(grep -c '^# generation' "$tmp/t1/best.genome")" = $G ]; then
  ok "progress lines, fitness.csv rows and best.genome entries per generation"
else
  ko "per-generation output" "$(tail -3 "$tmp/t1.log")"
fi
if same_files "$tmp/t1" "$tmp/t2"; then ok "1 thread and 2 threads give bit-identical files"; else ko "thread independence"; fi

# replay: the best of the last generation, replayed trial by trial with the run's config and
# that generation's offsets, reproduces its successes and (summing each trial's share) its fitness
last=$((G - 1))
for k in $(seq 0 15); do
  "$APPDIR/replay" "$tmp/t1/population.genome" "$tmp/t1/config.ini" --trial $k --generation $last \
    --out "$tmp/trace$k.csv"
done > "$tmp/replay.txt" 2>&1
if python3 - "$tmp/replay.txt" "$tmp/t1/fitness.csv" "$tmp/trace15.csv" <<'PY'
import csv, re, sys
fp, succ = [0.0] * 4, []
for line in open(sys.argv[1]):
    k = int(line.split()[1])
    fp[k // 4] += float(re.search(r"F_contribution=(\S+)", line).group(1))
    succ.append(int(re.search(r"success=(\d)", line).group(1)))
F = 4 / sum(1 / max(x, 0.001) for x in fp)
row = list(csv.DictReader(open(sys.argv[2])))[-1]
want = [int(row["best_t%d" % t]) for t in range(16)]
trace = list(csv.DictReader(open(sys.argv[3])))
ok = succ == want and abs(F - float(row["best"])) < 1e-4 and len(trace) == 60 and "palm_x" in trace[0]
print("replay F %.6f vs csv %.6f, successes %s vs %s, trace rows %d" % (F, float(row["best"]), succ, want, len(trace)))
sys.exit(0 if ok else 1)
PY
then ok "replay reproduces the best's 16 trials and fitness"; else ko "replay" "$(tail -3 "$tmp/replay.txt")"; fi

# SIGKILL at several moments, resume each time; the end must equal the uninterrupted run
for delay in 0.05 0.3 0.45; do
  rm -rf "$tmp/k"
  "$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/k" > /dev/null 2>&1 &
  pid=$!
  sleep $delay
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  "$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/k" --resume > "$tmp/k.log" 2>&1 &
  pid=$!
  sleep 0.2
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  "$EV" $cfg --seed 11 --generations $G --threads 1 --out "$tmp/k" --resume > "$tmp/k.log" 2>&1
  if same_files "$tmp/t1" "$tmp/k"; then ok "killed after ${delay}s and 0.2s, resumed: identical files"
  else ko "resume after kill at ${delay}s" "$(tail -2 "$tmp/k.log")"; fi
done

"$EV" $cfg --seed 11 --generations $G --out "$tmp/t1" --resume > "$tmp/done.log" 2>&1
grep -q "is complete" "$tmp/done.log" && ok "resuming a finished run says so" || ko "finished run" "$(cat "$tmp/done.log")"
"$EV" $cfg --seed 11 --generations 2 --out "$tmp/fresh" --resume > "$tmp/fresh.log" 2>&1
grep -q "no checkpoint in $tmp/fresh: starting fresh" "$tmp/fresh.log" && ok "--resume without a checkpoint starts fresh" || ko "fresh" "$(cat "$tmp/fresh.log")"
if "$EV" $cfg --seed 12 --generations $G --out "$tmp/k" --resume > "$tmp/diff.log" 2>&1; then
  ko "resume with another config refused" "exit 0"
else
  grep -q "config.ini differs" "$tmp/diff.log" && ok "resume with another config refused" || ko "resume refused" "$(cat "$tmp/diff.log")"
fi

# bad input, refused before any work (no output directory appears)
printf '[stage]\nstages = simple_prim\n[ga]\nelites = 200\n' > "$tmp/bad.cfg"
expect() { # NAME NEEDLE DIR CMD...
  local name=$1 needle=$2 dir=$3; shift 3
  if "$@" > "$tmp/o" 2> "$tmp/e"; then ko "$name" "exit 0"; return; fi
  if grep -qF -- "$needle" "$tmp/e" && [ ! -e "$dir/fitness.csv" ]; then ok "$name"; else ko "$name" "$(cat "$tmp/e")"; fi
}
expect "bad config refused with FILE:LINE" "$tmp/bad.cfg:4: key 'ga.elites': 200 exceeds ga.population" "$tmp/b1" \
  "$EV" "$tmp/bad.cfg" --out "$tmp/b1"
expect "unknown --set key refused" "key 'ga.popsize': unknown key" "$tmp/b2" "$EV" $cfg --out "$tmp/b2" --set ga.popsize=5
mkdir -p "$tmp/ro" && chmod 500 "$tmp/ro"
if [ "$(id -u)" = 0 ]; then
  expect "unwritable DIR refused" "output directory '/proc/selftalk': cannot create" "/proc/selftalk" \
    "$EV" $cfg --out /proc/selftalk
else
  expect "unwritable DIR refused" "not writable" "$tmp/ro" "$EV" $cfg --out "$tmp/ro"
fi
expect "missing config refused" "$tmp/none.cfg: cannot open config" "$tmp/b3" "$EV" "$tmp/none.cfg" --out "$tmp/b3"
echo "check_evolve: $pass passed, $fail failed"
[ "$fail" = 0 ]
