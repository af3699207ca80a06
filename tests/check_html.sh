#!/usr/bin/env bash
# Trial pages (issue 27): ./apps/replay --html writes one self-contained page of a trial (its
# shapes at every step, the trace, the summary; three.js inlined): under 2 MB for a primitive
# and for a 240-step integrated trial, loading nothing (tests/html_page.py static: no element or
# text that loads an address, three.js inlined unchanged with its licence), the trace the same
# with or without it, its option errors before the trial. Then in headless Chromium: the page
# renders (a screenshot that is not blank, the arm and the ball where the page's camera puts
# them, the ball lifted by the grasp), its script reports the steps, words and labels of the
# trace, the browser's network log has no request of the page (and has one of a control page
# that loads an image), a damaged or cut page shows an error text, a browser without WebGL
# still shows the trace. Pages of hostile names (markup and code in a URDF link, the genotype's
# file name, the three.js directory) stay inert: the names shown as text, none run. Without a browser the Chromium part is skipped with a message.
set -uo pipefail
CHECK=check_html
source "$(dirname "$0")/check_lib.sh"
PY=${PYTHON:-/usr/bin/python3}
HP=tests/html_page.py
THREE=${SELFTALK_THREE_DIR:-/usr/share/javascript/three}
RUN=data/evolved/prims_s2
REPLAY=("$APPDIR/replay" "$RUN/population.genome" "$RUN/config.ini" --stage main --trial 8)
MAX=$((2 * 1024 * 1024))

# a page and its trace: NAME REPLAY_ARGS...; checks the size and that it loads nothing
page() {
  local name=$1; shift
  if ! "$@" --html "$tmp/$name.html" --out "$tmp/$name.csv" > "$tmp/$name.out" 2> "$tmp/$name.err"; then
    ko "$name: replay --html" "$(cat "$tmp/$name.err")"; return 1
  fi
  local size rows
  size=$(stat -c %s "$tmp/$name.html") rows=$(($(wc -l < "$tmp/$name.csv") - 1))
  grep -qF "replay: $tmp/$name.html: a page of $rows steps, 35 shapes, $size bytes" "$tmp/$name.err" &&
    ok "$name: a page of $rows steps, $size bytes" || ko "$name: replay's report" "$(cat "$tmp/$name.err")"
  [ "$size" -lt "$MAX" ] && ok "$name: under 2 MB" || ko "$name: $size bytes (expected < $MAX)"
  "$PY" $HP static "$tmp/$name.html" "$THREE" > "$tmp/$name.static" 2>&1 &&
    ok "$name: loads nothing, three.js inlined with its licence" || ko "$name: static" "$(cat "$tmp/$name.static")"
}

page grasp "${REPLAY[@]}"
grep -qx "trial 8 main-prim grasp k=0 success=1 steps=80/80 end=full .*" "$tmp/grasp.out" &&
  ok "grasp: replay's summary line" || ko "grasp: summary" "$(cat "$tmp/grasp.out")"
"${REPLAY[@]}" --exact --out "$tmp/e1.csv" > /dev/null 2>&1
"${REPLAY[@]}" --exact --out "$tmp/e2.csv" --html "$tmp/e.html" > /dev/null 2>&1
cmp -s "$tmp/e1.csv" "$tmp/e2.csv" && ok "the trace is unchanged by --html" || ko "trace changed by --html"
# the 240-step integrated trials: the integration test's (caretaker words) and an ST-CT
# individual's talking to itself (type A: self-talk labels and linguistic outputs)
page integration "$APPDIR/replay" "$RUN/population.genome" data/evolved/integration_test/config.ini \
  --posteval integration --trial 0
page stct "$APPDIR/replay" data/evolved/unchained/int_stct_s1/population.genome data/evolved/unchained/int_stct_s1/config.ini \
  --trial 1 --generation 99
for n in integration stct; do
  [ "$(($(wc -l < "$tmp/$n.csv") - 1))" = 240 ] && ok "$n: 240 steps" || ko "$n: steps" "$(wc -l < "$tmp/$n.csv")"
done

