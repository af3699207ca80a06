/* SPDX-License-Identifier: MIT
 * Dynamic world backend (thesis §2.1, SPEC §3; lib/world/world_backend.h): the robot, the table and
 * the object as an ODE world. See selftalk/world.h for the contract and docs/PROTOCOL.md
 * ("Dynamic mode") for the physical parameters, their reasons and the measurements behind
 * them. The geometries come from lib/world/world_geom.c, shared with the kinematic world.
 *
 * Bodies: every link moved by a revolute joint starts an ODE body; links on fixed joints
 * (massless frames, the knuckles, torso_2, l_upper_arm) are folded into the body of their
 * parent (masses and inertias summed about the common centre of mass, geometries attached
 * with offsets). The root link and its fixed children are the static world. An ODE body's
 * origin is its centre of mass and its axes are those of its first link. Hinge angles are
 * measured from the zero pose the world is built in.
 *
 * Stepping: while no robot geometry can reach the table or the object within a sub-step
 * ("free motion"), the joints follow the servo law exactly (an unsaturated velocity servo
 * reaches its target velocity within one sub-step, and without contact none saturates: see
 * PROTOCOL), the robot's bodies are disabled and ODE steps the object alone. Near contact the
 * robot's bodies join ODE's step with the velocities the servos give them, and every sub-step
 * is ODE dynamics: hinge motors with bounded torque, stops, contacts; except for the joints of
 * dynamics.kinematic_joints, exact servos at all times, whose links are kinematic bodies.
 *
 * Determinism: nothing here depends on anything but the world's own state: collisions are
 * run pair by pair in a fixed order (no ODE space, whose geom lists reorder as geoms move);
 * each world has its own ODE threading implementation (ODE's default one is one object shared
 * by the whole process); quickstep's row shuffling draws from the world's own generator state
 * (lib/world/ode_rand.c), loaded before and stored after every quickstep.
 *
 * The backend's files, by stage (their shared state and functions: lib/world/dynworld.h):
 *   dynworld.c     the [dynamics] keys (stDynDef from the key table, checked where consumed),
 *                  the queries, the table of operations
 *   dyn_create.c   creation: bodies, hinges, geometries, the scene, exact servos, ODE's world
 *   dyn_contact.c  contacts: the pairs in a fixed order, contact joints, what touches what
 *   dyn_state.c    state and reset: placing bodies, free motion <-> ODE, reading the state
 *   dyn_step.c     stepping: the servos, the stops, a sub-step in free motion or in ODE's step
 *   dyn_redo.c     the redo strategies of a sub-step in ODE's step (softer constraints,
 *                  adaptive joints, the motor active set) */
#include <math.h>
#include <string.h>

#include "world/dynworld.h"

/* ---- configuration ----------------------------------------------------------------------- */

void st_dyn_def_from_config(const stConfig *c, stDynDef *d) {
  ST_ASSERT(c && d);
  memset(d, 0, sizeof *d);
#define ST__DYN_COPY(s, k, ...) d->k = c->s##_##k;
#define ST__DYN_COPY_STR(s, k, dflt, h) memcpy(d->k, c->s##_##k, sizeof d->k);
  ST_CONFIG_DYNAMICS_KEYS(ST__DYN_COPY, ST__DYN_COPY, ST__DYN_COPY, ST__DYN_COPY, ST__DYN_COPY_STR)
#undef ST__DYN_COPY
#undef ST__DYN_COPY_STR
}

/* the [dynamics] keys within the key table's ranges, checked here where they are consumed (as
 * the GA checks its own), then what the world needs of them together; before anything reaches
 * ODE, whose dError would end the process */
