/* SPDX-License-Identifier: MIT
 * compare: the dynamic world against MuJoCo on the same model, same run (make compare).
 *
 *   compare [--rounds R] [--steps N] [--set k=v[;k=v...]] [--config FILE] [--noslip N]
 *           [--kv KV] [--xml DIR] [--check-only]
 *
 * The MuJoCo model is our URDF (robot.urdf) imported by MuJoCo's own URDF importer (fixed
 * joints fused: the same welds, 18 moving bodies), saved as MJCF and completed the way the
 * dynamic world completes it (lib/world/dyn_create.c, docs/PROTOCOL.md "Dynamic mode"):
 *   - every hinge a velocity servo re-aimed every sub-step from its own angle (SPEC 3), torque
 *     limit = URDF effort x dynamics.effort_scale; the exact servos of dynamics.kinematic_joints
 *     without a limit (MuJoCo velocity actuators, gain kv, implicit integration);
 *   - the stops at the qhat range widened by dynamics.stop_margin_deg;
 *   - the ball: 0.2 kg, a solid sphere's inertia, sphere + flattened base (scene.*);
 *   - the table box and the floor plane; only the dynamic world's contact pairs (robot-table for
 *     the links moved by motors, robot-ball and robot-base for every link, ball and base with the
 *     table and the floor; no robot-robot), friction dynamics.friction for the robot's and
 *     dynamics.table_friction for the object's, condim 3 (a pyramid, as dContactApprox1);
 *   - the sub-step dynamics.substep (10 ms), 5 per 50 ms control step; MuJoCo's defaults
 *     otherwise (Newton, 100 iterations, pyramidal cones) and noslip_iterations 3 (--noslip) so
 *     that it holds the ball.
 * It is checked against the library's model before anything runs: every body's frame at the 16
 * start postures and 100 random ones equal to 1e-6 m (MuJoCo's forward kinematics against
 * st_robot_fk_angles), every body's mass equal to 1e-9 kg (MuJoCo's fused bodies against the
 * sum of each moving link's and its fixed children's masses); any miss ends the program.
 *
 * Scenarios, as apps/bench.c: free (the 4 reach starts, the arm sweeping in the air: no robot
 * contact), press (the scripted controller's grasp from the 4 grasp starts, recorded once in
 * the library's world and replayed in both: the hand closing on the ball on the table) and held
 * (the 4 move starts, the ball in the hand, the table gone for the ball, commands frozen), N
 * control steps each. R rounds, each running every scenario in the library's world and then in
 * MuJoCo; a rate is control steps per CPU-second of the thread (the steps alone: resets apart),
 * per scenario the median over the rounds; a ball is kept when it ends above the table top. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <mujoco/mujoco.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "selftalk/config.h"
#include "selftalk/episode.h"
#include "selftalk/robot.h"
#include "selftalk/scripted.h"
#include "selftalk/trial.h"
#include "selftalk/world.h"
#include "press_plan.h"

static const char *prog = "compare";
enum { ST_COMPARE_MAXBODY = 256 };

static void die(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
static void die(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "%s: ", prog);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  exit(1);
}

static double thread_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* ---- text ------------------------------------------------------------------------------- */

typedef struct buf {
  char *s;
  size_t n, cap;
} buf;

static void put(buf *b, const char *s, size_t n) {
  if (b->n + n + 1 > b->cap) {
    b->cap = 2 * (b->n + n + 1);
    if (!(b->s = realloc(b->s, b->cap))) die("out of memory");
  }
  memcpy(b->s + b->n, s, n);
  b->n += n;
  b->s[b->n] = 0;
}

static void putf(buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void putf(buf *b, const char *fmt, ...) {
  char t[1024];
  va_list ap;
  va_start(ap, fmt);
  const int n = vsnprintf(t, sizeof t, fmt, ap);
  va_end(ap);
  if (n < 0 || (size_t)n >= sizeof t) die("line too long");
  put(b, t, (size_t)n);
}

static char *read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) die("cannot read %s", path);
  buf b = {NULL, 0, 0};
  char t[4096];
  size_t n;
  while ((n = fread(t, 1, sizeof t, f)) > 0) put(&b, t, n);
  fclose(f);
  return b.s;
}

static void write_file(const char *path, const char *s) {
  FILE *f = fopen(path, "wb");
  if (!f || fputs(s, f) < 0 || fclose(f)) die("cannot write %s", path);
}

