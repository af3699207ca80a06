/* SPDX-License-Identifier: MIT
 * The dynamic world's creation (lib/world/dynworld.c has the map of its files): ODE's world, the
 * robot's links grouped into bodies with their masses, the hinges with their stops and motors,
 * the geometries, the table, floor and object, the exact servos (dynamics.kinematic_joints and
 * adaptive_joints); and the check, once per process, that quickstep's shuffling reaches the
 * world's own generator. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/model_internal.h"
#include "world/dynworld.h"
#include "world/ode_util.h"

/* ---- the interposition check ----------------------------------------------------------- */

/* quickstep's shuffling draws of the probe world in ODE 0.16.2 (12 constraint rows, 20
 * iterations: the rows are shuffled at iterations 8 and 16, a draw per row but the last) */
enum { PROBE_QUICKSTEP_DRAWS = 22 };

static pthread_once_t g_rand_once = PTHREAD_ONCE_INIT;
static const char *g_rand_why; /* NULL: quickstep draws from the world's own generator */
static char g_rand_why_buf[512];

/* one quickstep of the probe world, drawing from the library's generator (the program's own
 * generator is not touched): ODE 0.16.2's shuffling must reach it, that many times */
static void rand_check(void) {
  if (!st__ode_rand_bound()) {
    g_rand_why = "ODE's dRandInt cannot reach the library's per-thread generator in a program "
                 "linked with the shared library, which exports only the st_ API (link the "
                 "static library, as the apps do)";
    return;
  }
  const unsigned long before = st__ode_rand_calls();
  st__ode_rand_begin(0);
  st__ode_messages_begin();
  st__ode_probe_step(1);
  st__ode_messages_end();
  st__ode_rand_end();
  const unsigned long draws = st__ode_rand_calls() - before;
  if (!draws)
    g_rand_why = "ODE's dRandInt does not reach the library's per-thread generator in this "
                 "build (ODE binds it internally)";
  else if (draws != PROBE_QUICKSTEP_DRAWS) {
    snprintf(g_rand_why_buf, sizeof g_rand_why_buf, "ODE's quickstep drew %lu numbers in the "
             "probe step where ODE 0.16.2 draws %d: the ODE loaded (%s) is not the one the "
             "per-thread generator was written for", draws, (int)PROBE_QUICKSTEP_DRAWS,
             dGetConfiguration());
    g_rand_why = g_rand_why_buf;
  }
}

int st__dyn_rand_interposed(void) {
  pthread_once(&g_rand_once, rand_check);
  return g_rand_why == NULL;
}

/* ---- creation ---------------------------------------------------------------------------- */

/* inertia about the centre of mass must be symmetric positive definite */
static int inertia_ok(const double *I) {
  for (int i = 0; i < 9; i++)
    if (!isfinite(I[i])) return 0;
  double m1 = I[0], m2 = I[0] * I[4] - I[1] * I[3];
  double m3 = I[0] * (I[4] * I[8] - I[5] * I[7]) - I[1] * (I[3] * I[8] - I[5] * I[6]) +
              I[2] * (I[3] * I[7] - I[4] * I[6]);
  return m1 > 0 && m2 > 0 && m3 > 0;
}

/* links into bodies: a revolute joint starts one, a fixed joint folds its child into its
 * parent's (link_R, link_p: the child's frame in the first link's) */
static void group_links(dynInternal *d, const stModel *m) {
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  d->link_group[0] = -1;
  memcpy(d->link_R[0], I3, sizeof I3);
  for (int b = 1; b < m->nbody; b++) {
    const int pb = m->body_parent[b];
    if (m->jnt_type[b] == ST_JOINT_FIXED) {
      d->link_group[b] = d->link_group[pb];
      st__mat3_mul(d->link_R[pb], m->jnt_rot[b], d->link_R[b]);
      double o[3];
      st__mat3_vec(d->link_R[pb], m->jnt_pos[b], o);
      for (int i = 0; i < 3; i++) d->link_p[b][i] = d->link_p[pb][i] + o[i];
    } else {
      d->glink[d->ngroup] = b;
      d->link_group[b] = d->ngroup++;
      memcpy(d->link_R[b], I3, sizeof I3);
    }
  }
}

