/* SPDX-License-Identifier: MIT
 * libselftalk: helpers shared by the library's modules; not installed. */
#ifndef SELFTALK_INTERNAL_H
#define SELFTALK_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "selftalk/base.h"

#if defined(__GNUC__)
#define ST_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define ST_PRINTF(a, b)
#endif

#if defined(__GNUC__)
#define ST_NORETURN __attribute__((noreturn))
#else
#define ST_NORETURN
#endif

/* ST_ASSERT(cond): a broken precondition of a public function (a programmer error, which
 * stStatus does not report: see selftalk/base.h) aborts with the function, file:line and the
 * condition, as Box2D's B2_ASSERT does. On where ST_ASSERTS is defined (`make asan`, or
 * ASSERTS=1, as in the debug build `make OPT="-O0 -g" ASSERTS=1`); in release builds the
 * condition is only type-checked, never
 * evaluated, so it must have no side effect and costs nothing. */
#if defined(ST_ASSERTS)
#define ST_ASSERT(cond) \
  ((cond) ? (void)0 : st__assert_fail(__func__, __FILE__, __LINE__, #cond))
#else
#define ST_ASSERT(cond) ((void)sizeof(!(cond)))
#endif

/* Prints "selftalk: assertion failed in FUNC (FILE:LINE): COND" to stderr and aborts. */
void st__assert_fail(const char *func, const char *file, int line, const char *cond) ST_NORETURN;

#define ST_PI 3.14159265358979323846
#define ST_DEG (ST_PI / 180.0)

/* |v| of a 3-vector */
static inline double st__norm3(const double *v) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* c = a x b (3-vectors; c must not alias a or b) */
static inline void st__cross3(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Writes a formatted message into a caller's error buffer (nullable); returns 0. */
int st__errf(char *err, size_t errsz, const char *fmt, ...) ST_PRINTF(3, 4);

/* Puts "key 'KEY': " before the message already in err (nullable): an error that comes from a
 * config value names its key, e.g. "key 'stage.init_population': 1e: cannot open: ...". */
void st__err_key(char *err, size_t errsz, const char *key);

/* Parses a whole string as a finite double / an int; 0 on success, -1 otherwise. */
int st__parse_double(const char *s, double *out);
int st__parse_int(const char *s, int *out);

/* Copies at most n-1 bytes and always terminates; returns strlen(src) as strlcpy does. */
size_t st__strlcpy(char *dst, const char *src, size_t n);

/* The next line of the text [*p, end), for the readers of a file read whole: *line its start,
 * *len its length without the newline, *newline (nullable) 1 when a newline ends it. Moves *p
 * past it. Returns 0 at the end of the text, 1 otherwise. */
int st__text_line(const char **p, const char *end, const char **line, size_t *len, int *newline);

/* Comma-separated list values of config keys (robot.dof_joints, stage.primitives,
 * integrated.populations, dynamics.kinematic_joints, ...), read alike everywhere: the number of
 * items (0 for "", else commas + 1: "a," has two, the second empty) and item i (0 <= i < count)
 * without the spaces around it, *len 0 for an empty item. lib/core/config.c refuses empty items
 * in every list key; the readers of the lists go through these two. */
int st__list_count(const char *list);
void st__list_item(const char *list, int i, const char **item, size_t *len);

/* A text file's reader: st_text_read (at most ST_FILE_MAX bytes, no NUL byte), then
 * parse(path, text, len, ctx, ...) on the text, which it may change in place; the text is freed
 * after. Returns the first failure. */
typedef stStatus (*stTextParse)(const char *name, char *text, size_t len, void *ctx, char *err,
                                size_t errsz);
stStatus st__text_read_parse(const char *path, stTextParse parse, void *ctx, char *err,
                             size_t errsz);

/* The same for a text in memory (the readers' in-memory entry points, lib/core/readers.h):
 * st_text_check, then parse on a NUL-terminated copy. */
stStatus st__text_parse(const char *name, const char *text, size_t len, stTextParse parse,
                        void *ctx, char *err, size_t errsz);

/* A text read whole (NUL-terminated at len), line by line in place: the line-oriented readers
 * of the results files (lib/core/csv.c) and of number files (lib/core/stats.c). lineno counts
 * every line read. */
typedef struct stLines {
  char *text;
  size_t len, pos;
  int lineno;
} stLines;

/* The next line without its newline and surrounding white space (NUL-terminated in the text);
 * NULL at the end of the text. */
char *st__lines_next(stLines *t);

/* The next line that is neither blank nor a '#' comment, as st__lines_next; NULL at the end. */
char *st__lines_content(stLines *t);

#endif
