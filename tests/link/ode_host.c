/* SPDX-License-Identifier: MIT
 * A host program that uses ODE itself (tests/check_link.sh, issue 48): its own simulations, a
 * chain of six boxes on powered hinges stepped by quickstep (seeded with dRandSetSeed: its rows
 * are shuffled through ODE's dRandInt) and by the direct solver (through ODE's dxSolveLCP), a
 * few draws of ODE's generator and one ODE message. Its "host" lines (hashes of every state) and
 * its stderr are compared across three builds: ODE alone, with libselftalk.so and with
 * libselftalk.a, where the host also steps the library's own dynamic worlds (quickstep, schur,
 * dense) between its simulations on the same thread. A library safe to link changes nothing in
 * them. The "selftalk" lines say what the library did (a refusal where it cannot honour a key).
 *
 *   ode_host [SEGMENTS]      run from the repository (the library's worlds read data/) */
#include <ode/ode.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef WITH_SELFTALK
#include <selftalk/selftalk.h>
#endif

enum { NB = 6 };

typedef struct host {
  dWorldID world;
  dBodyID body[NB];
  dJointID joint[NB];
} host;

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
  const unsigned char *c = p;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
  return h;
}

static void host_create(host *s) {
  s->world = dWorldCreate();
  dWorldSetGravity(s->world, 0, 0, -9.81);
  dWorldSetQuickStepNumIterations(s->world, 20);
  dMass m;
  for (int i = 0; i < NB; i++) {
    s->body[i] = dBodyCreate(s->world);
    dMassSetBoxTotal(&m, 0.5 + 0.1 * i, 0.1, 0.05, 0.2);
    dBodySetMass(s->body[i], &m);
    dBodySetPosition(s->body[i], 0.02 * i, 0.0, -0.2 * (i + 1));
    s->joint[i] = dJointCreateHinge(s->world, 0);
    dJointAttach(s->joint[i], s->body[i], i ? s->body[i - 1] : 0);
    dJointSetHingeAnchor(s->joint[i], 0.02 * i, 0.0, -0.2 * i);
    dJointSetHingeAxis(s->joint[i], i % 2 ? 1.0 : 0.0, i % 2 ? 0.0 : 1.0, 0.0);
    dJointSetHingeParam(s->joint[i], dParamFMax, 2.0);
    dJointSetHingeParam(s->joint[i], dParamVel, 0.5 * (i % 3 - 1));
    dJointSetHingeParam(s->joint[i], dParamLoStop, -0.6);
    dJointSetHingeParam(s->joint[i], dParamHiStop, 0.6);
  }
}

/* steps with quickstep or the direct solver; the hash of every body's state after each step */
static uint64_t host_run(host *s, int quick, int steps, uint64_t h) {
  for (int k = 0; k < steps; k++) {
    if (quick) dWorldQuickStep(s->world, 0.01);
    else dWorldStep(s->world, 0.01);
    for (int i = 0; i < NB; i++) {
      h = fnv(h, dBodyGetPosition(s->body[i]), 3 * sizeof(dReal));
      h = fnv(h, dBodyGetQuaternion(s->body[i]), 4 * sizeof(dReal));
      h = fnv(h, dBodyGetAngularVel(s->body[i]), 3 * sizeof(dReal));
    }
  }
  return h;
}

#ifdef WITH_SELFTALK
/* the library's own dynamic world with one more key: a trial's first steps, hashed; a refusal
 * is printed as it is */
static void selftalk_steps(const char *set, int segment) {
  stConfig cfg;
  st_config_default(&cfg);
  char err[2048];
  stProtocol *p = NULL;
  stWorld *w = NULL;
  stDynDef def;
  if (st_config_set(&cfg, set, err, sizeof err) || st_protocol_create(&cfg, &p, err, sizeof err)) {
    printf("selftalk %s: refused: %s\n", set, err);
    return;
  }
  st_dyn_def_from_config(&cfg, &def);
  if (st_world_create_dynamic(p->robot, &p->scene, &def, &w, err, sizeof err)) {
    printf("selftalk %s: refused: %s\n", set, err);
    st_protocol_destroy(p);
    return;
  }
  st_world_set_seed(w, 7u + (unsigned)segment);
  st_world_reset(w, p->posture[0][0], p->scene.obj_pos[0], p->scene.target[0]);
  double y[ST_NDOF];
  uint64_t h = 14695981039346656037ull;
  for (int k = 0; k < 30; k++) {
    for (int d = 0; d < ST_NDOF; d++) y[d] = 0.5 + 0.4 * ((k + d) % 3 - 1);
    st_world_step_dynamic(w, y);
    h = fnv(h, w->qhat, ST_NDOF * sizeof(double));
    h = fnv(h, w->obj, 3 * sizeof(double));
  }
  printf("selftalk %s segment %d: %016llx\n", set, segment, (unsigned long long)h);
  st_world_destroy(w);
  st_protocol_destroy(p);
}
#endif

int main(int argc, char **argv) {
  const int segments = argc > 1 ? atoi(argv[1]) : 3;
  dInitODE2(0);
  host q, d;
  host_create(&q);
  host_create(&d);
  dRandSetSeed(12345);
  uint64_t hq = 14695981039346656037ull, hd = hq;
  for (int seg = 0; seg < segments; seg++) {
    hq = host_run(&q, 1, 40, hq);
    hd = host_run(&d, 0, 40, hd);
    int draws[4];
    for (int i = 0; i < 4; i++) draws[i] = dRandInt(1000);
    printf("host segment %d: quickstep %016llx step %016llx draws %d %d %d %d seed %lu\n", seg,
           (unsigned long long)hq, (unsigned long long)hd, draws[0], draws[1], draws[2], draws[3],
           dRandGetSeed());
    fflush(stdout);
    dMessage(3, "host message %d", seg); /* printed by ODE, or the host's handler: never lost */
#ifdef WITH_SELFTALK
    selftalk_steps("dynamics.solver=quickstep", seg);
    selftalk_steps("dynamics.lcp=schur", seg);
    selftalk_steps("dynamics.lcp=dense", seg);
    fflush(stdout);
#endif
  }
  dWorldDestroy(q.world);
  dWorldDestroy(d.world);
  dCloseODE();
  return 0;
}
