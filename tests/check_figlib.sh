# Helpers of the checks that draw with tools/*.py (check_figures.sh, check_pictures.sh), sourced
# after tests/check_lib.sh: draw (a PNG and an SVG, both checked by tests/valid_image.py), has
# (printed lines), refuses (exit 2, the message, no output written).
PY=${PYTHON:-/usr/bin/python3}
VALID=tests/valid_image.py

# draw NAME SCRIPT ARGS... -- TEXT...: writes $tmp/NAME.png and .svg (output in $tmp/NAME.out)
# and checks both files
draw() {
  local name=$1 script=$2; shift 2
  local args=() texts=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do args+=("$1"); shift; done
  [ $# -gt 0 ] && shift && texts=("$@")
  if ! "$PY" "tools/$script" "${args[@]}" -o "$tmp/$name.png" -o "$tmp/$name.svg" > "$tmp/$name.out" 2>&1; then
    ko "$name: $script failed" "$(cat "$tmp/$name.out")"; return 1
  fi
  local e
  if e=$("$PY" "$VALID" "$tmp/$name.png" 2>&1 | tail -1) && e=$("$PY" "$VALID" "$tmp/$name.svg" "${texts[@]}" 2>&1 | tail -1); then
    ok "$name: valid PNG and SVG"
  else
    ko "$name: invalid output" "$e"; return 1
  fi
}
# has NAME LINE...: NAME's output has every LINE
has() {
  local name=$1; shift
  for l in "$@"; do grep -qxF -- "$l" "$tmp/$name.out" || { ko "$name: printed values" "no '$l' in: $(cat "$tmp/$name.out")"; return; }; done
  ok "$name: printed values"
}
# refuses NAME NEEDLE SCRIPT ARGS...: exit 2, NEEDLE on stderr, no output file
refuses() {
  local name=$1 needle=$2 script=$3; shift 3
  rm -f "$tmp/bad.png" "$tmp/bad.svg"
  "$PY" "tools/$script" "$@" -o "$tmp/bad.png" -o "$tmp/bad.svg" > /dev/null 2> "$tmp/err"; local rc=$?
  if [ "$rc" = 2 ] && grep -qF -- "$needle" "$tmp/err" && [ ! -e "$tmp/bad.png" ] && [ ! -e "$tmp/bad.svg" ]; then
    ok "$name"
  else
    ko "$name" "rc=$rc $(cat "$tmp/err")"
  fi
}
