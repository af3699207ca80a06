/* SPDX-License-Identifier: MIT
 * Fault injection for tests/check_faults.sh, loaded with LD_PRELOAD into an app: the N-th call
 * (and every later one) of a libc function the run's writers use fails with the error a real
 * fault gives. Environment (each optional; N counts from 1):
 *   ST_FAULT_FSYNC_AT=N    fsync fails with ENOSPC (a full disk noticed at sync time)
 *   ST_FAULT_RENAME_AT=N   rename fails with EIO (the atomic replace fails)
 *   ST_FAULT_FOPEN_AT=N    fopen for writing ("w", "a") fails with EROFS (a read-only
 *                          directory; for root, who ignores permissions, without a mount)
 *   ST_FAULT_SLOW_RENAME_MS=M  every rename sleeps M ms once done (a slow disk): a run takes
 *                          at least that long per file it writes, on any machine, so a test
 *                          that acts on a running run (remount, kill, stop) has a window that
 *                          does not shrink on a fast machine; while it sleeps no file is open
 *                          and no temporary file waits
 *   ST_FAULT_HOLD=FILE     after each rename onto a file named "checkpoint", wait while FILE
 *                          exists (at most an hour): a test holds a run right after a
 *                          checkpoint, acts on it (kill, stop), then removes FILE; an event,
 *                          not a deadline, so a busy machine cannot make it race
 * Not part of the library; built by the Makefile next to the test binary. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* 1 when this call is the N-th or a later one of the counter's */
static int trips(const char *var, long *count) {
  const char *v = getenv(var);
  if (!v || !*v) return 0;
  return ++*count >= atol(v);
}

int fsync(int fd) {
  static long n;
  static int (*real)(int);
  if (trips("ST_FAULT_FSYNC_AT", &n)) return errno = ENOSPC, -1;
  if (!real) *(void **)&real = dlsym(RTLD_NEXT, "fsync");
  return real(fd);
}

int rename(const char *from, const char *to) {
  static long n;
  static int (*real)(const char *, const char *);
  if (trips("ST_FAULT_RENAME_AT", &n)) return errno = EIO, -1;
  if (!real) *(void **)&real = dlsym(RTLD_NEXT, "rename");
  int rc = real(from, to), e = errno;
  const char *slow = getenv("ST_FAULT_SLOW_RENAME_MS");
  const long ms = slow ? atol(slow) : 0;
  if (ms > 0) { /* after the rename: the file is whole, no temporary is left */
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
  }
  const char *hold = getenv("ST_FAULT_HOLD"), *base = strrchr(to, '/');
  if (rc == 0 && hold && *hold && !strcmp(base ? base + 1 : to, "checkpoint"))
    for (long i = 0; i < 360000 && access(hold, F_OK) == 0; i++) {
      struct timespec ts = {0, 10000000L}; /* 10 ms */
      nanosleep(&ts, NULL);
    }
  errno = e;
  return rc;
}

FILE *fopen(const char *path, const char *mode) {
  static long n;
  static FILE *(*real)(const char *, const char *);
  if ((strchr(mode, 'w') || strchr(mode, 'a')) && trips("ST_FAULT_FOPEN_AT", &n))
    return errno = EROFS, NULL;
  if (!real) *(void **)&real = dlsym(RTLD_NEXT, "fopen");
  return real(path, mode);
}
