#!/usr/bin/env bash
# Installs into a temporary prefix and builds docs/example_net.c against the installed copy
# with pkg-config, once with the whole library and once with the simulator-free core.
set -euo pipefail
BUILD=${BUILD:-build}
CHECK=check_install
source "$(dirname "$0")/check_lib.sh"

make --no-print-directory -s install PREFIX="$tmp/prefix" BUILD="$BUILD" >/dev/null
export PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig"
for pc in selftalk selftalk-core; do
  if cc -std=c99 -Wall -Wextra docs/example_net.c $(pkg-config --cflags --libs "$pc") -o "$tmp/ex_$pc" \
     && LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/ex_$pc" 3 > "$tmp/out_$pc" \
     && [ "$(grep -c '^generation' "$tmp/out_$pc")" = 3 ]; then
    ok "pkg-config $pc: example builds against the installed copy and runs"
  else
    ko "pkg-config $pc"
  fi
done
# the core must not pull the simulator in: the example built against selftalk-core above must
# exist, load the installed libselftalk-core, and load nothing of ODE or the full library
core_ex="$tmp/ex_selftalk-core"
if [ ! -x "$core_ex" ]; then
  ko "selftalk-core links without ODE (the example against selftalk-core was not built)"
elif ! libs=$(LD_LIBRARY_PATH="$tmp/prefix/lib" ldd "$core_ex" 2>&1); then
  ko "selftalk-core links without ODE (ldd failed: $libs)"
elif ! grep -q "libselftalk-core\.so\.0 => $tmp/prefix/lib/" <<<"$libs"; then
  ko "selftalk-core links without ODE (the example does not load the installed core: $libs)"
elif grep -qE 'libode|libselftalk\.so' <<<"$libs"; then
  ko "selftalk-core links without ODE (it loads: $(grep -E 'libode|libselftalk\.so' <<<"$libs" | tr -s ' \t\n' ' '))"
else
  ok "selftalk-core links without ODE"
fi
# a static link of the core works too
if cc -std=c99 docs/example_net.c -I"$tmp/prefix/include" "$tmp/prefix/lib/libselftalk-core.a" \
     $(pkg-config --libs inih) -lm -o "$tmp/ex_static" && "$tmp/ex_static" 2 | grep -q '^generation   1'; then
  ok "static core link"
else
  ko "static core link"
fi
# the statistics are in the core: Hollander & Wolfe's example (tests/test_stats.c) against the
# installed selftalk-core alone, p = 2 * 382 / 3003
cat > "$tmp/mwu.c" <<'C'
#include <stdio.h>
#include <selftalk/stats.h>
int main(void) {
  const double x[] = {0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
  const double y[] = {1.15, 0.88, 0.90, 0.74, 1.21};
  stMwuResult r;
  if (st_mwu(NULL, x, 10, y, 5, &r, NULL, 0)) return 1;
  printf("U=%g p=%.6f\n", r.u, r.p);
  return 0;
}
C
if cc -std=c99 -Wall -Wextra "$tmp/mwu.c" $(pkg-config --cflags --libs selftalk-core) -o "$tmp/mwu" &&
   [ "$(LD_LIBRARY_PATH="$tmp/prefix/lib" "$tmp/mwu")" = "U=15 p=0.254412" ] &&
   ! LD_LIBRARY_PATH="$tmp/prefix/lib" ldd "$tmp/mwu" | grep -qE 'libode|libselftalk\.so'; then
  ok "selftalk-core: st_mwu without the simulator"
else
  ko "selftalk-core: st_mwu without the simulator"
fi
echo "check_install: $pass passed, $fail failed"
[ "$fail" = 0 ]