/* ---- the two models --------------------------------------------------------------------- */

typedef struct hingeMap {
  int body;      /* the library's model body moved by the hinge */
  int dof;       /* its DOF */
  int kin;       /* an exact servo (dynamics.kinematic_joints) */
  double lo, hi; /* qhat range, rad */
  int qadr, dadr, act; /* MuJoCo: qpos and qvel address, actuator */
} hingeMap;

typedef struct mjWorld {
  mjModel *m;
  mjData *d;
  int ball_q, ball_body; /* the ball's free joint qpos address, its body */
} mjWorld;

typedef struct setup {
  stProtocol *p;
  stDynDef def;
  int nh;
  hingeMap h[64];
  mjModel *table, *notable; /* with and without the object's pairs with the table */
  double kv;
  int noslip;
} setup;

/* 1 when joint name is in the comma-separated list */
static int listed(const char *list, const char *name) {
  const size_t n = strlen(name);
  for (const char *s = list; *s;) {
    const char *e = strchr(s, ',');
    const size_t len = e ? (size_t)(e - s) : strlen(s);
    if (len == n && !strncmp(s, name, n)) return 1;
    s = e ? e + 1 : s + len;
  }
  return 0;
}

/* robot.xml as MuJoCo saved it, its geoms named r0, r1, ... (in order: MuJoCo's geom ids)
 * with no collision of their own (only the pairs collide), each hinge's range the library's
 * stops */
static char *edit_robot(const char *xml, const setup *su) {
  buf b = {NULL, 0, 0};
  int ng = 0;
  const stModel *md = su->p->robot->model;
  for (const char *s = xml; *s;) {
    const char *g = strstr(s, "<geom "), *j = strstr(s, "<joint ");
    const char *t = g && (!j || g < j) ? g : j;
    if (!t) {
      put(&b, s, strlen(s));
      break;
    }
    if (t == g) {
      put(&b, s, (size_t)(g - s) + 6);
      putf(&b, "name=\"r%d\" contype=\"0\" conaffinity=\"0\" ", ng++);
      s = g + 6;
      continue;
    }
    const char *end = strchr(j, '>'), *nm = strstr(j, "name=\""), *rg = strstr(j, "range=\"");
    if (!end || !nm || nm > end || !rg || rg > end) die("robot.xml: a joint without name or range");
    char name[ST_NAME_MAX];
    const char *q = strchr(nm + 6, '"');
    snprintf(name, sizeof name, "%.*s", (int)(q - nm - 6), nm + 6);
    const int body = st_model_joint(md, name);
    if (body < 0) die("robot.xml: joint %s unknown to the library's model", name);
    const double *r = su->p->robot->body_range[body];
    put(&b, s, (size_t)(rg - s) + 7);
    const double margin = su->def.stop_margin_deg * 3.14159265358979323846 / 180.0;
    putf(&b, "%.17g %.17g", r[0] - margin, r[1] + margin);
    s = strchr(rg + 7, '"');
  }
  return b.s;
}

