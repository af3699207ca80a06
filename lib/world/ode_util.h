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

/* ODE's random generator inside the library's world steps (lib/world/ode_rand.c): where the
 * static library is linked into the program, ODE's dRand, dRandInt, dRandReal, dRandGetSeed and
 * dRandSetSeed reach the library's definitions, which draw from one 32-bit state per thread
 * between st__ode_rand_begin (loading a world's state) and st__ode_rand_end (returning it), and
 * call ODE's own everywhere else. st__ode_rand_calls counts the dRandInt calls that reached
 * them on this thread; st__ode_rand_bound is 1 when the program's lookup of dRandInt finds the
 * library's (0 in a program linked with the shared library, which keeps them local). */
void st__ode_rand_begin(uint32_t state);
uint32_t st__ode_rand_end(void);
unsigned long st__ode_rand_calls(void);
int st__ode_rand_bound(void);

/* ODE's non-fatal dMessage warnings: st__ode_messages_install sets (again, when the program has
 * set its own since: kept and called) the process's handler, which counts the messages of a
 * thread inside st__ode_messages_begin / end (a library world's step) and passes every other
 * one on as before (the program's handler, or printed as ODE prints it). st__ode_messages reads
 * the count. */
void st__ode_messages_install(void);
void st__ode_messages_begin(void);
void st__ode_messages_end(void);
unsigned long st__ode_messages(void);
/* Sets the count back to an earlier reading (lib/world/ode_lcp.c's check mode: the warnings of
 * the solve it compares are not the step's). */
void st__ode_messages_rewind(unsigned long to);

/* The ODE found at run time against the one the interpositions were written for (ODE 0.16.2,
 * double precision): NULL when it is, else why not (the probes' findings, ODE's configuration);
 * st__ode_layout_lcp for dxSolveLCP (dynamics.lcp = schur), st__ode_layout_rand for quickstep's
 * generator (dynamics.solver = quickstep), st__ode_layout_precision for every dynamic world. */
const char *st__ode_layout_precision(void);

#endif
