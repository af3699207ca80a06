#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# One command for a video of any individual's trial: ./apps/replay writes the trial's trace and
# every step's shapes into a temporary directory, then tools/trial_video.py draws them.
#
#   tools/trial_video.sh GENOME CONFIG [replay options...] -o OUT.gif|OUT.mp4 [video options...]
#
# Replay options: all of ./apps/replay's but --out, --shapes, --at, --shapes-every and --html,
# which this script sets (e.g. --trial K, --stage main, --generation G, --index I, --posteval
# TEST [--caretaker], --set section.key=value, --force OUT=VALUE[@STEP]).
# Video options (tools/trial_video.py's): --stride N, --fps F, --size WxH, --dpi D, --view
# ELEV,AZIM, --colors N, --hold S, --list, --title TEXT (default: the genome file and the genotype
# replay took).
# --keep DIR also keeps the replay's files there (trace.csv, shapes.csv, replay.txt).
# Run from the directory replay would run in (a config's relative paths are read from there).
# APPDIR (apps) and PYTHON (/usr/bin/python3, Debian's, with matplotlib and Pillow) as the tests.
set -euo pipefail
prog=trial_video.sh
die() { echo "$prog: $*" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
APPDIR=${APPDIR:-apps}
PY=${PYTHON:-/usr/bin/python3}
[ $# -ge 2 ] || die "usage: $prog GENOME CONFIG [replay options...] -o OUT.gif|OUT.mp4 [--stride N] [--fps F] [--size WxH] [--dpi D] [--view ELEV,AZIM] [--colors N] [--hold S] [--list] [--title TEXT] [--keep DIR]"
genome=$1 config=$2
shift 2
replay=() video=() out="" title="" keep=""
while [ $# -gt 0 ]; do
  case $1 in
    -o|--video) [ $# -ge 2 ] || die "$1 needs a file name"; out=$2; shift 2 ;;
    --stride|--fps|--size|--dpi|--view|--colors|--hold)
      [ $# -ge 2 ] || die "$1 needs a value"; video+=("$1" "$2"); shift 2 ;;
    --list) video+=("$1"); shift ;;
    --title) [ $# -ge 2 ] || die "$1 needs a value"; title=$2; shift 2 ;;
    --keep) [ $# -ge 2 ] || die "$1 needs a directory"; keep=$2; shift 2 ;;
    --out|--shapes|--at|--shapes-every|--html|--three)
      die "$1: this script writes the replay's files itself (give -o OUT.gif for the video, --keep DIR for the trace and shapes)" ;;
    --exact|--caretaker) replay+=("$1"); shift ;;
    *) [ $# -ge 2 ] || die "replay option $1 needs a value"; replay+=("$1" "$2"); shift 2 ;;
  esac
done
[ -n "$out" ] || die "no -o OUT.gif or OUT.mp4"
[ -x "$APPDIR/replay" ] || die "$APPDIR/replay not found (build it: make; or set APPDIR)"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! "$APPDIR/replay" "$genome" "$config" "${replay[@]}" --out "$tmp/trace.csv" \
     --shapes "$tmp/shapes.csv" --shapes-every 1 > "$tmp/replay.txt" 2> "$tmp/replay.err"; then
  cat "$tmp/replay.err" >&2
  die "./apps/replay failed: no video"
fi
# the title: the genome file (its directory and name) and the genotype replay took ("replay:
# genotype I of FILE, trial offsets of generation G")
if [ -z "$title" ]; then
  title="$(basename "$(dirname "$genome")")/$(basename "$genome")"
  which=$(sed -n 's/^replay: genotype \([^ ]*\) of .*, trial offsets of generation \([^ ]*\)$/genotype \1, generation \2/p' "$tmp/replay.err" | head -1)
  title+=${which:+: $which}
fi
# seconds per step: robot.control_dt, from --set or the config (evolve's config.ini has it),
# else trial_video.py's default (0.05, the keys' default)
dt=$(sed -n 's/^control_dt *= *//p' "$config" | tail -1)
for ((i = 0; i < ${#replay[@]}; i++)); do
  case ${replay[i]} in robot.control_dt=*) dt=${replay[i]#robot.control_dt=} ;; esac
done
if [ -n "$keep" ]; then
  mkdir -p "$keep" && cp "$tmp/trace.csv" "$tmp/shapes.csv" "$tmp/replay.txt" "$keep/"
fi
"$PY" "$here/trial_video.py" "$tmp/shapes.csv" "$tmp/trace.csv" --summary "$tmp/replay.txt" \
  --title "$title" ${dt:+--dt "$dt"} "${video[@]}" -o "$out"
