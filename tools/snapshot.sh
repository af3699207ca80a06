#!/bin/sh
# SPDX-License-Identifier: MIT
# snapshot.sh SRC DST: copy a replication's directory (tools/replicate.mk's OUT) while its jobs
# run, so that the copy resumes as the original would (make -f tools/replicate.mk snapshot);
# snapshot.sh --restore SNAPSHOT OUT: copy a snapshot back into an OUT that does not exist
# (make -f tools/replicate.mk restore).
#
# Every run's checkpoint is copied first: evolve renames each one into place whole, and resuming
# rewinds the files written after it (fitness.csv, best.genome) to it, so the copy is a consistent
# resume point whatever the runs write meanwhile. Post-evaluation journals are append-only (a
# resume drops a partial last line). Temporary files (*.tmp, *.tmp.PID) are left out; each file
# lands in DST by its own rename, never half written. Any file name is copied (find -exec: a
# space, a newline, a leading '-'). Refused, before anything is copied (issue 48): an empty
# name, SRC and DST the same or one inside the other, and a DST whose run is ahead of SRC's (a
# checkpoint of a later generation, a longer journal: OUT and SNAPSHOT swapped would put an
# older checkpoint over a live run's newer one). A restore copies into DST.restore.PID beside
# DST and renames it to DST at the end: a failed restore leaves no DST (and removes its copy),
# so it can simply be run again.
set -eu
usage="usage: snapshot.sh [--restore] SRC DST"
die() { echo "snapshot.sh: $*" >&2; exit 2; }

# internal: find -exec calls the script again on batches of files (any name), as
# snapshot.sh --copy|--check SRC DST FILE...
case ${1-} in
--copy)
  src=$2 dst=$3; shift 3
  for f; do
    rel=${f#"$src"/}
    case $rel in */*) mkdir -p -- "$dst/${rel%/*}" || exit 1 ;; esac
    cp -p -- "$f" "$dst/$rel.tmp" || exit 1
    mv -f -- "$dst/$rel.tmp" "$dst/$rel" || exit 1
  done
  exit 0 ;;
--check) # a DST file ahead of its SRC counterpart: print both and fail
  src=$2 dst=$3; shift 3
  gen() { sed -n '2s/^# generation \([0-9][0-9]*\)$/\1/p' "$1"; }
  for f; do
    d=$dst/${f#"$src"/}
    [ -f "$d" ] || continue
    case $f in
    */checkpoint)
      a=$(gen "$f") b=$(gen "$d")
      [ -n "$a" ] && [ -n "$b" ] || { echo "$d: not a checkpoint (line 2: # generation N expected)"; exit 1; }
      [ "$b" -le "$a" ] || { echo "$d is at generation $b, $f at $a"; exit 1; } ;;
    *) # a journal: its complete lines (a resume drops a partial last one)
      a=$(tr -cd '\n' < "$f" | wc -c) b=$(tr -cd '\n' < "$d" | wc -c)
      [ "$b" -le "$a" ] || { echo "$d holds $b lines, $f $a"; exit 1; } ;;
    esac
  done
  exit 0 ;;
esac

restore=0
[ "${1-}" = --restore ] && { restore=1; shift; }
[ $# = 2 ] || die "$usage"
[ -n "$1" ] && [ -n "$2" ] || die "an empty directory name ('$1', '$2'): $usage"
[ -d "$1" ] || die "$1: no such directory"
src=$(realpath -e -- "$1") dst=$(realpath -m -- "$2")
[ "$dst" != / ] || die "$2: the root directory (expected a directory of its own)"
case "$dst/" in "$src/"*) die "$2 is $1 or inside it: a copy into itself" ;; esac
case "$src/" in "$dst/"*) die "$1 is inside $2: a copy into itself" ;; esac
self=$(realpath -e -- "$0")

if [ $restore = 1 ]; then
  [ ! -e "$dst" ] || die "restore: $2 exists (restoring over it would overwrite newer files): expected a path that does not exist"
  parent=${dst%/*}
  mkdir -p -- "${parent:-/}"
  work=$dst.restore.$$
  mkdir -- "$work"
  trap 'rm -rf -- "$work"' EXIT
  to=$work
else
  # a run of DST ahead of SRC's: refuse before copying anything
  if [ -d "$dst" ] && ! why=$(find "$src" -type f \( -name checkpoint -o -name posteval.journal \) \
      -exec sh "$self" --check "$src" "$dst" {} +); then
    die "$why: copying $1 to $2 would put an older run over a newer one (OUT and SNAPSHOT swapped?); nothing copied"
  fi
  to=$dst
fi
mkdir -p -- "$to"
find "$src" -type f -name checkpoint -exec sh "$self" --copy "$src" "$to" {} +
find "$src" -type f ! -name checkpoint ! -name '*.tmp' ! -name '*.tmp.[0-9]*' \
  -exec sh "$self" --copy "$src" "$to" {} +
if [ $restore = 1 ]; then
  [ ! -e "$dst" ] || die "restore: $2 appeared while restoring; nothing restored"
  mv -T -- "$work" "$dst"
  trap - EXIT
fi
echo "snapshot.sh: $1 -> $2: $(find "$dst" -type f -name checkpoint -printf x | wc -c) checkpoints, $(find "$dst" -type f -printf x | wc -c) files"