/* the scene around robot.xml; with_table: the object's pairs with the table */
static char *scene_xml(const setup *su, const mjModel *m0, int with_table) {
  const stScene *sc = &su->p->scene;
  const stDynDef *df = &su->def;
  buf b = {NULL, 0, 0};
  putf(&b, "<mujoco model=\"libselftalk compare\">\n  <include file=\"robot.xml\"/>\n");
  putf(&b, "  <option timestep=\"%.17g\" gravity=\"0 0 %.17g\" integrator=\"implicit\" "
           "noslip_iterations=\"%d\"/>\n", df->substep, -df->gravity, su->noslip);
  putf(&b, "  <size nconmax=\"400\" njmax=\"2000\"/>\n  <worldbody>\n");
  putf(&b, "    <geom name=\"table\" type=\"box\" pos=\"%.17g %.17g %.17g\" size=\"%.17g %.17g "
           "%.17g\" contype=\"0\" conaffinity=\"0\"/>\n",
       0.5 * (sc->table_lo[0] + sc->table_hi[0]), 0.5 * (sc->table_lo[1] + sc->table_hi[1]),
       0.5 * (sc->table_lo[2] + sc->table_hi[2]), 0.5 * (sc->table_hi[0] - sc->table_lo[0]),
       0.5 * (sc->table_hi[1] - sc->table_lo[1]), 0.5 * (sc->table_hi[2] - sc->table_lo[2]));
  putf(&b, "    <geom name=\"floor\" type=\"plane\" pos=\"0 0 %.17g\" size=\"3 3 0.1\" "
           "contype=\"0\" conaffinity=\"0\"/>\n", df->floor_z);
  const double I = 0.4 * sc->obj_mass * sc->obj_radius * sc->obj_radius;
  putf(&b, "    <body name=\"object\" pos=\"0 0 1\">\n      <freejoint name=\"object\"/>\n"
           "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n"
           "      <geom name=\"ball\" type=\"sphere\" size=\"%.17g\" contype=\"0\" "
           "conaffinity=\"0\"/>\n", sc->obj_mass, I, I, I, sc->obj_radius);
  putf(&b, "      <geom name=\"base\" type=\"cylinder\" size=\"%.17g %.17g\" pos=\"0 0 %.17g\" "
           "contype=\"0\" conaffinity=\"0\"/>\n    </body>\n  </worldbody>\n  <actuator>\n",
       sc->base_radius, 0.5 * sc->base_height, -sc->obj_radius + 0.5 * sc->base_height);
  const stModel *md = su->p->robot->model;
  for (int i = 0; i < su->nh; i++) {
    const hingeMap *h = &su->h[i];
    const char *name = md->jnt_name[h->body];
    if (h->kin)
      putf(&b, "    <velocity name=\"%s\" joint=\"%s\" kv=\"%.17g\"/>\n", name, name, su->kv);
    else {
      const double f = md->jnt_effort[h->body] * df->effort_scale;
      putf(&b, "    <velocity name=\"%s\" joint=\"%s\" kv=\"%.17g\" forcelimited=\"true\" "
               "forcerange=\"%.17g %.17g\"/>\n", name, name, su->kv, -f, f);
    }
  }
  putf(&b, "  </actuator>\n  <contact>\n");
  for (int g = 0; g < m0->ngeom; g++) {
    const int bd = m0->geom_bodyid[g];
    int moved = 0; /* a link moved by a bounded motor: its contacts with the table act */
    if (bd > 0) {
      const int jn = m0->body_jntadr[bd];
      moved = jn >= 0 && !listed(df->kinematic_joints, mj_id2name(m0, mjOBJ_JOINT, jn));
    }
    if (moved)
      putf(&b, "    <pair geom1=\"r%d\" geom2=\"table\" condim=\"3\" friction=\"%.17g %.17g 0 0 0\"/>\n",
           g, df->friction, df->friction);
    putf(&b, "    <pair geom1=\"r%d\" geom2=\"ball\" condim=\"3\" friction=\"%.17g %.17g 0 0 0\"/>\n",
         g, df->friction, df->friction);
    putf(&b, "    <pair geom1=\"r%d\" geom2=\"base\" condim=\"3\" friction=\"%.17g %.17g 0 0 0\"/>\n",
         g, df->friction, df->friction);
  }
  const char *obj[2] = {"ball", "base"};
  for (int o = 0; o < 2; o++) {
    if (with_table)
      putf(&b, "    <pair geom1=\"%s\" geom2=\"table\" condim=\"3\" friction=\"%.17g %.17g 0 0 0\"/>\n",
           obj[o], df->table_friction, df->table_friction);
    putf(&b, "    <pair geom1=\"%s\" geom2=\"floor\" condim=\"3\" friction=\"%.17g %.17g 0 0 0\"/>\n",
         obj[o], df->table_friction, df->table_friction);
  }
  putf(&b, "  </contact>\n</mujoco>\n");
  return b.s;
}

/* every moving body's mass in the library's model: its link and the links fused to it by fixed
 * joints, as the dynamic world groups them */
static double group_mass(const stModel *md, int b) {
  double m = md->body_mass[b];
  for (int c = 1; c < md->nbody; c++)
    if (md->body_parent[c] == b && md->jnt_type[c] == ST_JOINT_FIXED) m += group_mass(md, c);
  return m;
}

/* MuJoCo's model of the scene: robot.xml from MuJoCo's import of the URDF, edited, and the
 * scene around it, in dir; checked against the library's model */
