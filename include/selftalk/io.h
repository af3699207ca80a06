/* SPDX-License-Identifier: MIT
 * libselftalk: atomic file writing. Results and checkpoints are written to a temporary file
 * beside the target and renamed over it, so a killed run leaves either the old file or the
 * complete new one. */
#ifndef SELFTALK_IO_H
#define SELFTALK_IO_H

#include <stdio.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PATH_MAX 4096

/* A file being written atomically; a plain value owned by the caller. */
typedef struct stAtomicFile {
  FILE *f; /* write through this between open and commit */
  char path[ST_PATH_MAX];
  char tmp[ST_PATH_MAX];
} stAtomicFile;

/* Opens "<path>.tmp.<pid>" for writing. */
stStatus st_atomic_open(stAtomicFile *af, const char *path, char *err, size_t errsz);

/* Flushes, syncs, closes and renames the temporary file over path. On failure the temporary
 * file is removed and path is untouched. */
stStatus st_atomic_commit(stAtomicFile *af, char *err, size_t errsz);

/* Closes and removes the temporary file; path is untouched. */
void st_atomic_abort(stAtomicFile *af);

#ifdef __cplusplus
}
#endif

#endif
