/* SPDX-License-Identifier: MIT
 * dynamics.lcp = schur: ODE's LCP with the unbounded rows eliminated by a sparse
 * factorisation, ODE's own Dantzig solver on what is left.
 *
 * Why. dWorldStep's LCP (A x = b + w, lo <= x <= hi) has about 65 unbounded rows (the hinges'
 * constraint rows) and 25-40 bounded ones (motors, stops, contacts). ODE's Dantzig solver
 * (lcp.cpp, dxSolveLCP_Generic) moves the unbounded rows to the front, factors them densely
 * (n^3/6), then drives the bounded rows in one by one, each costing triangular solves and a
 * factor update over every row already clamped: the unbounded ones included. In a chain the
 * unbounded block is sparse (a joint's rows touch only the joints sharing one of its two
 * bodies), and its rows stay clamped throughout. Eliminating them first,
 *     S = A_BB - A_BU A_UU^-1 A_UB,   b' = b_B - A_BU A_UU^-1 b_U,
 * leaves an LCP in the bounded rows alone that ODE's own solver takes in the same order with
 * the same decisions (the unbounded rows never leave its clamped set), and
 *     x_U = A_UU^-1 (b_U - A_UB x_B).
 * So the solution is ODE's up to rounding, at a fraction of the cost: A_UU is factored
 * (LDL^T) in a minimum-degree order, which in a tree of joints makes little or no fill.
 *
 * How. libode.so calls dxSolveLCP through its PLT, so the definition here (C, with the C++
 * name of ODE 0.16.2: void dxSolveLCP(dxWorldProcessMemArena *, unsigned, dReal *, dReal *,
 * dReal *, unsigned, dReal *, int *), dReal double) takes precedence; ODE's own is found with
 * dlsym(RTLD_NEXT). Outside st__lcp_begin / st__lcp_end every call goes to ODE's unchanged.
 * The layout is lcp.h's: A row-major, rows dPAD(n) apart, its lower triangle filled (step.cpp
 * zeroes A and writes only the blocks of joints sharing a body); bx pairs (b, x); lh pairs
 * (lo, hi); findex: a friction row's normal row, or -1. */
#define _GNU_SOURCE
#include "world/ode_lcp.h"

#include <dlfcn.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ode/ode.h>

#include "core/internal.h"
#include "world/ode_util.h"

#if defined(__GNUC__) || defined(__clang__)
#define ST_THREAD_LOCAL __thread
#else
#error "lib/world/ode_lcp.c needs thread-local storage (__thread) and asm labels"
#endif

#define ODE_SOLVE_LCP "_Z10dxSolveLCPP22dxWorldProcessMemArenajPdS1_S1_jS1_Pi"

typedef void (*lcpFn)(void *arena, unsigned n, double *A, double *bx, double *w, unsigned nub,
                      double *lh, int *findex);

enum { ST_LCP_ORDERS = 4 };
typedef struct stLcpOrder {
  unsigned nu, words; /* nu 0: empty */
  uint64_t *pat;      /* the pattern it is for */
  unsigned *order;    /* position k of the factor: row order[k] of U */
  unsigned *lstart, *lrows; /* L's structure: column k's rows (positions > k, ascending) are
                               lrows[lstart[k] .. lstart[k + 1]) */
} stLcpOrder;

struct stLcp {
  stLcpStats st;
  /* scratch, grown as needed */
  unsigned cap_n;
  unsigned *perm, *U, *B, *posb, *posu, *ynz, *ycnt;
  int *findex_b;
  double *M, *Lv, *Y, *W, *z, *v, *S, *bx_b, *lh_b;
  double *copyA, *copybx, *copylh;
  int *copyf;
  unsigned copycap;
  /* minimum degree's work, A_UU's pattern, and the last patterns' orders */
  uint64_t *adj, *alive, *pat;
  int *deg;
  unsigned patcap, ordcap;
  stLcpOrder oc[ST_LCP_ORDERS];
  int oc_next;
  const stLcpOrder *ord; /* this problem's: one of oc's */
};

