/* SPDX-License-Identifier: MIT
 * The dynamic world's contacts (lib/world/dynworld.c has the map of its files): the colliding
 * pairs in a fixed order (no ODE space, whose geom lists reorder as geoms move), the contact
 * joints of ODE's next step, what touches what, and whether the robot is near the table or the
 * object (free motion ends there). */
#include <math.h>
#include <string.h>

#include "world/dynworld.h"

/* the group of body b when it is an adaptive joint's body, kinematic now; else -1 */
static int adaptive_kin_body(const dynInternal *d, dBodyID b) {
  if (!b || !d->nadapt) return -1;
  const int g = (int)(intptr_t)dBodyGetData(b) - 1;
  return g >= d->nkin0 && g < d->nkin ? g : -1;
}

/* narrow phase of one pair; with make, one contact joint per point. Returns 1 on contact.
 * ODE's colliders return at most the requested number of points, the first ones they find:
 * for the object's flat base on the table that is one side of the rim, and the object creeps.
 * So up to 16 are asked for and max_contacts of them kept, evenly spread over the list. */
static int collide(dynInternal *d, dGeomID a, dGeomID b, int make, double mu, int kind) {
  if (!a || !b) return 0;
  enum { ASK = 16 };
  const int n = dCollide(a, b, ASK, d->cg, sizeof d->cg[0]);
  const int keep = n < d->def.max_contacts ? n : d->def.max_contacts;
  if (make)
    for (int k = 0; k < keep; k++) {
      const int i = keep == n ? k : (int)((long)k * n / keep);
      dContact c;
      memset(&c, 0, sizeof c);
      c.surface = d->surface;
      c.surface.mu = mu;
      c.geom = d->cg[i];
      dBodyID b1 = dGeomGetBody(d->cg[i].g1), b2 = dGeomGetBody(d->cg[i].g2);
      const int a1 = adaptive_kin_body(d, b1), a2 = adaptive_kin_body(d, b2);
      if ((!b1 || dBodyIsKinematic(b1)) && (!b2 || dBodyIsKinematic(b2))) { /* no effect */
        /* an adaptive exact servo's body on the table: no force can tell its torque */
        if (a1 >= 0 && a1 < d->kin_static_hit) d->kin_static_hit = a1;
        if (a2 >= 0 && a2 < d->kin_static_hit) d->kin_static_hit = a2;
        continue;
      }
      dJointID j = dJointCreateContact(d->world, d->cgroup, &c);
      dJointAttach(j, b1, b2);
      if (a1 >= 0 || a2 >= 0) {
        if (d->ncfb < ST_DYN_MAX_CFB) {
          dJointSetFeedback(j, &d->cfb[d->ncfb]);
          d->cfb_body[d->ncfb] = a1 >= 0 ? a1 : a2;
          d->cfb_side[d->ncfb] = a1 >= 0 ? 0 : 1;
          d->ncfb++;
        } else if ((a1 >= 0 ? a1 : a2) < d->kin_static_hit) {
          d->kin_static_hit = a1 >= 0 ? a1 : a2; /* cannot be checked: make it dynamic */
        }
      }
      d->points[kind]++;
    }
  return n > 0;
}

/* world AABB of the object (sphere and base) */
static void object_aabb(const dynInternal *d, dReal oa[6]) {
  dReal t[6];
  dGeomGetAABB(d->scene.ball, oa);
  if (d->scene.base) {
    dGeomGetAABB(d->scene.base, t);
    for (int i = 0; i < 3; i++) {
      if (t[2 * i] < oa[2 * i]) oa[2 * i] = t[2 * i];
      if (t[2 * i + 1] > oa[2 * i + 1]) oa[2 * i + 1] = t[2 * i + 1];
    }
  }
}

