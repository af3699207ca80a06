/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include "world/ode_util.h"

#include <ode/ode.h>
#include <pthread.h>

static pthread_once_t g_once = PTHREAD_ONCE_INIT;

static void init_once(void) { dInitODE2(0); }

void st__ode_init(void) {
  pthread_once(&g_once, init_once);
  dAllocateODEDataForThread(dAllocateMaskAll);
}