static lcpFn g_ode;
static pthread_once_t g_ode_once = PTHREAD_ONCE_INIT;
static ST_THREAD_LOCAL stLcp *g_cur;
static ST_THREAD_LOCAL unsigned long g_entries;
static ST_THREAD_LOCAL int g_check;          /* st__lcp_check */
static ST_THREAD_LOCAL double g_check_max;
static ST_THREAD_LOCAL long g_check_n, g_check_warned;

static void find_ode(void) { *(void **)&g_ode = dlsym(RTLD_NEXT, ODE_SOLVE_LCP); }

static int ode_lcp_found(void) {
  pthread_once(&g_ode_once, find_ode);
  return g_ode != NULL;
}

static lcpFn ode_lcp(void) {
  pthread_once(&g_ode_once, find_ode);
  if (!g_ode) { /* the interposer is only reached from libode, which defines it */
    fprintf(stderr, "libselftalk: ODE's dxSolveLCP not found (dlsym: %s)\n", dlerror());
    abort();
  }
  return g_ode;
}

/* ---- scratch ------------------------------------------------------------------------------ */

stLcp *st__lcp_create(void) { return calloc(1, sizeof(stLcp)); }

static void free_scratch(stLcp *s) {
  free(s->perm), free(s->U), free(s->B), free(s->posb), free(s->posu), free(s->ynz);
  free(s->ycnt), free(s->findex_b), free(s->M), free(s->Lv), free(s->Y), free(s->W);
  free(s->z), free(s->v), free(s->S), free(s->bx_b), free(s->lh_b);
}

void st__lcp_destroy(stLcp *s) {
  if (!s) return;
  free_scratch(s);
  free(s->copyA), free(s->copybx), free(s->copylh), free(s->copyf);
  free(s->adj), free(s->alive), free(s->pat), free(s->deg);
  for (int e = 0; e < ST_LCP_ORDERS; e++)
    free(s->oc[e].pat), free(s->oc[e].order), free(s->oc[e].lstart), free(s->oc[e].lrows);
  free(s);
}

void st__lcp_stats(const stLcp *s, stLcpStats *out) {
  ST_ASSERT(s && out);
  *out = s->st;
}
void st__lcp_stats_reset(stLcp *s) {
  ST_ASSERT(s);
  memset(&s->st, 0, sizeof s->st);
}
void st__lcp_check(int on) {
  g_check = on;
  g_check_max = 0.0;
  g_check_n = 0;
  g_check_warned = 0;
}
double st__lcp_check_max_diff(void) { return g_check_max; }
long st__lcp_check_count(void) { return g_check_n; }
long st__lcp_check_warned(void) { return g_check_warned; }
void st__lcp_begin(stLcp *s) {
  ST_ASSERT(s && !g_cur); /* one world steps on a thread at a time */
  g_cur = s;
}
void st__lcp_end(void) { g_cur = NULL; }

static unsigned pad(unsigned n) { return n > 1 ? (n + 3u) & ~3u : n; } /* ODE's dPAD */

/* room for problems of n rows (0 when out of memory: the caller hands the problem to ODE) */
static int reserve(stLcp *s, unsigned n) {
  if (n <= s->cap_n) return 1;
  free_scratch(s);
  s->cap_n = 0;
  const size_t N = n, P = pad(n);
  s->perm = malloc(N * sizeof *s->perm), s->U = malloc(N * sizeof *s->U);
  s->B = malloc(N * sizeof *s->B), s->posb = malloc(N * sizeof *s->posb);
  s->posu = malloc(N * sizeof *s->posu), s->ycnt = malloc(N * sizeof *s->ycnt);
  s->ynz = malloc(N * N * sizeof *s->ynz), s->findex_b = malloc(N * sizeof *s->findex_b);
  s->M = malloc(N * N * sizeof *s->M), s->Lv = malloc(N * N * sizeof *s->Lv);
  s->Y = malloc(N * N * sizeof *s->Y), s->W = malloc(N * N * sizeof *s->W);
  s->z = malloc(N * sizeof *s->z), s->v = malloc(N * sizeof *s->v);
  s->S = malloc(P * N * sizeof *s->S), s->bx_b = malloc(2 * N * sizeof *s->bx_b);
  s->lh_b = malloc(2 * N * sizeof *s->lh_b);
  if (!(s->perm && s->U && s->B && s->posb && s->posu && s->ycnt && s->ynz && s->findex_b &&
        s->M && s->Lv && s->Y && s->W && s->z && s->v && s->S && s->bx_b && s->lh_b))
    return 0;
  s->cap_n = n;
  return 1;
}

