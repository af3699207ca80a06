/* SPDX-License-Identifier: MIT
 * Per-thread replacement of ODE's random generator, and a counter for ODE's warnings.
 *
 * dWorldQuickStep shuffles its constraint rows every 8 iterations with dRandInt, which in ODE
 * (misc.cpp) draws from ONE process-wide seed. Parallel trials sharing it would depend on how
 * their threads interleave. libode.so calls dRandInt through its PLT, so definitions with the
 * same names and signatures in the program (here, linked through libselftalk) take
 * precedence, and ODE's shuffling then draws from the calling thread's own state. The dynamic
 * world loads its per-trial state before each quickstep and stores it after, so a trial's
 * draws do not even depend on other worlds stepped by the same thread. lib/world/dynworld.c checks
 * at run time that the interposition is effective.
 *
 * The generator is ODE's own: the 32-bit linear congruential generator
 * s' = 1664525 s + 1013904223 (mod 2^32) (Numerical Recipes' constants). dRandInt maps the
 * draw to 0..n-1 with the high bits (multiply-shift), the best bits of an LCG.
 *
 * C99 has no _Thread_local: the state uses the __thread storage class of GCC and Clang (the
 * compilers the Makefile supports); other compilers would need their own keyword here. */
#include <ode/ode.h>
#include <stdarg.h>
#include <stdint.h>

#include "world/ode_util.h"

#if defined(__GNUC__) || defined(__clang__)
#define ST_THREAD_LOCAL __thread
#else
#error "lib/world/ode_rand.c needs thread-local storage (__thread); add your compiler's keyword"
#endif

static ST_THREAD_LOCAL uint32_t g_state;
static ST_THREAD_LOCAL unsigned long g_calls;
static ST_THREAD_LOCAL unsigned long g_messages;

static uint32_t next(void) {
  g_calls++;
  g_state = 1664525u * g_state + 1013904223u;
  return g_state;
}

unsigned long dRand(void) { return next(); }

unsigned long dRandGetSeed(void) { return g_state; }

void dRandSetSeed(unsigned long s) { g_state = (uint32_t)s; }

int dRandInt(int n) {
  if (n <= 0) return 0;
  return (int)(((uint64_t)next() * (uint64_t)(uint32_t)n) >> 32);
}

dReal dRandReal(void) { return (dReal)((double)next() / 4294967295.0); }

uint32_t st__ode_rand_get(void) { return g_state; }

void st__ode_rand_set(uint32_t state) { g_state = state; }

unsigned long st__ode_rand_calls(void) { return g_calls; }

/* ODE's dMessage (non-fatal warnings such as "LCP internal error") would print to stderr from
 * inside a trial: count them on the calling thread instead */
static void message_handler(int errnum, const char *msg, va_list ap) {
  (void)errnum;
  (void)msg;
  (void)ap;
  g_messages++;
}

void st__ode_messages_install(void) {
  if (!dGetMessageHandler()) dSetMessageHandler(message_handler);
}

unsigned long st__ode_messages(void) { return g_messages; }

void st__ode_messages_rewind(unsigned long to) { g_messages = to; }
