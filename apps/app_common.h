/* SPDX-License-Identifier: MIT
 * Argument handling shared by the apps: --config FILE, --set section.key=value (repeatable,
 * applied after the file), --help-config. Errors go to stderr as "PROG: message" and exit 2. */
#ifndef SELFTALK_APP_COMMON_H
#define SELFTALK_APP_COMMON_H

#include "selftalk/config.h"

#if defined(__GNUC__)
__attribute__((noreturn, format(printf, 2, 3)))
#endif
void app_die(const char *prog, const char *fmt, ...);

/* Collects config options while an app scans argv. */
typedef struct appConfigArgs {
  const char *config_path; /* nullable */
  const char *sets[256];
  int nsets;
} appConfigArgs;

/* The integer value of option opt (>= lo); dies naming the option and the value otherwise. */
int app_int_arg(const char *prog, const char *opt, const char *v, int lo);

/* If argv[*i] is a config option, consumes it (and its value) and returns 1. Handles
 * --help-config by printing the key reference and exiting 0. */
int app_config_arg(appConfigArgs *a, int argc, char **argv, int *i, const char *prog);

/* Defaults, then the config file (if any), then the overrides; dies on any error. */
void app_config_resolve(const appConfigArgs *a, stConfig *cfg, const char *prog);

/* The whole text file at path through the library's bounded reader (selftalk/io.h:
 * st_text_read, at most ST_FILE_MAX bytes, NUL bytes refused); dies naming
 * the file (and the line of a NUL byte). The text is NUL-terminated after its *len bytes (len
 * nullable); free() it. */
char *app_read_text(const char *prog, const char *path, size_t *len);

/* Seconds on one of three clocks: wall (monotonic), the process's CPU, the calling thread's CPU. */
typedef enum appClock { APP_WALL, APP_PROCESS_CPU, APP_THREAD_CPU } appClock;
double app_seconds(appClock which);

#endif
