/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/internal.h"
#include "selftalk/base.h"
#include "selftalk/io.h"

const char *st_status_str(stStatus status) {
  static const char *names[ST_STATUS_COUNT] = {
      "ok", "i/o error", "parse error", "value out of range", "invalid argument",
      "out of memory", "robot model error", "simulation unstable"};
  if ((int)status < 0 || status >= ST_STATUS_COUNT) return "unknown status";
  return names[status];
}

int st__errf(char *err, size_t errsz, const char *fmt, ...) {
  if (err && errsz) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errsz, fmt, ap);
    va_end(ap);
  }
  return 0;
}

int st__parse_double(const char *s, double *out) {
  char *end;
  while (isspace((unsigned char)*s)) s++;
  if (!*s) return -1;
  errno = 0;
  double v = strtod(s, &end);
  while (isspace((unsigned char)*end)) end++;
  if (*end || errno == ERANGE || !isfinite(v)) return -1;
  *out = v;
  return 0;
}

int st__parse_int(const char *s, int *out) {
  char *end;
  while (isspace((unsigned char)*s)) s++;
  if (!*s) return -1;
  errno = 0;
  long v = strtol(s, &end, 10);
  while (isspace((unsigned char)*end)) end++;
  if (*end || errno == ERANGE || v < INT_MIN || v > INT_MAX) return -1;
  *out = (int)v;
  return 0;
}

size_t st__strlcpy(char *dst, const char *src, size_t n) {
  size_t len = strlen(src);
  if (n) {
    size_t c = len < n - 1 ? len : n - 1;
    memcpy(dst, src, c);
    dst[c] = 0;
  }
  return len;
}

stStatus st_atomic_open(stAtomicFile *af, const char *path, char *err, size_t errsz) {
  memset(af, 0, sizeof *af);
  if (strlen(path) + 32 >= sizeof af->tmp) {
    st__errf(err, errsz, "%s: path too long", path);
    return ST_ERR_IO;
  }
  st__strlcpy(af->path, path, sizeof af->path);
  snprintf(af->tmp, sizeof af->tmp, "%s.tmp.%ld", path, (long)getpid());
  af->f = fopen(af->tmp, "w");
  if (!af->f) {
    st__errf(err, errsz, "%s: cannot write: %s", af->tmp, strerror(errno));
    return ST_ERR_IO;
  }
  return ST_OK;
}

stStatus st_atomic_commit(stAtomicFile *af, char *err, size_t errsz) {
  int bad = ferror(af->f) || fflush(af->f) != 0 || fsync(fileno(af->f)) != 0;
  int e = errno;
  if (fclose(af->f) != 0 && !bad) {
    bad = 1;
    e = errno;
  }
  af->f = NULL;
  if (!bad && rename(af->tmp, af->path) != 0) {
    bad = 1;
    e = errno;
  }
  if (bad) {
    remove(af->tmp);
    st__errf(err, errsz, "%s: cannot write: %s", af->path, strerror(e));
    return ST_ERR_IO;
  }
  return ST_OK;
}

void st_atomic_abort(stAtomicFile *af) {
  if (af->f) fclose(af->f);
  af->f = NULL;
  if (af->tmp[0]) remove(af->tmp);
}
