/* SPDX-License-Identifier: MIT
 * Inverse kinematics: Levenberg-Marquardt damped least squares in normalised joint units with
 * an analytic Jacobian (see selftalk/ik.h). */
#include "selftalk/ik.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"

#define NROW (3 + 3 * ST_IK_NAXIS)

stIkDef st_ik_default_def(void) {
  stIkDef d;
  memset(&d, 0, sizeof d);
  d.max_iter = 500;
  d.damping = 1e-2;
  d.damping_min = 1e-6;
  d.damping_max = 1e3;
  d.max_step = 0.1;
  d.tol_pos = 1e-5;
  d.tol_dir = 1e-4;
  for (int i = 0; i < ST_NDOF; i++) d.dof_weight[i] = i <= ST_DOF_WRIST_YAW ? 1.0 : 0.0;
  return d;
}

stIkTarget st_ik_target(int body, const double pos[3]) {
  stIkTarget t;
  memset(&t, 0, sizeof t);
  t.body = body;
  memcpy(t.pos, pos, sizeof t.pos);
  t.pos_weight = 1.0;
  return t;
}

void st_ik_target_align(stIkTarget *t, int k, const double axis[3], const double dir[3],
                        double weight) {
  ST_ASSERT(t && axis && dir);
  ST_ASSERT(k >= 0 && k < ST_IK_NAXIS);
  double na = st__norm3(axis), nd = st__norm3(dir);
  for (int i = 0; i < 3; i++) {
    t->axis[k][i] = na > 0 ? axis[i] / na : 0.0;
    t->dir[k][i] = nd > 0 ? dir[i] / nd : 0.0;
  }
  t->dir_weight[k] = weight;
}

/* v = R a (row-major R) */
static void rot(const double *R, const double *a, double *v) {
  for (int i = 0; i < 3; i++) v[i] = R[3 * i] * a[0] + R[3 * i + 1] * a[1] + R[3 * i + 2] * a[2];
}

/* The task's world point x, aligned axes a[k], weighted residual res[NROW] (rows of unused
 * terms are 0) and the errors of one posture's poses. */
typedef struct taskState {
  double x[3];
  double a[ST_IK_NAXIS][3];
  double res[NROW];
  double cost, pos_err, dir_err[ST_IK_NAXIS];
} taskState;

static void task_eval(const stIkTarget *t, const double (*R)[9], const double (*p)[3],
                      taskState *s) {
  const int b = t->body;
  rot(R[b], t->point, s->x);
  for (int i = 0; i < 3; i++) s->x[i] += p[b][i];
  const double sp = sqrt(t->pos_weight);
  double e2 = 0.0;
  for (int i = 0; i < 3; i++) {
    double e = t->pos[i] - s->x[i];
    e2 += e * e;
    s->res[i] = sp * e;
  }
  s->pos_err = sqrt(e2);
  s->cost = t->pos_weight * e2;
  for (int k = 0; k < ST_IK_NAXIS; k++) {
    rot(R[b], t->axis[k], s->a[k]);
    double *rk = s->res + 3 + 3 * k;
    if (t->dir_weight[k] <= 0.0) {
      rk[0] = rk[1] = rk[2] = 0.0;
      s->dir_err[k] = 0.0;
      continue;
    }
    const double sw = sqrt(t->dir_weight[k]);
    double d2 = 0.0, dot = 0.0, c[3];
    for (int i = 0; i < 3; i++) {
      double e = t->dir[k][i] - s->a[k][i];
      d2 += e * e;
      dot += t->dir[k][i] * s->a[k][i];
      rk[i] = sw * e;
    }
    st__cross3(t->dir[k], s->a[k], c);
    s->dir_err[k] = atan2(st__norm3(c), dot);
    s->cost += t->dir_weight[k] * d2;
  }
}

/* Jacobian of the weighted task point / axes w.r.t. the qhat of every DOF (columns of DOF
 * that do not move the body stay 0). J is NROW x ST_NDOF, row-major. */
static void task_jacobian(const stRobot *r, const stIkTarget *t, const double (*R)[9],
                          const double (*p)[3], const taskState *s, double *J) {
  const stModel *m = r->model;
  memset(J, 0, sizeof(double) * NROW * ST_NDOF);
  const double sp = sqrt(t->pos_weight);
  for (int b = t->body; b > 0; b = m->body_parent[b]) {
    const int d = r->body_dof[b];
    if (m->jnt_type[b] != ST_JOINT_REVOLUTE || d < 0) continue;
    double w[3], lever[3], c[3];
    rot(R[b], m->jnt_axis[b], w);
    const double scale = r->body_range[b][1] - r->body_range[b][0]; /* rad per unit qhat */
    for (int i = 0; i < 3; i++) lever[i] = s->x[i] - p[b][i];
    st__cross3(w, lever, c);
    for (int i = 0; i < 3; i++) J[i * ST_NDOF + d] += sp * scale * c[i];
    for (int k = 0; k < ST_IK_NAXIS; k++) {
      if (t->dir_weight[k] <= 0.0) continue;
      const double sw = sqrt(t->dir_weight[k]);
      st__cross3(w, s->a[k], c);
      for (int i = 0; i < 3; i++) J[(3 + 3 * k + i) * ST_NDOF + d] += sw * scale * c[i];
    }
  }
}

