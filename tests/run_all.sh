#!/usr/bin/env bash
# Runs every test of `make test` and prints one closing line for the whole run.
set -uo pipefail
BUILD=${BUILD:-build}
APPDIR=${APPDIR:-apps}
export BUILD APPDIR NETEVAL="$APPDIR/neteval"
total_pass=0 total_fail=0 parts_failed=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT

run_part() {
  local name=$1
  echo "== $name"
  shift
  "$@" 2>&1 | tee "$log"
  local rc=${PIPESTATUS[0]}
  local line
  line=$(grep -E '[0-9]+ passed, [0-9]+ failed' "$log" | tail -1)
  local p f
  p=$(echo "$line" | sed -nE 's/.* ([0-9]+) passed, ([0-9]+) failed.*/\1/p')
  f=$(echo "$line" | sed -nE 's/.* ([0-9]+) passed, ([0-9]+) failed.*/\2/p')
  total_pass=$((total_pass + ${p:-0}))
  total_fail=$((total_fail + ${f:-0}))
  # a part that exits non-zero, or reports no passed check at all (it ran nothing, or its
  # summary line is missing), fails
  if [ "$rc" != 0 ] || [ "${p:-0}" = 0 ]; then
    [ "$rc" = 0 ] && echo "run_all: '$name' reported no passed check: FAILED"
    parts_failed=$((parts_failed + 1))
    [ "${f:-0}" = 0 ] && total_fail=$((total_fail + 1))
  fi
}

run_part "unit tests (CUnit)" "./$BUILD/run_tests"
run_part "layers: no include of a higher layer in lib/" bash tests/check_layers.sh
run_part "a library safe to link: public exports only, a host's ODE unchanged" bash tests/check_link.sh
run_part "neteval against the independent reference" bash tests/check_neteval.sh
run_part "apps: argument and input errors" bash tests/check_apps.sh
run_part "simprobe against iKin v1.0" bash tests/check_simprobe.sh
run_part "evolve: threads, kill and resume, bad input" bash tests/check_evolve.sh
run_part "hostile inputs: checkpoints, URDFs, unbounded files, keys named" bash tests/check_inputs.sh
run_part "fault injection: full disk, read-only directory, failing sync and rename" bash tests/check_faults.sh
run_part "evolve under MPI: any number of ranks, faults, resume; cluster scripts" bash tests/check_mpi.sh
run_part "committed primitive runs replay 16/16 in main-prim" bash tests/check_populations.sh
run_part "scripted controller: every primitive is physically achievable" bash tests/check_scripted.sh
run_part "compare against MuJoCo: the harness on a tiny run" bash tests/check_compare.sh
run_part "integrated stage: score, conditions, resume, threads, replay" bash tests/check_integrated.sh
run_part "post-evaluations: tables, exclusion, threads, bad input" bash tests/check_posteval.sh
run_part "tools: run summaries and fitness plots" bash tests/check_tools.sh
run_part "stats: Mann-Whitney U, quartiles, the thesis's tables" bash tests/check_stats.sh
run_part "figures: the thesis's Figs. 3.1, 3.3-3.12 from CSVs" bash tests/check_figures.sh
run_part "pictures of the robot: replay --shapes, tools/draw_trial.py" bash tests/check_pictures.sh
run_part "trial pages: replay --html in headless Chromium" bash tests/check_html.sh
run_part "trial videos: tools/trial_video.sh, GIF and MP4 frames, bad input" bash tests/check_video.sh
run_part "make replicate: every step, killed and resumed (PRESET=tiny)" bash tests/check_replicate.sh
run_part "replicate.mk's directories: OUT make cannot quote, snapshot and restore" bash tests/check_snapshot.sh
run_part "the integrated trial-type order screen: tools/order_screen.mk, tiny" bash tests/check_order_screen.sh
run_part "golden results (tests/golden/golden.sha256)" bash tests/check_golden.sh
if [ "$BUILD" = build ]; then
  run_part "install + pkg-config" bash tests/check_install.sh
fi
echo
echo "make test: $total_pass passed, $total_fail failed"
[ "$parts_failed" = 0 ] && [ "$total_fail" = 0 ]
