/* SPDX-License-Identifier: MIT
 * grasp_probe: can the main-prim grasp trials be solved by simply lowering the palm onto the
 * ball and closing the hand? A diagnostic for the fitness landscape of the grasp primitive
 * (data/evolved/README.md), not part of the protocol.
 *
 *   build/grasp_probe [OPTION]... [section.key=value]...
 *     --dy M            palm offset along world y from the ball centre, m (default 0)
 *     --close-step N    close the hand from this step on at the latest (default 30)
 *     --thumb-flex Y    thumb flexion command while closing, 0..1 (default 1)
 *     --finger-flex Y   finger flexion command while closing, 0..1 (default 1)
 *     --trace GAP,DX,OPPOSE,K   run only grasp trial K (0..3) with these values and print
 *                       every step: ball centre, palm and tips relative to it, touch sensors
 *     --basin           the grasp basin (data/README.md "Hand"): 5 palm offsets along the fingers
 *                       x 3 across x 2 heights x 3 thumb oppositions x 2 closures x the 4 grasp
 *                       trials = 720 closings; one line per hold, then `basin held=N total=M`
 *     --hand OPPOSE,THUMB,FINGERS   print only the five fingertips in the palm frame (+x along
 *                       the fingers, +y towards the thumb, +z the palm normal, out of the palm)
 *                       for these normalised hand DOF (forward kinematics, no simulation)
 *
 * For each of the four main-prim grasp trials (generation 0 offsets) and each combination of
 * palm height above the ball top (gap), palm offset along world x from the ball centre (dx),
 * and thumb opposition, the controller: inverse kinematics once, palm centre to (ball x + dx,
 * ball y + dy, ball top + gap) with the palm facing down, held for the whole trial; the thumb
 * turned to the opposition at once; thumb and fingers closed at full speed once the palm is
 * within 1 cm of its goal (or from --close-step).
 * Scored by the library's own trial scoring (st_trial_run): success = the ball still
 * above the table at the end, 40 steps after its collision with the table goes off.
 * Prints one line per combination (successes, and the steps each trial lasted: 42 means the
 * ball fell within two steps of the table going) and a total. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/selftalk.h"

#define CLOSE_DIST 0.01 /* the hand closes once the palm is this close to its goal, m */

typedef struct probeOptions {
  double dy, thumb_flex, finger_flex;
  long close_step;
} probeOptions;

typedef struct probe {
  const stProtocol *p;
  const probeOptions *o;
  double gap, dx, oppose;
  int closing;
  double goal[ST_NDOF], pos[3];
  int along_fingers; /* --basin: dx, dy along / across the start posture's fingers, not world x, y */
  double close_to;   /* --basin: thumb and finger command once closing (else the options') */
  double d_g39, h39; /* --basin: d_g and h at the last step before the table goes */
} probe;

/* horizontal unit vector along the fingers (palm x axis) in posture qhat, and across them */
static void finger_axes(const stRobot *r, const double *qhat, double u[2], double v[2]) {
  double(*R)[9] = malloc(sizeof *R * (size_t)r->nbody);
  double(*p)[3] = malloc(sizeof *p * (size_t)r->nbody);
  u[0] = 1, u[1] = 0;
  if (R && p) {
    st_robot_fk(r, qhat, R, p);
    const double *Rp = R[r->palm_body], n = hypot(Rp[0], Rp[3]);
    if (n > 1e-9) u[0] = Rp[0] / n, u[1] = Rp[3] / n; /* column 0: the palm x axis in world */
  }
  free(R);
  free(p);
  v[0] = -u[1], v[1] = u[0];
}

