#!/usr/bin/env bash
# apps/posteval end to end (thesis 2.10, SPEC 11), on shrunk tables (--set) so that it stays a
# few seconds: the integration test on the committed primitive runs (a population file and a
# run still going: its checkpoint), the robustness and generalisation tests on tiny integrated
# runs made here with evolve (2 genotypes from prims_s2, 30-step trials, 2 generations). The
# trial tables are checked row by row against SPEC 11 (posture, object, target, words), the
# summaries against the trial rows, the exclusion rule on a run whose last fitness.csv row is
# edited, the files on 1 and 2 threads byte for byte; bad input is refused before any trial.
set -uo pipefail
CHECK=check_posteval
source "$(dirname "$0")/check_lib.sh"
PE="$APPDIR/posteval"
EV="$APPDIR/evolve"

# ---- tiny integrated runs: ST-CT seeds 1 and 2, NI seed 1
tiny=(--set integrated.populations=data/evolved/prims_s2/population.genome --set integrated.top=2
      --set ga.population=2 --set ga.elites=1 --set ga.parents=1 --set integrated.steps=30
      --generations 2 --threads 1)
for r in stct:1 stct:2 ni:1; do
  c=${r%%:*} s=${r##*:}
  "$EV" configs/integrated_$c.cfg "${tiny[@]}" --seed "$s" --out "$tmp/$c-s$s" > "$tmp/ev.log" 2>&1 ||
    ko "evolve $c seed $s" "$(tail -2 "$tmp/ev.log")"
done

# the rows of trials.csv and summary.csv against SPEC 11, in python: TEST DIR WORDS CONDITION
# EXPECTED_INDIVIDUALS [EXCLUDED_RUN]
check_files() {
  python3 - "$@" <<'PY'
import csv, math, sys
sys.path.insert(0, "tools")
import csvschema  # the library's columns (tools/csvschema.c)
test, d, words, cond, nind = sys.argv[1:6]
excluded = sys.argv[6] if len(sys.argv) > 6 else None
rows = list(csv.DictReader(open(d + "/trials.csv")))
summ = list(csv.DictReader(open(d + "/summary.csv")))
cfg = {}
sec = ""
for line in open(d + "/config.ini"):
    line = line.split("#")[0].strip()
    if line.startswith("["): sec = line[1:-1]
    elif "=" in line:
        k, v = (x.strip() for x in line.split("=", 1)); cfg[sec + "." + k] = v
bad = []
def need(ok, what):
    if not ok: bad.append(what)
need(list(rows[0].keys()) == list(csvschema.TRIALS) if rows else True, "trials.csv header")
need(list(summ[0].keys()) == list(csvschema.SUMMARY), "summary header")
need(len(summ) == int(nind), "%d summary rows (expected %s)" % (len(summ), nind))
P = [(0.40, 0.10), (0.20, 0.10), (0.30, 0.20), (0.30, 0.00)]
T = [(0.25, 0.10, 0.17), (0.25, -0.10, 0.17)]
n = int(cfg["posteval.generalisation_cells"]); size = float(cfg["posteval.generalisation_cell_size"])
reps = int(cfg["posteval.generalisation_repetitions"])
if test == "generalisation": ntr = n * n * 4 * reps; steps = int(cfg["posteval.generalisation_steps"])
else:
    ntr = int(cfg["posteval.%s_trials" % test]); steps = int(cfg["integrated.steps"])
for r in rows:
    i = int(r["trial"])
    need(r["test"] == test and r["condition"] == cond and r["words"] == words, "labels of %s" % r)
    if test == "generalisation":
        cell, post, rep = i // (4 * reps), i // reps % 4, i % reps
        cx, cy = 0.30 + (cell // n - (n - 1) / 2) * size, 0.10 + (cell % n - (n - 1) / 2) * size
        need((int(r["cell"]), int(r["posture"]), int(r["repetition"]), int(r["type"])) == (cell, post, rep, -1), "cell/posture/rep of trial %d" % i)
        need(abs(float(r["obj_x"]) - cx) <= 0.005 + 1e-12 and abs(float(r["obj_y"]) - cy) <= 0.005 + 1e-12, "object of trial %d" % i)
        need((r["target_x"], r["target_y"], r["target_z"]) == ("0.25", "0", "0.17000000000000001"), "target of trial %d" % i)
    else:
        k = i % 4
        need((int(r["type"]), int(r["posture"]), int(r["repetition"]), int(r["cell"])) == (k, k, i // 4, -1), "type/posture/rep of trial %d" % i)
        need(all(abs(float(r[c]) - v) <= 0.02 + 1e-12 for c, v in zip(("obj_x", "obj_y"), P[k])), "object of trial %d" % i)
        need(all(abs(float(r[c]) - v) <= 0.02 + 1e-12 for c, v in zip(("target_x", "target_y", "target_z"), T[k % 2])), "target of trial %d" % i)
    succ = r["success"] == "1"
    need(set(r["heard"]) <= set("rogm+"), "heard %s" % r["heard"])
    if words == "none": need(r["heard"] == "", "heard none %s" % r["heard"])
    if words == "caretaker": need(r["heard"] == "" or r["heard"][0] == "r", "caretaker starts with reach")
    need(r["open_jumped"] == str(int("o" not in r["heard"] and any(c in r["heard"] for c in "gm"))), "open_jumped %s" % r)
    need((int(r["reached_step"]) + 1 == int(r["steps_run"])) if succ else r["reached_step"] == "-1", "steps of %s" % r)
    need(int(r["steps_run"]) <= steps and (succ or r["end"] != "success"), "length of trial %d" % i)
# the same trials for every individual; the summary from the rows
by = {}
for r in rows: by.setdefault((r["run"], r["individual"]), []).append(r)
labels = {}
for s in summ: labels.setdefault(s["run_label"], set()).add(s["run"])
need(all(len(v) == 1 for v in labels.values()) and len(set().union(*labels.values())) == len(labels), "run numbers and labels")
need(all(r["run_label"] == next(s["run_label"] for s in summ if s["run"] == r["run"]) for r in rows), "run labels of rows")
tables = {tuple((r["trial"], r["obj_x"], r["obj_y"], r["target_x"], r["target_y"], r["target_z"]) for r in v) for v in by.values()}
need(len(tables) <= 1, "every individual sees the same table")
for s in summ:
    mine = by.get((s["run"], s["individual"]), [])
    ex = s["excluded"] == "1"
    need(ex == (s["run_label"] == excluded), "excluded flag of %s" % s["run_label"])
    need(len(mine) == (0 if ex else ntr) and int(s["trials"]) == ntr, "%d trial rows of %s (expected %d)" % (len(mine), s["run"], ntr))
    sc = sum(r["success"] == "1" for r in mine)
    need(int(s["successes"]) == sc and float(s["success_rate"]) == sc / ntr, "successes of %s" % s["run"])
    need(int(s["open_jumped"]) == sum(r["open_jumped"] == "1" for r in mine), "open_jumped of %s" % s["run"])
    st = [int(r["reached_step"]) + 1 for r in mine if r["success"] == "1"]
    m = float(s["mean_steps_to_target"])
    need(math.isnan(m) if not st else abs(m - sum(st) / len(st)) < 1e-12, "mean steps of %s" % s["run"])
print("%s %s: %d trial rows, %d summary rows, successes %s%s" % (test, cond, len(rows), len(summ),
      [s["successes"] for s in summ], "; " + "; ".join(bad[:5]) if bad else ""))
sys.exit(1 if bad else 0)
PY
}

same_out() { # DIR1 DIR2: the four files byte for byte, and no temporary file left
  for f in trials.csv summary.csv config.ini posteval.journal; do
    cmp -s "$1/$f" "$2/$f" || { echo "  $f differs"; return 1; }
  done
  [ "$(ls "$1" | wc -l)" = 4 ] && [ "$(ls "$2" | wc -l)" = 4 ]
}

# ---- integration: a population file and a run still going (its checkpoint)
int=(--set posteval.integration_top=2 --set posteval.integration_trials=8 --set integrated.steps=60)
"$PE" integration configs/prims.cfg data/evolved/prims_s2/population.genome data/evolved/prims_s3_run \
  "${int[@]}" --threads 1 --out "$tmp/i1" > "$tmp/i1.out" 2> "$tmp/i1.err"
rc1=$?
"$PE" integration configs/prims.cfg data/evolved/prims_s2/population.genome data/evolved/prims_s3_run \
  "${int[@]}" --threads 2 --out "$tmp/i2" > /dev/null 2>&1
if [ $rc1 = 0 ] && check_files integration "$tmp/i1" caretaker incremental 4 &&
   [ "$(cut -d, -f3,9 "$tmp/i1/summary.csv" | sort -u | tr '\n' ' ')" = "0,prims_s2 1,prims_s3_run run,run_label " ] &&
   grep -q '^posteval integration incremental: 32/32 trials (100.0%)' "$tmp/i1.err" &&
   grep -q '4 individuals (0 excluded), 32 trials' "$tmp/i1.err"; then
  ok "integration: top 2 of 2 primitive runs x 8 caretaker trials, rows as SPEC 11, summary, progress"
else ko "integration" "$(tail -2 "$tmp/i1.err")"; fi
if same_out "$tmp/i1" "$tmp/i2"; then ok "integration: 1 and 2 threads give byte-identical files"
else ko "integration threads"; fi

# replay --posteval: the same trial run again on its own, traced, must end as posteval's row says
# (genotype 1 of prims_s2, its 8 trials: heard,success,reached_step,end,steps_run,open_jumped)
RP="$APPDIR/replay"
want=$(awk -F, 'NR > 1 && $3 == 0 && $4 == 1 { print $5, $15, $11, $12, $16, $17, $13 }' "$tmp/i1/trials.csv")
got=$(for i in 0 1 2 3 4 5 6 7; do
  "$RP" data/evolved/prims_s2/population.genome configs/prims.cfg --posteval integration --trial $i \
    --index 1 "${int[@]}" --out "$tmp/rp$i.csv" 2> /dev/null |
    sed -E 's/.*trial ([0-9]+) .* heard=([a-z+]*) success=([01]) reached_step=(-?[0-9]+) steps=([0-9]+)\/[0-9]+ end=([a-z]+) open_jumped=([01])$/\1 \2 \3 \4 \6 \5 \7/'
done)
rows=$(awk 'END { print NR }' "$tmp/rp7.csv")
steps7=$(echo "$want" | awk '$1 == 7 { print $6 }')
if [ -n "$want" ] && [ "$got" = "$want" ] && [ "$rows" = $((steps7 + 1)) ] &&
   { "$RP" data/evolved/prims_s2/population.genome configs/prims.cfg --posteval robustness --trial 0 \
     --caretaker > "$tmp/rpc" 2>&1; [ $? = 2 ]; } && grep -q -- '--caretaker is the generalisation test' "$tmp/rpc"; then
  ok "replay --posteval integration: 8 trials end as posteval's rows (words heard, success, steps), one trace row per step"
else ko "replay --posteval" "want: $(echo $want | head -c 200) got: $(echo $got | head -c 200)"; fi

# ---- a killed test resumes (--resume) to the files of one run straight through
kr=(integration configs/prims.cfg data/evolved/prims_s2/population.genome
    --set posteval.integration_top=2 --set posteval.integration_trials=40 --set integrated.steps=100)
"$PE" "${kr[@]}" --threads 2 --out "$tmp/k1" > /dev/null 2>&1
"$PE" "${kr[@]}" --threads 1 --journal-every 0 --out "$tmp/k2" > /dev/null 2>&1 &
pid=$!
journalled() { [ "$(grep -c '^[0-9]' "$tmp/k2/posteval.journal" 2>/dev/null)" -ge 5 ] 2>/dev/null; }
wait_for 900 $pid journalled # until some trials are journalled (an event: no deadline)
kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null
before=$(grep -c '^[0-9]' "$tmp/k2/posteval.journal" 2>/dev/null || echo 0)
# what a kill -9 mid-write leaves (whether this one did depends on when it landed)
touch "$tmp/k2/posteval.journal.tmp.999999" "$tmp/k2/trials.csv.tmp.1"
"$PE" "${kr[@]}" --threads 2 --out "$tmp/k2" > /dev/null 2> "$tmp/k2.err"; rc_no=$?
left=$(ls "$tmp/k2" | grep -c '\.tmp\.')
"$PE" "${kr[@]}" --threads 2 --out "$tmp/k2" --resume > /dev/null 2> "$tmp/k2r.err"; rc=$?
if [ "$before" -ge 5 ] && [ "$before" -lt 80 ] && [ $rc_no = 2 ] && [ "$left" -ge 2 ] &&
   grep -q 'give --resume' "$tmp/k2.err" && [ $rc = 0 ] && same_out "$tmp/k1" "$tmp/k2" &&
   grep -q "80 trials ($before from the journal)" "$tmp/k2r.err"; then
  ok "killed after $before of 80 trials, --resume gives the files of a run straight through and removes the killed writer's temporary files (refused without --resume, which changes nothing)"
else ko "resume" "before=$before rc=$rc_no/$rc left=$left $(ls "$tmp/k2") $(tail -1 "$tmp/k2r.err")"; fi
# the journal's results are used as they are: unit 0 made open_jumped (heard grasp only) shows in the summary
cp -r "$tmp/k2" "$tmp/k3"
sed -i 's/^0,\(.*\),0,\([a-z]*\)$/0,\1,1,g/' "$tmp/k3/posteval.journal"  # heard grasp, never open
"$PE" "${kr[@]}" --out "$tmp/k3" --resume > /dev/null 2>&1
j1=$(awk -F, 'NR == 2 { print $8 }' "$tmp/k1/summary.csv") j3=$(awk -F, 'NR == 2 { print $8 }' "$tmp/k3/summary.csv")
if [ -n "$j1" ] && [ "$j3" = $((j1 + 1)) ]; then ok "resume takes the journalled results (an edited unit shows: open_jumped $j1 -> $j3)"
else ko "resume reads the journal" "open_jumped $j1 -> $j3"; fi
# a journal of other keys, and a damaged one, are refused naming the file and line
"$PE" "${kr[@]}" --set integrated.steps=90 --out "$tmp/k2" --resume > /dev/null 2> "$tmp/e1"; rc1=$?
sed -i '7s/^\([0-9]*\),0,/\1,7,/' "$tmp/k2/posteval.journal"
"$PE" "${kr[@]}" --out "$tmp/k2" --resume > /dev/null 2> "$tmp/e2"; rc2=$?
if [ $rc1 = 2 ] && grep -q 'posteval.journal:2: .* belongs to another test' "$tmp/e1" &&
   [ $rc2 = 2 ] && grep -q 'posteval.journal:7: not a trial line' "$tmp/e2" &&
   cmp -s "$tmp/k1/summary.csv" "$tmp/k2/summary.csv"; then
  ok "resume refuses a journal of other keys (line 2) and a damaged line (line 7); the files stay"
else ko "resume refusals" "$rc1 $(cat "$tmp/e1") / $rc2 $(cat "$tmp/e2")"; fi
# the journal covers the robot model read from robot.urdf (issue 48: a URDF changed in place,
# under the same key, left the journal resumable): a link's mass changed makes it another test's,
# a comment added to the file (nothing the model holds) does not
cp data/icub_left_arm.urdf "$tmp/arm.urdf"
ku=(integration configs/prims.cfg data/evolved/prims_s2/population.genome --set robot.urdf="$tmp/arm.urdf"
    --set posteval.integration_top=1 --set posteval.integration_trials=2 --set integrated.steps=5)
"$PE" "${ku[@]}" --out "$tmp/u1" > /dev/null 2> "$tmp/u0.err"; rc0=$?
sed -i '31s|<mass value="0.91179"/>|<mass value="0.91180"/>|' "$tmp/arm.urdf"
"$PE" "${ku[@]}" --out "$tmp/u1" --resume > /dev/null 2> "$tmp/u1.err"; rc1=$?
cp data/icub_left_arm.urdf "$tmp/arm.urdf" && echo '<!-- a comment: the same model -->' >> "$tmp/arm.urdf"
"$PE" "${ku[@]}" --out "$tmp/u1" --resume > /dev/null 2> "$tmp/u2.err"; rc2=$?
if [ $rc0 = 0 ] && [ $rc1 = 2 ] && grep -q 'posteval.journal:2: .* belongs to another test' "$tmp/u1.err" &&
   [ $rc2 = 0 ]; then
  ok "the journal covers the robot model: the URDF changed in place is refused, a comment added is not"
else ko "journal and the URDF" "$rc0/$rc1/$rc2 $(cat "$tmp/u0.err" "$tmp/u1.err" "$tmp/u2.err" | tail -3)"; fi
# the journal goes through the bounded reader (issue 17): a NUL byte, and a journal larger than
# its units can fill, are refused
cp -r "$tmp/k1" "$tmp/k4" && sed -i '6s/,/,\x00/' "$tmp/k4/posteval.journal"
"$PE" "${kr[@]}" --out "$tmp/k4" --resume > /dev/null 2> "$tmp/e3"; rc3=$?
cp -r "$tmp/k1" "$tmp/k5" && head -c 30000 /dev/zero | tr '\0' 'x' >> "$tmp/k5/posteval.journal"
"$PE" "${kr[@]}" --out "$tmp/k5" --resume > /dev/null 2> "$tmp/e4"; rc4=$?
if [ $rc3 = 2 ] && grep -q 'posteval.journal:6: NUL byte at column [0-9]* (expected a text file)' "$tmp/e3" &&
   [ $rc4 = 2 ] && grep -q 'posteval.journal: larger than .* (expected an input file of at most 21504 bytes)' "$tmp/e4"; then
  ok "resume refuses a journal with a NUL byte (line 6) or larger than its 80 units can fill"
else ko "journal through the bounded reader" "$rc3 $(cat "$tmp/e3") / $rc4 $(cat "$tmp/e4")"; fi

# ---- robustness: two ST-CT runs (self talk), one NI run (no words)
rob=(--set posteval.robustness_trials=8 --set integrated.steps=40)
"$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" "$tmp/stct-s2" "${rob[@]}" --threads 1 \
  --out "$tmp/r1" > /dev/null 2> "$tmp/r1.err"
rc1=$?
"$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" "$tmp/stct-s2" "${rob[@]}" --threads 2 \
  --out "$tmp/r2" > /dev/null 2>&1
"$PE" robustness configs/integrated_ni.cfg "$tmp/ni-s1" "${rob[@]}" --out "$tmp/rn" > /dev/null 2>&1
rc3=$?
if [ $rc1 = 0 ] && [ $rc3 = 0 ] && check_files robustness "$tmp/r1" selftalk ST-CT 2 &&
   check_files robustness "$tmp/rn" none NI 1 &&
   [ "$(awk -F, 'NR > 1 { print $13 }' "$tmp/r1/summary.csv" | tr '\n' ' ')" = "1 1 " ]; then
  ok "robustness: ST-CT (self talk) and NI (no words), the best of the last generation (1), rows as SPEC 11"
else ko "robustness" "$(tail -2 "$tmp/r1.err")"; fi
if same_out "$tmp/r1" "$tmp/r2"; then ok "robustness: 1 and 2 threads give byte-identical files"
else ko "robustness threads"; fi
# a run made with other stream keys and solver than the test's is tested, and the test says how
# to repeat one made with the run's keys (the shipped configs changed them on 2026-11-28)
if ! grep -q "note:" "$tmp/r1.err" &&
   "$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" "${rob[@]}" --set run.rng_seed=plain \
     --set dynamics.lcp=schur --out "$tmp/rk" > /dev/null 2> "$tmp/rk.err" &&
   grep -qxF "posteval: note: $tmp/stct-s1 was made with run.rng_seed = apart, the test runs with plain (its own trials; --set run.rng_seed=apart repeats a test made with the run's)" "$tmp/rk.err" &&
   grep -qxF "posteval: note: $tmp/stct-s1 was made with dynamics.lcp = warm, the test runs with schur (its own trials; --set dynamics.lcp=warm repeats a test made with the run's)" "$tmp/rk.err"; then
  ok "robustness: a run made with other keys than the test's (run.rng_seed, dynamics.lcp) is named with the keys that repeat it"
else ko "robustness: other keys noted" "$(cat "$tmp/rk.err" | head -3)"; fi

# ---- generalisation on a 3 x 3 grid, 1 repetition, 30 steps: stct-s1 as trained (no autonomous
# success in its last generation: excluded) and a copy whose last row claims a self-talk
# success (trial 1) -> run; then the caretaker variant runs both
cp -r "$tmp/stct-s1" "$tmp/stct-ok"
awk -F, -v OFS=, 'NR == 3 { $11 = 1 } { print }' "$tmp/stct-s1/fitness.csv" > "$tmp/stct-ok/fitness.csv"
gen=(--set posteval.generalisation_cells=3 --set posteval.generalisation_repetitions=1
     --set posteval.generalisation_steps=30)
"$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-s1" "$tmp/stct-ok" "${gen[@]}" --threads 1 \
  --out "$tmp/g1" > /dev/null 2> "$tmp/g1.err"
rc1=$?
"$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-s1" "$tmp/stct-ok" "${gen[@]}" --threads 2 \
  --out "$tmp/g2" > /dev/null 2>&1
"$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-s1" "$tmp/stct-ok" "${gen[@]}" --caretaker \
  --out "$tmp/g0" > /dev/null 2>&1
rc3=$?
if [ $rc1 = 0 ] && check_files generalisation "$tmp/g1" selftalk ST-CT 2 stct-s1 &&
   grep -q '2 individuals (1 excluded), 36 trials' "$tmp/g1.err" &&
   [ $rc3 = 0 ] && check_files generalisation "$tmp/g0" caretaker ST-CT0 2; then
  ok "generalisation: grid rows as SPEC 11, the exclusion rule from fitness.csv, the caretaker variant ST-CT0 runs both"
else ko "generalisation" "$(tail -2 "$tmp/g1.err")"; fi
if same_out "$tmp/g1" "$tmp/g2"; then ok "generalisation: 1 and 2 threads give byte-identical files"
else ko "generalisation threads"; fi

# the default output directory: runs/posteval/TEST-CONDITION under the working directory
repo=$PWD
(cd "$tmp" && "$repo/$PE" robustness "$repo/configs/integrated_ni.cfg" "$tmp/ni-s1" "${rob[@]}" \
   --set "robot.urdf=$repo/data/icub_left_arm.urdf" > /dev/null 2>&1)
(cd "$tmp" && "$repo/$PE" robustness "$repo/configs/integrated_ni.cfg" "$tmp/ni-s1" "${rob[@]}" \
   --set "robot.urdf=$repo/data/icub_left_arm.urdf" --condition NI-b > /dev/null 2>&1)
if cmp -s "$tmp/runs/posteval/robustness-NI/trials.csv" "$tmp/rn/trials.csv" &&
   cmp -s <(sed 's/,NI-b,/,NI,/' "$tmp/runs/posteval/robustness-NI-b/summary.csv") "$tmp/rn/summary.csv"; then
  ok "default output directory runs/posteval/TEST-CONDITION; --condition names the condition"
else ko "default output directory" "$(ls -R "$tmp/runs" 2>&1 | head -3)"; fi

# ---- refused before any trial (no trials.csv), exit 2, naming what is wrong
refused() { # NAME NEEDLE CMD...
  local name=$1 needle=$2; shift 2
  rm -rf "$tmp/bad"
  "$@" --out "$tmp/bad" > /dev/null 2> "$tmp/e"
  local rc=$?
  if [ $rc = 2 ] && grep -qF -- "$needle" "$tmp/e" && [ ! -e "$tmp/bad/trials.csv" ]; then ok "$name"
  else ko "$name" "exit $rc: $(cat "$tmp/e")"; fi
}
refused "a --set key the test does not read" \
  "key 'ga.population': 50 is read only by the simple-prim, main-prim and integrated stages, which this run (robustness test) does not have: a post-evaluation runs no genetic algorithm (expected the config file's value, 100)" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" --set ga.population=50
refused "another test's key" \
  "key 'posteval.generalisation_cells': 3 is read only by the generalisation test, which this run (robustness test) does not have" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" --set posteval.generalisation_cells=3
refused "integrated.steps in the generalisation test" \
  "the generalisation test's trials last posteval.generalisation_steps" \
  "$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-s1" --set integrated.steps=50
refused "a run of another condition" \
  "config.ini: key 'network.arch' is B, the config's is A (expected an integrated run of the config's condition)" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/ni-s1"
refused "the caretaker variant outside the generalisation test" \
  "the caretaker variant belongs to the generalisation test" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" --caretaker
refused "an unknown test" "test 'robust' (expected integration, robustness or generalisation)" \
  "$PE" robust configs/integrated_stct.cfg "$tmp/stct-s1"
refused "no inputs" "missing inputs" "$PE" robustness configs/integrated_stct.cfg
refused "a missing run directory" "$tmp/none: not a directory (expected an integrated run directory" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/none"
refused "integration genotypes of another size" "(expected 612" \
  "$PE" integration configs/prims.cfg "$tmp/stct-s1/population.genome"
refused "too few genotypes" "has 2 genotypes (expected at least posteval.integration_top = 10)" \
  "$PE" integration configs/prims.cfg "$tmp/stct-s1/population.genome" --set network.arch=A
refused "two inputs with one run label" "have the same run label 'prims_s2'" \
  "$PE" integration configs/prims.cfg data/evolved/prims_s2 data/evolved/prims_s2/population.genome
refused "--threads 0" "--threads '0': expected an integer >= 1" \
  "$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" --threads 0
# the exclusion rule's reader (issue 48): a trial's result neither 0 nor 1 (read as a success
# before), a generation's row twice (the first was taken)
for v in x "" 2; do
  rm -rf "$tmp/stct-x" && cp -r "$tmp/stct-s1" "$tmp/stct-x"
  awk -F, -v OFS=, -v v="$v" 'NR == 3 { $11 = v } { print }' "$tmp/stct-s1/fitness.csv" > "$tmp/stct-x/fitness.csv"
  refused "the exclusion rule: best_t1 '$v' refused" "$tmp/stct-x/fitness.csv:3: best_t1 '$v' (expected 0 or 1" \
    "$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-x" "${gen[@]}"
done
rm -rf "$tmp/stct-x" && cp -r "$tmp/stct-s1" "$tmp/stct-x"
{ cat "$tmp/stct-s1/fitness.csv"; tail -1 "$tmp/stct-s1/fitness.csv"; } > "$tmp/stct-x/fitness.csv"
refused "the exclusion rule: a generation's row twice refused" \
  "$tmp/stct-x/fitness.csv:4: generation 1 after 1 (expected one row per generation, in increasing order)" \
  "$PE" generalisation configs/integrated_stct.cfg "$tmp/stct-x" "${gen[@]}"
touch "$tmp/afile"
rm -rf "$tmp/bad"
"$PE" robustness configs/integrated_stct.cfg "$tmp/stct-s1" --out "$tmp/afile/sub" > /dev/null 2> "$tmp/e"
if [ $? = 2 ] && grep -q "output directory '$tmp/afile/sub': cannot create" "$tmp/e"; then
  ok "an output directory that cannot be made"
else ko "unwritable output" "$(cat "$tmp/e")"; fi

# ---- integrated.fail_end = exact against runout (PROTOCOL, "Speed"): the chain candidate whose
# chains drop the ball, with no words and with the caretaker; every column of trials.csv but end
# and steps_run (what was simulated: a run-out world may diverge after exact's end) agrees, and
# exact simulates fewer steps
hcg=data/evolved/chain_candidates/hcg_p2_s1
for v in nowords:--no-words caretaker:; do
  name=${v%%:*} flag=${v#*:}
  for m in exact runout; do
    "$PE" integration "$hcg/integration/config.ini" "$hcg/checkpoint" $flag --threads 2 \
      --out "$tmp/fe-$name-$m" --set posteval.integration_top=3 --set posteval.integration_trials=12 \
      --set integrated.fail_end=$m > /dev/null 2> "$tmp/e" || ko "fail_end=$m $name" "$(tail -2 "$tmp/e")"
  done
  if python3 - "$tmp/fe-$name-exact/trials.csv" "$tmp/fe-$name-runout/trials.csv" <<'PY'
import csv, sys
x, r = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(x) == len(r) == 36, (len(x), len(r))
for a, b in zip(x, r):
    for k in a:
        if k not in ("end", "steps_run"): assert a[k] == b[k], (k, a, b)
    # run out, a trial ends only by success or by its world diverging (which exact may not
    # have reached: it ended earlier, once nothing the row reports could change)
    assert a["end"] == b["end"] or a["end"] == "failure" and b["end"] == "full", (a, b)
    assert int(a["steps_run"]) <= int(b["steps_run"]), (a, b)
early = sum(int(a["steps_run"]) < int(b["steps_run"]) for a, b in zip(x, r))
sx, sr = (sum(int(t["steps_run"]) for t in f) for f in (x, r))
print(f"{early} early ends, steps {sx} of {sr}")
assert sx < sr and early > 0
PY
  then ok "integrated.fail_end=exact against runout, $name: the same rows, fewer steps"
  else ko "integrated.fail_end=exact against runout, $name"; fi
done

echo "check_posteval: $pass passed, $fail failed"
[ "$fail" = 0 ]
