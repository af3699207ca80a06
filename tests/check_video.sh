#!/usr/bin/env bash
# Videos of a replayed trial (tools/trial_video.sh, tools/trial_video.py): the GIF and the MP4
# have one frame per --stride steps of the trace and its last step, at the size asked for and
# the frame rate; each frame's words are the trace's (the word heard is the one given, or with
# self talk the label said the step before); damaged or mismatched inputs are refused with
# FILE:LINE and a non-zero exit, writing nothing. On 23-step trials of the committed runs
# (--set shortens them), so the check takes seconds.
set -uo pipefail
CHECK=check_video
source "$(dirname "$0")/check_lib.sh"
PY=${PYTHON:-/usr/bin/python3}
export APPDIR PYTHON="$PY"
STCT=(data/evolved/unchained/int_stct_s1/best.genome data/evolved/unchained/int_stct_s1/config.ini --generation 99
      --set integrated.steps=23)
VIDEO=tools/trial_video.sh

# expected frames: every STRIDE-th of N steps from the first, and the last
frames() { echo $(( ($1 + $2 - 1) / $2 + (($1 - 1) % $2 != 0) )); }
rows() { echo $(( $(wc -l < "$1") - 1 )); }
# a GIF's frame count, size and the delays (ms) of its first and last frames, read by Pillow
gif_info() {
  "$PY" -c 'import sys; from PIL import Image
im = Image.open(sys.argv[1]); n = im.n_frames; d0 = im.info["duration"]; im.seek(n - 1)
print(n, "%dx%d" % im.size, d0, im.info["duration"])' "$1"
}

# ---- a self-talk trial as a GIF: frames, size, delays, words ------------------------------
if bash "$VIDEO" "${STCT[@]}" --trial 1 --stride 5 --size 320x260 --list --keep "$tmp/st" \
     -o "$tmp/st.gif" > "$tmp/st.out" 2>&1; then
  ok "trial_video.sh: a self-talk trial"
else
  ko "trial_video.sh: a self-talk trial" "$(cat "$tmp/st.out")"
fi
n=$(rows "$tmp/st/trace.csv")
want=$(frames "$n" 5)
[ "$n" = 23 ] && [ "$want" = 6 ] && ok "the trace: 23 steps, so 6 frames at stride 5" || ko "trace rows" "$n steps, $want frames"
# default fps: real time, 1 / (0.05 s x 5) = 4 fps = 250 ms; the last frame held 1.5 s
got=$(gif_info "$tmp/st.gif" 2>&1)
[ "$got" = "$want 320x260 250 1500" ] && ok "GIF: $want frames, 320x260, 250 ms, the last 1500 ms" ||
  ko "GIF frames/size/delays" "got '$got', want '$want 320x260 250 1500'"
grep -qxF "trial_video: wrote $tmp/st.gif: 6 frames (steps 0..22, every 5 and the last), 320x260 pixels, 4 fps, $(stat -c %s "$tmp/st.gif") bytes" "$tmp/st.out" &&
  ok "GIF: the line printed" || ko "GIF: printed line" "$(tail -1 "$tmp/st.out")"
[ "$(sed -n 's/^trial_video: frame [0-9]*: step \([0-9]*\):.*/\1/p' "$tmp/st.out" | tr '\n' ' ')" = "0 5 10 15 20 22 " ] &&
  ok "frames: steps 0, 5, 10, 15, 20 and the last, 22" || ko "frame steps" "$(grep frame "$tmp/st.out")"
# each frame's words against the trace: said = selftalk_label of the step; heard = the label of
# the step before (self talk), none at step 0
words=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  { w[$1] = $c["selftalk_label"] }
  END { split("reach open grasp move", n, " ")
        for (s = 0; s <= 22; s += (s == 20 ? 2 : 5)) {
          h = s ? n[w[s - 1] + 1] " (self talk: its own word)" : "-"
          printf "trial_video: frame %d: step %d: heard %s; said %s;\n", (s == 22 ? 5 : s / 5), s, h, n[w[s] + 1] } }' "$tmp/st/trace.csv")
[ "$(grep '^trial_video: frame' "$tmp/st.out" | sed 's/; lifted.*/;/')" = "$words" ] &&
  ok "frames: the words heard and said are the trace's" || ko "frame words" "$(grep frame "$tmp/st.out") (want $words)"
# the pictures: the ball (orange) and the arm (blue-grey) in the first frame, and the picture
# above the text moves between the first and the last (the self-talk individual moves its arm)
"$PY" -c 'import sys; from PIL import Image, ImageChops
im = Image.open(sys.argv[1]); a = im.convert("RGB"); im.seek(im.n_frames - 1); b = im.convert("RGB")
px = list(a.getdata())
ball = sum(r > 180 and 80 < g < 175 and b < 100 for r, g, b in px)
arm = sum(b > 150 and b > r + 25 and g > r for r, g, b in px)
assert ball > 30 and arm > 1000, f"ball {ball} pixels, arm {arm}"
top = (0, 0, a.width, int(0.75 * a.height))
assert ImageChops.difference(a.crop(top), b.crop(top)).getbbox(), "no motion"' "$tmp/st.gif" 2> "$tmp/px.err" &&
  ok "GIF: the ball and the arm drawn, and moving" || ko "GIF pictures" "$(tail -1 "$tmp/px.err")"