static double lower(const double *A, unsigned skip, unsigned i, unsigned j) {
  return i >= j ? A[(size_t)i * skip + j] : A[(size_t)j * skip + i];
}

/* ---- the rows' roles, in ODE's order ------------------------------------------------------ */

/* ODE's dLCP constructor swaps every unbounded row without a friction index after the first
 * nub to the front, in this order; the bounded rows keep the order those swaps leave, which
 * is the order its Dantzig loop drives them in. U: the unbounded rows, B: the others. */
static void split_rows(stLcp *s, unsigned n, unsigned nub, const double *lh, const int *findex,
                       unsigned *nu, unsigned *nb) {
  unsigned *p = s->perm;
  for (unsigned k = 0; k < n; k++) p[k] = k;
  unsigned m = nub;
  for (unsigned k = nub; k < n; k++) {
    const unsigned r = p[k];
    if (findex && findex[r] >= 0) continue;
    if (lh[2 * r] == -dInfinity && lh[2 * r + 1] == dInfinity) {
      p[k] = p[m];
      p[m] = r;
      m++;
    }
  }
  for (unsigned k = 0; k < m; k++) s->U[k] = p[k], s->posu[p[k]] = k;
  for (unsigned k = m; k < n; k++) s->B[k - m] = p[k], s->posu[p[k]] = (unsigned)-1;
  *nu = m;
  *nb = n - m;
}

/* ---- the minimum-degree order of the unbounded block ------------------------------------- */

static int reserve_bits(stLcp *s, unsigned nu, unsigned words) {
  const unsigned need = nu * words;
  if (need <= s->patcap && nu <= s->ordcap) return 1;
  free(s->adj), free(s->alive), free(s->pat), free(s->deg);
  s->adj = malloc(need * sizeof *s->adj), s->pat = malloc(need * sizeof *s->pat);
  s->alive = malloc(words * sizeof *s->alive), s->deg = malloc(nu * sizeof *s->deg);
  int ok = s->adj && s->pat && s->alive && s->deg;
  for (int e = 0; e < ST_LCP_ORDERS; e++) {
    stLcpOrder *o = &s->oc[e];
    free(o->pat), free(o->order), free(o->lstart), free(o->lrows);
    o->pat = malloc(need * sizeof *o->pat), o->order = malloc(nu * sizeof *o->order);
    o->lstart = malloc((nu + 1) * sizeof *o->lstart);
    o->lrows = malloc(((size_t)nu * nu / 2 + 1) * sizeof *o->lrows);
    o->nu = 0; /* empty */
    ok = ok && o->pat && o->order && o->lstart && o->lrows;
  }
  s->patcap = ok ? need : 0;
  s->ordcap = ok ? nu : 0;
  return ok;
}

static int bit(const uint64_t *b, unsigned i) { return (int)(b[i / 64] >> (i % 64) & 1u); }

/* A_UU's pattern below A's diagonal (bit j of row i: U[j] < U[i], A's entry not zero), rows
 * in U's order, into s->pat: half of it, enough to tell patterns apart */
static void pattern(stLcp *s, const double *A, unsigned skip, unsigned nu, unsigned words) {
  uint64_t *pt = s->pat;
  memset(pt, 0, (size_t)nu * words * sizeof *pt);
  for (unsigned i = 0; i < nu; i++) { /* row U[i] left of the diagonal: contiguous in A */
    const double *row = A + (size_t)s->U[i] * skip;
    uint64_t *pi = pt + (size_t)i * words;
    for (unsigned c = 0; c < s->U[i]; c++) {
      const unsigned j = s->posu[c];
      if (j != (unsigned)-1 && row[c] != 0.0) pi[j / 64] |= (uint64_t)1 << (j % 64);
    }
  }
}

