/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "app_common.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "selftalk/io.h"
#include "selftalk/trialkind.h"

void app_die(const char *prog, const char *fmt, ...) {
  va_list ap;
  fprintf(stderr, "%s: ", prog);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  exit(2);
}

int app_int_arg(const char *prog, const char *opt, const char *v, int lo) {
  char *end;
  const long x = strtol(v, &end, 10);
  if (*end || end == v || x < lo || x > 2147483647L)
    app_die(prog, "%s '%s': expected an integer >= %d", opt, v, lo);
  return (int)x;
}

int app_config_arg(appConfigArgs *a, int argc, char **argv, int *i, const char *prog) {
  const char *arg = argv[*i];
  if (!strcmp(arg, "--help-config")) {
    st_config_help(stdout);
    exit(0);
  }
  if (!strcmp(arg, "--config") || !strcmp(arg, "--set")) {
    if (*i + 1 >= argc) app_die(prog, "%s needs a value", arg);
    const char *v = argv[++*i];
    if (arg[2] == 'c') {
      a->config_path = v;
    } else {
      if (a->nsets >= (int)(sizeof a->sets / sizeof a->sets[0])) app_die(prog, "too many --set");
      a->sets[a->nsets++] = v;
    }
    return 1;
  }
  if (!strncmp(arg, "--set=", 6) || !strncmp(arg, "--config=", 9)) {
    if (arg[2] == 'c') {
      a->config_path = arg + 9;
    } else {
      if (a->nsets >= (int)(sizeof a->sets / sizeof a->sets[0])) app_die(prog, "too many --set");
      a->sets[a->nsets++] = arg + 6;
    }
    return 1;
  }
  return 0;
}

/* the file's keys and rules, the trial kinds' naming its line; then the --set options', once
 * all are in */
void app_config_resolve(const appConfigArgs *a, stConfig *cfg, const char *prog) {
  char err[1024];
  st_config_default(cfg);
  if (a->config_path && (st_config_load(a->config_path, cfg, err, sizeof err) ||
                         st_trial_kinds_check(cfg, a->config_path, err, sizeof err)))
    app_die(prog, "%s", err);
  if (st_config_set_all(cfg, (const char *const *)a->sets, a->nsets, err, sizeof err))
    app_die(prog, "%s", err);
  if (a->nsets && st_trial_kinds_check(cfg, NULL, err, sizeof err))
    app_die(prog, "after the --set options: %s", err);
}

char *app_read_text(const char *prog, const char *path, size_t *len) {
  char *text, err[1024];
  size_t n;
  if (st_text_read(path, ST_FILE_MAX, &text, &n, err, sizeof err)) app_die(prog, "%s", err);
  if (len) *len = n;
  return text;
}

double app_seconds(appClock which) {
  static const clockid_t ids[] = {CLOCK_MONOTONIC, CLOCK_PROCESS_CPUTIME_ID, CLOCK_THREAD_CPUTIME_ID};
  struct timespec ts;
  clock_gettime(ids[which], &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