[ -z "$(find "$tmp" -maxdepth 1 -name '*.tmp')" ] && ok "no temporary file left" || ko "temporary files" "$(ls "$tmp")"

# ---- a caretaker trial, every step, --fps --------------------------------------------------
bash "$VIDEO" "${STCT[@]}" --trial 0 --fps 10 --size 200x160 --list --keep "$tmp/ct" \
  -o "$tmp/ct.gif" > "$tmp/ct.out" 2>&1
n=$(rows "$tmp/ct/trace.csv")
got=$(gif_info "$tmp/ct.gif" 2>&1)
[ "$got" = "$n 200x160 100 1500" ] && ok "GIF, stride 1: one frame per step ($n), 200x160, 100 ms" ||
  ko "GIF stride 1" "got '$got', want '$n 200x160 100 1500'"
care=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  { split("reach open grasp move", n, " "); w = $c["caretaker_word"]
    printf "trial_video: frame %d: step %d: heard %s;\n", $1, $1, (w < 0 ? "-" : n[w + 1] " (caretaker)") }' "$tmp/ct/trace.csv")
[ "$(grep '^trial_video: frame' "$tmp/ct.out" | sed 's/ said.*//')" = "$care" ] &&
  ok "frames: the caretaker's words" || ko "caretaker words" "$(grep frame "$tmp/ct.out" | head -5)"

# ---- MP4 (ffmpeg), counted by ffprobe ------------------------------------------------------
if command -v ffprobe > /dev/null; then
  bash "$VIDEO" "${STCT[@]}" --trial 1 --stride 4 --size 320x260 -o "$tmp/st.mp4" > "$tmp/mp4.out" 2>&1
  want=$(frames 23 4)
  got=$(ffprobe -v error -count_frames -select_streams v:0 -of csv=p=0 \
        -show_entries stream=codec_name,width,height,r_frame_rate,nb_read_frames "$tmp/st.mp4" 2>&1)
  [ "$got" = "h264,320,260,5/1,$want" ] && ok "MP4: $want frames, 320x260, 5 fps (ffprobe)" ||
    ko "MP4" "got '$got', want 'h264,320,260,5/1,$want' $(cat "$tmp/mp4.out")"
  bash "$VIDEO" "${STCT[@]}" --trial 1 --size 321x260 -o "$tmp/odd.mp4" > /dev/null 2> "$tmp/odd.err"
  [ $? != 0 ] && grep -qF -- "--size 321x260: MP4 (yuv420p) needs an even width and height" "$tmp/odd.err" &&
    [ ! -e "$tmp/odd.mp4" ] && ok "MP4: an odd size refused" || ko "MP4 odd size" "$(cat "$tmp/odd.err")"
else
  ko "MP4: ffprobe not found" "make deps installs ffmpeg"
fi