static int degree(const uint64_t *row, const uint64_t *alive, unsigned words) {
  int d = 0;
  for (unsigned w = 0; w < words; w++) d += __builtin_popcountll(row[w] & alive[w]);
  return d;
}

/* minimum degree on s->pat, each eliminated row's neighbours made a clique (ties: the lowest
 * row), into o's order; the neighbours at elimination are L's column (its structure, fill
 * included); only their degrees change */
static void min_degree(stLcp *s, unsigned nu, unsigned words, stLcpOrder *o) {
  unsigned *order = o->order, *rows = o->lrows, nl = 0;
  uint64_t *adj = s->adj, *alive = s->alive;
  int *deg = s->deg;
  memcpy(adj, s->pat, (size_t)nu * words * sizeof *adj);
  for (unsigned i = 0; i < nu; i++) /* the other half */
    for (unsigned j = 0; j < nu; j++)
      if (bit(s->pat + (size_t)i * words, j))
        adj[(size_t)j * words + i / 64] |= (uint64_t)1 << (i % 64);
  memset(alive, 0, words * sizeof *alive);
  for (unsigned i = 0; i < nu; i++) alive[i / 64] |= (uint64_t)1 << (i % 64);
  for (unsigned i = 0; i < nu; i++) deg[i] = degree(adj + (size_t)i * words, alive, words);
  for (unsigned step = 0; step < nu; step++) {
    unsigned best = nu;
    for (unsigned i = 0; i < nu; i++)
      if (bit(alive, i) && (best == nu || deg[i] < deg[best])) best = i;
    order[step] = best;
    o->lstart[step] = nl;
    alive[best / 64] &= ~((uint64_t)1 << (best % 64));
    const uint64_t *nb = adj + (size_t)best * words;
    for (unsigned j = 0; j < nu; j++) {
      if (!bit(nb, j) || !bit(alive, j)) continue;
      rows[nl++] = j; /* a row of U for now: its position is known at the end */
      uint64_t *aj = adj + (size_t)j * words;
      for (unsigned w = 0; w < words; w++) aj[w] |= nb[w] & alive[w];
      aj[j / 64] &= ~((uint64_t)1 << (j % 64));
      deg[j] = degree(aj, alive, words);
    }
  }
  o->lstart[nu] = nl;
  unsigned *pos = s->posb; /* free until reduce() */
  for (unsigned k = 0; k < nu; k++) pos[order[k]] = k;
  for (unsigned k = 0; k < nu; k++) { /* to positions, ascending (insertion: short lists) */
    unsigned *c = rows + o->lstart[k];
    const unsigned len = o->lstart[k + 1] - o->lstart[k];
    for (unsigned a = 0; a < len; a++) {
      const unsigned v = pos[c[a]];
      unsigned b = a;
      for (; b > 0 && c[b - 1] > v; b--) c[b] = c[b - 1];
      c[b] = v;
    }
  }
}

/* the order for s->pat: a pure function of the pattern, from the last few patterns' orders
 * when it is one of them (the rows' order in ODE's island changes with the contacts, so a few
 * patterns alternate), else computed */
static const stLcpOrder *ordering(stLcp *s, unsigned nu, unsigned words) {
  const size_t bytes = (size_t)nu * words * sizeof *s->pat;
  for (int e = 0; e < ST_LCP_ORDERS; e++)
    if (s->oc[e].nu == nu && s->oc[e].words == words && !memcmp(s->oc[e].pat, s->pat, bytes))
      return &s->oc[e];
  stLcpOrder *o = &s->oc[s->oc_next];
  s->oc_next = (s->oc_next + 1) % ST_LCP_ORDERS;
  min_degree(s, nu, words, o);
  memcpy(o->pat, s->pat, bytes);
  o->nu = nu;
  o->words = words;
  s->st.orderings++;
  return o;
}

/* ---- A_UU = L D L^T in that order --------------------------------------------------------- */