/* world poses (w->R, w->p) at zero joint angles: hinges measure their angle from this pose */
static void zero_pose(stWorld *w, dynInternal *d) {
  for (int b = 0; b < w->robot->model->nbody; b++) d->angle[b] = 0.0;
  st_robot_fk_angles(w->robot, d->angle, w->R, w->p);
}

/* mass M of body g, the sum of its links', and their common centre of mass C in the first
 * link's frame */
static stStatus body_mass(const dynInternal *d, const stModel *m, int g, double *M_out,
                          double C[3], char *err, size_t errsz) {
  double M = 0;
  C[0] = C[1] = C[2] = 0;
  for (int b = 0; b < m->nbody; b++) {
    if (d->link_group[b] != g || !(m->body_mass[b] > 0)) continue;
    double c[3];
    st__mat3_vec(d->link_R[b], m->body_com[b], c);
    for (int i = 0; i < 3; i++) C[i] += m->body_mass[b] * (c[i] + d->link_p[b][i]);
    M += m->body_mass[b];
  }
  const int gl = d->glink[g];
  if (!(M > 0 && isfinite(M))) {
    st__errf(err, errsz, "link '%s' (joint '%s'): no mass on a moving link and its fixed "
             "children (expected mass > 0)", m->body_name[gl], m->jnt_name[gl]);
    return ST_ERR_MODEL;
  }
  for (int i = 0; i < 3; i++) C[i] /= M;
  *M_out = M;
  return ST_OK;
}

/* inertia I of body g about its centre of mass C, in the first link's axes: its links'
 * inertias rotated and moved there (parallel axes) */
static stStatus body_inertia(const dynInternal *d, const stModel *m, int g, const double C[3],
                             double I[9], char *err, size_t errsz) {
  for (int i = 0; i < 9; i++) I[i] = 0;
  for (int b = 0; b < m->nbody; b++) {
    if (d->link_group[b] != g || !(m->body_mass[b] > 0)) continue;
    const double mb = m->body_mass[b];
    double c[3], T[9], RI[9], Rt[9];
    st__mat3_vec(d->link_R[b], m->body_com[b], c);
    for (int i = 0; i < 3; i++) c[i] += d->link_p[b][i] - C[i];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) Rt[3 * i + j] = d->link_R[b][3 * j + i];
    st__mat3_mul(d->link_R[b], m->body_inertia[b], RI);
    st__mat3_mul(RI, Rt, T); /* R I R^T */
    const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        I[3 * i + j] += T[3 * i + j] + mb * ((i == j ? c2 : 0.0) - c[i] * c[j]);
  }
  if (!inertia_ok(I)) {
    st__errf(err, errsz, "link '%s': inertia of the moving body is not positive definite "
             "(expected a physical inertia tensor)", m->body_name[d->glink[g]]);
    return ST_ERR_MODEL;
  }
  return ST_OK;
}

/* an ODE body per group of links, with its mass, where the zero pose puts it */
static stStatus create_bodies(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  for (int g = 0; g < d->ngroup; g++) {
    double M, C[3], I[9];
    stStatus st = body_mass(d, w->robot->model, g, &M, C, err, errsz);
    if (!st) st = body_inertia(d, w->robot->model, g, C, I, err, errsz);
    if (st) return st;
    memcpy(d->gcom[g], C, sizeof C);
    d->gbody[g] = dBodyCreate(d->world);
    dMass ms;
    dMassSetZero(&ms);
    dMassSetParameters(&ms, M, 0, 0, 0, I[0], I[4], I[8], I[1], I[2], I[5]);
    dBodySetMass(d->gbody[g], &ms);
    st__dyn_place_body(w, g);
  }
  return ST_OK;
}

/* the hinge of link b: anchored at the joint origin, axis from the model, stops stop_margin
 * outside the qhat range, a velocity motor of torque up to the URDF effort times effort_scale */