stStatus st__dyn_check_def(const stDynDef *d, double dt, int *nsub, char *err, size_t errsz) {
  stStatus st = ST_OK;
#define ST__DYN_CHECK(s, k, ...) \
  if (!st) st = st_config_check_number(#s, #k, (double)d->k, err, errsz);
#define ST__DYN_CHECK_NONE(s, k, dflt, h)
  ST_CONFIG_DYNAMICS_KEYS(ST__DYN_CHECK, ST__DYN_CHECK, ST__DYN_CHECK, ST__DYN_CHECK,
                          ST__DYN_CHECK_NONE)
#undef ST__DYN_CHECK
#undef ST__DYN_CHECK_NONE
  if (st) return st;
#define BAD(...) return st__errf(err, errsz, __VA_ARGS__), ST_ERR_RANGE
  if (!(d->substep <= dt))
    BAD("dynamics.substep: %g s (expected <= the control step %g s)", d->substep, dt);
  double n = floor(dt / d->substep + 0.5);
  if (!(fabs(n * d->substep - dt) <= 1e-9 * dt))
    BAD("dynamics.substep: %g s does not divide the control step %g s (expected control_dt / "
        "substep to be a whole number)", d->substep, dt);
  *nsub = (int)n;
  const stConfigKey *limit = st_config_key(st_config_find("dynamics", "adaptive_limit"));
  const double adaptive_limit = limit->def_num;
  if (!d->adaptive_joints[0] && d->adaptive_limit != adaptive_limit)
    BAD("dynamics.adaptive_limit: %g with dynamics.adaptive_joints empty (expected the default "
        "%g: it acts on the adaptive joints only)", d->adaptive_limit, adaptive_limit);
  if (d->motor_active_set && d->solver != ST_DYN_STEP)
    BAD("dynamics.motor_active_set: on with solver quickstep (expected solver step: it acts on "
        "the direct solver's LCP only)");
  if (d->lcp != ST_DYN_LCP_DENSE && d->solver != ST_DYN_STEP)
    BAD("dynamics.lcp: %s with solver quickstep (expected solver step: quickstep solves no "
        "LCP of its own)", st_config_enum_name("dynamics", "lcp", d->lcp));
  return ST_OK;
#undef BAD
}

/* ---- settings and queries ---------------------------------------------------------------- */

static void dyn_set_seed(stWorld *w, uint64_t key) { ((dynInternal *)w->internal_)->seed = key; }

static void dyn_set_object_table_collision(stWorld *w, int on) {
  ((dynInternal *)w->internal_)->obj_table = !!on;
}

static int dyn_object_fell(const stWorld *w) {
  const dynInternal *d = w->internal_;
  const stScene *s = w->scene;
  const double *o = w->obj;
  if (o[2] < s->table_top_z - d->def.fall_margin) return 1;
  const int off = o[0] < s->table_lo[0] || o[0] > s->table_hi[0] || o[1] < s->table_lo[1] ||
                  o[1] > s->table_hi[1];
  return off && o[2] < s->table_top_z;
}

static double dyn_object_ceiling(const stWorld *w) {
  const dynInternal *d = w->internal_;
  if (!(d->def.gravity > 0.0) || d->unstable) return INFINITY;
  dMass ms;
  dBodyGetMass(d->ball, &ms);
  const dReal *v = dBodyGetLinearVel(d->ball), *o = dBodyGetAngularVel(d->ball);
  dVector3 ob; /* the spin in the body frame, where the inertia is */
  dBodyVectorFromWorld(d->ball, o[0], o[1], o[2], ob);
  double rot = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) rot += ob[i] * ms.I[4 * i + j] * ob[j];
  const double ke = 0.5 * ms.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * rot;
  return w->obj[2] + ke / (ms.mass * d->def.gravity);
}

static int dyn_unstable(const stWorld *w) { return ((const dynInternal *)w->internal_)->unstable; }

static const char *dyn_unstable_reason(const stWorld *w) {
  return ((const dynInternal *)w->internal_)->reason;
}

static void dyn_info(const stWorld *w, stDynInfo *info) {
  const dynInternal *d = w->internal_;
  info->bodies = d->ngroup;
  info->hinges = d->nhinge;
  info->kinematic_hinges = d->nkin;
  info->geoms = d->geoms.n;
  info->substeps = d->nsub;
  info->solver = d->solver;
  info->rand_interposed = st__dyn_rand_interposed();
  info->solver_warnings = d->messages;
  info->solver_retries = d->retries;
  info->motor_redos = d->motor_redos;
  info->adaptive_redos = d->adapt_redos;
  info->adaptive_kinematic = d->nkin - d->nkin0;
  info->dyn_substeps = d->dyn_substeps;
  info->dyn_hinge_substeps = d->dyn_hinge_substeps;
  info->robot_in_ode = d->robot_dyn;
  stLcpStats ls;
  memset(&ls, 0, sizeof ls);
  if (d->lcp) st__lcp_stats(d->lcp, &ls);
  info->lcp_solves = ls.calls;
  info->lcp_reduced = ls.reduced;
  info->lcp_reduced_rows = ls.rows;
  info->lcp_unbounded_rows = ls.unbounded;
  info->lcp_orderings = ls.orderings;
  info->lcp_direct = ls.direct;
  info->lcp_fallbacks = ls.fallbacks;
  memcpy(info->contact_points, d->points, sizeof d->points);
}

static void dyn_joint_angles(const stWorld *w, double *angle) {
  const dynInternal *d = w->internal_;
  memcpy(angle, d->angle, sizeof(double) * (size_t)w->robot->nbody);
}

/* the object body's rotation, from ODE's 3x4 layout */
static void dyn_object_rotation(const stWorld *w, double R[9]) {
  const dReal *o = dBodyGetRotation(((const dynInternal *)w->internal_)->ball);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = o[4 * i + j];
}

const stWorldBackend st__dyn_backend = {
    .destroy = st__dyn_destroy,
    .reset = st__dyn_reset,
    .update = st__dyn_update,
    .joint_angles = dyn_joint_angles,
    .step = st__dyn_step,
    .set_seed = dyn_set_seed,
    .set_object_table_collision = dyn_set_object_table_collision,
    .object_fell = dyn_object_fell,
    .object_ceiling = dyn_object_ceiling,
    .unstable = dyn_unstable,
    .unstable_reason = dyn_unstable_reason,
    .info = dyn_info,
    .object_rotation = dyn_object_rotation,
};