/* Solves the n x n SPD system A x = b in place (Cholesky); 0 on success. */
static int cholesky_solve(double *A, int n, double *b) {
  for (int j = 0; j < n; j++) {
    double s = A[j * n + j];
    for (int k = 0; k < j; k++) s -= A[j * n + k] * A[j * n + k];
    if (!(s > 0.0)) return -1;
    A[j * n + j] = sqrt(s);
    for (int i = j + 1; i < n; i++) {
      double v = A[i * n + j];
      for (int k = 0; k < j; k++) v -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = v / A[j * n + j];
    }
  }
  for (int i = 0; i < n; i++) { /* L y = b */
    double v = b[i];
    for (int k = 0; k < i; k++) v -= A[i * n + k] * b[k];
    b[i] = v / A[i * n + i];
  }
  for (int i = n - 1; i >= 0; i--) { /* L^T x = y */
    double v = b[i];
    for (int k = i + 1; k < n; k++) v -= A[k * n + i] * b[k];
    b[i] = v / A[i * n + i];
  }
  return 0;
}

static int target_ok(const stRobot *r, const stIkTarget *t) {
  if (t->body < 0 || t->body >= r->nbody) return 0;
  if (!(t->pos_weight >= 0.0 && isfinite(t->pos_weight))) return 0;
  int used = t->pos_weight > 0.0;
  for (int k = 0; k < ST_IK_NAXIS; k++) {
    if (!(t->dir_weight[k] >= 0.0 && isfinite(t->dir_weight[k]))) return 0;
    if (t->dir_weight[k] > 0.0) {
      if (fabs(st__norm3(t->axis[k]) - 1.0) > 1e-6 || fabs(st__norm3(t->dir[k]) - 1.0) > 1e-6) return 0;
      used = 1;
    }
  }
  return used;
}

static int converged(const stIkDef *def, const stIkTarget *t, const taskState *s) {
  if (t->pos_weight > 0.0 && !(s->pos_err < def->tol_pos)) return 0;
  for (int k = 0; k < ST_IK_NAXIS; k++)
    if (t->dir_weight[k] > 0.0 && !(s->dir_err[k] < def->tol_dir)) return 0;
  return 1;
}

static void fill_result(stIkResult *res, const taskState *s, int iterations, int conv) {
  if (!res) return;
  res->pos_err = s->pos_err;
  for (int k = 0; k < ST_IK_NAXIS; k++) res->dir_err[k] = s->dir_err[k];
  res->cost = s->cost;
  res->iterations = iterations;
  res->converged = conv;
}

stStatus st_ik_evaluate(const stRobot *r, const stIkTarget *t, const double qhat[ST_NDOF],
                        stIkResult *result) {
  ST_ASSERT(r && t && qhat && result);
  if (!target_ok(r, t)) return ST_ERR_ARG;
  double *buf = malloc(sizeof(double) * 12 * (size_t)r->nbody);
  if (!buf) return ST_ERR_NOMEM;
  double(*R)[9] = (double(*)[9])buf;
  double(*p)[3] = (double(*)[3])(buf + 9 * (size_t)r->nbody);
  st_robot_fk(r, qhat, R, p);
  taskState s;
  task_eval(t, (const double(*)[9])R, (const double(*)[3])p, &s);
  fill_result(result, &s, 0, 0);
  free(buf);
  return ST_OK;
}

