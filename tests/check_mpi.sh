#!/usr/bin/env bash
# evolve under mpirun (issue 16): the files of any number of ranks are those of --threads 1
# (simple-prim, a main-prim generation, hand-over trials rolled in by the elite, the integrated
# stage); bad input is refused by rank 0
# alone with today's message; a killed or hanging worker ends the run with a clear error and
# an intact checkpoint, and the resume (with another number of ranks) ends with the same files;
# a rank that cannot evaluate (a node without the data) is named; a bad checkpoint is refused by
# the validated reader before anything changes. Also the cluster scripts of tools/cluster/ (no
# SLURM needed). The MPI checks are skipped when mpirun is missing or apps/evolve was built
# without MPI.
set -uo pipefail
CHECK=check_mpi
source "$(dirname "$0")/check_lib.sh"
EV="$APPDIR/evolve"
BUILD=${BUILD:-build}
cfg=configs/simple_prim.cfg

# ---- the cluster scripts (always) ----
out=$(DRY_RUN=1 SLURM_ARRAY_TASK_ID=13 bash tools/cluster/replication.sbatch integrated)
out4=$(DRY_RUN=1 SLURM_ARRAY_TASK_ID=2 bash tools/cluster/replication.sbatch chain)
out5=$(DRY_RUN=1 PROTOCOL=thesis RUNS=/scratch/r SLURM_ARRAY_TASK_ID=13 bash tools/cluster/replication.sbatch integrated)
subm=$(DRY_RUN=1 bash tools/cluster/submit_replication.sh | sed 's/^sbatch --parsable --export=ALL //')
subm0=$(DRY_RUN=1 PROTOCOL=thesis bash tools/cluster/submit_replication.sh | grep -c ' chain$')
out2=$(DRY_RUN=1 SLURM_ARRAY_TASK_ID=9 SLURM_CPUS_PER_TASK=16 bash tools/cluster/replication.sbatch prims)
out3=$(DRY_RUN=1 SLURM_NTASKS=64 bash tools/cluster/evolve_mpi.sbatch configs/main_prim.cfg 3)
SLURM_ARRAY_TASK_ID=40 bash tools/cluster/replication.sbatch integrated 2> "$tmp/arr.err"; rc=$?
if [ "$out" = "./apps/evolve configs/integrated_st.cfg --seed 4 --threads 1 --out runs/integrated_st-s4 --resume --set integrated.populations=runs/chain-s*/population.genome" ] &&
   [ "$out4" = "./apps/evolve configs/chain_prim.cfg --seed 3 --threads 1 --out runs/chain-s3 --resume --set stage.init_population=runs/prims-s3/population.genome" ] &&
   [ "$out5" = "./apps/evolve configs/integrated_st.cfg --seed 4 --threads 1 --out /scratch/r/integrated_st-s4 --resume --set integrated.populations=/scratch/r/prims-s*/population.genome" ] &&
   [ "$subm" = "--array=0-9 tools/cluster/replication.sbatch prims
--array=0-9 --dependency=afterok:PRIMS_JOB tools/cluster/replication.sbatch chain
--array=0-39 --dependency=afterok:CHAIN_JOB tools/cluster/replication.sbatch integrated" ] && [ "$subm0" = 0 ] &&
   [ "$out2" = "./apps/evolve configs/prims.cfg --seed 10 --threads 16 --out runs/prims-s10 --resume" ] &&
   [ "$out3" = "mpirun -n 65 --oversubscribe --bind-to none ./apps/evolve configs/main_prim.cfg --seed 3 --threads 1 --out runs/main_prim-s3 --resume" ] &&
   [ $rc = 2 ] && grep -q "task 40: 4 conditions x 10 seeds (tasks 0-39)" "$tmp/arr.err"; then
  ok "cluster scripts: array task -> config, seed, directory; the chain stage from its seed's primitive run, the integrated runs from the protocol's; MPI across tasks; out of range refused"
else
  ko "cluster script commands" "$out | $out2 | $out3 | $out4 | $out5 | $subm | $subm0 | $(cat "$tmp/arr.err")"
fi
# an array task run for real (no SLURM: one task), twice: the second finds the run complete
small=(--generations 2 --set ga.population=8 --set ga.elites=2 --set ga.parents=4 --set ga.success_genotypes=2)
for k in 1 2; do
  RUNS="$tmp/runs" EVOLVE="$EV" EVOLVE_ARGS="${small[*]}" SLURM_ARRAY_TASK_ID=0 \
    bash tools/cluster/replication.sbatch prims > "$tmp/arr$k.log" 2>&1
done
if [ "$(wc -l < "$tmp/runs/prims-s1/fitness.csv")" = 3 ] && grep -q "is complete" "$tmp/arr2.log"; then
  ok "an array task runs its run, and run again only finds it complete (--resume)"
else
  ko "array task run" "$(tail -n 3 "$tmp/arr1.log" "$tmp/arr2.log")"
fi

# the scaling model's inputs and outputs: per-individual costs, then the modelled generation
"$BUILD/eval_cost" $cfg --population data/evolved/simple_prim_s3.genome --count 6 > "$tmp/cost.csv" 2> "$tmp/cost.err"
python3 tools/mpi_model.py "$tmp/cost.csv" --slots 1,2,4 --samples 20 --serial 0.01 > "$tmp/model.txt" 2>&1
if [ "$(grep -c '^[0-5],' "$tmp/cost.csv")" = 6 ] && grep -q '^# 6 individuals of .*, simple-prim stage, generation 0: CPU per individual min' "$tmp/cost.csv" &&
   [ "$(awk -F, '/^[0-9]+,/ { s = s $1 " "; if ($6 <= 0 || $6 > 1.0001) s = s "bad " } END { print s }' \
        "$tmp/model.txt")" = "1 2 4 " ]; then
  ok "eval_cost's per-individual costs feed tools/mpi_model.py"
else
  ko "eval_cost / mpi_model" "$(cat "$tmp/cost.err" "$tmp/model.txt")"
fi

# ---- MPI ----
skip() {
  echo "$CHECK: skipped: $1 (the MPI checks)"
  echo "$CHECK: $pass passed, $fail failed"
  [ "$fail" = 0 ]
  exit
}
command -v mpirun > /dev/null || skip "no mpirun (make deps installs OpenMPI)"
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
# (grep reads all its input, not -q: under pipefail a writer cut off by -q's early exit fails the
# pipeline, SIGPIPE, however well the line matched)
if ! "$EV" --help 2>&1 | grep "built with MPI" > /dev/null; then
  # an evolve without MPI under mpirun refuses (every rank would run the whole evolution)
  timeout -k 10 600 mpirun -q --oversubscribe -n 2 "$EV" $cfg --out "$tmp/nompi" > /dev/null 2> "$tmp/nompi.err"; rc=$?
  if [ $rc != 0 ] && [ ! -e "$tmp/nompi" ] && [ "$(grep -c "started as 2 MPI ranks, but built without MPI" "$tmp/nompi.err")" = 1 ]; then
    ok "an evolve built without MPI refuses to run as several ranks"
  else
    ko "evolve without MPI under mpirun" "$(cat "$tmp/nompi.err")"
  fi
  skip "$EV was built without MPI (MPI=0 or no mpicc)"
fi
# under AddressSanitizer (make asan) the ranks run without LeakSanitizer: OpenMPI leaves
# allocations of its components (unloaded at MPI_Finalize, so not even suppressible by library)
# unfreed; every other check of the sanitizers stays on (the link-order check is off: start_run
# preloads the fault shim before libasan)
mpienv=()
if ldd "$EV" 2> /dev/null | grep libasan > /dev/null; then
  mpienv=(env "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0:verify_asan_link_order=0")
fi
# -q: OpenMPI's own notices; a bound on the time (a hang must fail the check, not the suite)
mpirun_() { timeout -k 10 600 ${mpienv[@]+"${mpienv[@]}"} mpirun -q --oversubscribe "$@"; }
mpi() { # NP ARGS...: evolve on NP ranks
  local np=$1; shift
  mpirun_ -n "$np" "$EV" "$@"
}

# the files of 3 ranks (2 evaluating, 2 threads each by default), of 1 rank (rank 0 evaluates
# on its threads) and of 2 ranks resuming a 3-rank run are those of --threads 1
G=6
"$EV" $cfg --seed 11 --generations $G --threads 1 --out "$tmp/t1" > /dev/null 2>&1
mpi 3 $cfg --seed 11 --generations $G --out "$tmp/m3" > "$tmp/m3.log" 2>&1
mpi 1 $cfg --seed 11 --generations $G --out "$tmp/m1" > "$tmp/m1.log" 2>&1
if same_files "$tmp/t1" "$tmp/m3" && same_files "$tmp/t1" "$tmp/m1" &&
   grep -q "^evolve: MPI: 3 ranks; rank 0 runs the GA and writes the files, ranks 1-2 evaluate" "$tmp/m3.log" &&
   grep -q "^evolve: MPI: 600 evaluations in 6 generations; CPU per evaluation" "$tmp/m3.log" &&
   [ "$(grep -c '^gen ' "$tmp/m3.log")" = $G ] && ! grep -q "MPI" "$tmp/m1.log"; then
  ok "simple-prim: mpirun -n 3 and -n 1 give the files of --threads 1"
else
  ko "simple-prim under MPI" "$(tail -n 3 "$tmp/m3.log" "$tmp/m1.log")"
fi

# one main-prim generation (dynamic trials of very different costs), 12 genotypes of the
# committed simple-prim population
mp=(configs/main_prim.cfg --seed 5 --generations 1 --set ga.population=12 --set ga.elites=2
    --set ga.parents=4 --set ga.success_genotypes=1)
# ARGS on --threads 1 and on 3 ranks of 1 thread into $tmp/TAG1 and $tmp/TAG3: the same files
mpi_vs_threads() { # TAG ARGS...
  local tag=$1; shift
  "$EV" "$@" --threads 1 --out "$tmp/${tag}1" > /dev/null 2>&1
  mpi 3 "$@" --threads 1 --out "$tmp/${tag}3" > "$tmp/${tag}3.log" 2>&1
  same_files "$tmp/${tag}1" "$tmp/${tag}3" &&
    grep -q "(1 thread each: 2 evaluation slots on 1 host)" "$tmp/${tag}3.log"
}
if mpi_vs_threads p "${mp[@]}"; then
  ok "one main-prim generation: mpirun -n 3 gives the files of --threads 1"
else
  ko "main-prim under MPI" "$(tail -n 3 "$tmp/p3.log")"
fi

# main-prim's hand-over trials rolled in by the elite (stage.handover_rollin = elite): the
# elite's genotype travels in every task, so the ranks roll in as --threads 1 does
el=(configs/main_prim.cfg --seed 12 --generations 2 --set ga.population=4 --set ga.elites=1
    --set ga.parents=2 --set ga.success_genotypes=4 --set stage.primitives=open
    --set stage.init_population=data/evolved/prims_s2/population.genome --set stage.handover=true
    --set stage.handover_rollin=elite)
if mpi_vs_threads e "${el[@]}"; then
  ok "hand-over trials rolled in by the elite: mpirun -n 3 gives the files of --threads 1"
else
  ko "elite roll-ins under MPI" "$(tail -n 3 "$tmp/e3.log")"
fi

# the integrated stage (ST-CT: self talk and the prediction fitness), tiny
tiny=(configs/integrated_stct.cfg --set "integrated.populations=data/evolved/simple_prim_s*.genome"
      --set integrated.top=1 --set ga.population=4 --set ga.elites=1 --set ga.parents=2
      --set integrated.steps=30 --generations 2)
"$EV" "${tiny[@]}" --threads 1 --out "$tmp/i1" > /dev/null 2>&1
mpi 3 "${tiny[@]}" --out "$tmp/i3" > "$tmp/i3.log" 2>&1
if same_files "$tmp/i1" "$tmp/i3"; then ok "the integrated stage: mpirun -n 3 gives the files of --threads 1"
else ko "integrated under MPI" "$(tail -n 3 "$tmp/i3.log")"; fi

# bad input: refused by rank 0 before any work, with the message of a plain run, once
printf '[stage]\nstages = simple_prim\n[ga]\nelites = 200\n' > "$tmp/bad.cfg"
"$EV" "$tmp/bad.cfg" --out "$tmp/b0" > /dev/null 2> "$tmp/b0.err"
mpi 3 "$tmp/bad.cfg" --out "$tmp/b1" > /dev/null 2> "$tmp/b1.err"; rc1=$?
mpi 3 $cfg --out "$tmp/b2" --set ga.popsize=5 > /dev/null 2> "$tmp/b2.err"; rc2=$?
msg=$(cat "$tmp/b0.err")
if [ $rc1 != 0 ] && [ $rc2 != 0 ] && [ -n "$msg" ] && [ "$(grep -cxF -- "$msg" "$tmp/b1.err")" = 1 ] &&
   [ "$(grep -c "^evolve:" "$tmp/b1.err")" = 1 ] && [ "$(grep -c "key 'ga.popsize': unknown key" "$tmp/b2.err")" = 1 ] &&
   [ ! -e "$tmp/b1" ] && [ ! -e "$tmp/b2" ]; then
  ok "bad input refused by rank 0 alone, before any work, with a plain run's message"
else
  ko "bad input under MPI" "$(cat "$tmp/b1.err" "$tmp/b2.err")"
fi

# --resume under MPI reads the checkpoint through the validated reader on rank 0 (issue 17): a
# bad one is refused once, naming the file, line and field, with the directory as it was
cp -r "$tmp/t1" "$tmp/rb"
sed -i 's/^# stage_idx 0$/# stage_idx 5/' "$tmp/rb/checkpoint"
rb_digest() { (cd "$tmp/rb" && find . | sort && find . -type f -exec sha256sum {} + | sort); }
before=$(rb_digest)
mpi 3 $cfg --seed 11 --generations $G --out "$tmp/rb" --resume > /dev/null 2> "$tmp/rb.err"; rc=$?
if [ $rc != 0 ] && [ "$before" = "$(rb_digest)" ] &&
   [ "$(grep -c "^evolve: .*$tmp/rb/checkpoint:3: field 'stage_idx': 5 is out of range" "$tmp/rb.err")" = 1 ]; then
  ok "--resume under MPI: a bad checkpoint refused by the validated reader, the directory unchanged"
else
  ko "bad checkpoint under MPI" "rc $rc: $(cat "$tmp/rb.err")"
fi

descendants() { # PID
  local p
  for p in $(pgrep -P "$1"); do echo "$p"; descendants "$p"; done
}
# the pid of rank R of the MPI job started by background job PID (timeout, mpirun, the ranks)
rank_pid() { # PID RANK
  local p
  for p in $(descendants "$1"); do
    tr '\0' '\n' < "/proc/$p/environ" 2> /dev/null | grep -x "OMPI_COMM_WORLD_RANK=$2" > /dev/null && echo "$p"
  done
}
# starts an MPI run in the background into DIR and waits for its first checkpoint, after which
# rank 0 holds (the fault shim's ST_FAULT_HOLD) until release: the run is still going when a
# worker is killed or stopped, however busy the machine (issue 48: a slow disk's window of a few
# seconds was missed under load)
SHIM="$PWD/$BUILD/fault_shim.so"
start_run() { # DIR LOG NP ARGS...
  local dir=$1 log=$2; shift 2
  touch "$tmp/hold"
  # 10 s between the launcher's SIGTERM and its SIGKILL: OpenMPI's 1 s ended rank 0 before it
  # could say why on a box busy with four evolutions (the killed worker, 2026-11-28)
  LD_PRELOAD="$SHIM" ST_FAULT_HOLD="$tmp/hold" OMPI_MCA_odls_base_sigkill_timeout=10 \
    mpi "$@" --out "$dir" > "$log" 2>&1 &
  bg=$!
  wait_for 900 "$bg" test -e "$dir/checkpoint"
}
release() { rm -f "$tmp/hold"; }
K=16
"$EV" $cfg --seed 11 --generations $K --threads 1 --out "$tmp/full" > /dev/null 2>&1

# a worker killed (-9) mid-run: the job ends non-zero, rank 0 says what happened and leaves the
# files of its last generation; resumed on 2 ranks: the files of the uninterrupted run
start_run "$tmp/k" "$tmp/k.log" 3 $cfg --seed 11 --generations $K --threads 1
victim=$(rank_pid "$bg" 1)
[ -n "$victim" ] && kill -9 "$victim"
release
wait "$bg"; rc=$?
ck_ok=0
if [ -f "$tmp/k/checkpoint" ]; then
  bytes=$(sed -n 's/^# csv_bytes //p' "$tmp/k/checkpoint")
  [ "$(stat -c %s "$tmp/k/fitness.csv")" -ge "${bytes:-999999999}" ] && ck_ok=1
fi
mpi 2 $cfg --seed 11 --generations $K --threads 1 --out "$tmp/k" --resume > "$tmp/k2.log" 2>&1; rc2=$?
if [ -n "$victim" ] && [ $rc != 0 ] && [ $ck_ok = 1 ] &&
   grep -q "evolve: ended by the MPI launcher (SIGTERM): another rank died" "$tmp/k.log" &&
   grep -q "$tmp/k keeps the files of the last finished generation" "$tmp/k.log" &&
   ! grep -q "^gen    $((K - 1)) " "$tmp/k.log" && [ $rc2 = 0 ] && same_files "$tmp/full" "$tmp/k"; then
  ok "a killed worker ends the run (exit $rc) with a clear message; resumed on 2 ranks: identical files"
else
  ko "killed worker" "victim '$victim' rc $rc checkpoint $ck_ok: $(tail -n 4 "$tmp/k.log" "$tmp/k2.log")"
fi

# a hanging worker (stopped): rank 0 gives up after SELFTALK_MPI_TIMEOUT seconds, says so and
# ends the job; resumed without MPI: identical files
export SELFTALK_MPI_TIMEOUT=2
start_run "$tmp/h" "$tmp/h.log" 3 $cfg --seed 11 --generations $K --threads 1
victim=$(rank_pid "$bg" 2)
[ -n "$victim" ] && kill -STOP "$victim"
release
wait "$bg"; rc=$?
[ -n "$victim" ] && kill -CONT "$victim" 2> /dev/null
unset SELFTALK_MPI_TIMEOUT
"$EV" $cfg --seed 11 --generations $K --threads 2 --out "$tmp/h" --resume > "$tmp/h2.log" 2>&1; rc2=$?
if [ -n "$victim" ] && [ $rc != 0 ] &&
   grep -qE "evolve: MPI: (no rank answered|rank [0-9]+ took no message) for 2 s .*a rank hangs or a node is unreachable" "$tmp/h.log" &&
   grep -q "evolve: ending every rank (MPI_Abort). $tmp/h keeps the files" "$tmp/h.log" &&
   [ $rc2 = 0 ] && same_files "$tmp/full" "$tmp/h"; then
  ok "a hanging worker ends the run after the timeout (exit $rc); resumed without MPI: identical files"
else
  ko "hanging worker" "victim '$victim' rc $rc: $(tail -n 4 "$tmp/h.log" "$tmp/h2.log")"
fi

# a rank that cannot evaluate (here: started where data/ is missing, as on a node without the
# files) is named by rank 0, and the job ends
mpirun_ -n 1 "$EV" $cfg --out "$tmp/w" : -n 2 -wdir "$tmp" "$PWD/$EV" > /dev/null 2> "$tmp/w.err"; rc=$?
if [ $rc != 0 ] && [ "$(grep -c "^evolve: MPI rank 1 (host .*) cannot evaluate: key 'robot.urdf': data/icub_left_arm.urdf: cannot open" "$tmp/w.err")" = 1 ] &&
   [ "$(grep -c "^evolve:" "$tmp/w.err")" = 1 ]; then
  ok "a rank that cannot build the protocol is named once, and the job ends (exit $rc)"
else
  ko "rank without data" "$(cat "$tmp/w.err")"
fi

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
