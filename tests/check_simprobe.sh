#!/usr/bin/env bash
# simprobe against the real robot's kinematics: the iKin v1.0 left-arm DH chain, computed here
# in Python independently of the URDF and the library, must give simprobe's `ee` within 1 mm.
# Also: the 16 initial postures pass, and an out-of-range joint is refused naming its range.
set -uo pipefail
APPDIR=${APPDIR:-apps}
CHECK=check_simprobe
source "$(dirname "$0")/check_lib.sh"

configs="0,0,0,0,0,15,0,0,0 0,0,-30,30,0,60,0,0,0 20,30,-60,90,40,100,-45,-30,10 -10,-10,-95,10,-37,15,90,-90,40 40,40,5,160,80,106,-90,0,-20 10,5,-45,60,20,50,30,-60,25"
for c in $configs; do
  out=$("$APPDIR/simprobe" --deg "$c" 2>&1) || { ko "ee $c" "$out"; continue; }
  ee=$(echo "$out" | sed -n 's/^ee //p')
  err=$(python3 - "$c" "$ee" <<'PY'
import math, sys
deg = [float(v) for v in sys.argv[1].split(",")]
ee = [float(v) for v in sys.argv[2].split()]
pi = math.pi
# iKin iCubArm("left") v1.0: a, d, alpha, offset(deg); chain torso pitch, roll, yaw, arm
tab = [(0.032, 0, pi/2, 0), (0, -0.0055, pi/2, -90), (0.0233647, -0.1433, -pi/2, 105),
       (0, 0.10774, -pi/2, 90), (0, 0, pi/2, -90), (0.015, 0.15228, -pi/2, 75),
       (-0.015, 0, pi/2, 0), (0, 0.1373, pi/2, -90), (0, 0, pi/2, 90), (0.0625, -0.016, 0, 0)]
q = [deg[1], 0.0, deg[0]] + deg[2:9]
T = [[0, -1, 0, 0], [0, 0, -1, 0], [1, 0, 0, 0], [0, 0, 0, 1]]  # H0
for (a, d, al, off), qk in zip(tab, q):
    th = math.radians(qk + off)
    ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(al), math.sin(al)
    A = [[ct, -st*ca, st*sa, a*ct], [st, ct*ca, -ct*sa, a*st], [0, sa, ca, d], [0, 0, 0, 1]]
    T = [[sum(T[i][k]*A[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
ref = (-T[0][3], -T[1][3], T[2][3])  # root frame (x back, y right) -> world (x fwd, y left)
print("%.3g" % math.dist(ref, ee))
PY
)
  if [ -n "$err" ] && python3 -c "import sys; sys.exit(0 if float('$err') < 1e-3 else 1)"; then
    ok "ee $c (|ee - iKin| = $err m)"
  else
    ko "ee $c" "|ee - iKin| = $err m"
  fi
done

out=$("$APPDIR/simprobe" --postures)
if [ "$(echo "$out" | grep -c '^posture [0-9]* [a-z]* ok$')" = 16 ]; then ok "16/16 postures"; else ko "postures" "$out"; fi

if err=$("$APPDIR/simprobe" --deg 0,0,0,0,0,200,0,0,0 2>&1); then
  ko "out-of-range joint refused" "exit 0"
elif echo "$err" | grep -qF "l_elbow = 200 is outside its range [15, 106] degrees"; then
  ok "out-of-range joint refused"
else
  ko "out-of-range joint refused" "$err"
fi
if err=$("$APPDIR/simprobe" --deg 50,0,0,0,0,20,0,0,0 2>&1); then
  ko "torso beyond the experiment's range refused" "exit 0"
elif echo "$err" | grep -qF "torso_yaw = 50 is outside its range [-10, 40] degrees"; then
  ok "torso beyond the experiment's range refused"
else
  ko "torso beyond the experiment's range refused" "$err"
fi
echo "check_simprobe: $pass passed, $fail failed"
[ "$fail" = 0 ]
