/* SPDX-License-Identifier: MIT
 * libselftalk: helpers shared by the library's modules; not installed. */
#ifndef SELFTALK_INTERNAL_H
#define SELFTALK_INTERNAL_H

#include <stddef.h>

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

#endif