# option errors: exit 2, the reason, before the trial (no summary line, no page)
bad_opt() { # NAME NEEDLE ARGS...
  local name=$1 needle=$2; shift 2
  "${REPLAY[@]}" "$@" > "$tmp/o.out" 2> "$tmp/o.err"; local rc=$?
  [ "$rc" = 2 ] && grep -qF -- "$needle" "$tmp/o.err" && [ ! -s "$tmp/o.out" ] && [ ! -e "$tmp/x.html" ] &&
    ok "$name" || ko "$name" "rc=$rc $(cat "$tmp/o.err" "$tmp/o.out")"
}
bad_opt "no three.js: says how to install it" "$tmp/none/three.min.js: cannot open" --html "$tmp/x.html" --three "$tmp/none"
grep -qF "Debian's libjs-three, \`apt-get install libjs-three\` or \`make deps\`" "$tmp/o.err" &&
  ok "no three.js: names the package" || ko "no three.js message" "$(cat "$tmp/o.err")"
SELFTALK_THREE_DIR=$tmp/none bad_opt "SELFTALK_THREE_DIR is read" "$tmp/none/three.min.js: cannot open" --html "$tmp/x.html"
bad_opt "--three without --html" "--three DIR is where --html FILE finds three.js: give --html" --three "$THREE"
bad_opt "--html: an unwritable file" "--html: $tmp/none/x.html.tmp." --html "$tmp/none/x.html"

# ---- hostile names (issue 48) ---------------------------------------------------------------
# A URDF link listed in robot.touch_links, the genotype's file name and the three.js directory
# hold markup and code, each of which sets data-pwned on the page when run. The writer escapes
# each where it lands (apps/trial_page.c, sb_escaped) and the page's script builds its elements
# from text nodes: the pages work, show the names as text and run none of them.
# First the writer's property on its fuzz seeds and on a page with the real three.js
# (build/page_check: tests/fuzz/fuzz_page.c without libFuzzer)
{ printf 't\0l\0l_hand\0%s\0o\0' "$THREE"; cat "$THREE/three.min.js"; printf '\0'
  cat "$THREE/examples/js/controls/OrbitControls.js"; } > "$tmp/page-seed"
