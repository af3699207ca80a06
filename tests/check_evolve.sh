#!/usr/bin/env bash
# apps/evolve end to end: thread-count independence, SIGKILL + --resume giving identical files,
# and bad input refused before any work.
set -uo pipefail
CHECK=check_evolve
source "$(dirname "$0")/check_lib.sh"
EV="$APPDIR/evolve"
# the fault shim holds a run after a checkpoint while $tmp/hold exists (ST_FAULT_HOLD): a test
# acts on a running run at an event, not after a delay a busy machine would miss
SHIM="$PWD/${BUILD:-build}/fault_shim.so"
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0 # the shim before libasan
cfg=configs/simple_prim.cfg
G=8

"$EV" $cfg --seed 11 --generations $G --threads 1 --out "$tmp/t1" > "$tmp/t1.log" 2>&1
"$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/t2" > "$tmp/t2.log" 2>&1
if [ "$(grep -c '^gen ' "$tmp/t1.log")" = $G ] && [ "$(wc -l < "$tmp/t1/fitness.csv")" = $((G + 1)) ] &&
   [ "$(head -1 "$tmp/t1/fitness.csv")" = "$(python3 -c 'import sys; sys.path.insert(0, "tools")
import csvschema; print(",".join(csvschema.fitness_columns(False, 16)))')" ] &&
   [ "$(grep -c '^# generation' "$tmp/t1/best.genome")" = $G ]; then
  ok "progress lines, fitness.csv rows and best.genome entries per generation"
else
  ko "per-generation output" "$(tail -3 "$tmp/t1.log")"
fi
if same_files "$tmp/t1" "$tmp/t2"; then ok "1 thread and 2 threads give bit-identical files"; else ko "thread independence"; fi

# The simple-prim results themselves are pinned once, by the golden result `evolution`
# (tests/check_golden.sh, tests/golden/golden.sha256): the episode loop (issue 14) left them
# bit-identical to the two loops it replaced, on the first hand and on the hand of issue 12.

# replay: the best of the last generation, replayed trial by trial with the run's config and
# that generation's offsets, reproduces its successes and (summing each trial's share) its fitness
last=$((G - 1))
for k in $(seq 0 15); do
  "$APPDIR/replay" "$tmp/t1/population.genome" "$tmp/t1/config.ini" --trial $k --generation $last \
    --out "$tmp/trace$k.csv"
done > "$tmp/replay.txt" 2> "$tmp/replay.err"
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

# replay picks from best.genome (one record per generation): the last record with its own
# generation's offsets by default, or the record of --generation G; the same genotype as the
# population's best at the last generation (elitism keeps it first), so the same summary line
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 5 > "$tmp/rb1.txt" 2> "$tmp/rb1.err"
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 5 --generation 3 > "$tmp/rb2.txt" 2> "$tmp/rb2.err"
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 5 --index 3 --generation 3 > "$tmp/rb3.txt" 2>/dev/null
if grep -q "genotype $last of .*offsets of generation $last" "$tmp/rb1.err" &&
   cmp -s "$tmp/rb1.txt" <(grep '^trial 5 ' "$tmp/replay.txt") &&
   grep -q "genotype 3 of .*offsets of generation 3" "$tmp/rb2.err" && cmp -s "$tmp/rb2.txt" "$tmp/rb3.txt"; then
  ok "replay of best.genome picks the record of the generation asked (default: the last)"
else
  ko "replay best.genome defaults" "$(cat "$tmp/rb1.err" "$tmp/rb2.err")"
fi
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 5 --generation 99 > /dev/null 2> "$tmp/rb4.err"; rc1=$?
"$APPDIR/replay" "$tmp/t1/best.genome" configs/prims.cfg --trial 5 > /dev/null 2> "$tmp/rb5.err"; rc2=$?
if [ $rc1 != 0 ] && grep -q "generation 99: .* has no genotype of that generation (it has 0..$last)" "$tmp/rb4.err" &&
   [ $rc2 != 0 ] && grep -q "prims.cfg runs simple-prim then main-prim: give --stage" "$tmp/rb5.err"; then
  ok "replay refuses a generation the file lacks and a chained config without --stage"
else
  ko "replay refusals" "$(cat "$tmp/rb4.err" "$tmp/rb5.err")"
fi

# replay --force: the focus output forced to the target in a reach trial makes the focus wrong
# at every step, so S = f_f / 5 = (1 - 1) / 5 = 0 throughout (eq. 2.4); a bad value is refused
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 0 --force 12=1 --out "$tmp/forced.csv" > "$tmp/rf1.txt" 2>/dev/null
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 0 --force 9=2 > /dev/null 2> "$tmp/rf2.err"; rc=$?
if grep -q " sum_S=0.000000 " "$tmp/rf1.txt" &&
   [ "$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
                  $c["focus_target"] != 1 || $c["S"] != 0 { bad++ } END { print NR - 1, bad + 0 }' "$tmp/forced.csv")" = "60 0" ] &&
   [ $rc != 0 ] && grep -q "replay: --force '9=2': value 2 (expected 0..1)" "$tmp/rf2.err"; then
  ok "replay --force overrides an output for the whole trial (focus on the target: S = 0) and refuses a bad value"
else
  ko "replay --force" "$(cat "$tmp/rf1.txt" "$tmp/rf2.err")"
fi

# SIGKILL at several moments, resume each time; the end must equal the uninterrupted run. The
# moments are the run's own events, however busy the machine: its config.ini written (before any
# generation), then generation 0's and generation 2's records; the resumed run is killed once it
# has recorded one more generation
for lines in 0 2 4; do
  rm -rf "$tmp/k"
  "$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/k" > /dev/null 2>&1 &
  pid=$!
  if [ $lines = 0 ]; then wait_for 600 $pid test -e "$tmp/k/config.ini"
  else wait_for 600 $pid has_lines "$tmp/k/fitness.csv" $lines; fi
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  # what a kill -9 between a temporary file's open and its rename leaves: the resume removes it
  [ -d "$tmp/k" ] && touch "$tmp/k/checkpoint.tmp.999999" "$tmp/k/fitness.csv.tmp.1"
  more=$(lines_of "$tmp/k/fitness.csv")
  more=$((more > 0 ? more + 1 : 2))
  "$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/k" --resume > "$tmp/k.log" 2>&1 &
  pid=$!
  wait_for 600 $pid has_lines "$tmp/k/fitness.csv" $more
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  "$EV" $cfg --seed 11 --generations $G --threads 1 --out "$tmp/k" --resume > "$tmp/k.log" 2>&1
  if same_files "$tmp/t1" "$tmp/k"; then ok "killed at fitness.csv line $lines and once more a generation on, resumed: identical files"
  else ko "resume after kill at fitness.csv line $lines" "$(tail -2 "$tmp/k.log")"; fi
done

"$EV" $cfg --seed 11 --generations $G --out "$tmp/t1" --resume > "$tmp/done.log" 2>&1
grep -q "is complete" "$tmp/done.log" && ok "resuming a finished run says so" || ko "finished run" "$(cat "$tmp/done.log")"
"$EV" $cfg --seed 11 --generations 2 --out "$tmp/fresh" --resume > "$tmp/fresh.log" 2>&1
grep -q "no checkpoint in $tmp/fresh: starting fresh" "$tmp/fresh.log" && ok "--resume without a checkpoint starts fresh" || ko "fresh" "$(cat "$tmp/fresh.log")"
# a finished run whose checkpoint was removed (as data/evolved/ keeps them): --resume refuses
# to start it again over its files, which stay as they were
mkdir -p "$tmp/fin" && cp "$tmp/t1/"{config.ini,fitness.csv,population.genome} "$tmp/fin/"
sum0=$(cat "$tmp/fin/"* | md5sum)
"$EV" $cfg --seed 11 --generations $G --out "$tmp/fin" --resume > "$tmp/fin.log" 2>&1
if [ $? != 0 ] && grep -q "$tmp/fin/population.genome: a finished run's population and no checkpoint to resume from" "$tmp/fin.log" &&
   [ "$(cat "$tmp/fin/"* | md5sum)" = "$sum0" ] && [ "$(ls "$tmp/fin" | wc -l)" = 3 ]; then
  ok "--resume on a finished run without its checkpoint is refused, its files kept"
else ko "finished run without checkpoint" "$(cat "$tmp/fin.log")"; fi
if "$EV" $cfg --seed 12 --generations $G --out "$tmp/k" --resume > "$tmp/diff.log" 2>&1; then
  ko "resume with another config refused" "exit 0"
else
  # the key that differs named, with both values and the --set that resumes
  grep -qF "$tmp/k/config.ini has run.seed = 11, this run 12 (resume needs the same config and --set options: --set run.seed=11)" "$tmp/diff.log" &&
    ok "resume with another config refused, naming the key and both values" || ko "resume refused" "$(cat "$tmp/diff.log")"
fi

# --generations is the run's cap key (issue 48): config.ini records the cap the run was made
# under. A run held after its first checkpoint (the fault shim), killed and resumed under another
# --generations continues to that cap, and its files, config.ini with the new cap included, are
# those of a run made under it from the start; a cap the checkpoint is past is refused
touch "$tmp/hold"
ST_FAULT_HOLD="$tmp/hold" LD_PRELOAD="$SHIM" "$EV" $cfg --seed 11 --generations $((G + 5)) --threads 2 \
  --out "$tmp/cap" > /dev/null 2>&1 &
pid=$!
wait_for 900 $pid test -e "$tmp/cap/checkpoint"
grep -qx "max_generations = $((G + 5))" "$tmp/cap/config.ini" && ck_cap=1 || ck_cap=0
kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null; rm -f "$tmp/hold"
"$EV" $cfg --seed 11 --generations $G --threads 2 --out "$tmp/cap" --resume > "$tmp/cap.log" 2>&1; rc=$?
"$EV" $cfg --seed 11 --generations 1 --threads 2 --out "$tmp/cap" --resume > /dev/null 2> "$tmp/cap1.err"; rc1=$?
if [ $ck_cap = 1 ] && [ $rc = 0 ] && grep -qx "max_generations = $G" "$tmp/t1/config.ini" &&
   same_files "$tmp/t1" "$tmp/cap" && [ $rc1 != 0 ] &&
   grep -q "checkpoint:2: field 'generation': $G is out of range (expected an integer in \[1, 1\]" "$tmp/cap1.err"; then
  ok "--generations is ga.max_generations in config.ini; resumed under another, the files of a run made under it"
else ko "--generations recorded" "cap $ck_cap rc $rc/$rc1 $(tail -2 "$tmp/cap.log") $(cat "$tmp/cap1.err")"; fi
expect "--generations out of the key's range is refused as the key would be" \
  "evolve: --generations 10000001 (the run's ga.max_generations): key 'ga.max_generations': 10000001 is out of range (expected an integer in [1, 10000000])" \
  "$tmp/capx" "$EV" $cfg --generations 10000001 --out "$tmp/capx"

# postures.vary_starts: main-prim open and grasp trials from drawn starts; thread-independent,
# replayed trial by trial from the same draws (the harmonic mean of F_open and F_grasp and the
# successes of the csv's last row), and other results than the fixed starts give
vary=(--generations 2 --seed 11 --set ga.population=4 --set ga.elites=1 --set ga.parents=2
      --set ga.success_genotypes=4 --set stage.primitives=open,grasp)
"$EV" configs/main_prim.cfg "${vary[@]}" --set postures.vary_starts=true --threads 1 --out "$tmp/v1" > "$tmp/v1.log" 2>&1
"$EV" configs/main_prim.cfg "${vary[@]}" --set postures.vary_starts=true --threads 2 --out "$tmp/v2" > "$tmp/v2.log" 2>&1
"$EV" configs/main_prim.cfg "${vary[@]}" --threads 2 --out "$tmp/v0" > "$tmp/v0.log" 2>&1
for k in 4 5 6 7 8 9 10 11; do
  "$APPDIR/replay" "$tmp/v1/population.genome" "$tmp/v1/config.ini" --trial $k --generation 1
done > "$tmp/vreplay.txt" 2> "$tmp/vreplay.err"
if same_files "$tmp/v1" "$tmp/v2" && ! cmp -s "$tmp/v1/fitness.csv" "$tmp/v0/fitness.csv" &&
   [ "$(grep -c 'vary_starts: the \(open\|grasp\) start drawn for generation 1 (draw [0-9]*)' "$tmp/vreplay.err")" = 8 ] &&
   grep -q '^vary_starts = true' "$tmp/v1/config.ini" &&
   python3 - "$tmp/vreplay.txt" "$tmp/v1/fitness.csv" <<'PY'
import csv, re, sys
fp, succ = [0.0, 0.0], []
for line in open(sys.argv[1]):
    k = int(line.split()[1])
    fp[k // 4 - 1] += float(re.search(r"F_contribution=(\S+)", line).group(1))
    succ.append(int(re.search(r"success=(\d)", line).group(1)))
F = 2 / sum(1 / max(x, 0.001) for x in fp)
row = list(csv.DictReader(open(sys.argv[2])))[-1]
want = [int(row["best_t%d" % t]) for t in range(4, 12)]
print("replay F %.6f vs csv %s, successes %s vs %s" % (F, row["best"], succ, want))
sys.exit(0 if succ == want and abs(F - float(row["best"])) < 1e-4 else 1)
PY
then
  ok "postures.vary_starts: threads 1 = 2, replayed from the same draws, other results than fixed starts"
else
  ko "postures.vary_starts" "$(tail -2 "$tmp/v1.log") $(cat "$tmp/vreplay.txt" "$tmp/vreplay.err" | tail -3)"
fi

# postures.vary_replace_generations = 1 with extra: generation 0 is replace's (the row of the
# replace run above: the same seed, population and trials), generation 1 extra's (its varied
# trials run); the progress line says which; a varied trial of generation 0 is not replayed
"$EV" configs/main_prim.cfg "${vary[@]}" --set postures.vary_starts=true --set postures.vary_trials=extra \
  --set postures.vary_replace_generations=1 --threads 2 --out "$tmp/vs" > "$tmp/vs.log" 2>&1
"$APPDIR/replay" "$tmp/vs/population.genome" "$tmp/vs/config.ini" --trial 28 --generation 0 > /dev/null 2> "$tmp/vs0.err"
vs0=$?
"$APPDIR/replay" "$tmp/vs/population.genome" "$tmp/vs/config.ini" --trial 28 --generation 1 > /dev/null 2>&1
if [ $vs0 != 0 ] && [ $? = 0 ] && grep -q "generation 0 runs no varied trials .*expected --generation 1 or later" "$tmp/vs0.err" &&
   grep -q "^gen    0 .*(varied: replacing 8)" "$tmp/vs.log" && grep -q "^gen    1 .*(varied [0-8]/8)" "$tmp/vs.log" &&
   python3 - "$tmp/v1/fitness.csv" "$tmp/vs/fitness.csv" <<'PY'
import csv, sys
rep, sch = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
same = [k for k in rep[0] if k in sch[0]]
v0 = [sch[0]["best_v%d" % t] for t in range(8)]
print("generation 0 alike in %s; varied columns %s" % (all(rep[0][k] == sch[0][k] for k in same), v0))
sys.exit(0 if all(rep[0][k] == sch[0][k] for k in same) and v0 == ["0"] * 8 and
         rep[1]["best"] != sch[1]["best"] else 1)
PY
then
  ok "postures.vary_replace_generations: generation 0 as replace, generation 1 with the varied trials"
else
  ko "postures.vary_replace_generations" "$(tail -2 "$tmp/vs.log") $(cat "$tmp/vs0.err")"
fi

# a first stage completing at the run's generation limit leaves the next one unrun: the run
# stops at the limit, not with "all stages complete" (4 of the first 10 genotypes of
# data/evolved/simple_prim_s3.genome solve simple-prim's 16 at seed 3's generation 0)
"$EV" configs/prims.cfg --seed 3 --generations 1 --threads 1 --out "$tmp/sl" \
  --set stage.init_population=data/evolved/simple_prim_s3.genome --set ga.population=10 \
  --set ga.elites=1 --set ga.parents=2 --set ga.success_genotypes=2 > "$tmp/sl.log" 2>&1
if grep -q "^evolve: simple-prim complete at generation 0" "$tmp/sl.log" &&
   grep -q "^evolve: stopped after generation 0 (generation limit)" "$tmp/sl.log" &&
   ! grep -q "all stages complete" "$tmp/sl.log"; then
  ok "simple-prim complete at the generation limit: stopped at the limit, main-prim not run"
else
  ko "a stage complete at the limit" "$(tail -2 "$tmp/sl.log")"
fi

# stage.handover and stage.chain_trials (SPEC 12): main-prim's hand-over trials (open's, here)
# and chained trials; thread-independent; the hand-over trials replayed one by one (the fixed
# and hand-over trials' shares of F_open, summed, are the best's fitness, the successes those of
# the csv's last row); with chained trials F is the harmonic mean of F_open and F_chain
ho=(--generations 2 --seed 12 --set ga.population=4 --set ga.elites=1 --set ga.parents=2
    --set ga.success_genotypes=4 --set stage.primitives=open
    --set stage.init_population=data/evolved/prims_s2/population.genome)
"$EV" configs/main_prim.cfg "${ho[@]}" --set stage.handover=true --threads 1 --out "$tmp/h1" > "$tmp/h1.log" 2>&1
"$EV" configs/main_prim.cfg "${ho[@]}" --set stage.handover=true --threads 2 --out "$tmp/h2" > "$tmp/h2.log" 2>&1
chain=(--set stage.chain_trials=2 --set integrated.steps=60)
"$EV" configs/main_prim.cfg "${ho[@]}" "${chain[@]}" --threads 1 --out "$tmp/c1" > "$tmp/c1.log" 2>&1
"$EV" configs/main_prim.cfg "${ho[@]}" "${chain[@]}" --threads 2 --out "$tmp/c2" > "$tmp/c2.log" 2>&1
for k in 4 5 6 7 16 17 18 19; do
  "$APPDIR/replay" "$tmp/h1/population.genome" "$tmp/h1/config.ini" --trial $k --generation 1 --index 0
done > "$tmp/hreplay.txt" 2> "$tmp/hreplay.err"
if same_files "$tmp/h1" "$tmp/h2" && same_files "$tmp/c1" "$tmp/c2" &&
   grep -q '(hand-over [ 0-9]*/4, [ 0-9]* handed over)' "$tmp/h1.log" &&
   grep -q '(chained [0-2]/2, F_chain' "$tmp/c1.log" &&
   [ "$(grep -c 'handover_step=' "$tmp/hreplay.txt")" = 4 ] &&
   python3 - "$tmp/hreplay.txt" "$tmp/h1/fitness.csv" "$tmp/c1/fitness.csv" <<'PY'
import csv, re, sys
F, succ = 0.0, []
for line in open(sys.argv[1]):
    F += float(re.search(r"F_contribution=(\S+)", line).group(1))
    succ.append(int(re.search(r"success=(\d)", line).group(1)))
row = list(csv.DictReader(open(sys.argv[2])))[-1]
want = [int(row["best_t%d" % t]) for t in range(4, 8)] + [int(row["best_h%d" % t]) for t in range(4)]
c = list(csv.DictReader(open(sys.argv[3])))[-1]
Fc = 2 / (1 / max(float(c["best_F_open"]), 0.001) + 1 / max(float(c["best_F_chain"]), 0.001))
print("replay F_open %.6f vs csv %s, successes %s vs %s; chained F %.6f vs %s" %
      (F, row["best"], succ, want, Fc, c["best"]))
sys.exit(0 if succ == want and abs(F - float(row["best"])) < 1e-4 and
         abs(Fc - float(c["best"])) < 1e-9 * Fc and "best_c1" in c else 1)
PY
then
  ok "stage.handover and stage.chain_trials: threads 1 = 2, hand-over trials replayed to the csv's F and successes"
else
  ko "stage.handover, stage.chain_trials" "$(tail -2 "$tmp/h1.log" "$tmp/c1.log") $(cat "$tmp/hreplay.txt" "$tmp/hreplay.err" | tail -3)"
fi

# stage.handover_rollin = elite: the hand-over trials' roll-in acted by the generation's genotype
# 0 (its elite), from the hand-over step on by the individual; threads 1 = 2 over 2 generations,
# other results than self roll-ins. The initial population puts a weaker genotype of prims_s2
# (its 61st) first, so that generation 0's best is not its elite: that best's trials, replayed
# from the initial population with --rollin (genotype 0), and generation 1's best's, with the
# run's best.genome (generation 0's best is generation 1's elite), give the csv's F and
# successes; a hand-over trial of such a config is refused without --rollin
P=data/evolved/prims_s2/population.genome
{ echo "# genes 612"; for g in 60 0 1 2; do sed -n "$((3 * g + 4))p" $P; done; } > "$tmp/einit.genome"
el=("${ho[@]}" --set stage.init_population="$tmp/einit.genome" --set stage.handover=true
    --set stage.handover_rollin=elite)
"$EV" configs/main_prim.cfg "${el[@]}" --threads 1 --out "$tmp/e1" > "$tmp/e1.log" 2>&1
"$EV" configs/main_prim.cfg "${el[@]}" --threads 2 --out "$tmp/e2" > "$tmp/e2.log" 2>&1
"$EV" configs/main_prim.cfg "${el[@]}" --set stage.handover_rollin=self --threads 1 --out "$tmp/es" > /dev/null 2>&1
b0=$(($(grep -v '^#' "$tmp/einit.genome" | grep -n -x -F "$(grep -v '^#' "$tmp/e1/best.genome" | head -1)" | cut -d: -f1 | head -1) - 1))
for k in 4 5 6 7 16 17 18 19; do
  r=(); [ $k -ge 16 ] && r=(--rollin "$tmp/einit.genome")
  "$APPDIR/replay" "$tmp/einit.genome" "$tmp/e1/config.ini" --trial $k --generation 0 --index $b0 "${r[@]}"
done > "$tmp/ereplay0.txt" 2> "$tmp/ereplay0.err"
for k in 4 5 6 7 16 17 18 19; do
  r=(); [ $k -ge 16 ] && r=(--rollin "$tmp/e1/best.genome")
  "$APPDIR/replay" "$tmp/e1/population.genome" "$tmp/e1/config.ini" --trial $k --generation 1 --index 0 "${r[@]}"
done > "$tmp/ereplay1.txt" 2> "$tmp/ereplay1.err"
"$APPDIR/replay" "$tmp/e1/population.genome" "$tmp/e1/config.ini" --trial 16 --generation 1 > /dev/null 2> "$tmp/enoroll.err"; rc=$?
if same_files "$tmp/e1" "$tmp/e2" && ! cmp -s "$tmp/e1/fitness.csv" "$tmp/es/fitness.csv" &&
   grep -q '^handover_rollin = elite' "$tmp/e1/config.ini" && [ "$b0" -ge 1 ] &&
   [ "$(cat "$tmp/ereplay0.txt" "$tmp/ereplay1.txt" | grep -c 'handover_step=')" = 8 ] &&
   [ "$(grep -c 'roll-in by genotype 0 of .*einit.genome (stage.handover_rollin = elite)' "$tmp/ereplay0.err")" = 4 ] &&
   [ "$(grep -c 'roll-in by genotype 0 of .*best.genome (stage.handover_rollin = elite)' "$tmp/ereplay1.err")" = 4 ] &&
   [ $rc != 0 ] && grep -q 'stage.handover_rollin = elite): give it with --rollin FILE' "$tmp/enoroll.err" &&
   python3 - "$tmp/ereplay0.txt" "$tmp/ereplay1.txt" "$tmp/e1/fitness.csv" <<'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[3])))
ok = True
for g in (0, 1):
    F, succ = 0.0, []
    for line in open(sys.argv[1 + g]):
        F += float(re.search(r"F_contribution=(\S+)", line).group(1))
        succ.append(int(re.search(r"success=(\d)", line).group(1)))
    row = rows[g]
    want = [int(row["best_t%d" % t]) for t in range(4, 8)] + [int(row["best_h%d" % t]) for t in range(4)]
    print("generation %d: replay F_open %.6f vs csv %s, successes %s vs %s" % (g, F, row["best"], succ, want))
    ok = ok and succ == want and abs(F - float(row["best"])) < 1e-4
sys.exit(0 if ok else 1)
PY
then
  ok "stage.handover_rollin = elite: threads 1 = 2, hand-over trials replayed with the elite to the csv's F and successes"
else
  ko "stage.handover_rollin = elite" "best of generation 0: genotype $b0; $(tail -2 "$tmp/e1.log") $(cat "$tmp/ereplay0.txt" "$tmp/ereplay1.txt" "$tmp/ereplay0.err" "$tmp/enoroll.err" | tail -5)"
fi
# killed and resumed: the elite is the checkpointed population's genotype 0, nothing more
el4=("${el[@]}" --generations 4)
"$EV" configs/main_prim.cfg "${el4[@]}" --threads 1 --out "$tmp/e4" > /dev/null 2>&1
touch "$tmp/hold" # held after its first checkpoint (the fault shim), however busy the machine
ST_FAULT_HOLD="$tmp/hold" LD_PRELOAD="$SHIM" "$EV" configs/main_prim.cfg "${el4[@]}" --threads 2 \
  --out "$tmp/ek" > /dev/null 2>&1 &
pid=$!
wait_for 900 $pid test -e "$tmp/ek/checkpoint"
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
rm -f "$tmp/hold"
done_before=$(($(wc -l < "$tmp/ek/fitness.csv") - 1))
"$EV" configs/main_prim.cfg "${el4[@]}" --threads 1 --out "$tmp/ek" --resume > "$tmp/ek.log" 2>&1
if [ "$done_before" -ge 1 ] && [ "$done_before" -lt 4 ] && same_files "$tmp/e4" "$tmp/ek"; then
  ok "stage.handover_rollin = elite: killed after $done_before generations, resumed: identical files"
else
  ko "elite roll-ins resumed" "killed after $done_before generations: $(tail -2 "$tmp/ek.log")"
fi
# refused where it cannot act: without hand-over trials, in a stage that has none, without elites
"$EV" configs/main_prim.cfg --generations 1 --set stage.handover_rollin=elite --out "$tmp/er1" > /dev/null 2> "$tmp/er1.err"; r1=$?
"$EV" configs/simple_prim.cfg --generations 1 --set stage.handover=true --set stage.handover_rollin=elite --out "$tmp/er2" > /dev/null 2> "$tmp/er2.err"; r2=$?
"$EV" configs/main_prim.cfg --generations 1 --set stage.handover=true --set stage.handover_rollin=elite --set ga.elites=0 --out "$tmp/er3" > /dev/null 2> "$tmp/er3.err"; r3=$?
"$EV" configs/integrated_st.cfg --generations 1 --set stage.handover=true --set stage.handover_rollin=elite --out "$tmp/er4" > /dev/null 2> "$tmp/er4.err"; r4=$?
if [ $r1 != 0 ] && grep -q "stage.handover_rollin.*expected stage.handover = true" "$tmp/er1.err" &&
   [ $r2 != 0 ] && grep -q "stage.handover" "$tmp/er2.err" && grep -q "main-prim" "$tmp/er2.err" &&
   [ $r3 != 0 ] && grep -q "stage.handover_rollin.*ga.elites >= 1" "$tmp/er3.err" &&
   [ $r4 != 0 ] && grep -q "stage.handover" "$tmp/er4.err" &&
   [ ! -e "$tmp/er1" ] && [ ! -e "$tmp/er2" ] && [ ! -e "$tmp/er3" ] && [ ! -e "$tmp/er4" ]; then
  ok "stage.handover_rollin = elite refused without hand-over trials, in simple-prim and the integrated stage, without elites"
else
  ko "elite roll-ins refused" "$(cat "$tmp/er1.err" "$tmp/er2.err" "$tmp/er3.err" "$tmp/er4.err")"
fi

# trials the simulation gives up on are reported: with a speed limit of 1 mm/s every one of the
# 4 genotypes x 4 grasp trials diverges (the --set options also check population-dependent
# rules only once all are in: population=4 comes before elites=1)
"$EV" configs/main_prim.cfg --generations 1 --threads 1 --out "$tmp/un" --set ga.population=4 \
  --set ga.elites=1 --set ga.parents=2 --set ga.success_genotypes=1 --set stage.primitives=grasp \
  --set dynamics.unstable_speed=0.001 > "$tmp/un.log" 2>&1
if grep -q '^gen    0 .* solves  0/4 .*| 16 unstable trials$' "$tmp/un.log"; then
  ok "unstable trials counted in the progress line; --set order free"
else
  ko "unstable trials" "$(cat "$tmp/un.log")"
fi

# bad input, refused before any work (no output directory appears)
printf '[stage]\nstages = simple_prim\n[ga]\nelites = 200\n' > "$tmp/bad.cfg"
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
expect "missing config refused" "$tmp/none.cfg: cannot open: No such file or directory" "$tmp/b3" "$EV" "$tmp/none.cfg" --out "$tmp/b3"
# a dynamic world that cannot be built is refused before simple-prim runs, not after it
expect "bad dynamics.kinematic_joints refused before the first stage" \
  "dynamics.kinematic_joints: 'l_elbow' names 1 joints but not 'torso_pitch'" "$tmp/b4" \
  "$EV" configs/prims.cfg --out "$tmp/b4" --set dynamics.kinematic_joints=l_elbow
# keys none of the run's stages reads are refused unless at their default (never silently
# ignored): the integrated stage's keys in a primitive run, the dynamic world's in simple-prim
expect "network.arch refused by the primitive stages" \
  "key 'network.arch': A is read only by the integrated stage and the integration, robustness and generalisation tests, which this run (simple-prim) does not have" \
  "$tmp/b4" "$EV" $cfg --out "$tmp/b4" --set network.arch=A
for kv in network.typeb_init_gene=1 ga.mutation_rate_integrated=0.05 ga.integrated_generations=7; do
  expect "$kv refused by the primitive stages" "key '${kv%%=*}': ${kv#*=} is read only by the integrated stage" \
    "$tmp/b5" "$EV" configs/prims.cfg --out "$tmp/b5" --set "$kv"
done
expect "a dynamics key refused by simple-prim" \
  "key 'dynamics.gravity': 5 is read only by the main-prim and integrated stages" "$tmp/b6" \
  "$EV" $cfg --out "$tmp/b6" --set dynamics.gravity=5
expect "the hand's dynamics.kinematic_joints refused by simple-prim" \
  "key 'dynamics.kinematic_joints': torso_pitch is read only by the main-prim and integrated stages" \
  "$tmp/b7" "$EV" $cfg --out "$tmp/b7" --set dynamics.kinematic_joints=torso_pitch
# and the primitive stages' keys in an integrated run (its trials start from the reach postures,
# last integrated.steps, stop after ga.integrated_generations)
expect "ga.max_generations refused by the integrated stage" \
  "key 'ga.max_generations': 7 is read only by the simple-prim and main-prim stages, which this run (integrated) does not have" \
  "$tmp/b8" "$EV" configs/integrated_ct.cfg --out "$tmp/b8" --set ga.max_generations=7
expect "a grasp posture refused by the integrated stage" \
  "key 'postures.grasp_partial_thumb_flex': 0.1 is read only by the simple-prim and main-prim stages" \
  "$tmp/b9" "$EV" configs/integrated_st.cfg --out "$tmp/b9" --set postures.grasp_partial_thumb_flex=0.1

# network.arch acts in replay: the base genotype is refused as type A (612 genes, 696 expected);
# grown to type A with 84 random genes it replays trial 5 exactly as the base genotype, because
# type A's linguistic cluster feeds nothing the motor outputs or the focus read (thesis 2.9.1)
python3 - "$tmp/t1/best.genome" "$tmp/grown.genome" <<'PY'
import random, sys
last = [l.strip() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")][-1]
r = random.Random(13)
with open(sys.argv[2], "w") as f:
    f.write("# genes 696\n" + last + "".join("%04x" % r.randrange(65536) for _ in range(84)) + "\n")
PY
"$APPDIR/replay" "$tmp/t1/best.genome" "$tmp/t1/config.ini" --trial 5 --set network.arch=A > /dev/null 2> "$tmp/ra1.err"; rc=$?
"$APPDIR/replay" "$tmp/grown.genome" "$tmp/t1/config.ini" --trial 5 --generation $last --set network.arch=A \
  > "$tmp/ra2.txt" 2> "$tmp/ra2.err"
if [ $rc != 0 ] && grep -q "612 genes (expected 696) (network.arch = A)" "$tmp/ra1.err" &&
   [ -s "$tmp/ra2.txt" ] && cmp -s "$tmp/ra2.txt" "$tmp/rb1.txt"; then
  ok "replay reads network.arch: a base genotype refused as A; grown to A it replays the same trial"
else
  ko "replay network.arch" "$(cat "$tmp/ra1.err" "$tmp/ra2.err" "$tmp/ra2.txt")"
fi
echo "check_evolve: $pass passed, $fail failed"
[ "$fail" = 0 ]
