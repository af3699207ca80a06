/* SPDX-License-Identifier: MIT
 * libselftalk: file input and output. Every input file (config, genome, checkpoint, URDF, mesh,
 * score table) is read by one bounded reader; results and checkpoints are written to a
 * temporary file beside the target and renamed over it, so a killed run leaves either the old
 * file or the complete new one. */
#ifndef SELFTALK_IO_H
#define SELFTALK_IO_H

#include <stdio.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_PATH_MAX 4096

/* The largest input file a reader takes: 64 MiB, 17 times the best.genome of a 1500-generation
 * run (the thesis' cap) and 250 times a 100-genotype checkpoint. A larger file, or a device
 * that never ends (/dev/zero), is refused instead of filling the memory. */
#define ST_FILE_MAX ((size_t)64 << 20)

/* Reads the whole file at path, at most max bytes, into a new buffer (*data, freed with
 * free()) with a terminating NUL after its *len bytes. Errors: "PATH: cannot open: REASON",
 * "PATH: cannot read: REASON" (a directory, an I/O error), "PATH: larger than 64 MiB (expected
 * an input file of at most 67108864 bytes)". On failure *data is NULL and *len 0. */
ST_API stStatus st_file_read(const char *path, size_t max, char **data, size_t *len, char *err,
                      size_t errsz);

/* Refuses a NUL byte in text that should be text (a genome line followed by NUL and junk
 * would otherwise read as the line alone): "NAME:LINE: NUL byte at column C (expected a text
 * file)". */
ST_API stStatus st_text_check(const char *name, const char *text, size_t len, char *err, size_t errsz);

/* A whole text file: st_file_read, then st_text_check on what it read, with their errors. On
 * failure *text is NULL and *len 0. */
ST_API stStatus st_text_read(const char *path, size_t max, char **text, size_t *len, char *err,
                      size_t errsz);

/* A file being written atomically; a plain value owned by the caller. */
typedef struct stAtomicFile {
  FILE *f; /* write through this between open and commit */
  char path[ST_PATH_MAX];
  char tmp[ST_PATH_MAX];
} stAtomicFile;

/* Opens "<path>.tmp.<pid>" for writing. */
ST_API stStatus st_atomic_open(stAtomicFile *af, const char *path, char *err, size_t errsz);

/* Flushes, syncs, closes and renames the temporary file over path. On failure the temporary
 * file is removed and path is untouched. */
ST_API stStatus st_atomic_commit(stAtomicFile *af, char *err, size_t errsz);

/* Closes and removes the temporary file; path is untouched. */
ST_API void st_atomic_abort(stAtomicFile *af);

/* Removes "<path>.tmp.<digits>" files that a writer killed between open and commit left
 * beside path (a kill -9 cannot be cleaned up after), except this process's own. For a run
 * starting or resuming in its directory: one writer per directory. Returns how many were
 * removed, or -1 (errno set) when the directory cannot be read. */
ST_API int st_atomic_clean(const char *path);

#ifdef __cplusplus
}
#endif

#endif
