/* SPDX-License-Identifier: MIT
 * For the fuzz target of an app's reader (fuzz_score.c), which includes the app's source
 * itself (its main renamed) so that it reaches exactly the code the app runs: the few
 * functions of apps/app_common.c a reader calls. app_read_text hands over the fuzz input
 * (NUL bytes refused as the bounded reader does), app_die jumps back to the target, which frees
 * what the reader held. Include before the app's source. */
#ifndef SELFTALK_FUZZ_APP_SHIM_H
#define SELFTALK_FUZZ_APP_SHIM_H

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/config.h"
#include "selftalk/io.h"

static jmp_buf g_die;
static void *shim_keep(void *p);
static const char *g_input;
static size_t g_input_len;

__attribute__((noreturn)) void app_die(const char *prog, const char *fmt, ...) {
  (void)prog;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (getenv("FUZZ_SHOW_ERRORS")) fprintf(stderr, "%s\n", msg);
  longjmp(g_die, 1);
}

char *app_read_text(const char *prog, const char *path, size_t *len) {
  char err[512];
  if (st_text_check(path, g_input, g_input_len, err, sizeof err)) app_die(prog, "%s", err);
  char *text = malloc(g_input_len + 1);
  if (!text) abort();
  memcpy(text, g_input, g_input_len);
  text[g_input_len] = 0;
  if (len) *len = g_input_len;
  return shim_keep(text);
}

int app_int_arg(const char *prog, const char *opt, const char *v, int lo) {
  (void)prog, (void)opt, (void)lo;
  return atoi(v);
}

int app_config_arg(appConfigArgs *a, int argc, char **argv, int *i, const char *prog) {
  (void)a, (void)argc, (void)argv, (void)i, (void)prog;
  return 0;
}

void app_config_resolve(const appConfigArgs *a, stConfig *cfg, const char *prog) {
  (void)a, (void)prog;
  st_config_default(cfg);
}

/* The app's allocations, tracked (the app's source is compiled with malloc, calloc, realloc
 * and free renamed to these): after a refusal the target frees what the reader held
 * (shim_free_all), after an acceptance it checks that the app freed everything (shim_live). */
#define SHIM_MAX 64
static void *g_live[SHIM_MAX];

static void shim_forget(void *p) {
  for (int i = 0; p && i < SHIM_MAX; i++)
    if (g_live[i] == p) g_live[i] = NULL;
}

static void *shim_keep(void *p) {
  for (int i = 0; p && i < SHIM_MAX; i++)
    if (!g_live[i]) return g_live[i] = p;
  if (p) abort(); /* more live blocks than the readers hold */
  return p;
}

/* the block's slot found before realloc: GCC's -Wuse-after-free (make asan, -O1) refuses any
 * use of p after it, even a comparison */
static void *shim_realloc(void *p, size_t n) {
  int slot = -1;
  for (int i = 0; p && i < SHIM_MAX && slot < 0; i++)
    if (g_live[i] == p) slot = i;
  void *q = realloc(p, n);
  if (q && slot >= 0) g_live[slot] = q;
  else if (q) shim_keep(q);
  return q;
}
__attribute__((unused)) static void *shim_malloc(size_t n) { return shim_keep(malloc(n)); }
__attribute__((unused)) static void *shim_calloc(size_t n, size_t m) { return shim_keep(calloc(n, m)); }
static void shim_free(void *p) {
  shim_forget(p);
  free(p);
}

static void shim_free_all(void) {
  for (int i = 0; i < SHIM_MAX; i++) free(g_live[i]), g_live[i] = NULL;
}

static int shim_live(void) {
  int n = 0;
  for (int i = 0; i < SHIM_MAX; i++) n += g_live[i] != NULL;
  return n;
}

#define malloc shim_malloc
#define calloc shim_calloc
#define realloc shim_realloc
#define free shim_free

#endif