seeds=(tests/fuzz/seeds/page/* "$tmp/page-seed")
[ -d tests/fuzz/regressions/page ] && seeds+=(tests/fuzz/regressions/page/*)
"./${BUILD:-build}/page_check" "${seeds[@]}" > "$tmp/pc" 2>&1 &&
  ok "the page writer keeps the page's elements and comments whatever the names ($(cat "$tmp/pc"), page_check)" ||
  ko "page writer (build/page_check ${seeds[*]})" "$(cat "$tmp/pc")"
pwn() { echo "<img src onerror=document.documentElement.dataset.pwned=$1>"; }
cat > "$tmp/hostile.py" <<'PY'
import html, re, sys
tmp, ini, name = sys.argv[1:4]
urdf = re.search(r"^urdf = (.*)$", open(ini).read(), re.M).group(1)
open(f"{tmp}/hostile.urdf", "w").write(open(urdf).read().replace('"l_ring_3"', '"' + html.escape(name) + '"'))
text = open(ini).read().replace(f"urdf = {urdf}", f"urdf = {tmp}/hostile.urdf")
text = re.sub(r"^(touch_links = .*)l_ring_3", lambda m: m.group(1) + name, text, flags=re.M)
open(f"{tmp}/hostile.ini", "w").write(text)
PY
"$PY" "$tmp/hostile.py" "$tmp" "$RUN/config.ini" "$(pwn 3)"
HGENOME="$tmp/$(pwn 4).genome"
cp "$RUN/population.genome" "$HGENOME"
THREE_A="$tmp/three-a/x*/document.documentElement.dataset.pwned=1;/*" # ends the comment
THREE_B="$tmp/three-b/x</script>$(pwn 2)"                              # ends the element
for d in "$THREE_A" "$THREE_B"; do
  mkdir -p "$d/examples/js/controls" && ln -s "$THREE/three.min.js" "$d/three.min.js" &&
    ln -s "$THREE/examples/js/controls/OrbitControls.js" "$d/examples/js/controls/OrbitControls.js"
done
hostile() { # NAME THREE_DIR GENOME CONFIG
  "$APPDIR/replay" "$3" "$4" --stage main --trial 8 --html "$tmp/$1.html" --three "$2" \
    > /dev/null 2> "$tmp/$1.err" || { ko "$1: replay --html" "$(cat "$tmp/$1.err")"; return; }
  "$PY" $HP static "$tmp/$1.html" "$2" > "$tmp/$1.static" 2>&1 &&
    ok "$1: every name escaped where it lands (static)" || ko "$1: static" "$(cat "$tmp/$1.static")"
}
hostile hostile-a "$THREE_A" "$HGENOME" "$tmp/hostile.ini"
hostile hostile-b "$THREE_B" "$RUN/population.genome" "$RUN/config.ini"

# ---- in a browser ---------------------------------------------------------------------------
BROWSER=
for b in chromium chromium-browser; do command -v "$b" > /dev/null && { BROWSER=$b; break; }; done
if [ -z "$BROWSER" ]; then
  echo "$CHECK: the browser checks are SKIPPED: no chromium (\`make deps\` installs Debian's chromium)"
  echo "$CHECK: $pass passed, $fail failed"
  [ "$fail" = 0 ]; exit
fi
# NAME URL [FLAGS...]: a screenshot ($tmp/NAME.png) and the DOM its script left ($tmp/NAME.dom);
# software WebGL (SwiftShader), the browser's own background requests off, a fresh profile
browse() {
  local name=$1 url=$2; shift 2
  timeout 600 "$BROWSER" --headless --no-sandbox --disable-gpu --enable-unsafe-swiftshader \
    --hide-scrollbars --window-size=1200,800 --virtual-time-budget=5000 --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$tmp/profile-$name" "$@" --screenshot="$tmp/$name.png" --dump-dom "$url" \
    > "$tmp/$name.dom" 2> "$tmp/$name.browser"
}
status() { grep -o 'data-status="[^"]*"' "$tmp/$1.dom"; }

for s in 0 last; do
  browse "grasp-$s" "file://$tmp/grasp.html#step=$s&size=1200x800" --log-net-log="$tmp/net-$s.json"
  step=$([ $s = last ] && echo 79 || echo 0)
  "$PY" $HP report "$tmp/grasp-$s.dom" "$tmp/grasp.csv" $step > "$tmp/rep" 2>&1 &&
    ok "grasp step $s: the page read the trace's 80 steps and words, the ball where the trace has it" || ko "grasp step $s: report" "$(cat "$tmp/rep")"
  # at step 0 the ball is free under the hand; at the last step the fingers hide part of it
  "$PY" $HP pixels "$tmp/grasp-$s.png" "$tmp/grasp-$s.dom" $([ $s = 0 ] && echo 0.6 || echo 0.15) > "$tmp/pix" 2>&1 &&
    ok "grasp step $s: renders: $(sed 's/^html_page: //' "$tmp/pix")" || ko "grasp step $s: pixels" "$(cat "$tmp/pix")"
  "$PY" $HP netlog "$tmp/net-$s.json" > "$tmp/net" 2>&1 && ok "grasp step $s: the page requested nothing" ||
    ko "grasp step $s: network" "$(cat "$tmp/net")"
done
ball_y() { grep -o 'data-ball="[^"]*"' "$tmp/$1.dom" | cut -d, -f2; }
y0=$(ball_y grasp-0) y1=$(ball_y grasp-last)
[ -n "$y0" ] && [ -n "$y1" ] && [ "$y1" -lt $((y0 - 100)) ] && ok "the ball is lifted: at y $y0 then $y1 (pixels)" ||
  ko "the ball lifted" "y $y0 then $y1"
# the network check sees a page that loads something
cat > "$tmp/loads.html" <<'HTML'
<!DOCTYPE html><html><body><img src="http://selftalk.invalid/x.png">page</body></html>
HTML
browse loads "file://$tmp/loads.html" --log-net-log="$tmp/net-loads.json"
"$PY" $HP netlog "$tmp/net-loads.json" > "$tmp/net" 2>&1
grep -qF "the page requested ['http://selftalk.invalid/x.png']" "$tmp/net" &&
  ok "the network check sees a page's request" || ko "network check control" "$(cat "$tmp/net")"

for n in integration stct; do
  browse "$n" "file://$tmp/$n.html#step=120&size=1200x800"
  "$PY" $HP report "$tmp/$n.dom" "$tmp/$n.csv" 120 > "$tmp/rep" 2>&1 &&
    ok "$n: the page read the trace's 240 steps, words and labels" || ko "$n: report" "$(cat "$tmp/rep")"
  "$PY" $HP pixels "$tmp/$n.png" "$tmp/$n.dom" 0.15 > "$tmp/pix" 2>&1 &&
    ok "$n: renders" || ko "$n: pixels" "$(cat "$tmp/pix")"
done
grep -q 'data-labels="[^"]*[0-3]' "$tmp/stct.dom" && grep -q '>Linguistic outputs<' "$tmp/stct.dom" &&
  ok "stct: self-talk labels and linguistic outputs shown" || ko "stct: labels" "$(grep -o 'data-labels="[^"]\{0,60\}' "$tmp/stct.dom")"

# the hostile pages in the browser: they work, nothing of the names ran, no element was added
for n in hostile-a hostile-b; do
  browse "$n" "file://$tmp/$n.html#step=40"
  if [ "$(status $n)" = 'data-status="ok"' ] && ! grep -q 'data-pwned' "$tmp/$n.dom" && ! grep -qi '<img' "$tmp/$n.dom"; then
    ok "$n: inert in the browser (no data-pwned, no <img>, the page drawn)"
  else
    ko "$n: in the browser" "$(status $n) $(grep -o 'data-pwned="[^"]*"' "$tmp/$n.dom") $(grep -oi '<img[^>]*>' "$tmp/$n.dom" | head -3)"
  fi
done
grep -qE '<span id="t3" class="(on)?">&lt;img src onerror=document.documentElement.dataset.pwned=3&gt;</span>' "$tmp/hostile-a.dom" &&
  grep -qF "<h1 id=\"title\">$tmp/&lt;img src onerror=document.documentElement.dataset.pwned=4&gt;.genome genotype 0" "$tmp/hostile-a.dom" &&
  ok "hostile-a: the link's and the genotype file's names shown as text" ||
  ko "hostile-a: names as text" "$(grep -o '<span id="t3"[^<]*' "$tmp/hostile-a.dom") $(grep -o '<h1 id="title">[^<]*' "$tmp/hostile-a.dom")"

# damaged pages: a digit of the data changed, the file cut inside the data
"$PY" - "$tmp/grasp.html" "$tmp" <<'PY'
import sys
s = open(sys.argv[1]).read()
i = s.index('"d_g":[') + 7
j = next(k for k in range(i, len(s)) if s[k].isdigit())
open(sys.argv[2] + "/digit.html", "w").write(s[:j] + ("1" if s[j] != "1" else "2") + s[j + 1:])
k = s.index('id="trial-data"')
open(sys.argv[2] + "/cut.html", "w").write(s[:k + 30000])
PY
for n in digit cut; do
  browse "$n" "file://$tmp/$n.html"
  [ "$(status $n)" = 'data-status="error"' ] &&
    grep -qF '<b>This trial page cannot be shown:</b> <span id="error-text">the trial data is damaged (checksum' "$tmp/$n.dom" &&
    grep -q '<body class="failed">' "$tmp/$n.dom" && "$PY" tests/valid_image.py "$tmp/$n.png" &&
    ok "damaged page ($n): the error text shown" || ko "damaged page ($n)" "$(status $n) $(grep -o 'id="error-text">[^<]*' "$tmp/$n.dom")"
done
# no WebGL: the trace and the summary still shown, the reason where the robot would be
browse nogl "file://$tmp/grasp.html#step=5" --disable-3d-apis
[ "$(status nogl)" = 'data-status="no-3d"' ] && grep -qF 'The robot cannot be drawn: WebGL is not available' "$tmp/nogl.dom" &&
  grep -qF 'id="s-step">5 / 79<' "$tmp/nogl.dom" && ok "without WebGL: the trace shown, and why the robot is not" ||
  ko "without WebGL" "$(status nogl) $(grep -o 'id="msg">[^<]*' "$tmp/nogl.dom")"

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
