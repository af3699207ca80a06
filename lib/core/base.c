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
#include <dirent.h>
#include <sys/stat.h>
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

void st__assert_fail(const char *func, const char *file, int line, const char *cond) {
  fprintf(stderr, "selftalk: assertion failed in %s (%s:%d): %s\n", func, file, line, cond);
  fflush(stderr);
  abort();
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

void st__err_key(char *err, size_t errsz, const char *key) {
  if (!err || !errsz) return;
  const size_t n = strlen(err) + 1;
  char *msg = malloc(n);
  if (!msg) return; /* the message without its key is still a message */
  memcpy(msg, err, n);
  snprintf(err, errsz, "key '%s': %s", key, msg);
  free(msg);
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

int st__text_line(const char **p, const char *end, const char **line, size_t *len, int *newline) {
  if (*p >= end) return 0;
  const char *nl = memchr(*p, '\n', (size_t)(end - *p));
  const char *e = nl ? nl : end;
  *line = *p;
  *len = (size_t)(e - *p);
  if (newline) *newline = nl != NULL;
  *p = nl ? nl + 1 : end;
  return 1;
}

int st__list_count(const char *list) {
  if (!*list) return 0;
  int n = 1;
  for (; *list; list++) n += *list == ',';
  return n;
}

void st__list_item(const char *list, int i, const char **item, size_t *len) {
  for (; i > 0; i--) list = strchr(list, ',') + 1; /* i < st__list_count: the commas are there */
  while (*list == ' ') list++;
  size_t n = strcspn(list, ",");
  while (n && list[n - 1] == ' ') n--;
  *item = list;
  *len = n;
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

/* ---- bounded input ---- */

/* "64 MiB" for whole mebibytes, else "N bytes" */
static void size_text(size_t n, char *buf, size_t bufsz) {
  if (n && n % ((size_t)1 << 20) == 0) snprintf(buf, bufsz, "%zu MiB", n >> 20);
  else snprintf(buf, bufsz, "%zu bytes", n);
}

/* first buffer size: the file's size when it has one (a regular file), plus the end check */
static size_t first_capacity(FILE *f, size_t max) {
  struct stat sb;
  size_t cap = 65536;
  if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size >= 0 &&
      (unsigned long long)sb.st_size < max)
    cap = (size_t)sb.st_size + 2;
  return cap < max + 2 ? cap : max + 2;
}

/* reads f into *buf until EOF or until it holds more than max bytes (too large); returns the
 * bytes read, or (size_t)-1 on a read error or when out of memory (*enomem) */
static size_t read_bounded(FILE *f, size_t max, char **buf, int *enomem) {
  size_t cap = first_capacity(f, max), n = 0; /* cap <= max + 2: max + 1 bytes and a NUL */
  if (!(*buf = malloc(cap))) return *enomem = 1, (size_t)-1;
  for (;;) {
    if (n + 1 == cap) { /* full (one byte kept for the NUL) */
      if (n > max) return n;
      size_t nc = cap <= (max + 2) / 2 ? 2 * cap : max + 2;
      char *b = realloc(*buf, nc);
      if (!b) return *enomem = 1, (size_t)-1;
      *buf = b;
      cap = nc;
    }
    size_t got = fread(*buf + n, 1, cap - 1 - n, f);
    n += got;
    if (got == 0) return ferror(f) ? (size_t)-1 : n;
  }
}

stStatus st_file_read(const char *path, size_t max, char **data, size_t *len, char *err,
                      size_t errsz) {
  ST_ASSERT(path && data && len);
  *data = NULL;
  *len = 0;
  FILE *f = fopen(path, "rb");
  if (!f) {
    st__errf(err, errsz, "%s: cannot open: %s", path, strerror(errno));
    return ST_ERR_IO;
  }
  char *buf = NULL;
  int enomem = 0;
  errno = 0;
  size_t n = read_bounded(f, max, &buf, &enomem);
  int e = errno;
  fclose(f);
  stStatus st = ST_OK;
  char lim[32];
  size_text(max, lim, sizeof lim);
  if (enomem) {
    st__errf(err, errsz, "%s: out of memory", path);
    st = ST_ERR_NOMEM;
  } else if (n == (size_t)-1) {
    st__errf(err, errsz, "%s: cannot read: %s", path, strerror(e ? e : EIO));
    st = ST_ERR_IO;
  } else if (n > max) {
    st__errf(err, errsz, "%s: larger than %s (expected an input file of at most %zu bytes)", path,
             lim, max);
    st = ST_ERR_RANGE;
  }
  if (st) {
    free(buf);
    return st;
  }
  buf[n] = 0;
  *data = buf;
  *len = n;
  return ST_OK;
}

stStatus st_text_check(const char *name, const char *text, size_t len, char *err, size_t errsz) {
  ST_ASSERT(name && (text || len == 0));
  const char *nul = memchr(text, 0, len);
  if (!nul) return ST_OK;
  size_t line = 1, col = 1;
  for (const char *p = text; p < nul; p++) {
    col++;
    if (*p == '\n') line++, col = 1;
  }
  st__errf(err, errsz, "%s:%zu: NUL byte at column %zu (expected a text file)", name, line, col);
  return ST_ERR_PARSE;
}

stStatus st_text_read(const char *path, size_t max, char **text, size_t *len, char *err,
                      size_t errsz) {
  ST_ASSERT(path && text && len);
  stStatus st = st_file_read(path, max, text, len, err, errsz);
  if (!st && (st = st_text_check(path, *text, *len, err, errsz))) {
    free(*text);
    *text = NULL;
    *len = 0;
  }
  return st;
}

stStatus st__text_parse(const char *name, const char *text, size_t len, stTextParse parse,
                        void *ctx, char *err, size_t errsz) {
  stStatus st = st_text_check(name, text, len, err, errsz);
  if (st) return st;
  char *copy = malloc(len + 1);
  if (!copy) return st__errf(err, errsz, "%s: out of memory", name), ST_ERR_NOMEM;
  if (len) memcpy(copy, text, len);
  copy[len] = 0;
  st = parse(name, copy, len, ctx, err, errsz);
  free(copy);
  return st;
}

stStatus st__text_read_parse(const char *path, stTextParse parse, void *ctx, char *err,
                             size_t errsz) {
  char *text;
  size_t len;
  stStatus st = st_text_read(path, ST_FILE_MAX, &text, &len, err, errsz);
  if (st) return st;
  st = parse(path, text, len, ctx, err, errsz);
  free(text);
  return st;
}

stStatus st_atomic_open(stAtomicFile *af, const char *path, char *err, size_t errsz) {
  ST_ASSERT(af && path);
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

int st_atomic_clean(const char *path) {
  ST_ASSERT(path);
  char dir[ST_PATH_MAX];
  st__strlcpy(dir, path, sizeof dir);
  char *slash = strrchr(dir, '/');
  const char *base = slash ? slash + 1 : path;
  if (slash) *slash = '\0';
  if (slash == dir) st__strlcpy(dir, "/", sizeof dir);
  const char *where = slash ? dir : ".";
  DIR *d = opendir(where);
  if (!d) return -1;
  char own[32];
  snprintf(own, sizeof own, "%ld", (long)getpid());
  const size_t nb = strlen(base);
  int removed = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    const char *n = e->d_name;
    if (strncmp(n, base, nb) != 0 || strncmp(n + nb, ".tmp.", 5) != 0) continue;
    const char *pid = n + nb + 5;
    if (!*pid || strspn(pid, "0123456789") != strlen(pid) || strcmp(pid, own) == 0) continue;
    char full[2 * ST_PATH_MAX];
    snprintf(full, sizeof full, "%s/%s", where, n);
    if (remove(full) == 0) removed++;
  }
  closedir(d);
  return removed;
}

/* the step of a commit that failed, for the message */
enum { COMMIT_OK, COMMIT_WRITE, COMMIT_SYNC, COMMIT_RENAME };

static int commit_steps(stAtomicFile *af, int *e) {
  int step = COMMIT_OK;
  errno = 0;
  if (ferror(af->f) || fflush(af->f) != 0) step = COMMIT_WRITE;
  else if (fsync(fileno(af->f)) != 0) step = COMMIT_SYNC;
  *e = errno;
  if (fclose(af->f) != 0 && !step) step = COMMIT_WRITE, *e = errno;
  af->f = NULL;
  if (!step && rename(af->tmp, af->path) != 0) step = COMMIT_RENAME, *e = errno;
  if (step && !*e) *e = EIO; /* ferror without errno */
  return step;
}

stStatus st_atomic_commit(stAtomicFile *af, char *err, size_t errsz) {
  ST_ASSERT(af);
  int e = 0;
  const int step = commit_steps(af, &e);
  if (!step) return ST_OK;
  remove(af->tmp);
  if (step == COMMIT_RENAME)
    st__errf(err, errsz, "%s: cannot write: renaming %s over it: %s", af->path, af->tmp, strerror(e));
  else
    st__errf(err, errsz, "%s: cannot write: %s %s: %s", af->path,
             step == COMMIT_SYNC ? "syncing" : "writing", af->tmp, strerror(e));
  return ST_ERR_IO;
}

void st_atomic_abort(stAtomicFile *af) {
  ST_ASSERT(af);
  if (af->f) fclose(af->f);
  af->f = NULL;
  if (af->tmp[0]) remove(af->tmp);
}