/* M (nu x nu, lower triangle, row-major) holds A_UU permuted, then L below the diagonal and D
 * on it; Lv holds L's columns packed as the order's lrows (for the solves). Right-looking over
 * L's structure: the work is the factor's, not n^3/6. Returns 0 on a pivot that is not
 * positive (ODE's matrix is positive definite: CFM > 0). */
static int factor(stLcp *s, const double *A, unsigned skip, unsigned nu) {
  double *M = s->M;
  const stLcpOrder *o = s->ord;
  const unsigned *q = o->order, *U = s->U, *rows = o->lrows;
  /* only L's structure and the diagonal are read and written below: A_UU's pattern is in it */
  for (unsigned k = 0; k < nu; k++) {
    const unsigned uk = U[q[k]];
    M[(size_t)k * nu + k] = A[(size_t)uk * skip + uk];
    for (unsigned ii = o->lstart[k]; ii < o->lstart[k + 1]; ii++)
      M[(size_t)rows[ii] * nu + k] = lower(A, skip, U[q[rows[ii]]], uk);
  }
  for (unsigned k = 0; k < nu; k++) {
    const double dk = M[(size_t)k * nu + k];
    if (!(dk > 0.0) || !isfinite(dk)) return 0;
    const unsigned a = o->lstart[k], nl = o->lstart[k + 1];
    for (unsigned ii = a; ii < nl; ii++) {
      const unsigned i = rows[ii];
      const double lik = M[(size_t)i * nu + k] / dk;
      for (unsigned jj = a; jj <= ii; jj++) {
        const unsigned j = rows[jj];
        M[(size_t)i * nu + j] -= lik * M[(size_t)j * nu + k];
      }
    }
    for (unsigned ii = a; ii < nl; ii++) s->Lv[ii] = M[(size_t)rows[ii] * nu + k] /= dk;
  }
  return 1;
}

/* y := L^-1 y, from row `from` on (the rows before it are zero); returns the first nonzero */
static unsigned lsolve(const stLcp *s, unsigned nu, double *y, unsigned from) {
  unsigned first = nu;
  for (unsigned k = from; k < nu; k++) {
    const double yk = y[k];
    if (yk == 0.0) continue;
    if (first == nu) first = k;
    for (unsigned ii = s->ord->lstart[k]; ii < s->ord->lstart[k + 1]; ii++)
      y[s->ord->lrows[ii]] -= s->Lv[ii] * yk;
  }
  return first;
}

/* ---- the reduction ------------------------------------------------------------------------ */

/* The reduced problem of the bounded rows: S, b' (s->S, s->bx_b), their bounds and friction
 * indices (s->lh_b, s->findex_b); Y = L^-1 A_UB and z = L^-1 b_U kept for the way back.
 * Returns 0 when a friction row's normal row is unbounded (not ODE's contacts: not reduced). */