static void probe_reset(void *self, const stEpisodeSpec *t) {
  probe *n = self;
  const stRobot *r = n->p->robot;
  static const double normal[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  memcpy(n->goal, t->qhat0, sizeof n->goal);
  double u[2] = {1, 0}, v[2] = {0, 1};
  if (n->along_fingers) finger_axes(r, t->qhat0, u, v);
  n->pos[0] = t->obj[0] + n->dx * u[0] + n->o->dy * v[0];
  n->pos[1] = t->obj[1] + n->dx * u[1] + n->o->dy * v[1];
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
  if (dx * dx + dy * dy + dz * dz < CLOSE_DIST * CLOSE_DIST || step >= n->o->close_step)
    n->closing = 1;
  for (int k = 0; k < ST_NET_MAX_OUT; k++) out[k] = k < ST_NDOF ? n->goal[k] : 0.0;
  out[ST_DOF_THUMB_OPPOSE] = n->oppose;
  if (n->along_fingers) { /* --basin: the start's flexion is kept until the hand closes */
    if (n->closing) out[ST_DOF_THUMB_FLEX] = out[ST_DOF_FINGER_FLEX] = n->close_to;
  } else {
    out[ST_DOF_THUMB_FLEX] = n->closing ? n->o->thumb_flex : 0.0;
    out[ST_DOF_FINGER_FLEX] = n->closing ? n->o->finger_flex : 0.0;
  }
  out[ST_NET_OUT_FOCUS] = 0.0; /* focus on the object, as grasp trials want */
}

/* One line per step; positions relative to the ball centre, so "x > 0" is the far side. */
static void probe_trace(void *ctx, const stTraceStep *s) {
  (void)ctx;
  const stQuantities *q = s->q;
  const double *o = s->world->obj, *thumb = q->tip[ST_TOUCH_THUMB],
               *little = q->tip[ST_TOUCH_LITTLE], *middle = q->tip[ST_TOUCH_MIDDLE];
  printf("%3d ball %.4f %.4f %.4f palm %+.4f %+.4f %+.4f thumb %+.4f %+.4f %+.4f little %+.4f "
         "%+.4f %+.4f middle %+.4f %+.4f %+.4f touch ",
         s->step, o[0], o[1], o[2], q->palm[0] - o[0], q->palm[1] - o[1], q->palm[2] - o[2],
         thumb[0] - o[0], thumb[1] - o[1], thumb[2] - o[2], little[0] - o[0], little[1] - o[1],
         little[2] - o[2], middle[0] - o[0], middle[1] - o[1], middle[2] - o[2]);
  for (int i = 0; i < ST_NTOUCH; i++) putchar('0' + s->world->contacts.touch_object[i]);
  printf(" h %.3f S %.4f P %.4f\n", q->h, s->S, s->P);
}

/* --basin: d_g and h at the step before the object-table collision goes off */
static void basin_trace(void *ctx, const stTraceStep *s) {
  probe *n = ctx;
  if (s->step == n->p->cfg.stage_grasp_table_off_step - 1) n->d_g39 = s->q->d_g, n->h39 = s->q->h;
}

/* --basin: every closing of the sweep, in parallel (one workspace per thread); the lines come
 * out in sweep order whatever the thread count */
static int basin(const stProtocol *p, const probeOptions *o0) {
  static const double dxs[] = {-0.03, -0.015, 0.0, 0.015, 0.03}, dys[] = {-0.02, 0.0, 0.02};
  static const double gaps[] = {-0.004, 0.004}, opposes[] = {0.3, 0.6, 0.9}, closes[] = {0.6, 1.0};
  enum { NX = 5, NY = 3, NG = 2, NO = 3, NC = 2, N = NX * NY * NG * NO * NC * ST_NPOSTURE };
  static probe res[N];
  static probeOptions opt[N];
  int fail = 0;
#pragma omp parallel
  {
    stWorkspace ws = {NULL, NULL, NULL};
#pragma omp for schedule(dynamic)
    for (int i = 0; i < N; i++) {
      int j = i;
      const int k = j % ST_NPOSTURE; j /= ST_NPOSTURE;
      const int ci = j % NC; j /= NC;
      const int oi = j % NO; j /= NO;
      const int gi = j % NG; j /= NG;
      const int yi = j % NY; j /= NY;
      opt[i] = *o0;
      opt[i].dy = dys[yi];
      probe n = {p, &opt[i], gaps[gi], dxs[j], opposes[oi], 0, {0}, {0}, 1, closes[ci], NAN, NAN};
      stTrialResult r;
      char err[1024];
      stTrialSpec t;
      const stController c = {probe_reset, probe_act, ST_NET_NIN, &n, ST_NET_NOUT, 0, NULL};
      st_trial_spec(p, ST_STAGE_MAIN, 0, ST_PRIM_GRASP * ST_NPOSTURE + k, &t);
      const int bad = st_trial_run(p, &ws, &t, &c, 1, &r, basin_trace, &n, err, sizeof err);
      if (bad) {
#pragma omp critical
        {
          fprintf(stderr, "grasp_probe: %s\n", err);
          fail = 1;
        }
      }
      n.closing = !bad && r.success; /* reused: held */
      res[i] = n;
    }
    st_workspace_free(&ws);
  }
  if (fail) return 1;
  int held = 0;
  for (int i = 0; i < N; i++) {
    const probe *n = &res[i];
    if (!n->closing) continue;
    held++;
    printf("held trial %d dx %+.3f dy %+.3f gap %+.3f oppose %.1f close %.1f d_g39 %.4f h39 %.3f\n",
           i % ST_NPOSTURE, n->dx, n->o->dy, n->gap, n->oppose, n->close_to, n->d_g39, n->h39);
  }
  printf("basin held=%d total=%d\n", held, N);
  return 0;
}

/* --hand: fingertips in the palm frame; the arm does not matter, so it stays at q-hat 0 */
static int hand_tips(const stRobot *r, double oppose, double thumb, double fingers) {
  double qhat[ST_NDOF] = {0};
  qhat[ST_DOF_THUMB_OPPOSE] = oppose;
  qhat[ST_DOF_THUMB_FLEX] = thumb;
  qhat[ST_DOF_FINGER_FLEX] = fingers;
  double(*R)[9] = malloc(sizeof *R * (size_t)r->nbody);
  double(*p)[3] = malloc(sizeof *p * (size_t)r->nbody);
  if (!R || !p) {
    free(R);
    free(p);
    fprintf(stderr, "grasp_probe: out of memory\n");
    return 1;
  }
  st_robot_fk(r, qhat, R, p);
  static const char *names[ST_NTIP] = {"thumb", "index", "middle", "ring", "little"};
  for (int f = 0; f < ST_NTIP; f++) {
    double l[3];
    st_robot_point_local(R[r->palm_body], p[r->palm_body], p[r->tip_body[f]], l);
    printf("%-6s %+.4f %+.4f %+.4f\n", names[f], l[0], l[1], l[2]);
  }
  free(R);
  free(p);
  return 0;
}

#if defined(__GNUC__)
__attribute__((noreturn, format(printf, 1, 2)))
#endif
static void die(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("grasp_probe: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  exit(2);
}

static double number(const char *opt, const char *s, double lo, double hi) {
  char *end;
  errno = 0;
  const double v = s ? strtod(s, &end) : 0.0;
  if (!s || end == s || *end || errno || !(v >= lo && v <= hi))
    die("%s: '%s' (expected a number in [%g, %g])", opt, s ? s : "(missing)", lo, hi);
  return v;
}

static int run_trial(const stProtocol *p, stWorkspace *ws, probe *n, int k, stTraceFn trace,
                     stTrialResult *r) {
  char err[1024];
  const stController c = {probe_reset, probe_act, ST_NET_NIN, n, ST_NET_NOUT, 0, NULL};
  stTrialSpec t;
  st_trial_spec(p, ST_STAGE_MAIN, 0, ST_PRIM_GRASP * ST_NPOSTURE + k, &t);
  if (st_trial_run(p, ws, &t, &c, 1, r, trace, NULL, err, sizeof err)) {
    fprintf(stderr, "grasp_probe: %s\n", err);
    return 1;
  }
  return 0;
}

int main(int argc, char **argv) {
  stConfig cfg;
  char err[1024];
  probeOptions o = {0.0, 1.0, 1.0, 30};
  const char *trace = NULL, *hand = NULL;
  int do_basin = 0;
  st_config_default(&cfg);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--dy")) o.dy = number(a, v, -0.1, 0.1), i++;
    else if (!strcmp(a, "--close-step")) o.close_step = (long)number(a, v, 0, 80), i++;
    else if (!strcmp(a, "--thumb-flex")) o.thumb_flex = number(a, v, 0, 1), i++;
    else if (!strcmp(a, "--finger-flex")) o.finger_flex = number(a, v, 0, 1), i++;
    else if (!strcmp(a, "--basin")) do_basin = 1;
    else if (!strcmp(a, "--trace")) {
      if (!v) die("%s: expected GAP,DX,OPPOSE,K", a);
      trace = v, i++;
    } else if (!strcmp(a, "--hand")) {
      if (!v) die("%s: expected OPPOSE,THUMB,FINGERS", a);
      hand = v, i++;
    } else if (a[0] == '-') die("unknown option '%s' (expected --basin, --dy, --close-step, "
                                "--thumb-flex, --finger-flex, --trace, --hand or section.key=value)", a);
    else if (st_config_set(&cfg, a, err, sizeof err)) die("%s", err);
  }
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) die("%s", err);
  stWorkspace ws = {NULL, NULL, NULL};
  int rc = 0;
  if (do_basin && (trace || hand || o.dy != 0.0 || o.thumb_flex != 1.0 || o.finger_flex != 1.0 ||
                   o.close_step != 30))
    die("--basin sweeps its own offsets and closures (expected no --trace, --hand, --dy, "
        "--thumb-flex, --finger-flex or --close-step with it)");
  if (do_basin) {
    rc = basin(p, &o);
  } else if (hand) {
    double o3[3];
    char extra;
    if (sscanf(hand, "%lf,%lf,%lf%c", &o3[0], &o3[1], &o3[2], &extra) != 3 ||
        !(o3[0] >= 0 && o3[0] <= 1 && o3[1] >= 0 && o3[1] <= 1 && o3[2] >= 0 && o3[2] <= 1))
      die("--hand '%s': expected OPPOSE,THUMB,FINGERS, each in 0..1", hand);
    rc = hand_tips(p->robot, o3[0], o3[1], o3[2]);
  } else if (trace) {
    double gap, dx, oppose;
    int k;
    char extra;
    if (sscanf(trace, "%lf,%lf,%lf,%d%c", &gap, &dx, &oppose, &k, &extra) != 4 || k < 0 ||
        k >= ST_NPOSTURE || !(oppose >= 0 && oppose <= 1))
      die("--trace '%s': expected GAP,DX,OPPOSE,K with OPPOSE in 0..1 and K in 0..3", trace);
    probe n = {p, &o, gap, dx, oppose, 0, {0}, {0}, 0, 0.0, NAN, NAN};
    stTrialResult r;
    rc = run_trial(p, &ws, &n, k, probe_trace, &r);
    if (!rc) printf("trial %d: success %d, %ld steps\n", k, r.success, r.steps_run);
  } else {
    static const double gaps[] = {-0.005, 0.005, 0.015};
    static const double dxs[] = {-0.07, -0.055, -0.04, -0.025, 0.0, 0.02};
    static const double opposes[] = {0.0, 0.5, 0.8, 1.0};
    int total = 0, solved = 0;
    for (size_t gi = 0; gi < sizeof gaps / sizeof *gaps; gi++)
      for (size_t xi = 0; xi < sizeof dxs / sizeof *dxs; xi++)
        for (size_t oi = 0; oi < sizeof opposes / sizeof *opposes; oi++) {
          int ok = 0;
          char steps[64] = "";
          for (int k = 0; k < ST_NPOSTURE; k++) {
            probe n = {p, &o, gaps[gi], dxs[xi], opposes[oi], 0, {0}, {0}, 0, 0.0, NAN, NAN};
            stTrialResult r;
            if ((rc = run_trial(p, &ws, &n, k, NULL, &r))) goto done;
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
  }
done:
  st_workspace_free(&ws);
  st_protocol_destroy(p);
  return rc;
}
