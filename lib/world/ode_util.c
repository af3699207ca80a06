/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include "world/ode_util.h"

#include <ode/ode.h>
#include <pthread.h>
#include <stdio.h>

static pthread_once_t g_once = PTHREAD_ONCE_INIT;

static void init_once(void) { dInitODE2(0); }

void st__ode_init(void) {
  pthread_once(&g_once, init_once);
  dAllocateODEDataForThread(dAllocateMaskAll);
}

/* the headers the library was compiled against say dReal is double; a libode of another
 * precision would read every array the library hands it wrongly */
static pthread_once_t g_precision_once = PTHREAD_ONCE_INIT;
static const char *g_precision_why;
static char g_precision_buf[400];

static void check_precision(void) {
  st__ode_init();
  if (!dCheckConfiguration("ODE_double_precision")) {
    snprintf(g_precision_buf, sizeof g_precision_buf, "the ODE loaded is not built in double "
             "precision (its configuration: %s), and libselftalk was compiled against ODE "
             "%s's double-precision headers", dGetConfiguration(), dODE_VERSION);
    g_precision_why = g_precision_buf;
  }
}

const char *st__ode_layout_precision(void) {
  pthread_once(&g_precision_once, check_precision);
  return g_precision_why;
}

void st__ode_probe_step(int quickstep) {
  st__ode_init();
  dWorldID wd = dWorldCreate();
  dThreadingImplementationID th = dThreadingAllocateSelfThreadedImplementation();
  if (th) dWorldSetStepThreadingImplementation(wd, dThreadingImplementationGetFunctions(th), th);
  dBodyID b[2];
  dMass m;
  dMassSetSphereTotal(&m, 1.0, 0.1);
  for (int i = 0; i < 2; i++) {
    b[i] = dBodyCreate(wd);
    dBodySetMass(b[i], &m);
    dBodySetPosition(b[i], 0.0, 0.0, -0.2 * (i + 1));
  }
  for (int i = 0; i < 2; i++) {
    dJointID j = dJointCreateHinge(wd, 0);
    dJointAttach(j, b[i], i ? b[0] : 0);
    dJointSetHingeAnchor(j, 0.0, 0.0, -0.2 * i);
    dJointSetHingeAxis(j, 1.0, 0.0, 0.0);
    dJointSetHingeParam(j, dParamFMax, 1.0); /* a bounded motor row: an LCP, not a linear solve */
  }
  dWorldSetGravity(wd, 0, 0, -9.81);
  dWorldSetQuickStepNumIterations(wd, 20);
  if (quickstep) dWorldQuickStep(wd, 0.01);
  else dWorldStep(wd, 0.01);
  dWorldDestroy(wd);
  if (th) dThreadingFreeImplementation(th);
}
