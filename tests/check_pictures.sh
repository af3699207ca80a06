#!/usr/bin/env bash
# Pictures of the robot: ./apps/replay --shapes writes the collision shapes of the chosen steps
# (CSV rows as docs/PROTOCOL.md, "Robot pictures", says: every robot geometry, the ball and its
# base, the table, the target), the ball where the trace has the object, the trace unchanged;
# tools/draw_trial.py draws them as a valid PNG and SVG with the trace's values in the titles
# and refuses malformed input with FILE:LINE, writing nothing. On the committed seed-2 run's
# best (a main-prim grasp trial, dynamic mode: 80 steps).
set -uo pipefail
CHECK=check_pictures
source "$(dirname "$0")/check_lib.sh"
source "$(dirname "$0")/check_figlib.sh"
RUN=data/evolved/prims_s2
REPLAY=("$APPDIR/replay" "$RUN/population.genome" "$RUN/config.ini" --stage main --trial 8)
COLS="step,kind,owner,type,sx,sy,sz,px,py,pz,r00,r01,r02,r10,r11,r12,r20,r21,r22"

# ---- replay --shapes ------------------------------------------------------------------------
if "${REPLAY[@]}" --out "$tmp/t.csv" --shapes "$tmp/s.csv" --at 40,0,last > "$tmp/r.out" 2> "$tmp/r.err"; then
  ok "replay --shapes runs"
else
  ko "replay --shapes" "$(cat "$tmp/r.err")"
fi
[ "$(head -1 "$tmp/s.csv")" = "$COLS" ] && ok "shapes: the header" || ko "shapes: header" "$(head -1 "$tmp/s.csv")"
# per step: the model's 31 collision geometries, the ball's sphere and base, table, target
counts=$(awk -F, 'NR > 1 { n[$1 "," $2 "," $4]++ } END { for (k in n) print k ":" n[k] }' "$tmp/s.csv" | sort -t, -k1,1n -k2 | tr '\n' ' ')
want="0,ball,cylinder:1 0,ball,sphere:1 0,robot,box:4 0,robot,cylinder:26 0,robot,sphere:1 0,table,box:1 0,target,sphere:1 "
want+="${want//0,/40,}${want//0,/79,}"
[ "$counts" = "$want" ] && ok "shapes: steps 0, 40 and the last (79), 35 shapes each" || ko "shapes: rows per step" "$counts"
# the ball is the trace's object, the target the trace's target, at every step written (the same
# doubles, both printed with 9 digits: equal as text)
join_ok=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } FNR == 1 { next }
  NR == FNR { o = c["obj_x"]; t = c["target_x"]
              obj[$1] = $o "," $(o + 1) "," $(o + 2); tgt[$1] = $t "," $(t + 1) "," $(t + 2); next }
  $2 == "ball" && $4 == "sphere" { n++; if ($8 "," $9 "," $10 != obj[$1]) bad++ }
  $2 == "target" { n++; if ($8 "," $9 "," $10 != tgt[$1]) bad++ }
  END { print n + 0, bad + 0 }' "$tmp/t.csv" "$tmp/s.csv")
[ "$join_ok" = "6 0" ] && ok "shapes: the ball and the target where the trace has them" || ko "shapes vs trace" "$join_ok (checked, wrong)"
# the table box of the default scene: x 0.10..0.60, y -0.30..0.50, top at -0.08, 0.03 thick
grep -qxF "0,table,table,box,0.5,0.8,0.03,0.35,0.1,-0.095,1,0,0,0,1,0,0,0,1" "$tmp/s.csv" &&
  ok "shapes: the table" || ko "shapes: table" "$(grep table "$tmp/s.csv" | head -1)"
grep -qF "replay: $tmp/s.csv: 35 shapes at each of 3 steps" "$tmp/r.err" && ok "replay reports the shapes written" || ko "replay report" "$(cat "$tmp/r.err")"
# the trace is the same with and without --shapes (bit for bit with --exact)
"${REPLAY[@]}" --exact --out "$tmp/e1.csv" > /dev/null 2>&1
"${REPLAY[@]}" --exact --out "$tmp/e2.csv" --shapes "$tmp/e.csv" --shapes-every 30 > /dev/null 2>&1
cmp -s "$tmp/e1.csv" "$tmp/e2.csv" && ok "the trace is unchanged by --shapes" || ko "trace changed by --shapes"
[ "$(cut -d, -f1 "$tmp/e.csv" | sed 1d | uniq | tr '\n' ' ')" = "0 30 60 79 " ] &&
  ok "--shapes-every 30: steps 0, 30, 60 and the last" || ko "--shapes-every" "$(cut -d, -f1 "$tmp/e.csv" | uniq | tr '\n' ' ')"
[ "$(wc -l < "$tmp/e.csv")" = $((1 + 4 * 35)) ] && ok "--shapes-every: 35 rows per step" || ko "--shapes-every rows" "$(wc -l < "$tmp/e.csv")"
"${REPLAY[@]}" --shapes "$tmp/w.csv" --at 10,500 > /dev/null 2> "$tmp/w.err"
grep -qF "replay: --at 500: the trial ended at step 79 (no shapes for it)" "$tmp/w.err" &&
  [ "$(cut -d, -f1 "$tmp/w.csv" | sed 1d | uniq)" = 10 ] && ok "--at beyond the trial: a warning" || ko "--at 500" "$(cat "$tmp/w.err")"

