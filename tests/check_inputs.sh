#!/usr/bin/env bash
# Hostile inputs refused end to end (issue 17): bad checkpoints refused by --resume naming the
# file, the line and the field, with the run directory left byte for byte as it was; URDFs the
# world cannot simulate refused at load, naming robot.urdf, the file and the element; files
# without end and files named by keys; posture failures naming the keys that made them.
set -uo pipefail
CHECK=check_inputs
source "$(dirname "$0")/check_lib.sh"
EV="$APPDIR/evolve"
cfg=configs/simple_prim.cfg

# a run of 3 generations of 6, stopped: its checkpoint (done 0 once edited) is one a resume
# accepts (the control below), and each case below breaks one thing of it
"$EV" $cfg --seed 5 --generations 3 --threads 1 --out "$tmp/c0" > "$tmp/c0.log" 2>&1
sed -i 's/^# done 1$/# done 0/' "$tmp/c0/checkpoint"
digest() { (cd "$1" && find . | sort && find . -type f -exec sha256sum {} + | sort); }

# bad_ckpt NAME NEEDLE FILE CMD...: CMD (run in a copy of c0, on FILE) breaks the copy; resuming
# must fail, print NEEDLE (c1 stands for the copy's path) and leave every file as it was
bad_ckpt() {
  local name=$1 needle=$2 file=$3; shift 3
  rm -rf "$tmp/c1" && cp -r "$tmp/c0" "$tmp/c1"
  "$@" "$tmp/c1/$file"
  local before; before=$(digest "$tmp/c1")
  needle=${needle//c1/$tmp/c1}
  if "$EV" $cfg --seed 5 --generations 6 --threads 1 --out "$tmp/c1" --resume > "$tmp/o" 2> "$tmp/e"; then
    ko "$name" "exit 0"
  elif ! grep -qF -- "$needle" "$tmp/e"; then
    ko "$name" "expected '$needle' in: $(cat "$tmp/e")"
  elif [ "$before" != "$(digest "$tmp/c1")" ]; then
    ko "$name" "the run directory changed"
  else
    ok "$name"
  fi
}
py() { python3 -c "$1" "$2"; } # py CODE FILE: CODE edits the file sys.argv[1]

bad_ckpt "stage_idx 5 refused" "c1/checkpoint:3: field 'stage_idx': 5 is out of range (expected an integer in [0, 0]: the run has one stage)" \
  checkpoint sed -i 's/^# stage_idx 0$/# stage_idx 5/'
bad_ckpt "stage_idx -1 refused" "c1/checkpoint:3: field 'stage_idx': -1 is out of range" \
  checkpoint sed -i 's/^# stage_idx 0$/# stage_idx -1/'
bad_ckpt "stage_idx 100000000 refused" "c1/checkpoint:3: field 'stage_idx': 100000000 is out of range" \
  checkpoint sed -i 's/^# stage_idx 0$/# stage_idx 100000000/'
bad_ckpt "generation 2147483647 refused" "c1/checkpoint:2: field 'generation': 2147483647 is out of range (expected an integer in [1, 6]" \
  checkpoint sed -i 's/^# generation 3$/# generation 2147483647/'
bad_ckpt "done 7 refused" "c1/checkpoint:5: field 'done': 7 is out of range (expected an integer in [0, 1]" \
  checkpoint sed -i 's/^# done 0$/# done 7/'
bad_ckpt "missing generation refused" "c1/checkpoint:2: field 'generation': missing (expected '# generation N' on line 2; found '# stage_idx 0')" \
  checkpoint sed -i '/^# generation 3$/d'
bad_ckpt "missing csv_bytes refused" "c1/checkpoint:6: field 'csv_bytes': missing" \
  checkpoint sed -i '/^# csv_bytes /d'
bad_ckpt "missing best_bytes refused" "c1/checkpoint:7: field 'best_bytes': missing (expected '# best_bytes N' on line 7; found '# genes 612')" \
  checkpoint sed -i '/^# best_bytes /d'
bad_ckpt "csv_bytes beyond fitness.csv refused (no NUL padding)" "c1/checkpoint:6: field 'csv_bytes': 999999 exceeds the length of c1/fitness.csv" \
  checkpoint sed -i 's/^# csv_bytes .*/# csv_bytes 999999/'
bad_ckpt "fitness.csv shorter than the checkpoint refused" "c1/checkpoint:6: field 'csv_bytes': " \
  fitness.csv sed -i '$d'
bad_ckpt "best.genome cut refused" "c1/checkpoint:7: field 'best_bytes': " \
  best.genome truncate -s -10
bad_ckpt "not a checkpoint (magic inside a comment) refused" "c1/checkpoint:1: not a selftalk checkpoint (expected '# selftalk-checkpoint 1' as the first line)" \
  checkpoint sed -i '1s/.*/# copy of a selftalk-checkpoint 1 file/'
# 99 of ga.population = 100 genotypes: the checkpoint is blamed, not an "initial population"
bad_ckpt "too few genotypes blame the checkpoint" "c1/checkpoint: field 'genotypes': 99 genotypes (expected ga.population = 100)" \
  checkpoint sed -i '$d'
bad_ckpt "NUL byte in the checkpoint refused" "c1/checkpoint:9: NUL byte at column 5 (expected a text file)" \
  checkpoint py 'import sys; p = sys.argv[1]; b = bytearray(open(p, "rb").read()); i = b.index(b"# genes 612\n") + 16; b[i] = 0; open(p, "wb").write(b)'
bad_ckpt "a directory for a checkpoint refused" "c1/checkpoint: cannot read: Is a directory" \
  checkpoint py 'import os, sys; os.remove(sys.argv[1]); os.mkdir(sys.argv[1])'

# the control: the same copy, unbroken, resumes to the end
rm -rf "$tmp/c1" && cp -r "$tmp/c0" "$tmp/c1"
if "$EV" $cfg --seed 5 --generations 6 --threads 1 --out "$tmp/c1" --resume > "$tmp/o" 2> "$tmp/e" &&
   [ "$(wc -l < "$tmp/c1/fitness.csv")" = 7 ] && grep -q '^# done 1$' "$tmp/c1/checkpoint"; then
  ok "the unbroken checkpoint resumes (3 more generations)"
else
  ko "control resume" "$(cat "$tmp/e")"
fi

# files named by keys: the key, the file and the reason
expect "stage.init_population: a missing file names the key" \
  "evolve: key 'stage.init_population': 1e: cannot open: No such file or directory" "$tmp/k1" \
  "$EV" $cfg --out "$tmp/k1" --set stage.init_population=1e
expect "stage.init_population=/dev/zero refused at the size limit" \
  "key 'stage.init_population': /dev/zero: larger than 64 MiB (expected an input file of at most 67108864 bytes)" \
  "$tmp/k2" timeout 600 "$EV" $cfg --out "$tmp/k2" --set stage.init_population=/dev/zero
expect "robot.urdf: a missing file names the key" "key 'robot.urdf': $tmp/none.urdf: cannot open" "$tmp/k3" \
  "$EV" $cfg --out "$tmp/k3" --set robot.urdf="$tmp/none.urdf"
expect "a config file that never ends refused" "/dev/zero: larger than 64 MiB" "$tmp/k4" \
  timeout 600 "$EV" /dev/zero --out "$tmp/k4"

# URDFs the world cannot simulate, refused at load in every mode: the shipped arm with one
# element broken (a zero-length cylinder aborted libccd even in kinematic mode)
urdf=data/icub_left_arm.urdf
bad_urdf() { # NAME NEEDLE SED-SCRIPT
  sed "$3" "$urdf" > "$tmp/bad.urdf"
  cmp -s "$tmp/bad.urdf" "$urdf" && { ko "$1" "the sed script changed nothing"; return; }
  expect "$1" "key 'robot.urdf': $tmp/bad.urdf: $2" "$tmp/u" "$EV" $cfg --out "$tmp/u" --set robot.urdf="$tmp/bad.urdf"
}
bad_urdf "zero-length collision cylinder refused" "link 'l_index_3': collision 1: cylinder length 0 (expected 1e-06..10 m)" \
  '/<link name="l_index_3">/,/<\/link>/s/length="[0-9.]*"/length="0"/'
bad_urdf "mass 1e308 refused" "link 'chest': inertial: mass 1e+308 kg (expected 1e-06..1000 kg)" \
  '/<link name="chest">/,/<\/link>/s/mass value="[0-9.]*"/mass value="1e308"/'
bad_urdf "zero mass refused" "link 'l_forearm': inertial: mass 0 kg" \
  '/<link name="l_forearm">/,/<\/link>/s/mass value="[0-9.]*"/mass value="0"/'
bad_urdf "non-positive-definite inertia refused" "link 'l_forearm': inertial: inertia is not positive definite" \
  '/<link name="l_forearm">/,/<\/link>/s/ixx="[0-9.e-]*"/ixx="-1e-4"/'
bad_urdf "origin 1e308 refused" "joint 'l_elbow': origin xyz (1e+308, " \
  '/<joint name="l_elbow"/,/<\/joint>/s/<origin xyz="[^ ]*/<origin xyz="1e308/'
# simprobe printed nan with exit 0 for that origin
sed '/<joint name="l_elbow"/,/<\/joint>/s/<origin xyz="[^ ]*/<origin xyz="1e308/' "$urdf" > "$tmp/far.urdf"
expect "simprobe refuses the 1e308 origin" "simprobe: key 'robot.urdf': $tmp/far.urdf: joint 'l_elbow': origin xyz" "$tmp/none" \
  "$APPDIR/simprobe" --deg 0,0,0,30,0,60,0,0,0 --set robot.urdf="$tmp/far.urdf"

# in-range scene and posture values that make a posture impossible name the keys
expect "an unreachable object names the scene keys" \
  "posture reach 0: inverse kinematics did not reach the target" "$tmp/p1" \
  "$EV" $cfg --out "$tmp/p1" --generations 1 --set scene.object_center_x=0.8
grep -qF "[keys: scene.object_center_x, scene.object_center_y, scene.table_top_z" "$tmp/e" &&
  ok "... and lists scene.object_center_x" || ko "posture keys (scene)" "$(cat "$tmp/e")"
expect "a grasp gap out of reach names the grasp keys" "posture grasp 0: inverse kinematics" "$tmp/p2" \
  "$EV" $cfg --out "$tmp/p2" --generations 1 --set postures.grasp_gap=0.25
grep -qF "postures.grasp_ball_x, postures.grasp_gap, postures.grasp_oppose, postures.ik_torso_pitch, postures.ik_wrist_prosup, postures.ik_wrist_pitch]" "$tmp/e" &&
  ok "... and lists postures.grasp_gap" || ko "posture keys (grasp)" "$(cat "$tmp/e")"

echo "check_inputs: $pass passed, $fail failed"
[ "$fail" = 0 ]
