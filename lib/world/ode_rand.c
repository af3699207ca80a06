/* SPDX-License-Identifier: MIT
 * Per-thread replacement of ODE's random generator inside the library's world steps, and a
 * counter for ODE's warnings.
 *
 * dWorldQuickStep shuffles its constraint rows every 8 iterations with dRandInt, which in ODE
 * (misc.cpp) draws from ONE process-wide seed. Parallel trials sharing it would depend on how
 * their threads interleave. libode.so calls dRandInt through its PLT, so definitions with the
 * same names and signatures in the program take precedence: the static library linked into a
 * program (the apps) defines them (visible: the program exports them to libode), and ODE's
 * shuffling then reaches them. The shared library keeps them local (tools/libselftalk.map): a
 * program linking it keeps ODE's, and quickstep is refused there (lib/world/dynworld.c).
 *
 * Confined (issue 48): only a thread inside st__ode_rand_begin / st__ode_rand_end (a library
 * world's quickstep) draws from its own state; every other call, the host program's own ODE
 * simulations included, goes to ODE's functions unchanged (dlsym RTLD_NEXT), so a host gets
 * the same results with and without the library linked (tests/check_link.sh). The dynamic world
 * loads its per-trial state in st__ode_rand_begin and stores it from st__ode_rand_end, so a
 * trial's draws do not even depend on other worlds stepped by the same thread.
 *
 * The generator is ODE's own: the 32-bit linear congruential generator
 * s' = 1664525 s + 1013904223 (mod 2^32) (Numerical Recipes' constants). dRandInt maps the
 * draw to 0..n-1 with the high bits (multiply-shift), the best bits of an LCG.
 *
 * C99 has no _Thread_local: the state uses the __thread storage class of GCC and Clang (the
 * compilers the Makefile supports); other compilers would need their own keyword here. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <ode/ode.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "world/ode_util.h"

#if defined(__GNUC__) || defined(__clang__)
#define ST_THREAD_LOCAL __thread
/* ODE's names the static library defines for libode to call: exported from the program (the
 * library is compiled with -fvisibility=hidden) */
#define ST_INTERPOSE __attribute__((visibility("default")))
#else
#error "lib/world/ode_rand.c needs thread-local storage (__thread); add your compiler's keyword"
#endif

static ST_THREAD_LOCAL uint32_t g_state;
static ST_THREAD_LOCAL int g_own; /* inside st__ode_rand_begin / end */
static ST_THREAD_LOCAL unsigned long g_calls;
static ST_THREAD_LOCAL unsigned long g_messages;
static ST_THREAD_LOCAL int g_counting; /* inside st__ode_messages_begin / end */

/* ---- ODE's own functions, for every call outside a library step ---- */

typedef struct odeRand {
  unsigned long (*rand)(void);
  unsigned long (*get_seed)(void);
  void (*set_seed)(unsigned long);
  int (*rand_int)(int);
  dReal (*rand_real)(void);
} odeRand;

static odeRand g_ode;
static pthread_once_t g_ode_once = PTHREAD_ONCE_INIT;

static void find_ode(void) {
  *(void **)&g_ode.rand = dlsym(RTLD_NEXT, "dRand");
  *(void **)&g_ode.get_seed = dlsym(RTLD_NEXT, "dRandGetSeed");
  *(void **)&g_ode.set_seed = dlsym(RTLD_NEXT, "dRandSetSeed");
  *(void **)&g_ode.rand_int = dlsym(RTLD_NEXT, "dRandInt");
  *(void **)&g_ode.rand_real = dlsym(RTLD_NEXT, "dRandReal");
}

static const odeRand *ode(void) {
  pthread_once(&g_ode_once, find_ode);
  if (!g_ode.rand || !g_ode.get_seed || !g_ode.set_seed || !g_ode.rand_int || !g_ode.rand_real) {
    /* these definitions are only reached where libode defines the originals */
    fprintf(stderr, "libselftalk: ODE's random generator functions not found (dlsym)\n");
    abort();
  }
  return &g_ode;
}

static uint32_t next(void) {
  g_state = 1664525u * g_state + 1013904223u;
  return g_state;
}

ST_INTERPOSE unsigned long dRand(void) { return g_own ? next() : ode()->rand(); }

ST_INTERPOSE unsigned long dRandGetSeed(void) { return g_own ? g_state : ode()->get_seed(); }

ST_INTERPOSE void dRandSetSeed(unsigned long s) {
  if (g_own) g_state = (uint32_t)s;
  else ode()->set_seed(s);
}

ST_INTERPOSE int dRandInt(int n) {
  g_calls++; /* reached: st__ode_rand_calls */
  if (!g_own) return ode()->rand_int(n);
  if (n <= 0) return 0;
  return (int)(((uint64_t)next() * (uint64_t)(uint32_t)n) >> 32);
}

ST_INTERPOSE dReal dRandReal(void) {
  return g_own ? (dReal)((double)next() / 4294967295.0) : ode()->rand_real();
}

void st__ode_rand_begin(uint32_t state) {
  g_state = state;
  g_own = 1;
}

uint32_t st__ode_rand_end(void) {
  g_own = 0;
  return g_state;
}

unsigned long st__ode_rand_calls(void) { return g_calls; }

int st__ode_rand_bound(void) {
  /* the program's lookup of ODE's name: ours when the static library is linked into it (libode's
   * calls then reach ours too, unless ODE binds them internally: the probe in dynworld.c) */
  int (*found)(int);
  *(void **)&found = dlsym(RTLD_DEFAULT, "dRandInt");
  return found == dRandInt;
}

/* ---- ODE's warnings ----
 * ODE's dMessage (non-fatal warnings such as "LCP internal error") would print to stderr from
 * inside a trial: counted on the calling thread instead, while it steps a library world. The
 * handler is process-wide, so the others' messages go where they went before: to the handler
 * the program had set, or printed as ODE prints them (error.cpp's printMessage). */

static dMessageFunction *g_prev;
static pthread_mutex_t g_handler_lock = PTHREAD_MUTEX_INITIALIZER;

static void message_handler(int errnum, const char *msg, va_list ap) {
  if (g_counting) {
    g_messages++;
    return;
  }
  if (g_prev) {
    g_prev(errnum, msg, ap);
    return;
  }
  fflush(stderr);
  fflush(stdout);
  if (errnum) fprintf(stderr, "\n%s %d: ", "ODE Message", errnum);
  else fprintf(stderr, "\n%s: ", "ODE Message");
  vfprintf(stderr, msg, ap);
  fprintf(stderr, "\n");
  fflush(stderr);
}

void st__ode_messages_install(void) {
  pthread_mutex_lock(&g_handler_lock);
  dMessageFunction *cur = dGetMessageHandler();
  if (cur != message_handler) { /* first use, or the program set its own since: keep it */
    g_prev = cur;
    dSetMessageHandler(message_handler);
  }
  pthread_mutex_unlock(&g_handler_lock);
}

void st__ode_messages_begin(void) { g_counting = 1; }

void st__ode_messages_end(void) { g_counting = 0; }

unsigned long st__ode_messages(void) { return g_messages; }

void st__ode_messages_rewind(unsigned long to) { g_messages = to; }
