/* SPDX-License-Identifier: MIT
 * libselftalk: ODE set-up shared by the worlds (lib/world/ode_util.c), and the per-thread replacement
 * of ODE's random generator and warning counter (lib/world/ode_rand.c); not installed. */
#ifndef SELFTALK_ODE_UTIL_H
#define SELFTALK_ODE_UTIL_H

#include <stdint.h>

/* Initialises ODE once per process (thread-safe) and allocates ODE's per-thread data for the
 * calling thread (ODE requires it of every thread that calls it). */
void st__ode_init(void);

/* One step (quickstep when quickstep is set, else step) of a world of two bodies hanging from
 * powered hinges: 12 constraint rows, 2 of them bounded. For the checks that ODE's calls reach
 * the library's definitions (lib/world/ode_rand.c, lib/world/ode_lcp.c). */
void st__ode_probe_step(int quickstep);

/* The calling thread's replacement of ODE's random generator (lib/world/ode_rand.c): dRand,
 * dRandInt, dRandReal, dRandGetSeed and dRandSetSeed are defined by the library over one
 * 32-bit state per thread, so that every world can load its own state before a quickstep
 * and store it afterwards. st__ode_rand_calls counts the draws made on this thread (for the
 * check that ODE's calls reach these definitions). */
uint32_t st__ode_rand_get(void);
void st__ode_rand_set(uint32_t state);
unsigned long st__ode_rand_calls(void);

/* Installs (once, only when none is set) a handler for ODE's non-fatal dMessage warnings that
 * counts them on the calling thread instead of printing them; st__ode_messages reads the
 * count. */
void st__ode_messages_install(void);
unsigned long st__ode_messages(void);
/* Sets the count back to an earlier reading (lib/world/ode_lcp.c's check mode: the warnings of
 * the solve it compares are not the step's). */
void st__ode_messages_rewind(unsigned long to);

#endif