static stStatus create_hinge(stWorld *w, dynInternal *d, int b, char *err, size_t errsz) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  const double lo = r->body_range[b][0], hi = r->body_range[b][1];
  const double effort = m->jnt_effort[b] * d->def.effort_scale;
  const double *a = m->jnt_axis[b];
  const double an = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(isfinite(lo) && isfinite(hi) && lo < hi && hi - lo < 2 * ST_PI) ||
      !(effort >= 0 && isfinite(effort)) || !(an > 1e-9 && isfinite(an))) {
    st__errf(err, errsz, "joint '%s': range %g..%g rad, effort %g N m, axis norm %g (expected "
             "a finite range narrower than 360 degrees, a finite effort >= 0 and an axis)",
             m->jnt_name[b], lo, hi, effort, an);
    return ST_ERR_MODEL;
  }
  const int pg = d->link_group[m->body_parent[b]];
  dJointID j = dJointCreateHinge(d->world, 0);
  dJointAttach(j, d->gbody[d->link_group[b]], pg >= 0 ? d->gbody[pg] : 0);
  dJointSetHingeAnchor(j, w->p[b][0], w->p[b][1], w->p[b][2]);
  double ax[3];
  st__mat3_vec(w->R[b], a, ax);
  dJointSetHingeAxis(j, ax[0], ax[1], ax[2]);
  dJointSetHingeParam(j, dParamLoStop, lo - d->stop_margin);
  dJointSetHingeParam(j, dParamHiStop, hi + d->stop_margin);
  dJointSetHingeParam(j, dParamFudgeFactor, d->def.fudge_factor);
  dJointSetHingeParam(j, dParamStopERP, d->def.erp);
  dJointSetHingeParam(j, dParamStopCFM, d->def.cfm);
  dJointSetHingeParam(j, dParamCFM, d->def.cfm);
  dJointSetHingeParam(j, dParamVel, 0.0);
  dJointSetHingeParam(j, dParamFMax, effort);
  dynHinge *hg = &d->hinge[d->nhinge++];
  hg->fmax = effort;
  if (d->def.motor_active_set) dJointSetFeedback(j, &hg->fb);
  hg->j = j;
  hg->link = b;
  hg->dof = r->body_dof[b];
  hg->lo = lo;
  hg->hi = hi;
  hg->lo_set = lo - d->stop_margin;
  hg->hi_set = hi + d->stop_margin;
  return ST_OK;
}

static stStatus create_hinges(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  const stModel *m = w->robot->model;
  for (int b = 1; b < m->nbody; b++) {
    if (m->jnt_type[b] != ST_JOINT_REVOLUTE) continue;
    stStatus st = create_hinge(w, d, b, err, errsz);
    if (st) return st;
  }
  return ST_OK;
}

/* geometry i on its body, with the offset of its link and of the body's centre of mass (on
 * the static root: placed in the world, whose frame the root's is) */
static void attach_geom(stWorld *w, dynInternal *d, int i) {
  const stRobot *r = w->robot;
  const stModel *m = r->model;
  const int l = m->geom_body[i], g = d->link_group[l];
  dGeomID geom = d->geoms.g[i];
  double gp[3], gR[9];
  st__mat3_vec(d->link_R[l], m->geom_pos[i], gp);
  for (int k = 0; k < 3; k++) gp[k] += d->link_p[l][k];
  st__mat3_mul(d->link_R[l], m->geom_rot[i], gR);
  dMatrix3 Ro;
  st__mat3_to_ode(gR, Ro);
  if (g >= 0) {
    dGeomSetBody(geom, d->gbody[g]);
    dGeomSetOffsetRotation(geom, Ro);
    dGeomSetOffsetPosition(geom, gp[0] - d->gcom[g][0], gp[1] - d->gcom[g][1],
                           gp[2] - d->gcom[g][2]);
  } else {
    dGeomSetRotation(geom, Ro);
    dGeomSetPosition(geom, gp[0], gp[1], gp[2]);
  }
  dynGeom *dg = &d->geom[i];
  dg->link = l;
  dg->dyn = g >= 0;
  dg->is_arm = r->body_is_arm[l];
  dg->touch = r->body_touch[l];
}