static int reduce(stLcp *s, const double *A, unsigned skip, const double *bx, const double *lh,
                  const int *findex, unsigned nu, unsigned nb) {
  const unsigned *q = s->ord->order, *U = s->U, *B = s->B;
  for (unsigned r = 0; r < nb; r++) s->posb[B[r]] = r;
  for (unsigned k = 0; k < nu; k++) s->posb[U[k]] = (unsigned)-1;
  for (unsigned r = 0; r < nb; r++) {
    const int f = findex ? findex[B[r]] : -1;
    if (f >= 0 && s->posb[f] == (unsigned)-1) return 0;
    s->findex_b[r] = f >= 0 ? (int)s->posb[f] : -1;
    s->lh_b[2 * r] = lh[2 * B[r]];
    s->lh_b[2 * r + 1] = lh[2 * B[r] + 1];
  }
  double *Y = s->Y, *z = s->z;
  for (unsigned r = 0; r < nb; r++) {
    double *y = Y + (size_t)r * nu;
    unsigned from = nu;
    for (unsigned k = 0; k < nu; k++) {
      y[k] = lower(A, skip, U[q[k]], B[r]);
      if (y[k] != 0.0 && from == nu) from = k;
    }
    unsigned *nz = s->ynz + (size_t)r * nu, cnt = 0;
    for (unsigned k = lsolve(s, nu, y, from); k < nu; k++)
      if (y[k] != 0.0) nz[cnt++] = k;
    s->ycnt[r] = cnt;
  }
  for (unsigned k = 0; k < nu; k++) z[k] = bx[2 * U[q[k]]];
  lsolve(s, nu, z, 0);
  /* S = A_BB - Y^T D^-1 Y, b' = b_B - Y^T D^-1 z: W = D^-1 Y, v = D^-1 z */
  const double *M = s->M;
  const unsigned sb = pad(nb);
  double *W = s->W;
  for (unsigned k = 0; k < nu; k++) s->v[k] = 1.0 / M[(size_t)k * nu + k];
  for (unsigned r = 0; r < nb; r++)
    for (unsigned k = 0; k < nu; k++) W[(size_t)r * nu + k] = Y[(size_t)r * nu + k] * s->v[k];
  for (unsigned k = 0; k < nu; k++) s->v[k] *= z[k];
  /* the dot products over the sparser column's nonzeros (the vectors are stored whole) */
  for (unsigned r = 0; r < nb; r++) {
    const double *yr = Y + (size_t)r * nu, *wr = W + (size_t)r * nu;
    const unsigned *nzr = s->ynz + (size_t)r * nu;
    for (unsigned c = 0; c <= r; c++) {
      const double *yc = Y + (size_t)c * nu;
      const unsigned *nz = s->ycnt[c] < s->ycnt[r] ? s->ynz + (size_t)c * nu : nzr;
      const unsigned cnt = s->ycnt[c] < s->ycnt[r] ? s->ycnt[c] : s->ycnt[r];
      double acc = 0.0;
      for (unsigned t = 0; t < cnt; t++) acc += wr[nz[t]] * yc[nz[t]];
      const double a = lower(A, skip, B[r], B[c]) - acc;
      s->S[(size_t)r * sb + c] = a;
      s->S[(size_t)c * sb + r] = a;
    }
    double acc = 0.0;
    for (unsigned t = 0; t < s->ycnt[r]; t++) acc += yr[nzr[t]] * s->v[nzr[t]];
    s->bx_b[2 * r] = bx[2 * B[r]] - acc;
    s->bx_b[2 * r + 1] = 0.0;
  }
  return 1;
}

/* x_U = A_UU^-1 (b_U - A_UB x_B) = P^T L^-T D^-1 (z - Y x_B); every x into bx */
static void back(stLcp *s, double *bx, unsigned nu, unsigned nb) {
  const double *M = s->M, *Y = s->Y;
  double *v = s->v;
  for (unsigned k = 0; k < nu; k++) v[k] = s->z[k];
  for (unsigned r = 0; r < nb; r++) {
    const double xr = s->bx_b[2 * r + 1];
    bx[2 * s->B[r] + 1] = xr;
    if (xr == 0.0) continue;
    const double *yr = Y + (size_t)r * nu;
    const unsigned *nz = s->ynz + (size_t)r * nu;
    for (unsigned t = 0; t < s->ycnt[r]; t++) v[nz[t]] -= yr[nz[t]] * xr;
  }
  for (unsigned k = 0; k < nu; k++) v[k] /= M[(size_t)k * nu + k];
  for (unsigned k = nu; k-- > 0;) {
    double acc = v[k];
    for (unsigned ii = s->ord->lstart[k]; ii < s->ord->lstart[k + 1]; ii++)
      acc -= s->Lv[ii] * v[s->ord->lrows[ii]];
    v[k] = acc;
  }
  for (unsigned k = 0; k < nu; k++) bx[2 * s->U[s->ord->order[k]] + 1] = v[k];
}