static void build_mujoco(setup *su, const char *dir) {
  char err[1024] = "", path[4200];
  const stModel *md = su->p->robot->model;
  if (strlen(dir) > 4000) die("--xml: a directory name shorter than 4000 characters");
  mjModel *m0 = mj_loadXML(su->p->cfg.robot_urdf, NULL, err, sizeof err);
  if (!m0) die("MuJoCo cannot import %s: %s", su->p->cfg.robot_urdf, err);
  snprintf(path, sizeof path, "%s/imported.xml", dir);
  if (!mj_saveLastXML(path, m0, err, sizeof err)) die("mj_saveLastXML: %s", err);
  /* hinges: the library's, mapped to MuJoCo's joints by name */
  su->nh = 0;
  for (int b = 1; b < md->nbody; b++) {
    if (md->jnt_type[b] != ST_JOINT_REVOLUTE) continue;
    hingeMap *h = &su->h[su->nh++];
    h->body = b;
    h->dof = su->p->robot->body_dof[b];
    h->kin = listed(su->def.kinematic_joints, md->jnt_name[b]);
    h->lo = su->p->robot->body_range[b][0];
    h->hi = su->p->robot->body_range[b][1];
  }
  char *imported = read_file(path), *robot = edit_robot(imported, su);
  snprintf(path, sizeof path, "%s/robot.xml", dir);
  write_file(path, robot);
  for (int with = 0; with < 2; with++) {
    char *xml = scene_xml(su, m0, with);
    snprintf(path, sizeof path, "%s/%s", dir, with ? "scene.xml" : "scene_notable.xml");
    write_file(path, xml);
    free(xml);
    mjModel *m = mj_loadXML(path, NULL, err, sizeof err);
    if (!m) die("MuJoCo cannot load the scene: %s", err);
    *(with ? &su->table : &su->notable) = m;
  }
  free(imported);
  free(robot);
  mjModel *m = su->table;
  for (int g = 0; g < m0->ngeom; g++) { /* the pairs' geoms are the geoms they were made for */
    char nm[16];
    snprintf(nm, sizeof nm, "r%d", g);
    const int id = mj_name2id(m, mjOBJ_GEOM, nm);
    if (id < 0 || strcmp(mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[id]) ? mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[id]) : "world",
                         mj_id2name(m0, mjOBJ_BODY, m0->geom_bodyid[g]) ? mj_id2name(m0, mjOBJ_BODY, m0->geom_bodyid[g]) : "world"))
      die("geom %s: not on the body it was named for", nm);
  }
  /* mj_saveLastXML writes 6 digits: the import's own frames, inertias and shapes, as compiled
   * from the URDF, are copied back into both models (then MuJoCo's derived constants again) */
  for (int with = 0; with < 2; with++) {
    mjModel *mm = with ? su->table : su->notable;
    for (int b = 1; b < m0->nbody; b++) {
      const int id = mj_name2id(mm, mjOBJ_BODY, mj_id2name(m0, mjOBJ_BODY, b));
      if (id < 0) die("body %s lost in the scene", mj_id2name(m0, mjOBJ_BODY, b));
      memcpy(mm->body_pos + 3 * id, m0->body_pos + 3 * b, 3 * sizeof(mjtNum));
      memcpy(mm->body_quat + 4 * id, m0->body_quat + 4 * b, 4 * sizeof(mjtNum));
      memcpy(mm->body_ipos + 3 * id, m0->body_ipos + 3 * b, 3 * sizeof(mjtNum));
      memcpy(mm->body_iquat + 4 * id, m0->body_iquat + 4 * b, 4 * sizeof(mjtNum));
      memcpy(mm->body_inertia + 3 * id, m0->body_inertia + 3 * b, 3 * sizeof(mjtNum));
      mm->body_mass[id] = m0->body_mass[b];
    }
    for (int g = 0; g < m0->ngeom; g++) {
      char nm[16];
      snprintf(nm, sizeof nm, "r%d", g);
      const int id = mj_name2id(mm, mjOBJ_GEOM, nm);
      memcpy(mm->geom_pos + 3 * id, m0->geom_pos + 3 * g, 3 * sizeof(mjtNum));
      memcpy(mm->geom_quat + 4 * id, m0->geom_quat + 4 * g, 4 * sizeof(mjtNum));
      memcpy(mm->geom_size + 3 * id, m0->geom_size + 3 * g, 3 * sizeof(mjtNum));
    }
    for (int j = 0; j < m0->njnt; j++) {
      const int id = mj_name2id(mm, mjOBJ_JOINT, mj_id2name(m0, mjOBJ_JOINT, j));
      memcpy(mm->jnt_pos + 3 * id, m0->jnt_pos + 3 * j, 3 * sizeof(mjtNum));
      memcpy(mm->jnt_axis + 3 * id, m0->jnt_axis + 3 * j, 3 * sizeof(mjtNum));
    }
    mjData *d = mj_makeData(mm);
    mj_setConst(mm, d);
    mj_deleteData(d);
  }
  mj_deleteModel(m0);
  for (int i = 0; i < su->nh; i++) {
    hingeMap *h = &su->h[i];
    const int jn = mj_name2id(m, mjOBJ_JOINT, md->jnt_name[h->body]);
    if (jn < 0) die("MuJoCo's model has no joint %s", md->jnt_name[h->body]);
    h->qadr = m->jnt_qposadr[jn];
    h->dadr = m->jnt_dofadr[jn];
    h->act = mj_name2id(m, mjOBJ_ACTUATOR, md->jnt_name[h->body]);
  }
}

