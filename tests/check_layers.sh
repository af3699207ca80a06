#!/usr/bin/env bash
# The layers of lib/ (the Makefile's LAYERS, lowest first: core model world task episode run
# posteval): no file of lib/ (nor of a layer's subfolders, lib/episode/trials/) and no public
# header includes a header of a higher layer. A header's layer is the folder of the lib/
# source that implements it (selftalk/trial.h:
# lib/episode/trial.c; selftalk/io.h: core; lib/LAYER/x.h: LAYER); selftalk/selftalk.h, which
# includes them all, is above every layer. Then the check itself is tried on a copy with one
# upward include added: it must find it.
set -uo pipefail
CHECK=check_layers
source "$(dirname "$0")/check_lib.sh"

read -r -a LAYERS <<<"$(sed -n 's/^LAYERS := //p' Makefile)"
rank_of_layer() { # LAYER: its index in LAYERS, or nothing
  local i
  for i in "${!LAYERS[@]}"; do [ "${LAYERS[$i]}" = "$1" ] && { echo "$i"; return; }; done
}

# the layer rank of an include's target, in the tree ROOT ("" when it is no header of ours)
rank_of_include() { # ROOT INCLUDE
  local root=$1 inc=$2 name src
  case "$inc" in
    selftalk/selftalk.h) echo "${#LAYERS[@]}" ;;
    selftalk/io.h) rank_of_layer core ;;
    selftalk/*.h)
      name=${inc#selftalk/}
      name=${name%.h}
      src=$(cd "$root" && ls lib/*/"$name".c lib/*/"$name".cpp 2>/dev/null | head -1)
      if [ -n "$src" ]; then src=${src#lib/}; rank_of_layer "${src%%/*}"; fi ;;
    */*.h) rank_of_layer "${inc%%/*}" ;;
  esac
}

# prints "FILE:LINE: includes INC (LAYER above LAYER)" for every upward include under ROOT
upward() { # ROOT
  local root=$1 f own line inc r
  while IFS= read -r f; do
    case "$f" in
      lib/*) own=${f#lib/}; own=$(rank_of_layer "${own%%/*}") ;;
      include/selftalk/selftalk.h) continue ;;
      *) own=$(rank_of_include "$root" "selftalk/$(basename "$f")") ;;
    esac
    [ -n "$own" ] || { echo "$f: no layer (a header of include/selftalk/ without a lib/ source)"; continue; }
    while IFS=: read -r line inc; do
      inc=${inc#*\"}
      inc=${inc%%\"*}
      r=$(rank_of_include "$root" "$inc")
      if [ -n "$r" ] && [ "$r" -gt "$own" ]; then
        echo "$f:$line: includes $inc (layer ${LAYERS[$r]:-selftalk.h} above ${LAYERS[$own]})"
      fi
    done < <(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$root/$f")
  done < <(cd "$root" && ls lib/*/*.c lib/*/*.cpp lib/*/*.h lib/*/*/*.c lib/*/*/*.h include/selftalk/*.h 2>/dev/null)
}

nfiles=$(ls lib/*/*.c lib/*/*.cpp lib/*/*.h lib/*/*/*.c lib/*/*/*.h include/selftalk/*.h 2>/dev/null | wc -l)
if [ "${#LAYERS[@]}" -lt 2 ]; then
  ko "the layers" "no LAYERS line in the Makefile"
elif out=$(upward .) && [ -z "$out" ]; then
  ok "no upward include in $nfiles files of lib/ and include/selftalk/ (${LAYERS[*]})"
else
  ko "upward includes" "$(printf '\n%s' "$out")"
fi

# the check sees an upward include: the tree copied, one core file including an episode header
mkdir -p "$tmp/tree"
cp -r lib include Makefile "$tmp/tree/"
printf '#include "selftalk/trial.h"\n' >> "$tmp/tree/lib/core/rng.c"
out=$(upward "$tmp/tree")
if grep -q '^lib/core/rng.c:[0-9]*: includes selftalk/trial.h (layer episode above core)$' <<<"$out"; then
  ok "an upward include added to a copy is found"
else
  ko "an upward include added to a copy is found" "got: $out"
fi

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
