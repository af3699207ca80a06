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