/* the checks: frames at the postures, masses */
static void check_model(const setup *su) {
  const stRobot *r = su->p->robot;
  const stModel *md = r->model;
  const mjModel *m = su->table;
  mjData *d = mj_makeData(m);
  double *ang = malloc(sizeof(double) * (size_t)r->nbody), (*R)[9] = malloc(sizeof(double[9]) * (size_t)r->nbody);
  double (*P)[3] = malloc(sizeof(double[3]) * (size_t)r->nbody);
  double dmax = 0, mmax = 0;
  int nbodies = 0, nposture = 0;
  unsigned long long rs = 0x9e3779b97f4a7c15ull;
  for (int t = 0; t < ST_NPRIM * ST_NPOSTURE + 100; t++) {
    double qhat[ST_NDOF];
    if (t < ST_NPRIM * ST_NPOSTURE) memcpy(qhat, su->p->posture[t / ST_NPOSTURE][t % ST_NPOSTURE], sizeof qhat);
    else
      for (int k = 0; k < ST_NDOF; k++) { /* xorshift: random postures over the whole range */
        rs ^= rs << 13, rs ^= rs >> 7, rs ^= rs << 17;
        qhat[k] = (double)(rs >> 11) / 9007199254740992.0;
      }
    st_robot_angles(r, qhat, ang);
    st_robot_fk_angles(r, ang, R, P);
    mj_resetData(m, d);
    for (int i = 0; i < su->nh; i++) d->qpos[su->h[i].qadr] = ang[su->h[i].body];
    mj_kinematics(m, d);
    for (int b = 1; b < m->nbody; b++) {
      const int lb = st_model_body(md, mj_id2name(m, mjOBJ_BODY, b));
      if (lb < 0) continue; /* the ball */
      for (int k = 0; k < 3; k++) {
        const double e = fabs(d->xpos[3 * b + k] - P[lb][k]);
        if (!(e <= dmax)) dmax = e;
      }
      if (t == 0) {
        const double e = fabs(m->body_mass[b] - group_mass(md, lb));
        if (!(e <= mmax)) mmax = e;
        nbodies++;
      }
    }
    nposture++;
  }
  int moving = 0;
  for (int b = 1; b < md->nbody; b++) moving += md->jnt_type[b] == ST_JOINT_REVOLUTE;
  printf("model: MuJoCo %d.%d.%d imported %s: %d moving bodies (the library's: %d), %d hinges, "
         "%d geoms, %d contact pairs; frames at %d postures max |dp| %.2g m (<= 1e-6), masses "
         "max |dm| %.2g kg (<= 1e-9)\n", mj_version() / 100, mj_version() / 10 % 10,
         mj_version() % 10, su->p->cfg.robot_urdf, nbodies, moving, m->njnt - 1, m->ngeom,
         m->npair, nposture, dmax, mmax);
  fflush(stdout);
  free(ang), free(R), free(P);
  mj_deleteData(d);
  if (nbodies != moving || !(dmax <= 1e-6) || !(mmax <= 1e-9)) die("the models differ");
}

/* ---- the scenarios ------------------------------------------------------------------------ */

enum { FREE = 0, PRESS, HELD, NSCEN };
static const char *scen_name[NSCEN] = {"free", "press", "held"};

/* one trial: start posture, object, commands per step (steps x ST_NDOF), the table's pairs
 * with the object */
