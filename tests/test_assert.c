/* SPDX-License-Identifier: MIT
 * ST_ASSERT (lib/core/internal.h): a broken precondition aborts with the function, file:line
 * and the condition. Death tests: the call runs in a forked child whose stderr is read back.
 * The macro is tried in every build (this file turns it on for itself); a library function's
 * assert only where the library was built with them (make asan, ASSERTS=1), since in a release
 * build the same call would read out of bounds. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

/* ST_ASSERTS comes from the Makefile with the library's own flags: remember it before this
 * file turns the macro on for its own probe */
#if defined(ST_ASSERTS)
#define LIB_ASSERTS 1
#else
#define LIB_ASSERTS 0
#define ST_ASSERTS
#endif

#include "core/internal.h"
#include "selftalk/fitness.h"
#include "selftalk/trial.h"
#include "test_util.h"

/* runs fn(arg) in a child; returns 1 when it died of SIGABRT, with its stderr in msg */
static int dies(void (*fn)(int), int arg, char *msg, size_t n) {
  int fd[2];
  msg[0] = '\0';
  if (pipe(fd) != 0) return 0;
  fflush(NULL); /* nothing buffered is written twice */
  const pid_t pid = fork();
  if (pid < 0) return 0;
  if (pid == 0) {
    close(fd[0]);
    dup2(fd[1], 2);
    fn(arg);
    _exit(0); /* no assert fired: exit normally, without the parent's atexit handlers */
  }
  close(fd[1]);
  size_t len = 0;
  ssize_t r;
  while (len + 1 < n && (r = read(fd[0], msg + len, n - 1 - len)) > 0) len += (size_t)r;
  msg[len] = '\0';
  close(fd[0]);
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return 0;
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT;
}

static void probe(int index) {
  ST_ASSERT(index >= 0 && index < 16);
}

static void test_assert_macro(void) {
  char msg[512];
  CU_ASSERT(!dies(probe, 3, msg, sizeof msg));
  CU_ASSERT_STRING_EQUAL(msg, "");
  CU_ASSERT(dies(probe, 16, msg, sizeof msg));
  ST_ASSERT_CONTAINS(msg, "selftalk: assertion failed in probe (tests/test_assert.c:");
  ST_ASSERT_CONTAINS(msg, "): index >= 0 && index < 16\n");
}

static void trial_spec_at(int index) {
  /* the index is checked before the protocol is read: a zeroed one will do */
  stProtocol *p = calloc(1, sizeof *p);
  stTrialSpec t;
  if (p) st_trial_spec(p, ST_STAGE_SIMPLE, 0, index, &t);
  free(p);
}

static void harmonic_of(int n) {
  /* eq. 2.13's harmonic mean of no primitive's fitness is 0 / 0: the call is refused */
  stFitnessDef d;
  memset(&d, 0, sizeof d);
  const double fp[1] = {1.0};
  (void)st_harmonic_fitness(&d, fp, n);
}

static void test_assert_library(void) {
  if (!LIB_ASSERTS) return; /* release build: asserts compiled out */
  char msg[512];
  CU_ASSERT(dies(trial_spec_at, ST_PRIM_TRIALS, msg, sizeof msg));
  ST_ASSERT_CONTAINS(msg, "selftalk: assertion failed in st_trial_spec (lib/episode/trial.c:");
  ST_ASSERT_CONTAINS(msg, "index < (stage == ST_STAGE_MAIN ? ST_MAIN_TRIALS_MAX : ST_PRIM_TRIALS)");
  CU_ASSERT(dies(trial_spec_at, -1, msg, sizeof msg));
  CU_ASSERT(!dies(harmonic_of, 1, msg, sizeof msg));
  CU_ASSERT(dies(harmonic_of, 0, msg, sizeof msg));
  ST_ASSERT_CONTAINS(msg, "selftalk: assertion failed in st_harmonic_fitness (lib/task/fitness.c:");
  ST_ASSERT_CONTAINS(msg, "): d && fp && n > 0\n");
}

void st_suite_assert(void) {
  ST_ADD_SUITE("assert");
  ST_ADD_TEST(test_assert_macro);
  ST_ADD_TEST(test_assert_library);
}