# replay's option errors: exit 2, the option named, nothing run
bad_opt() { # NAME NEEDLE ARGS...
  local name=$1 needle=$2; shift 2
  "${REPLAY[@]}" "$@" > /dev/null 2> "$tmp/o.err"; local rc=$?
  [ "$rc" = 2 ] && grep -qF -- "$needle" "$tmp/o.err" && ok "$name" || ko "$name" "rc=$rc $(cat "$tmp/o.err")"
}
bad_opt "--at: a bad list" "--at '5,x': expected step numbers 0..100000 and 'last', comma-separated" --shapes "$tmp/x.csv" --at 5,x
bad_opt "--at: a negative step" "--at '-1': expected step numbers" --shapes "$tmp/x.csv" --at -1
bad_opt "--at without --shapes" "--at and --shapes-every choose the steps of --shapes FILE: give --shapes" --at 5
bad_opt "--shapes-every 0" "--shapes-every '0': expected an integer >= 1" --shapes "$tmp/x.csv" --shapes-every 0
bad_opt "--shapes: an unwritable file" "$tmp/none/s.csv: cannot write" --shapes "$tmp/none/s.csv"

# ---- tools/draw_trial.py ----------------------------------------------------------------------
# the object-target distances of the trace (checked against draw_trial's printed values)
col() { head -1 "$tmp/t.csv" | tr , '\n' | grep -nx "$1" | cut -d: -f1; } # a trace column by name
dist() { awk -F, -v s="$1" -v ox="$(col obj_x)" -v tx="$(col target_x)" \
  '$1 == s { printf "%.4f", sqrt(($ox - $tx)^2 + ($(ox + 1) - $(tx + 1))^2 + ($(ox + 2) - $(tx + 2))^2) }' "$tmp/t.csv"; }
draw pic draw_trial.py "$tmp/s.csv" --trace "$tmp/t.csv" --title "grasp trial 8" -- \
  "grasp trial 8" "step 0 (t = 0.05 s)" "step 40 (t = 2.05 s)" "step 79 (t = 4.00 s)" "touching 1  lifted 1" "x (m)"
grep -q "^draw_trial: step 0: 35 shapes, ball (.*), target (.*) radius 0.06, ball-target $(dist 0) m$" "$tmp/pic.out" &&
  grep -q "^draw_trial: step 79: 35 shapes, .*ball-target $(dist 79) m$" "$tmp/pic.out" &&
  ok "pic: printed values (the trace's object-target distance)" || ko "pic: printed values" "$(cat "$tmp/pic.out") (want $(dist 0), $(dist 79))"
dr=$(awk -F, -v r="$(col d_r)" -v g="$(col d_g)" '$1 == 40 { printf "d_r = %.3f m  d_g = %.3f m", $r, $g }' "$tmp/t.csv")
"$PY" "$VALID" "$tmp/pic.svg" "$dr" && ok "pic: the trace's d_r and d_g in a title ($dr)" || ko "pic: titles"
# every step of a file, picked and laid out
draw pic2 draw_trial.py "$tmp/e.csv" --steps first,30,last --cols 2 --view 10,80 -- "step 0" "step 30" "step 79" "e.csv"
[ "$(grep -c '^draw_trial: step' "$tmp/pic2.out")" = 3 ] && ok "pic2: three panels" || ko "pic2 panels" "$(cat "$tmp/pic2.out")"

# malformed input: FILE:LINE and what was expected, no picture
sed '3s/,robot,/,robt,/' "$tmp/s.csv" > "$tmp/b1.csv"
refuses "draw: an unknown kind" "$tmp/b1.csv:3: kind 'robt' (expected robot, ball, table, target)" draw_trial.py "$tmp/b1.csv"
awk -F, -v OFS=, 'NR == 5 { $11 = 2 } 1' "$tmp/s.csv" > "$tmp/b2.csv"
refuses "draw: not a rotation" "$tmp/b2.csv:5: r00..r22 is not a rotation" draw_trial.py "$tmp/b2.csv"
sed '4s/,[^,]*$//' "$tmp/s.csv" > "$tmp/b3.csv"
refuses "draw: a short row" "$tmp/b3.csv:4: 18 fields (expected 19, as the header)" draw_trial.py "$tmp/b3.csv"
sed '6s/,box,/,cone,/' "$tmp/s.csv" > "$tmp/b4.csv"
refuses "draw: an unknown type" "$tmp/b4.csv:6: type 'cone' (expected sphere, box, cylinder, mesh)" draw_trial.py "$tmp/b4.csv"
cut -d, -f1-9 "$tmp/s.csv" > "$tmp/b5.csv"
refuses "draw: missing columns" "$tmp/b5.csv:1: header without pz,r00,r01" draw_trial.py "$tmp/b5.csv"
awk -F, -v OFS=, 'NR == 7 { $5 = "nan" } 1' "$tmp/s.csv" > "$tmp/b6.csv"
refuses "draw: a non-finite size" "$tmp/b6.csv:7: sx 'nan' (expected a finite number)" draw_trial.py "$tmp/b6.csv"
refuses "draw: a step not in the file" "--steps: $tmp/s.csv has no shapes of step 5 (it has steps 0, 40, 79" draw_trial.py "$tmp/s.csv" --steps 0,5
"$APPDIR/replay" "$RUN/population.genome" "$RUN/config.ini" --stage main --trial 9 --out "$tmp/other.csv" > /dev/null 2>&1
refuses "draw: the trace of another trial" "(expected the trace of the same replay)" draw_trial.py "$tmp/s.csv" --trace "$tmp/other.csv"
sed '2d' "$tmp/t.csv" > "$tmp/t0.csv"
refuses "draw: a drawn step missing from the trace" "$tmp/t0.csv: no row of step 0 (expected the trace of the replay that wrote $tmp/s.csv)" draw_trial.py "$tmp/s.csv" --trace "$tmp/t0.csv"
refuses "draw: a bad --view" "--view 'up': expected ELEV,AZIM in degrees" draw_trial.py "$tmp/s.csv" --view up

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