typedef struct trialPlan {
  double q0[ST_NDOF], obj[3], target[3];
  double *y;
  int table;
} trialPlan;

/* press, as apps/bench.c plans it (apps/press_plan.h) */
static void press_plan(const setup *su, int k, int steps, trialPlan *tp) {
  char err[1024];
  tp->y = malloc(sizeof(double) * ST_NDOF * (size_t)steps);
  if (!tp->y) die("out of memory");
  if (st_press_plan(su->p, &su->def, k, steps, tp->q0, tp->obj, tp->target, tp->y, err, sizeof err))
    die("press: %s", err);
  tp->table = 1;
}

static void make_plans(const setup *su, int steps, trialPlan plans[NSCEN][ST_NPOSTURE]) {
  const stProtocol *p = su->p;
  for (int k = 0; k < ST_NPOSTURE; k++) {
    trialPlan *f = &plans[FREE][k], *h = &plans[HELD][k];
    /* free: a reach start, the arm and hand sweeping slowly about it (< 0.05 of each range) */
    memcpy(f->q0, p->posture[ST_PRIM_REACH][k], sizeof f->q0);
    memcpy(f->obj, p->scene.obj_pos[k], sizeof f->obj);
    memcpy(f->target, p->scene.target[k % 2], sizeof f->target);
    f->y = malloc(sizeof(double) * ST_NDOF * (size_t)steps);
    for (int t = 0; t < steps; t++)
      for (int d = 0; d < ST_NDOF; d++) {
        const double v = f->q0[d] + 0.05 * sin(6.283185307179586 * t / 40.0 + d);
        f->y[ST_NDOF * t + d] = v < 0 ? 0 : v > 1 ? 1 : v;
      }
    f->table = 1;
    press_plan(su, k, steps, &plans[PRESS][k]);
    /* held: a move start, the ball in the hand, the table gone for it, commands frozen */
    memcpy(h->q0, p->posture[ST_PRIM_MOVE][k], sizeof h->q0);
    memcpy(h->obj, p->scene.obj_pos[k], sizeof h->obj);
    memcpy(h->target, p->scene.target[k % 2], sizeof h->target);
    h->y = malloc(sizeof(double) * ST_NDOF * (size_t)steps);
    for (int t = 0; t < steps; t++) memcpy(h->y + ST_NDOF * t, h->q0, sizeof h->q0);
    h->table = 0;
  }
}

/* what a scenario's trials did in one engine, one round */
typedef struct result {
  double cpu;    /* thread CPU seconds of the steps */
  long steps, kept, contacts, substeps_contact, substeps;
} result;

/* the library's world: a trial; the steps timed, the reset not */
static void ours_trial(stWorld *w, const setup *su, const trialPlan *tp, int steps, result *res) {
  st_world_set_seed(w, 1);
  st_world_reset(w, tp->q0, tp->obj, tp->target);
  if (!tp->table) st_world_set_object_table_collision(w, 0);
  double y[ST_NET_MAX_OUT] = {0};
  const double c0 = thread_cpu();
  int t = 0;
  for (; t < steps && !st_world_unstable(w); t++) {
    memcpy(y, tp->y + ST_NDOF * t, sizeof(double) * ST_NDOF);
    st_world_step_dynamic(w, y);
  }
  res->cpu += thread_cpu() - c0;
  res->steps += t;
  res->kept += !st_world_unstable(w) && w->obj[2] > su->p->scene.table_hi[2];
  stDynInfo in;
  st_world_dynamic_info(w, &in);
  for (int k = 0; k < ST_DYN_PAIR_COUNT; k++) res->contacts += in.contact_points[k];
  res->substeps_contact += in.dyn_substeps;
  res->substeps += (long)in.substeps * w->step;
}