/* the robot's geometries (lib/world/world_geom.c), each attached */
static stStatus create_geoms(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  stStatus st = st__robot_geoms_create(w->robot->model, 1, &d->geoms, err, errsz);
  if (st) return st;
  for (int i = 0; i < d->geoms.n; i++) attach_geom(w, d, i);
  return ST_OK;
}

/* scene: table, floor, and the object (sphere + flattened base, one body) */
static stStatus create_scene(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  const stScene *sc = w->scene;
  if (!(sc->obj_radius > 0 && sc->obj_mass > 0 && sc->base_radius >= 0 && sc->base_height >= 0 &&
        sc->base_height <= 2 * sc->obj_radius)) {
    st__errf(err, errsz, "scene: object radius %g, mass %g, base %g x %g (expected positive "
             "radius and mass, a base inside the sphere's height)", sc->obj_radius, sc->obj_mass,
             sc->base_radius, sc->base_height);
    return ST_ERR_RANGE;
  }
  const double *lo = sc->table_lo, *hi = sc->table_hi;
  if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2])) {
    st__errf(err, errsz, "scene: empty table box (expected min < max on every axis)");
    return ST_ERR_RANGE;
  }
  st__scene_geoms_create(sc, &d->scene);
  dGeomGetAABB(d->scene.table, d->table_aabb);
  d->floor = dCreatePlane(0, 0, 0, 1, d->def.floor_z);
  d->ball = dBodyCreate(d->world);
  dMass ms;
  dMassSetSphereTotal(&ms, sc->obj_mass, sc->obj_radius);
  dBodySetMass(d->ball, &ms);
  dGeomSetBody(d->scene.ball, d->ball);
  if (d->scene.base) {
    dGeomSetBody(d->scene.base, d->ball);
    dGeomSetOffsetPosition(d->scene.base, 0, 0, -sc->obj_radius + 0.5 * sc->base_height);
  }
  return ST_OK;
}

/* dynamics.kinematic_joints: those hinges become exact servos (joint disabled, body kinematic).
 * They must be the chain's first hinges (hinges are in model order, parents first), so that
 * every kinematic body's parent is the static root or kinematic itself. */
static stStatus mark_kinematic(dynInternal *d, const stModel *m, char *err, size_t errsz) {
  enum { MAX_KIN = 64 };
  char names[MAX_KIN][ST_NAME_MAX];
  const int n = st__split_names(d->def.kinematic_joints, names, MAX_KIN);
  if (n < 0 || n > d->nhinge || n > MAX_KIN) {
    st__errf(err, errsz, "dynamics.kinematic_joints: '%s' (expected at most the model's %d hinge "
             "names, each shorter than %d characters)", d->def.kinematic_joints, d->nhinge,
             ST_NAME_MAX);
    return ST_ERR_RANGE;
  }
  for (int k = 0; k < n; k++) {
    const char *need = m->jnt_name[d->hinge[k].link];
    int listed = 0;
    for (int j = 0; j < n; j++) listed |= !strcmp(names[j], need);
    if (!listed) {
      st__errf(err, errsz, "dynamics.kinematic_joints: '%s' names %d joints but not '%s' "
               "(expected the chain's first %d hinges, each once)", d->def.kinematic_joints, n,
               need, n);
      return ST_ERR_RANGE;
    }
  }
  for (int k = 0; k < n; k++) {
    d->hinge[k].kin = 1;
    dJointDisable(d->hinge[k].j);
    dBodySetKinematic(d->gbody[k]);
  }
  d->nkin = n;
  return ST_OK;
}

/* dynamics.adaptive_joints: hinges after those of kinematic_joints, in chain order, that are
 * exact servos while the torque they need stays within their limit (st__dyn_set_kin switches
 * them) */