# ---- refused: FILE:LINE, non-zero exit, no video -------------------------------------------
K=$tmp/st
refuses() { # NAME NEEDLE ARGS... (trial_video.py's)
  local name=$1 needle=$2; shift 2
  rm -f "$tmp/bad.gif"
  "$PY" tools/trial_video.py "$@" -o "$tmp/bad.gif" > /dev/null 2> "$tmp/err"; local rc=$?
  if [ "$rc" != 0 ] && grep -qF -- "$needle" "$tmp/err" && [ ! -e "$tmp/bad.gif" ] && [ ! -e "$tmp/bad.gif.tmp" ]; then
    ok "$name"
  else
    ko "$name" "rc=$rc $(cat "$tmp/err")"
  fi
}
ncol=$(head -1 "$K/trace.csv" | tr , '\n' | wc -l)
sed '5s/,[^,]*$//' "$K/trace.csv" > "$tmp/t1.csv"
refuses "a cut trace line" "$tmp/t1.csv:5: $((ncol - 1)) fields (expected $ncol, as the header)" "$K/shapes.csv" "$tmp/t1.csv"
awk -F, -v OFS=, 'NR == 7 { $17 = "x" } 1' "$K/trace.csv" > "$tmp/t2.csv"
refuses "a damaged number" "$tmp/t2.csv:7: obj_x 'x' (expected a finite number)" "$K/shapes.csv" "$tmp/t2.csv"
sed '6d' "$K/trace.csv" > "$tmp/t3.csv"
refuses "a missing step" "$tmp/t3.csv:6: step 5 (expected 4: one row per step)" "$K/shapes.csv" "$tmp/t3.csv"
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } NR == 4 { $c["ling_reach"] = 10; $c["ling_move"] = 10 } 1' "$K/trace.csv" > "$tmp/t4.csv"
refuses "two words heard at once" "$tmp/t4.csv:4: ling_reach..ling_move 10, " "$K/shapes.csv" "$tmp/t4.csv"
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } NR == 3 { $c["event"] = "end_maybe" } 1' "$K/trace.csv" > "$tmp/t5.csv"
refuses "an unknown event" "$tmp/t5.csv:3: event 'end_maybe' (expected empty, end_success" "$K/shapes.csv" "$tmp/t5.csv"
head -10 "$K/trace.csv" > "$tmp/t6.csv"
refuses "a cut trace" "$K/shapes.csv: shapes of step 9, but $tmp/t6.csv has steps 0..8 (expected the files of one replay)" "$K/shapes.csv" "$tmp/t6.csv"
: > "$tmp/t7.csv"
refuses "an empty trace" "$tmp/t7.csv:1: empty (expected an ./apps/replay trace (--out)" "$K/shapes.csv" "$tmp/t7.csv"
refuses "a missing trace" "$tmp/none.csv: No such file or directory" "$K/shapes.csv" "$tmp/none.csv"
cut -d, -f1-40 "$K/trace.csv" > "$tmp/t8.csv"
refuses "a trace without the words" "$tmp/t8.csv:1: header without touching,lifted,caretaker_word,selftalk_label" "$K/shapes.csv" "$tmp/t8.csv"
"$APPDIR/replay" "${STCT[@]}" --trial 2 --out "$tmp/other.csv" > /dev/null 2>&1
refuses "the trace of another trial" "(expected the trace of the same replay)" "$K/shapes.csv" "$tmp/other.csv"
"$APPDIR/replay" "${STCT[@]}" --trial 1 --out "$tmp/t9.csv" --shapes "$tmp/s5.csv" --shapes-every 5 > /dev/null 2>&1
refuses "shapes of every 5th step, frames of every step" "$tmp/s5.csv: no shapes of step 1 (expected every frame's step: ./apps/replay --shapes FILE --shapes-every 1)" "$tmp/s5.csv" "$tmp/t9.csv"
"$PY" tools/trial_video.py "$tmp/s5.csv" "$tmp/t9.csv" --stride 5 --size 200x160 -o "$tmp/s5.gif" > /dev/null 2>&1 &&
  [ "$(gif_info "$tmp/s5.gif" | cut -d' ' -f1)" = 6 ] && ok "shapes of every 5th step, frames of every 5th: 6 frames" || ko "--shapes-every 5 --stride 5"
sed 's/steps=23\/23/steps=30\/30/' "$K/replay.txt" > "$tmp/r1.txt"
refuses "a summary of another replay" "$tmp/r1.txt:1: steps=30/30 but the trace has 23 steps" "$K/shapes.csv" "$K/trace.csv" --summary "$tmp/r1.txt"
sed '3s/,robot,/,robt,/' "$K/shapes.csv" > "$tmp/s1.csv"
refuses "a damaged shapes file" "$tmp/s1.csv:3: kind 'robt' (expected robot, ball, table, target)" "$tmp/s1.csv" "$K/trace.csv"
"$PY" tools/trial_video.py "$K/shapes.csv" "$K/trace.csv" -o "$tmp/bad.avi" > /dev/null 2> "$tmp/err"
[ $? = 2 ] && grep -qF "$tmp/bad.avi: unknown video format (expected a name ending in .gif or .mp4)" "$tmp/err" &&
  [ ! -e "$tmp/bad.avi" ] && ok "an unknown format" || ko "an unknown format" "$(cat "$tmp/err")"
refuses "a bad --size" "--size '10x10': expected WxH in pixels, 64..4096 each" "$K/shapes.csv" "$K/trace.csv" --size 10x10
refuses "--stride 0" "--stride 0: out of range" "$K/shapes.csv" "$K/trace.csv" --stride 0
# the one command: its own options refused, replay's failure passed on
bash "$VIDEO" "${STCT[@]}" --trial 1 --out "$tmp/x.csv" -o "$tmp/w1.gif" > /dev/null 2> "$tmp/w1.err"
[ $? = 2 ] && grep -qF -- "--out: this script writes the replay's files itself" "$tmp/w1.err" && [ ! -e "$tmp/w1.gif" ] &&
  ok "trial_video.sh: --out refused" || ko "trial_video.sh --out" "$(cat "$tmp/w1.err")"
bash "$VIDEO" "${STCT[@]}" --trial 99 -o "$tmp/w2.gif" > /dev/null 2> "$tmp/w2.err"
[ $? != 0 ] && grep -qF "replay: " "$tmp/w2.err" && grep -qF "./apps/replay failed: no video" "$tmp/w2.err" && [ ! -e "$tmp/w2.gif" ] &&
  ok "trial_video.sh: replay's error passed on" || ko "trial_video.sh replay error" "$(cat "$tmp/w2.err")"
bash "$VIDEO" "${STCT[@]}" --trial 1 > /dev/null 2> "$tmp/w3.err"
[ $? = 2 ] && grep -qF "no -o OUT.gif or OUT.mp4" "$tmp/w3.err" && ok "trial_video.sh: no output named" || ko "trial_video.sh no -o" "$(cat "$tmp/w3.err")"

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