/* MuJoCo: the same trial; every sub-step the servo velocities from the hinges' angles */
static void mj_trial(mjWorld *mw, const setup *su, const trialPlan *tp, int steps, result *res) {
  const mjModel *m = mw->m;
  mjData *d = mw->d;
  const stRobot *r = su->p->robot;
  double ang[ST_COMPARE_MAXBODY];
  st_robot_angles(r, tp->q0, ang);
  mj_resetData(m, d);
  for (int i = 0; i < su->nh; i++) d->qpos[su->h[i].qadr] = ang[su->h[i].body];
  double *bq = d->qpos + mw->ball_q;
  bq[0] = tp->obj[0], bq[1] = tp->obj[1], bq[2] = tp->obj[2];
  bq[3] = 1, bq[4] = bq[5] = bq[6] = 0;
  mj_forward(m, d);
  const int nsub = (int)floor(r->dt / su->def.substep + 0.5);
  const double alpha = r->alpha_dynamic * 3.14159265358979323846 / 180.0, vmax = r->max_velocity;
  const double c0 = thread_cpu();
  int t = 0, bad = 0;
  for (; t < steps && !bad; t++) {
    const double *y = tp->y + ST_NDOF * t;
    for (int s = 0; s < nsub; s++) {
      for (int i = 0; i < su->nh; i++) { /* the library's servo law (lib/world/dyn_step.c) */
        const hingeMap *h = &su->h[i];
        double yd = y[h->dof];
        yd = yd < 0 ? 0 : yd > 1 ? 1 : yd;
        double v = alpha * (yd - (d->qpos[h->qadr] - h->lo) / (h->hi - h->lo));
        d->ctrl[h->act] = v > vmax ? vmax : v < -vmax ? -vmax : v;
      }
      mj_step(m, d);
      res->contacts += d->ncon;
      res->substeps++;
    }
    for (int i = 0; i < m->nq; i++) bad |= !isfinite(d->qpos[i]);
  }
  res->cpu += thread_cpu() - c0;
  res->steps += t;
  res->kept += !bad && d->xpos[3 * mw->ball_body + 2] > su->p->scene.table_hi[2];
}

static void usage(void) {
  fprintf(stderr, "usage: %s [--rounds R] [--steps N] [--set k=v[;k=v...]] [--config FILE] "
                  "[--noslip N] [--kv KV] [--xml DIR] [--check-only]\n", prog);
  exit(2);
}