static stStatus mark_adaptive(dynInternal *d, const stModel *m, char *err, size_t errsz) {
  enum { MAX_AD = 16 };
  char names[MAX_AD][ST_NAME_MAX];
  const int n = st__split_names(d->def.adaptive_joints, names, MAX_AD);
  d->nkin0 = d->nkin;
  if (n < 0 || n > MAX_AD || d->nkin + n > d->nhinge) {
    st__errf(err, errsz, "dynamics.adaptive_joints: '%s' (expected at most %d hinge names, each "
             "shorter than %d characters)", d->def.adaptive_joints, MAX_AD, ST_NAME_MAX);
    return ST_ERR_RANGE;
  }
  for (int k = 0; k < n; k++) {
    const int i = d->nkin + k;
    const char *need = m->jnt_name[d->hinge[i].link];
    const int pg = d->link_group[m->body_parent[d->hinge[i].link]];
    if (strcmp(names[k], need) || pg != i - 1 || d->hinge[i].fmax <= 0.0) {
      st__errf(err, errsz, "dynamics.adaptive_joints: '%s': joint %d is '%s' (expected the %d "
               "powered hinges that follow dynamics.kinematic_joints along the chain, in order: "
               "'%s' here)", d->def.adaptive_joints, k + 1, names[k], n, need);
      return ST_ERR_RANGE;
    }
  }
  d->nadapt = n;
  if (n && d->solver != ST_DYN_STEP) {
    st__errf(err, errsz, "dynamics.adaptive_joints: '%s' with solver quickstep (expected solver "
             "step)", d->def.adaptive_joints);
    return ST_ERR_RANGE;
  }
  for (int g = 0; g < d->ngroup; g++) dBodySetData(d->gbody[g], (void *)(intptr_t)(g + 1));
  if (n)
    for (int i = 0; i < d->nhinge; i++)
      if (!d->hinge[i].kin) dJointSetFeedback(d->hinge[i].j, &d->hinge[i].fb);
  return ST_OK;
}

/* the whole ODE world, phase by phase */
static stStatus build(stWorld *w, dynInternal *d, char *err, size_t errsz) {
  group_links(d, w->robot->model);
  zero_pose(w, d);
  stStatus st = create_bodies(w, d, err, errsz);
  if (!st) st = create_hinges(w, d, err, errsz);
  if (!st) st = create_geoms(w, d, err, errsz);
  if (!st) st = create_scene(w, d, err, errsz);
  if (!st) st = mark_kinematic(d, w->robot->model, err, errsz);
  if (!st) st = mark_adaptive(d, w->robot->model, err, errsz);
  return st;
}

/* d->field = calloc(n, its element size), 1 when it was allocated */
#define ALLOC(field, n) ((d->field = calloc((n), sizeof *d->field)) != NULL)

/* the per-body and per-geometry arrays, each tried (st__dyn_destroy frees those allocated); 0
 * when one is out of memory */
static int alloc_arrays(dynInternal *d, const stModel *m) {
  const size_t nb = (size_t)m->nbody, ng = (size_t)m->ngeom + 1, nc = ST_DYN_MAX_CFB;
  return ALLOC(gbody, nb) & ALLOC(glink, nb) & ALLOC(gcom, nb) & ALLOC(link_group, nb) &
         ALLOC(link_R, nb) & ALLOC(link_p, nb) & ALLOC(hinge, nb) & ALLOC(angle, nb) &
         ALLOC(vel, nb) & ALLOC(saved, nb + 1) & ALLOC(geom, ng) & ALLOC(want_kin, nb) &
         ALLOC(vprev, nb) & ALLOC(cpos, nb) & ALLOC(cfb, nc) & ALLOC(cfb_body, nc) &
         ALLOC(cfb_side, nc);
}
#undef ALLOC

/* the ODE world with its own threading implementation, its contact group and the parameters of
 * the [dynamics] keys; 0 when out of memory */
