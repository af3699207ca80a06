/* SPDX-License-Identifier: MIT
 * libselftalk: internals of the dynamic world shared with lib/kinworld.c (dispatch of the
 * functions common to both kinds of world) and lib/ode_rand.c; not installed. */
#ifndef SELFTALK_DYNWORLD_H
#define SELFTALK_DYNWORLD_H

#include <stdint.h>

#include "selftalk/world.h"

/* st_world_reset / st_world_update of a world with w->dynamic set; st__dyn_destroy frees its
 * ODE internals (st_world_destroy, which calls it, frees the world itself). */
void st__dyn_destroy(stWorld *w);
void st__dyn_reset(stWorld *w, const double *qhat, const double obj[3], const double target[3]);
void st__dyn_update(stWorld *w);

/* The calling thread's replacement of ODE's random generator (lib/ode_rand.c): dRand,
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

#endif