int main(int argc, char **argv) {
  int rounds = 10, steps = 60, check_only = 0;
  const char *sets = "", *config = NULL, *xmldir = NULL;
  setup su;
  memset(&su, 0, sizeof su);
  su.kv = 1e4;
  su.noslip = 3;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--check-only")) check_only = 1;
    else if (!v) usage();
    else if (!strcmp(a, "--rounds")) rounds = atoi(v), i++;
    else if (!strcmp(a, "--steps")) steps = atoi(v), i++;
    else if (!strcmp(a, "--set")) sets = v, i++;
    else if (!strcmp(a, "--config")) config = v, i++;
    else if (!strcmp(a, "--noslip")) su.noslip = atoi(v), i++;
    else if (!strcmp(a, "--kv")) su.kv = atof(v), i++;
    else if (!strcmp(a, "--xml")) xmldir = v, i++;
    else usage();
  }
  if (rounds < 1 || steps < 1 || su.noslip < 0 || !(su.kv > 0)) usage();
  char err[1024];
  stConfig cfg;
  st_config_default(&cfg);
  if (config && st_config_load(config, &cfg, err, sizeof err)) die("%s", err);
  char setbuf[1024];
  snprintf(setbuf, sizeof setbuf, "%s", sets);
  for (char *save = NULL, *kv = strtok_r(setbuf, ";", &save); kv; kv = strtok_r(NULL, ";", &save))
    if (st_config_set(&cfg, kv, err, sizeof err)) die("--set: %s", err);
  if (st_protocol_create(&cfg, &su.p, err, sizeof err)) die("%s", err);
  if (su.p->robot->nbody > ST_COMPARE_MAXBODY) die("more than %d links", ST_COMPARE_MAXBODY);
  st_dyn_def_from_config(&cfg, &su.def);
  char tmp[] = "/tmp/selftalk_compare_XXXXXX", dir[4001];
  if (!mkdtemp(tmp)) die("mkdtemp failed");
  if (strlen(xmldir ? xmldir : tmp) >= sizeof dir) die("--xml: a shorter directory name");
  snprintf(dir, sizeof dir, "%s", xmldir ? xmldir : tmp);
  if (xmldir) mkdir(xmldir, 0777);
  build_mujoco(&su, dir);
  check_model(&su);
  if (!xmldir) {
    char path[4200];
    const char *files[] = {"imported.xml", "robot.xml", "scene.xml", "scene_notable.xml"};
    for (int i = 0; i < 4; i++) snprintf(path, sizeof path, "%s/%s", tmp, files[i]), unlink(path);
    rmdir(tmp);
  }
  if (check_only) {
    mj_deleteModel(su.table);
    mj_deleteModel(su.notable);
    st_protocol_destroy(su.p);
    return 0;
  }

  trialPlan (*plans)[ST_NPOSTURE] = calloc(NSCEN, sizeof *plans);
  make_plans(&su, steps, plans);
  stWorld *w = NULL;
  if (st_world_create_dynamic(su.p->robot, &su.p->scene, &su.def, &w, err, sizeof err))
    die("%s", err);
  mjWorld mw[2];
  for (int i = 0; i < 2; i++) {
    mw[i].m = i ? su.table : su.notable;
    mw[i].d = mj_makeData(mw[i].m);
    const int fj = mj_name2id(mw[i].m, mjOBJ_JOINT, "object");
    mw[i].ball_q = mw[i].m->jnt_qposadr[fj];
    mw[i].ball_body = mw[i].m->jnt_bodyid[fj];
  }
  double *rate[2][NSCEN];
  result tot[2][NSCEN];
  memset(tot, 0, sizeof tot);
  for (int e = 0; e < 2; e++)
    for (int s = 0; s < NSCEN; s++) rate[e][s] = calloc((size_t)rounds, sizeof(double));
  for (int r = 0; r < rounds; r++) /* interleaved: a drift in the machine's load hits both */
    for (int s = 0; s < NSCEN; s++)
      for (int e = 0; e < 2; e++) {
        result res;
        memset(&res, 0, sizeof res);
        for (int k = 0; k < ST_NPOSTURE; k++) {
          const trialPlan *tp = &plans[s][k];
          if (e == 0) ours_trial(w, &su, tp, steps, &res);
          else mj_trial(&mw[tp->table], &su, tp, steps, &res);
        }
        rate[e][s][r] = (double)res.steps / res.cpu;
        tot[e][s].steps += res.steps, tot[e][s].kept += res.kept, tot[e][s].contacts += res.contacts;
        tot[e][s].substeps_contact += res.substeps_contact, tot[e][s].substeps += res.substeps;
      }
  double ratio[NSCEN];
  const long trials = (long)rounds * ST_NPOSTURE;
  printf("libselftalk: %s%s; MuJoCo: implicit, Newton, noslip %d, velocity servos kv %g; %d "
         "rounds x %d trials x %d steps per scenario, control steps per CPU-second (median)\n",
         st_config_enum_name("dynamics", "lcp", su.def.lcp), sets[0] ? "" : " (the default)",
         su.noslip, su.kv, rounds, ST_NPOSTURE, steps);
  for (int s = 0; s < NSCEN; s++) {
    double med[2];
    for (int e = 0; e < 2; e++) {
      qsort(rate[e][s], (size_t)rounds, sizeof(double), cmp_double);
      med[e] = rounds % 2 ? rate[e][s][rounds / 2]
                          : 0.5 * (rate[e][s][rounds / 2 - 1] + rate[e][s][rounds / 2]);
    }
    ratio[s] = med[0] / med[1];
    printf("scenario=%s libselftalk=%.0f mujoco=%.0f ratio=%.2f kept=%ld/%ld mujoco_kept=%ld/%ld "
           "robot_in_ode=%.0f%% contacts_per_substep=%.2f mujoco_contacts_per_substep=%.2f\n",
           scen_name[s], med[0], med[1], ratio[s], tot[0][s].kept, trials, tot[1][s].kept, trials,
           100.0 * (double)tot[0][s].substeps_contact / (double)tot[0][s].substeps,
           (double)tot[0][s].contacts / (double)tot[0][s].substeps,
           (double)tot[1][s].contacts / (double)tot[1][s].substeps);
  }
  printf("compare: press %.2f held %.2f free %.2f (libselftalk / MuJoCo, per CPU-second, same run)\n",
         ratio[PRESS], ratio[HELD], ratio[FREE]);
  for (int e = 0; e < 2; e++)
    for (int s = 0; s < NSCEN; s++) free(rate[e][s]);
  for (int s = 0; s < NSCEN; s++)
    for (int k = 0; k < ST_NPOSTURE; k++) free(plans[s][k].y);
  free(plans);
  for (int i = 0; i < 2; i++) mj_deleteData(mw[i].d);
  mj_deleteModel(su.table);
  mj_deleteModel(su.notable);
  st_world_destroy(w);
  st_protocol_destroy(su.p);
  return 0;
}
