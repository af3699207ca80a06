/* SPDX-License-Identifier: MIT
 * libselftalk: status codes, version and the error-buffer convention shared by every module. */
#ifndef SELFTALK_BASE_H
#define SELFTALK_BASE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ST_API marks the public functions (as Box2D's B2_API): the library is compiled with
 * -fvisibility=hidden, so that its shared objects export these and nothing else (not its
 * internals, st__*, nor what it takes from ODE: tests/check_link.sh). */
#if defined(__GNUC__) || defined(__clang__)
#define ST_API __attribute__((visibility("default")))
#else
#define ST_API
#endif

#define ST_VERSION_MAJOR 0
#define ST_VERSION_MINOR 1
#define ST_VERSION_PATCH 0
#define ST_VERSION_STRING "0.1.0"

/* Result of every call that can fail on input or the environment. Programmer errors
 * (NULL where a pointer is required) are not reported here. */
typedef enum stStatus {
  ST_OK = 0,
  ST_ERR_IO,       /* a file could not be opened, read, written or renamed */
  ST_ERR_PARSE,    /* malformed text: config, genome, URDF, number */
  ST_ERR_RANGE,    /* a well-formed value outside its allowed range */
  ST_ERR_ARG,      /* inconsistent arguments (sizes, architecture, unknown key) */
  ST_ERR_NOMEM,    /* allocation failed */
  ST_ERR_MODEL,    /* a robot model is missing something the library needs */
  ST_ERR_UNSTABLE, /* the simulation diverged (NaN or runaway values) */
  ST_STATUS_COUNT
} stStatus;

/* Short English name of a status, e.g. "parse error". Never NULL. */
ST_API const char *st_status_str(stStatus status);

/* Error buffers: functions that can fail take (char *err, size_t errsz) and, on failure,
 * write one line without a trailing newline, usually "FILE:LINE: key 'x': problem
 * (expected ...)". Nullable: err (then no message is written). */

#ifdef __cplusplus
}
#endif

#endif