stStatus st_ik_solve(const stRobot *r, const stIkDef *def, const stIkTarget *t,
                     double qhat[ST_NDOF], stIkResult *result) {
  ST_ASSERT(r && def && t && qhat); /* result is nullable */
  if (!target_ok(r, t) || def->max_iter < 0 || !(def->damping > 0.0) ||
      !(def->damping_min > 0.0) || !(def->damping_max >= def->damping) || !(def->max_step > 0.0))
    return ST_ERR_ARG;
  int active[ST_NDOF], na = 0;
  for (int d = 0; d < ST_NDOF; d++) {
    if (!(def->dof_weight[d] >= 0.0 && isfinite(def->dof_weight[d]))) return ST_ERR_ARG;
    if (def->dof_weight[d] > 0.0) active[na++] = d;
  }
  const size_t nb = (size_t)r->nbody;
  double *buf = malloc(sizeof(double) * 24 * nb);
  if (!buf) return ST_ERR_NOMEM;
  double(*R)[9] = (double(*)[9])buf, (*Rt)[9] = (double(*)[9])(buf + 9 * nb);
  double(*p)[3] = (double(*)[3])(buf + 18 * nb), (*pt)[3] = (double(*)[3])(buf + 21 * nb);

  double q[ST_NDOF], qt[ST_NDOF];
  memcpy(q, qhat, sizeof q);
  for (int i = 0; i < na; i++) {
    double *v = &q[active[i]];
    *v = *v < 0.0 ? 0.0 : *v > 1.0 ? 1.0 : *v;
  }
  st_robot_fk(r, q, R, p);
  taskState s, st;
  task_eval(t, (const double(*)[9])R, (const double(*)[3])p, &s);

  double J[NROW * ST_NDOF], H[ST_NDOF * ST_NDOF], g[ST_NDOF];
  double lambda = def->damping;
  int it = 0, have_j = 0;
  while (it < def->max_iter && !converged(def, t, &s)) {
    if (!have_j) {
      /* normal equations H = J^T J, g = J^T res over every DOF (unused rows/cols are 0) */
      task_jacobian(r, t, (const double(*)[9])R, (const double(*)[3])p, &s, J);
      for (int a = 0; a < ST_NDOF; a++) {
        double v = 0.0;
        for (int k = 0; k < NROW; k++) v += J[k * ST_NDOF + a] * s.res[k];
        g[a] = v;
        for (int b = 0; b <= a; b++) {
          double h = 0.0;
          for (int k = 0; k < NROW; k++) h += J[k * ST_NDOF + a] * J[k * ST_NDOF + b];
          H[a * ST_NDOF + b] = H[b * ST_NDOF + a] = h;
        }
      }
      have_j = 1;
    }
    /* free set: active DOF, minus those at a limit whose step leaves the range */
    int fr[ST_NDOF], nf = na;
    memcpy(fr, active, sizeof(int) * (size_t)na);
    double dq[ST_NDOF];
    for (int pass = 0; pass <= na; pass++) {
      double A[ST_NDOF * ST_NDOF], x[ST_NDOF];
      for (int i = 0; i < nf; i++) {
        for (int j = 0; j < nf; j++) A[i * nf + j] = H[fr[i] * ST_NDOF + fr[j]];
        A[i * nf + i] += lambda * lambda / def->dof_weight[fr[i]];
        x[i] = g[fr[i]];
      }
      memset(dq, 0, sizeof dq);
      if (nf == 0 || cholesky_solve(A, nf, x)) {
        nf = 0;
        break;
      }
      for (int i = 0; i < nf; i++) dq[fr[i]] = x[i];
      int keep = 0;
      for (int i = 0; i < nf; i++) {
        int d = fr[i];
        int out = (q[d] <= 0.0 && dq[d] < 0.0) || (q[d] >= 1.0 && dq[d] > 0.0);
        if (!out) fr[keep++] = d;
      }
      if (keep == nf) break;
      nf = keep;
    }
    if (nf == 0) break; /* every DOF blocked by its limits */
    double mx = 0.0;
    for (int i = 0; i < nf; i++) mx = fmax(mx, fabs(dq[fr[i]]));
    const double sc = mx > def->max_step ? def->max_step / mx : 1.0;
    memcpy(qt, q, sizeof qt);
    for (int i = 0; i < nf; i++) {
      double v = q[fr[i]] + sc * dq[fr[i]];
      qt[fr[i]] = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    }
    st_robot_fk(r, qt, Rt, pt);
    task_eval(t, (const double(*)[9])Rt, (const double(*)[3])pt, &st);
    it++;
    if (st.cost < s.cost) {
      double(*tr)[9] = R;
      double(*tp)[3] = p;
      R = Rt, Rt = tr, p = pt, pt = tp;
      memcpy(q, qt, sizeof q);
      s = st;
      have_j = 0;
      lambda = fmax(lambda / 3.0, def->damping_min);
    } else {
      lambda *= 5.0;
      if (lambda > def->damping_max) break; /* stalled: a local minimum or unreachable */
    }
  }
  const int conv = converged(def, t, &s);
  memcpy(qhat, q, sizeof q);
  fill_result(result, &s, it, conv);
  free(buf);
  return conv ? ST_OK : ST_ERR_RANGE;
}
