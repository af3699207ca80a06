#!/usr/bin/env bash
# End-to-end checks of the apps' command lines: bad input is refused with a message naming the
# file, line and key, and a non-zero exit.
set -uo pipefail
APPDIR=${APPDIR:-apps}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0

# expect_fail NAME NEEDLE CMD...: the command must exit non-zero and print NEEDLE on stderr
expect_fail() {
  local name=$1 needle=$2; shift 2
  if "$@" >"$tmp/out" 2>"$tmp/err"; then
    echo "check_apps: $name FAILED (exit 0)"; fail=$((fail + 1)); return
  fi
  if grep -qF -- "$needle" "$tmp/err"; then
    echo "check_apps: $name ok"; pass=$((pass + 1))
  else
    echo "check_apps: $name FAILED: expected '$needle' in: $(cat "$tmp/err")"; fail=$((fail + 1))
  fi
}

python3 - "$tmp" <<'PY'
import random, sys
d = sys.argv[1]
r = random.Random(5)
with open(d + "/g.genome", "w") as f:
    f.write("# genes 612\n" + "".join("%04x" % r.randrange(65536) for _ in range(612)) + "\n")
with open(d + "/rows", "w") as f:
    for _ in range(3):
        f.write(" ".join("%.3f" % r.random() for _ in range(25)) + "\n")
PY
printf '[ga]\npopulation = 100\nmutaton_rate = 0.1\n' > "$tmp/bad.cfg"
printf '[ga]\nmutation_rate = 0.1\n' > "$tmp/good.cfg"

expect_fail "bad config key" "$tmp/bad.cfg:3: key 'ga.mutaton_rate': unknown key" \
  "$APPDIR/neteval" "$tmp/g.genome" --config "$tmp/bad.cfg"
expect_fail "missing config" "$tmp/none.cfg: cannot open: No such file or directory" \
  "$APPDIR/neteval" "$tmp/g.genome" --config "$tmp/none.cfg"
expect_fail "bad --set" "--set network.lamda=2: key 'network.lamda': unknown key" \
  "$APPDIR/neteval" "$tmp/g.genome" --set network.lamda=2
expect_fail "bad --set value" "key 'network.lambda': 'x' is not a number" \
  "$APPDIR/neteval" "$tmp/g.genome" --set network.lambda=x
expect_fail "wrong arch for genome" "612 genes (expected 696)" \
  "$APPDIR/neteval" "$tmp/g.genome" --arch A
expect_fail "unknown arch" "--arch 'C': unknown architecture" "$APPDIR/neteval" "$tmp/g.genome" --arch C
expect_fail "missing genome" "$tmp/nope.genome: cannot open" "$APPDIR/neteval" "$tmp/nope.genome"
printf '0.1 0.2\n' > "$tmp/short"
expect_fail "short row" "stdin:1: 2 numbers (expected 25 for architecture base)" \
  sh -c "'$APPDIR/neteval' '$tmp/g.genome' < '$tmp/short'"
{ cat "$tmp/rows"; echo "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 abc"; } > "$tmp/nan"
expect_fail "non-number" "stdin:4: field 25 'abc' is not a number" \
  sh -c "'$APPDIR/neteval' '$tmp/g.genome' < '$tmp/nan'"

printf '0 0 0\0 0 0\n' > "$tmp/nul"
expect_fail "NUL byte in a row" "stdin:1: NUL byte at column 6" \
  sh -c "'$APPDIR/neteval' '$tmp/g.genome' < '$tmp/nul'"
{ head -c 70000 /dev/zero | tr '\0' ' '; echo; } > "$tmp/long"
expect_fail "endless row" "stdin:1: line longer than 65536 bytes" \
  sh -c "'$APPDIR/neteval' '$tmp/g.genome' < '$tmp/long'"
# the last row needs no newline
if [ "$(head -c -1 "$tmp/rows" | "$APPDIR/neteval" "$tmp/g.genome" | wc -l)" = 3 ]; then
  echo "check_apps: last row without a newline ok"; pass=$((pass + 1))
else
  echo "check_apps: last row without a newline FAILED"; fail=$((fail + 1))
fi

# a good config and override are accepted, and lambda changes the output
a=$("$APPDIR/neteval" "$tmp/g.genome" --config "$tmp/good.cfg" < "$tmp/rows" | head -1)
b=$("$APPDIR/neteval" "$tmp/g.genome" --set network.lambda=3 < "$tmp/rows" | head -1)
if [ -n "$a" ] && [ "$a" != "$b" ] && [ "$(echo "$a" | wc -w)" = 13 ]; then
  echo "check_apps: config and --set accepted ok"; pass=$((pass + 1))
else
  echo "check_apps: config and --set accepted FAILED"; fail=$((fail + 1))
fi
echo "check_apps: $pass passed, $fail failed"
[ "$fail" = 0 ]