/* the problem by the reduction (1), or 0 when it does not apply (nothing written) */
static int solve_reduced(stLcp *s, void *arena, unsigned n, const double *A, double *bx,
                         unsigned nub, const double *lh, const int *findex) {
  if (!reserve(s, n)) return 0;
  unsigned nu, nb;
  split_rows(s, n, nub, lh, findex, &nu, &nb);
  if (nu < 2) return 0; /* nothing to gain */
  const unsigned words = (nu + 63) / 64, skip = pad(n);
  if (!reserve_bits(s, nu, words)) return 0;
  pattern(s, A, skip, nu, words);
  s->ord = ordering(s, nu, words);
  if (!factor(s, A, skip, nu)) return 0;
  if (!reduce(s, A, skip, bx, lh, findex, nu, nb)) return 0;
  /* S is positive definite, but in a matrix this ill-conditioned (phalanx inertias of 1e-7
   * kg m^2 against CFM / h of 1e-3) rounding can make ODE's Dantzig warn on it where the whole
   * problem's pivoting did not (or the other way round). Its warning stands: the world redoes
   * the sub-step softer, as after one of ODE's own. (Solving the whole problem again instead
   * would take ODE's step arena twice, which it is not sized for.) */
  if (nb) ode_lcp()(arena, nb, s->S, s->bx_b, NULL, 0, s->lh_b, s->findex_b);
  back(s, bx, nu, nb);
  s->st.reduced++;
  s->st.rows += n;
  s->st.unbounded += nu;
  return 1;
}

/* check mode: ODE's solution on copies (kept), the reduction's compared with it */
static int reserve_copy(stLcp *s, unsigned n) {
  if (n <= s->copycap) return 1;
  free(s->copyA), free(s->copybx), free(s->copylh), free(s->copyf);
  s->copyA = malloc((size_t)pad(n) * n * sizeof *s->copyA);
  s->copybx = malloc(2 * (size_t)n * sizeof *s->copybx);
  s->copylh = malloc(2 * (size_t)n * sizeof *s->copylh);
  s->copyf = malloc((size_t)n * sizeof *s->copyf);
  s->copycap = s->copyA && s->copybx && s->copylh && s->copyf ? n : 0;
  return s->copycap != 0;
}

static void solve_checked(stLcp *s, void *arena, unsigned n, double *A, double *bx, double *w,
                          unsigned nub, double *lh, int *findex) {
  if (!reserve_copy(s, n)) {
    ode_lcp()(arena, n, A, bx, w, nub, lh, findex);
    return;
  }
  memcpy(s->copyA, A, (size_t)pad(n) * n * sizeof *A);
  memcpy(s->copybx, bx, 2 * (size_t)n * sizeof *bx);
  memcpy(s->copylh, lh, 2 * (size_t)n * sizeof *lh);
  if (findex) memcpy(s->copyf, findex, (size_t)n * sizeof *findex);
  const unsigned long msgs = st__ode_messages();
  const int reduced = solve_reduced(s, arena, n, s->copyA, s->copybx, nub, s->copylh,
                                    findex ? s->copyf : NULL);
  const int warned = st__ode_messages() != msgs;
  st__ode_messages_rewind(msgs);
  ode_lcp()(arena, n, A, bx, w, nub, lh, findex);
  if (!reduced) return;
  if (warned) { /* not a solution to compare: the world would have redone the sub-step */
    g_check_warned++;
    return;
  }
  g_check_n++;
  double dx = 0.0, xmax = 1.0;
  for (unsigned i = 0; i < n; i++) {
    const double xo = bx[2 * i + 1], d = fabs(s->copybx[2 * i + 1] - xo);
    if (!(d <= dx)) dx = d; /* NaN too */
    if (fabs(xo) > xmax) xmax = fabs(xo);
  }
  if (!(dx / xmax <= g_check_max)) g_check_max = dx / xmax;
}

/* what the probe step's LCP looked like (check_interposed) */
typedef struct lcpProbe {
  int on, calls;
  unsigned n, nub;
  int layout_ok;
} lcpProbe;
static ST_THREAD_LOCAL lcpProbe g_probe;

/* the probe's problem as ODE 0.16.2's step.cpp and lcp.h lay it out: two powered hinges give 12
 * rows, each hinge's 5 unbounded rows (lo -inf, hi +inf) followed by its motor row bounded by its
 * dParamFMax (+-1), nub 0 (the solver finds the unbounded rows itself), no friction rows
 * (findex -1), no outer w, lh as (lo, hi) pairs and A's rows dPAD(12) apart with a positive
 * diagonal */