/* the object's pairs: with the table (when on) and the floor; ORs object_table into c */
void st__dyn_collide_object(stWorld *w, int make, stContacts *c) {
  dynInternal *d = w->internal_;
  dReal oa[6];
  object_aabb(d, oa);
  if (d->obj_table && st__aabb_overlap(oa, d->table_aabb)) {
    const double mu = d->def.table_friction;
    int hit = collide(d, d->scene.ball, d->scene.table, make, mu, ST_DYN_PAIR_OBJECT_TABLE);
    hit |= collide(d, d->scene.base, d->scene.table, make, mu, ST_DYN_PAIR_OBJECT_TABLE);
    if (hit) c->object_table = 1;
  }
  if (oa[4] <= d->def.floor_z) {
    collide(d, d->scene.ball, d->floor, make, d->def.table_friction, ST_DYN_PAIR_OBJECT_FLOOR);
    collide(d, d->scene.base, d->floor, make, d->def.table_friction, ST_DYN_PAIR_OBJECT_FLOOR);
  }
}

/* every pair that can collide, in a fixed order: robot-table, robot-object, then the object's
 * own pairs. No robot-robot pairs. ORs what touches what into c. The robot's geometries must
 * be where its ODE bodies are (robot in ODE, or poses just set). */
void st__dyn_collide_all(stWorld *w, int make, stContacts *c) {
  dynInternal *d = w->internal_;
  dReal oa[6];
  object_aabb(d, oa);
  for (int i = 0; i < d->geoms.n; i++) {
    const dynGeom *g = &d->geom[i];
    dGeomID gi = d->geoms.g[i];
    dReal a[6];
    dGeomGetAABB(gi, a);
    if (g->dyn && st__aabb_overlap(a, d->table_aabb) &&
        collide(d, gi, d->scene.table, make, d->def.friction, ST_DYN_PAIR_ROBOT_TABLE)) {
      if (g->is_arm) c->arm_table = 1;
      if (g->touch >= 0) c->touch[g->touch] = 1;
    }
    if (st__aabb_overlap(a, oa)) {
      int hit = collide(d, gi, d->scene.ball, make, d->def.friction, ST_DYN_PAIR_ROBOT_BALL);
      hit |= collide(d, gi, d->scene.base, make, d->def.friction, ST_DYN_PAIR_ROBOT_BASE);
      if (hit) {
        c->robot_object = 1;
        if (g->touch >= 0) c->touch[g->touch] = c->touch_object[g->touch] = 1;
      }
    }
  }
  st__dyn_collide_object(w, make, c);
}

void st__dyn_contacts_or(stContacts *acc, const stContacts *c) {
  for (int i = 0; i < ST_NTOUCH; i++) {
    acc->touch[i] |= c->touch[i];
    acc->touch_object[i] |= c->touch_object[i];
  }
  acc->arm_table |= c->arm_table;
  acc->robot_object |= c->robot_object;
  acc->object_table |= c->object_table;
}

/* 1 when some robot geometry comes within margin of the table or the object: judged on
 * exact world AABBs of the primitives computed from the link poses w->R / w->p (no ODE call),
 * the object's AABB grown by its own motion over one sub-step */
int st__dyn_robot_near(const stWorld *w, double margin) {
  const dynInternal *d = w->internal_;
  const stModel *m = w->robot->model;
  dReal oa[6];
  object_aabb(d, oa);
  const dReal *ov = dBodyGetLinearVel(d->ball);
  for (int k = 0; k < 3; k++) {
    const double grow = fabs(ov[k]) * d->h;
    oa[2 * k] -= grow;
    oa[2 * k + 1] += grow;
  }
  for (int i = 0; i < d->geoms.n; i++) {
    const dynGeom *g = &d->geom[i];
    if (!g->dyn) continue; /* the static root does not move */
    const int l = g->link;
    const double *Rl = w->R[l];
    double Rg[9], c[3], half[3];
    st__mat3_mul(Rl, m->geom_rot[i], Rg);
    st__mat3_vec(Rl, m->geom_pos[i], c);
    for (int k = 0; k < 3; k++) c[k] += w->p[l][k];
    if (!st__geom_half_aabb(m, i, Rg, half)) half[0] = half[1] = half[2] = d->geoms.bound[i];
    dReal a[6];
    for (int k = 0; k < 3; k++) {
      a[2 * k] = c[k] - half[k] - margin;
      a[2 * k + 1] = c[k] + half[k] + margin;
    }
    if (st__aabb_overlap(a, d->table_aabb) || st__aabb_overlap(a, oa)) return 1;
  }
  return 0;
}
