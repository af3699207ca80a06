/* SPDX-License-Identifier: MIT
 * grasp_probe: can the main-prim grasp trials be solved by simply lowering the palm onto the
 * ball and closing the hand? A diagnostic for the fitness landscape of the grasp primitive
 * (data/evolved/README.md), not part of the protocol.
 *
 *   build/grasp_probe [section.key=value]...
 *
 * For each of the four main-prim grasp trials (generation 0 offsets) and each combination of
 * palm height above the ball top (gap), palm offset along world x from the ball centre (dx),
 * and thumb opposition, the controller: inverse kinematics once, palm centre to (ball x + dx,
 * ball y, ball top + gap) with the palm facing down, held for the whole trial; the thumb turned
 * to the opposition at once; thumb and fingers closed at full speed once the palm is within
 * 1 cm of its goal (or from step 30).
 * Scored by the library's own trial scoring (st_trial_run_controller): success = the ball still
 * above the table at the end, 40 steps after its collision with the table goes off.
 * Prints one line per combination (successes, and the steps each trial lasted: 42 means the
 * ball fell within two steps of the table going) and a total. */
#include <stdio.h>
#include <string.h>

#include "selftalk/selftalk.h"

#define CLOSE_DIST 0.01 /* the hand closes once the palm is this close to its goal, m ... */
#define CLOSE_LAST 30    /* ... or from this step on (the table goes at step 40) */

typedef struct probe {
  const stProtocol *p;
  double gap, dx, oppose;
  int closing;
  double goal[ST_NDOF], pos[3];
} probe;

static void probe_reset(void *self, const stTrialSpec *t) {
  probe *n = self;
  const stRobot *r = n->p->robot;
  static const double normal[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  memcpy(n->goal, t->qhat0, sizeof n->goal);
  n->pos[0] = t->obj[0] + n->dx;
  n->pos[1] = t->obj[1];
  n->pos[2] = t->obj[2] + n->p->scene.obj_radius + n->gap;
  n->closing = 0;
  stIkTarget target = st_ik_target(r->palm_body, n->pos);
  st_ik_target_align(&target, 0, normal, down, 0.01);
  const stIkDef def = st_ik_default_def();
  (void)st_ik_solve(r, &def, &target, n->goal, NULL); /* the best posture found is good enough */
}

static void probe_act(void *self, const stWorld *w, const stQuantities *q, const double *in,
                      int step, double *out) {
  (void)w, (void)in;
  probe *n = self;
  const double dx = q->palm[0] - n->pos[0], dy = q->palm[1] - n->pos[1], dz = q->palm[2] - n->pos[2];
  if (dx * dx + dy * dy + dz * dz < CLOSE_DIST * CLOSE_DIST || step >= CLOSE_LAST) n->closing = 1;
  for (int k = 0; k < ST_NET_MAX_OUT; k++) out[k] = k < ST_NDOF ? n->goal[k] : 0.0;
  out[ST_DOF_THUMB_OPPOSE] = n->oppose;
  out[ST_DOF_THUMB_FLEX] = out[ST_DOF_FINGER_FLEX] = n->closing ? 1.0 : 0.0;
  out[ST_NET_OUT_FOCUS] = 0.0; /* focus on the object, as grasp trials want */
}

int main(int argc, char **argv) {
  stConfig cfg;
  char err[1024];
  st_config_default(&cfg);
  for (int i = 1; i < argc; i++)
    if (st_config_set(&cfg, argv[i], err, sizeof err)) {
      fprintf(stderr, "grasp_probe: %s\n", err);
      return 2;
    }
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) {
    fprintf(stderr, "grasp_probe: %s\n", err);
    return 2;
  }
  static const double gaps[] = {-0.005, 0.005, 0.015};
  static const double dxs[] = {-0.07, -0.055, -0.04, -0.025, 0.0, 0.02};
  static const double opposes[] = {0.0, 0.5, 0.8, 1.0};
  stWorkspace ws = {NULL, NULL};
  int total = 0, solved = 0;
  for (size_t gi = 0; gi < sizeof gaps / sizeof *gaps; gi++)
    for (size_t xi = 0; xi < sizeof dxs / sizeof *dxs; xi++)
      for (size_t oi = 0; oi < sizeof opposes / sizeof *opposes; oi++) {
        int ok = 0;
        char steps[64] = "";
        for (int k = 0; k < ST_NPOSTURE; k++) {
          probe n = {p, gaps[gi], dxs[xi], opposes[oi], 0, {0}, {0}};
          const stController c = {probe_reset, probe_act, ST_NET_NIN, &n};
          stTrialSpec t;
          st_trial_spec(p, ST_STAGE_MAIN, 0, ST_PRIM_GRASP * ST_NPOSTURE + k, &t);
          stTrialResult r;
          if (st_trial_run_controller(p, &ws, &t, &c, 1, &r, NULL, NULL, err, sizeof err)) {
            fprintf(stderr, "grasp_probe: %s\n", err);
            return 1;
          }
          ok += r.success;
          const size_t len = strlen(steps);
          snprintf(steps + len, sizeof steps - len, " %ld%s", r.steps_run, r.success ? "*" : "");
        }
        printf("gap %+.3f dx %+.3f oppose %.1f: %d/4 (steps%s)\n", gaps[gi], dxs[xi],
               opposes[oi], ok, steps);
        total += ST_NPOSTURE;
        solved += ok;
      }
  printf("grasp_probe: %d of %d grasp trials held the ball\n", solved, total);
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  return 0;
}