static int probe_layout(unsigned n, const double *A, const double *bx, const double *w,
                        unsigned nub, const double *lh, const int *findex) {
  if (n != 12 || nub != 0 || w || !A || !bx || !lh) return 0;
  for (unsigned i = 0; i < n; i++) {
    const double lo = lh[2 * i], hi = lh[2 * i + 1];
    if (findex && findex[i] != -1) return 0;
    if (!(A[(size_t)i * pad(n) + i] > 0.0) || !isfinite(bx[2 * i])) return 0;
    if (i % 6 == 5 ? !(lo == -1.0 && hi == 1.0) : !(isinf(lo) && lo < 0 && isinf(hi) && hi > 0))
      return 0;
  }
  return 1;
}

/* ODE's dxSolveLCP, as libode.so calls it: visible, so that the program exports it to libode
 * (the library is compiled with -fvisibility=hidden; the shared library keeps it local) */
void st__lcp_entry(void *arena, unsigned n, double *A, double *bx, double *w, unsigned nub,
                   double *lh, int *findex) __asm__(ODE_SOLVE_LCP)
    __attribute__((visibility("default")));

void st__lcp_entry(void *arena, unsigned n, double *A, double *bx, double *w, unsigned nub,
                   double *lh, int *findex) {
  g_entries++;
  if (g_probe.on && !g_probe.calls++) {
    g_probe.n = n, g_probe.nub = nub;
    g_probe.layout_ok = probe_layout(n, A, bx, w, nub, lh, findex);
  }
  stLcp *s = g_cur;
  if (s) {
    s->st.calls++;
    if (g_check) {
      solve_checked(s, arena, n, A, bx, w, nub, lh, findex);
      return;
    }
    /* an outer w (step.cpp passes none) would need w of the unbounded rows too: ODE's */
    if (!w && solve_reduced(s, arena, n, A, bx, nub, lh, findex)) return;
  }
  ode_lcp()(arena, n, A, bx, w, nub, lh, findex);
}

/* ---- the interposition check -------------------------------------------------------------- */

static pthread_once_t g_check_once = PTHREAD_ONCE_INIT;
static const char *g_why; /* NULL: the reduction can act */
static char g_why_buf[512];

static void check_interposed(void) {
  lcpFn found;
  *(void **)&found = dlsym(RTLD_DEFAULT, ODE_SOLVE_LCP);
  if (found != (lcpFn)st__lcp_entry) { /* the shared library: ODE's own is the program's */
    g_why = "ODE's calls of dxSolveLCP cannot reach the library's in a program linked with the "
            "shared library, which exports only the st_ API (link the static library, as the "
            "apps do)";
    return;
  }
  if (!ode_lcp_found()) {
    g_why = "ODE's own dxSolveLCP (ODE 0.16.2's C++ name) is not in the ODE loaded";
    return;
  }
  const unsigned long before = g_entries;
  memset(&g_probe, 0, sizeof g_probe);
  g_probe.on = 1;
  st__ode_probe_step(0);
  g_probe.on = 0;
  if (g_entries == before) {
    g_why = "ODE's calls of dxSolveLCP do not reach the library's in this build (ODE binds "
            "them internally)";
    return;
  }
  if (g_probe.calls != 1 || !g_probe.layout_ok) {
    snprintf(g_why_buf, sizeof g_why_buf, "the probe step's LCP (%d calls, the first of %u rows, "
             "nub %u) is not laid out as ODE 0.16.2's (1 call of 12 rows, nub 0, the two motor "
             "rows bounded by their dParamFMax, the others unbounded): the ODE loaded (%s) is not "
             "the one the reduction was written for", g_probe.calls, g_probe.n, g_probe.nub,
             dGetConfiguration());
    g_why = g_why_buf;
  }
}

const char *st__lcp_unavailable(void) {
  pthread_once(&g_check_once, check_interposed);
  return g_why;
}
