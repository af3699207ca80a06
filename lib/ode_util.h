/* SPDX-License-Identifier: MIT
 * libselftalk: ODE set-up shared by the worlds; not installed. */
#ifndef SELFTALK_ODE_UTIL_H
#define SELFTALK_ODE_UTIL_H

/* Initialises ODE once per process (thread-safe) and allocates ODE's per-thread data for the
 * calling thread (ODE requires it of every thread that calls it). */
void st__ode_init(void);

#endif
