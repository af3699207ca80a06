#!/bin/sh
# SPDX-License-Identifier: MIT
# snapshot.sh SRC DST: copy a replication's directory (tools/replicate.mk's OUT) while its jobs
# run, so that the copy resumes as the original would (make -f tools/replicate.mk snapshot /
# restore). Every run's checkpoint is copied first: evolve renames each one into place whole, and
# resuming rewinds the files written after it (fitness.csv, best.genome) to it, so the copy is a
# consistent resume point whatever the runs write meanwhile. Post-evaluation journals are
# append-only (a resume drops a partial last line). Temporary files (*.tmp) are left out; each
# file lands in DST by its own rename, never half written.
set -eu
[ $# = 2 ] || { echo "usage: snapshot.sh SRC DST" >&2; exit 2; }
src=${1%/} dst=${2%/}
[ -d "$src" ] || { echo "snapshot.sh: $src: no such directory" >&2; exit 2; }
copy() { # FILE under src -> the same path under dst
  rel=${1#"$src"/}
  mkdir -p "$dst/$(dirname "$rel")"
  cp -p "$1" "$dst/$rel.tmp" && mv "$dst/$rel.tmp" "$dst/$rel"
}
find "$src" -type f -name checkpoint | while IFS= read -r f; do copy "$f"; done
find "$src" -type f ! -name checkpoint ! -name '*.tmp' | while IFS= read -r f; do copy "$f"; done
echo "snapshot.sh: $src -> $dst: $(find "$dst" -type f -name checkpoint | wc -l) checkpoints, $(find "$dst" -type f | wc -l) files"