static int create_ode_world(dynInternal *d) {
  const stDynDef *def = &d->def;
  d->world = dWorldCreate();
  d->threading = dThreadingAllocateSelfThreadedImplementation();
  if (!d->threading) return 0;
  dWorldSetStepThreadingImplementation(d->world, dThreadingImplementationGetFunctions(d->threading),
                                       d->threading);
  d->cgroup = dJointGroupCreate(0);
  dWorldSetGravity(d->world, 0, 0, -def->gravity);
  dWorldSetERP(d->world, def->erp);
  dWorldSetCFM(d->world, def->cfm);
  dWorldSetQuickStepNumIterations(d->world, def->iterations);
  dWorldSetQuickStepW(d->world, def->sor_w);
  dWorldSetContactSurfaceLayer(d->world, def->surface_layer);
  d->surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
  d->surface.mu = def->friction;
  d->surface.soft_erp = def->contact_erp;
  d->surface.soft_cfm = def->contact_cfm;
  return 1;
}

stStatus st__dyn_create(stWorld *w, const stDynDef *def, char *err, size_t errsz) {
  int nsub = 0;
  stStatus st = st__dyn_check_def(def, w->robot->dt, &nsub, err, errsz);
  if (st) return st;
  st__ode_init();
  st__ode_messages_install();
  const char *why = st__ode_layout_precision();
  if (why) return st__errf(err, errsz, "dynamic world: %s", why), ST_ERR_RANGE;
  if (def->solver == ST_DYN_QUICKSTEP) {
    pthread_once(&g_rand_once, rand_check);
    if (g_rand_why)
      return st__errf(err, errsz, "dynamics.solver: quickstep, but %s (expected step)", g_rand_why),
             ST_ERR_RANGE;
  }
  if (def->lcp != ST_DYN_LCP_DENSE && (why = st__lcp_unavailable()))
    return st__errf(err, errsz, "dynamics.lcp: %s, but %s (expected dense)",
                    st_config_enum_name("dynamics", "lcp", def->lcp), why), ST_ERR_RANGE;
  dynInternal *d = calloc(1, sizeof *d);
  if (!d) return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  d->head.backend = &st__dyn_backend;
  w->internal_ = d;
  d->def = *def;
  d->stop_margin = def->stop_margin_deg * ST_DEG;
  d->limit_tolerance = def->limit_tolerance_deg * ST_DEG;
  d->nsub = nsub;
  d->h = w->robot->dt / nsub;
  d->solver = def->solver;
  if (!alloc_arrays(d, w->robot->model) || !create_ode_world(d))
    return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
  if (def->lcp != ST_DYN_LCP_DENSE) {
    if (!(d->lcp = st__lcp_create()))
      return st__errf(err, errsz, "dynamic world: out of memory"), ST_ERR_NOMEM;
    st__lcp_set_mode(d->lcp, def->lcp);
    /* room in ODE's step arena for the check mode's second solve (lib/world/ode_lcp.h): the
     * steps' own need is far below 1 MB */
    const dWorldStepReserveInfo reserve = {sizeof reserve, 2.0f, 1u << 20};
    dWorldSetStepMemoryReservationPolicy(d->world, &reserve);
  }
  if ((st = build(w, d, err, errsz))) return st;
  d->obj_table = 1;
  return ST_OK;
}

void st__dyn_destroy(stWorld *w) {
  dynInternal *d = w->internal_;
  st__robot_geoms_destroy(w->robot->model, &d->geoms);
  st__scene_geoms_destroy(&d->scene);
  if (d->floor) dGeomDestroy(d->floor);
  if (d->cgroup) dJointGroupDestroy(d->cgroup);
  if (d->world) dWorldDestroy(d->world); /* its bodies and hinges too */
  if (d->threading) dThreadingFreeImplementation(d->threading);
  void *arrays[] = {d->gbody,  d->glink,    d->gcom,  d->link_group, d->link_R,   d->link_p,
                    d->hinge,  d->angle,    d->vel,   d->saved,      d->geom,     d->want_kin,
                    d->vprev,  d->cpos,     d->cfb,   d->cfb_body,   d->cfb_side};
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
  st__lcp_destroy(d->lcp);
  free(d);
  w->internal_ = NULL;
}
