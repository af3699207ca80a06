/* SPDX-License-Identifier: MIT
 * dynamics.lcp = schur: ODE's LCP with the unbounded rows eliminated by a sparse
 * factorisation, ODE's own Dantzig solver on what is left; block: the same elimination by the
 * hinges' 5 x 5 blocks; warm: block, and what is left solved directly from the last sub-step's
 * active set, checked, ODE's Dantzig when the check fails (each section below says why).
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
#include "selftalk/world.h"
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
/* dynamics.lcp = block: at most BLK_MAX blocks of 5 unbounded rows (a hinge's) */
enum { BLK_MAX = 32, B5 = 5, BB = B5 * B5, WARM_KINDS = 16, WARM_RANKS = 64 };
typedef struct stBlkOrder {
  unsigned ng;                   /* 0: empty */
  uint64_t pat[BLK_MAX];         /* the pattern it is for: bit j < i of pat[i], block (i, j) */
  unsigned char ord[BLK_MAX], pos[BLK_MAX]; /* elimination position -> block -> position */
  uint64_t str[BLK_MAX];         /* L's block structure: bit j of str[k], positions j > k */
  unsigned short lbeg[BLK_MAX + 1]; /* L's blocks of column k: lbeg[k] .. lbeg[k + 1] ... */
  unsigned char lrow[BLK_MAX * (BLK_MAX - 1) / 2]; /* ... in rows (positions) lrow[e] */
  unsigned short bidx[BLK_MAX * BLK_MAX]; /* block (i, j) of L, i > j: bidx[i * BLK_MAX + j] */
} stBlkOrder;
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
  int *findex_b, *f0;
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
  /* dynamics.lcp = block, warm (below) */
  int mode;                             /* ST_DYN_LCP_* */
  unsigned ng, ga0[BLK_MAX];            /* the unbounded rows' blocks: first row in A */
  double *Db, *Lb, *Tb;                 /* the factor's blocks (diagonal, below) and a column */
  uint64_t gpat[BLK_MAX];               /* this problem's block pattern */
  stBlkOrder bo[ST_LCP_ORDERS];
  int bo_next;
  const stBlkOrder *bord;               /* this problem's: one of bo's */
  uint64_t *ymask;                      /* per bounded row: Y's blocks that may be nonzero */
  double *dinv, *F, *xd, *lo2, *hi2, *rhs, *lh0, *wcol, *dinvc;
  unsigned *cl;
  unsigned char *rs, *kind, *rank;      /* warm: a bounded row's status, kind, rank in kind */
  int p1_ok;                            /* warm: phase 1 settled (hi2: phase 2's bounds) */
  unsigned char hist[2][WARM_KINDS][WARM_RANKS]; /* warm: the last solve's statuses by kind and
                                           rank, phase 1 and 2 (0: none yet) */
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

stLcp *st__lcp_create(void) {
  stLcp *s = calloc(1, sizeof(stLcp));
  if (s) s->mode = ST_DYN_LCP_SCHUR;
  return s;
}

static void free_scratch(stLcp *s) {
  free(s->perm), free(s->U), free(s->B), free(s->posb), free(s->posu), free(s->ynz);
  free(s->ycnt), free(s->findex_b), free(s->M), free(s->Lv), free(s->Y), free(s->W);
  free(s->z), free(s->v), free(s->S), free(s->bx_b), free(s->lh_b);
  free(s->ymask), free(s->dinv), free(s->F), free(s->xd), free(s->lo2), free(s->lh0), free(s->f0);
  free(s->Db), free(s->Lb), free(s->Tb), free(s->wcol), free(s->dinvc);
  free(s->hi2), free(s->rhs), free(s->cl), free(s->rs), free(s->kind), free(s->rank);
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
void st__lcp_set_mode(stLcp *s, int mode) {
  ST_ASSERT(s && mode > ST_DYN_LCP_DENSE && mode < ST_DYN_LCP_COUNT);
  s->mode = mode;
}
void st__lcp_reset(stLcp *s) {
  ST_ASSERT(s);
  memset(&s->st, 0, sizeof s->st);
  memset(s->hist, 0, sizeof s->hist); /* a trial's guesses depend on that trial alone */
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
  s->ymask = malloc(N * sizeof *s->ymask), s->dinv = malloc(N * sizeof *s->dinv);
  s->F = malloc(N * N * sizeof *s->F), s->xd = malloc(N * sizeof *s->xd);
  s->lo2 = malloc(N * sizeof *s->lo2), s->lh0 = malloc(2 * N * sizeof *s->lh0);
  s->f0 = malloc(N * sizeof *s->f0);
  s->Db = malloc((size_t)BLK_MAX * BB * sizeof *s->Db);
  s->Lb = malloc((size_t)BLK_MAX * (BLK_MAX - 1) / 2 * BB * sizeof *s->Lb);
  s->Tb = malloc((size_t)BLK_MAX * BB * sizeof *s->Tb);
  s->wcol = malloc(N * sizeof *s->wcol), s->dinvc = malloc(N * sizeof *s->dinvc);
  s->hi2 = malloc(N * sizeof *s->hi2), s->rhs = malloc(N * sizeof *s->rhs);
  s->cl = malloc(N * sizeof *s->cl), s->rs = malloc(N), s->kind = malloc(N);
  s->rank = malloc(N);
  if (!(s->perm && s->U && s->B && s->posb && s->posu && s->ycnt && s->ynz && s->findex_b &&
        s->M && s->Lv && s->Y && s->W && s->z && s->v && s->S && s->bx_b && s->lh_b &&
        s->ymask && s->dinv && s->F && s->xd && s->lo2 && s->lh0 && s->f0 && s->Db && s->Lb && s->Tb && s->wcol && s->dinvc && s->hi2 && s->rhs && s->cl &&
        s->rs && s->kind && s->rank))
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

/* The bounded rows' bounds and friction indices in the reduced problem's numbering (s->lh_b,
 * s->findex_b), shared by every reduction. Returns 0 when a friction row's normal row is
 * unbounded (not ODE's contacts: not reduced). */
static int bounded_rows(stLcp *s, const double *lh, const int *findex, unsigned nu, unsigned nb) {
  const unsigned *U = s->U, *B = s->B;
  for (unsigned r = 0; r < nb; r++) s->posb[B[r]] = r;
  for (unsigned k = 0; k < nu; k++) s->posb[U[k]] = (unsigned)-1;
  for (unsigned r = 0; r < nb; r++) {
    const int f = findex ? findex[B[r]] : -1;
    if (f >= 0 && s->posb[f] == (unsigned)-1) return 0;
    s->findex_b[r] = f >= 0 ? (int)s->posb[f] : -1;
    s->lh_b[2 * r] = lh[2 * B[r]];
    s->lh_b[2 * r + 1] = lh[2 * B[r] + 1];
  }
  return 1;
}

/* The reduced problem of the bounded rows: S, b' (s->S, s->bx_b), their bounds and friction
 * indices (s->lh_b, s->findex_b); Y = L^-1 A_UB and z = L^-1 b_U kept for the way back.
 * Returns 0 when a friction row's normal row is unbounded (not ODE's contacts: not reduced). */
static int reduce(stLcp *s, const double *A, unsigned skip, const double *bx, const double *lh,
                  const int *findex, unsigned nu, unsigned nb) {
  const unsigned *q = s->ord->order, *U = s->U, *B = s->B;
  if (!bounded_rows(s, lh, findex, nu, nb)) return 0;
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

/* ---- dynamics.lcp = block: the same reduction by the joints' blocks ------------------------ */

/* What schur spends its time on is bookkeeping, not arithmetic: in press its factor takes ~2,600
 * multiply-adds, done through index lists one entry at a time. A hinge's 5 unbounded rows are
 * consecutive in A (step.cpp writes a joint's rows together) and couple as a dense 5 x 5 block
 * with those of every joint that shares a body, so the same elimination is done here on 5 x 5
 * blocks with loops of fixed length: the pattern is one bit per pair of blocks, the order is
 * chosen among ~13 blocks (kept for the last few patterns), and A is read block by block. Zeros
 * inside a block are stored and multiplied, which changes nothing but rounding. Unbounded rows
 * that do not come in runs of 5 (a motor made unbounded by motor_active_set, another joint type)
 * go to schur's scalar reduction. */

/* the unbounded rows (ascending in A, split_rows) as runs of exactly 5 consecutive rows; 0 when
 * they are not, or there are more than BLK_MAX runs */
static int blk_groups(stLcp *s, unsigned nu) {
  if (nu % B5 || nu / B5 > BLK_MAX) return 0;
  s->ng = nu / B5;
  for (unsigned g = 0; g < s->ng; g++) {
    const unsigned *u = s->U + B5 * g;
    if (u[4] != u[0] + 4) return 0; /* ascending: 4 apart means consecutive */
    s->ga0[g] = u[0];
  }
  return 1;
}

/* a double's bits without the sign: not zero exactly when the value is not +-0 */
static uint64_t nzbits(const double *v) {
  uint64_t b;
  memcpy(&b, v, sizeof b);
  return b << 1;
}

/* bit j of gpat[i] (j < i): some entry of A's block (rows of i, columns of j) is not zero; every
 * entry is read, so no nonzero can fall outside the structure */
static void blk_pattern(stLcp *s, const double *A, unsigned skip) {
  uint64_t acc[BLK_MAX];
  for (unsigned i = 0; i < s->ng; i++) {
    for (unsigned j = 0; j < i; j++) acc[j] = 0;
    for (unsigned t = 0; t < B5; t++) {
      const double *row = A + (size_t)(s->ga0[i] + t) * skip;
      for (unsigned j = 0; j < i; j++) {
        const double *v = row + s->ga0[j];
        acc[j] |= nzbits(v) | nzbits(v + 1) | nzbits(v + 2) | nzbits(v + 3) | nzbits(v + 4);
      }
    }
    uint64_t p = 0;
    for (unsigned j = 0; j < i; j++) p |= (uint64_t)(acc[j] != 0) << j;
    s->gpat[i] = p;
  }
}

/* minimum degree over the blocks (ties: the lowest block), each eliminated block's neighbours
 * made a clique: the neighbours at elimination are L's block column. Then L's blocks column by
 * column (lbeg, lrow) and where each one is (bidx). */
static void blk_min_degree(const stLcp *s, stBlkOrder *o) {
  const unsigned ng = s->ng;
  uint64_t adj[BLK_MAX], nbr[BLK_MAX];
  for (unsigned i = 0; i < ng; i++) adj[i] = s->gpat[i];
  for (unsigned i = 0; i < ng; i++)
    for (unsigned j = 0; j < i; j++)
      if (s->gpat[i] >> j & 1) adj[j] |= (uint64_t)1 << i;
  uint64_t alive = ng == 64 ? ~(uint64_t)0 : ((uint64_t)1 << ng) - 1;
  for (unsigned step = 0; step < ng; step++) {
    unsigned best = ng, bdeg = 0;
    for (unsigned i = 0; i < ng; i++) {
      if (!(alive >> i & 1)) continue;
      const unsigned deg = (unsigned)__builtin_popcountll(adj[i] & alive);
      if (best == ng || deg < bdeg) best = i, bdeg = deg;
    }
    alive &= ~((uint64_t)1 << best);
    const uint64_t nb = adj[best] & alive;
    for (uint64_t m = nb; m; m &= m - 1) {
      const unsigned j = (unsigned)__builtin_ctzll(m);
      adj[j] |= nb & ~((uint64_t)1 << j);
    }
    o->ord[step] = (unsigned char)best;
    nbr[step] = nb;
  }
  for (unsigned k = 0; k < ng; k++) o->pos[o->ord[k]] = (unsigned char)k;
  unsigned e = 0;
  for (unsigned k = 0; k < ng; k++) {
    uint64_t st = 0;
    for (uint64_t m = nbr[k]; m; m &= m - 1) st |= (uint64_t)1 << o->pos[__builtin_ctzll(m)];
    o->str[k] = st;
    o->lbeg[k] = (unsigned short)e;
    for (uint64_t m = st; m; m &= m - 1) {
      const unsigned i = (unsigned)__builtin_ctzll(m);
      o->lrow[e] = (unsigned char)i;
      o->bidx[i * BLK_MAX + k] = (unsigned short)e++;
    }
  }
  o->lbeg[ng] = (unsigned short)e;
}

/* the order for this problem's block pattern: from the last few when it is one of them */
static const stBlkOrder *blk_ordering(stLcp *s) {
  const unsigned ng = s->ng;
  for (int e = 0; e < ST_LCP_ORDERS; e++) {
    const stBlkOrder *o = &s->bo[e];
    if (o->ng == ng && !memcmp(o->pat, s->gpat, ng * sizeof *o->pat)) return o;
  }
  stBlkOrder *o = &s->bo[s->bo_next];
  s->bo_next = (s->bo_next + 1) % ST_LCP_ORDERS;
  blk_min_degree(s, o);
  o->ng = ng;
  memcpy(o->pat, s->gpat, ng * sizeof *o->pat);
  s->st.orderings++;
  return o;
}

/* A's 5 x 5 block (rows from r, columns from c; r > c: below the diagonal) into dst, row-major */
static void blk_load(double *dst, const double *A, unsigned skip, unsigned r, unsigned c) {
  for (unsigned a = 0; a < B5; a++) memcpy(dst + B5 * a, A + (size_t)(r + a) * skip + c, B5 * sizeof *dst);
}

/* ... the same block when it lies above the diagonal (r < c): read from its transpose */
static void blk_load_t(double *dst, const double *A, unsigned skip, unsigned r, unsigned c) {
  for (unsigned b = 0; b < B5; b++) {
    const double *src = A + (size_t)(c + b) * skip + r;
    for (unsigned a = 0; a < B5; a++) dst[B5 * a + b] = src[a];
  }
}

/* D := L D L^T of a 5 x 5 block in place (lower triangle read; L below the diagonal, D on it),
 * 1 / D into inv (multiplied by, not divided: a division's latency is the chain's); 0 on a
 * pivot that is not positive */
static int ldl5(double *D, double *inv) {
  for (unsigned a = 0; a < B5; a++) {
    double *Da = D + B5 * a;
    for (unsigned b = 0; b < a; b++) { /* Da[b] := L_ab d_b, from the rows above */
      const double *Db = D + B5 * b;
      double acc = Da[b];
      for (unsigned c = 0; c < b; c++) acc -= Da[c] * Db[c];
      Da[b] = acc;
    }
    double d = Da[a];
    for (unsigned b = 0; b < a; b++) {
      const double l = Da[b] * inv[b];
      d -= l * Da[b];
      Da[b] = l;
    }
    if (!(d > 0.0) || !isfinite(d)) return 0;
    Da[a] = d;
    inv[a] = 1.0 / d;
  }
  return 1;
}

/* dst -= X Y^T (5 x 5 blocks, row-major; only dst's lower triangle when lower) */
static void gemm5_sub(double *dst, const double *X, const double *Y, int lower) {
  for (unsigned a = 0; a < B5; a++) {
    const double *Xa = X + B5 * a;
    const unsigned nb = lower ? a + 1 : B5;
    for (unsigned b = 0; b < nb; b++) {
      const double *Yb = Y + B5 * b;
      dst[B5 * a + b] -= Xa[0] * Yb[0] + Xa[1] * Yb[1] + Xa[2] * Yb[2] + Xa[3] * Yb[3] + Xa[4] * Yb[4];
    }
  }
}

/* A_UU = L D L^T in the block order: D's blocks (their L and D) in s->Db by position, L's
 * off-diagonal blocks in s->Lb (o->lrow's order), 1 / D in dinv. Only the blocks of L's
 * structure are read or written. Returns 0 on a pivot that is not positive. */
static int blk_factor(stLcp *s, const double *A, unsigned skip) {
  const stBlkOrder *o = s->bord;
  const unsigned ng = s->ng;
  double *Db = s->Db, *Lb = s->Lb, *T = s->Tb;
  for (unsigned k = 0; k < ng; k++) { /* A's blocks into place (a fill block reads A's zeros) */
    const unsigned ak = s->ga0[o->ord[k]];
    blk_load(Db + BB * k, A, skip, ak, ak);
    for (unsigned e = o->lbeg[k]; e < o->lbeg[k + 1]; e++) {
      const unsigned ai = s->ga0[o->ord[o->lrow[e]]];
      if (ai > ak) blk_load(Lb + BB * e, A, skip, ai, ak);
      else blk_load_t(Lb + BB * e, A, skip, ai, ak);
    }
  }
  for (unsigned k = 0; k < ng; k++) {
    double *Dk = Db + BB * k;
    if (!ldl5(Dk, s->dinv + B5 * k)) return 0;
    const unsigned e0 = o->lbeg[k], e1 = o->lbeg[k + 1];
    for (unsigned e = e0; e < e1; e++) { /* T = A_ik L_kk^-T = L_ik D_k, then L_ik = T D_k^-1 */
      double *Te = T + BB * (e - e0), *Le = Lb + BB * e;
      for (unsigned a = 0; a < B5; a++) {
        double *t = Te + B5 * a;
        const double *l = Le + B5 * a;
        t[0] = l[0];
        t[1] = l[1] - Dk[5] * t[0];
        t[2] = l[2] - Dk[10] * t[0] - Dk[11] * t[1];
        t[3] = l[3] - Dk[15] * t[0] - Dk[16] * t[1] - Dk[17] * t[2];
        t[4] = l[4] - Dk[20] * t[0] - Dk[21] * t[1] - Dk[22] * t[2] - Dk[23] * t[3];
      }
      for (unsigned a = 0; a < B5; a++)
        for (unsigned b = 0; b < B5; b++) Le[B5 * a + b] = Te[B5 * a + b] * s->dinv[B5 * k + b];
    }
    for (unsigned e = e0; e < e1; e++) { /* A_ij -= L_ik D_k L_jk^T, i >= j in the column */
      const unsigned i = o->lrow[e];
      for (unsigned f = e0; f <= e; f++) {
        const unsigned j = o->lrow[f];
        if (i == j) gemm5_sub(Db + BB * i, T + BB * (e - e0), Lb + BB * f, 1);
        else gemm5_sub(Lb + BB * o->bidx[i * BLK_MAX + j], T + BB * (e - e0), Lb + BB * f, 0);
      }
    }
  }
  return 1;
}

/* y := L^-1 y (y by positions, 5 per block), y set only in the blocks of mask; returns the
 * blocks that may now be nonzero (the others still unset) */
static uint64_t blk_lsolve(const stLcp *s, double *y, uint64_t mask) {
  const stBlkOrder *o = s->bord;
  for (unsigned k = 0; k < s->ng; k++) {
    if (!(mask >> k & 1)) continue;
    const double *Dk = s->Db + BB * k;
    double *yk = y + B5 * k;
    yk[1] -= Dk[5] * yk[0];
    yk[2] -= Dk[10] * yk[0] + Dk[11] * yk[1];
    yk[3] -= Dk[15] * yk[0] + Dk[16] * yk[1] + Dk[17] * yk[2];
    yk[4] -= Dk[20] * yk[0] + Dk[21] * yk[1] + Dk[22] * yk[2] + Dk[23] * yk[3];
    for (unsigned e = o->lbeg[k]; e < o->lbeg[k + 1]; e++) {
      const unsigned i = o->lrow[e];
      double *yi = y + B5 * i;
      if (!(mask >> i & 1)) {
        memset(yi, 0, B5 * sizeof *yi);
        mask |= (uint64_t)1 << i;
      }
      const double *L = s->Lb + BB * e;
      for (unsigned a = 0; a < B5; a++, L += B5)
        yi[a] -= L[0] * yk[0] + L[1] * yk[1] + L[2] * yk[2] + L[3] * yk[3] + L[4] * yk[4];
    }
  }
  return mask;
}

/* v := L^-T v (v whole) */
static void blk_ltsolve(const stLcp *s, double *v) {
  const stBlkOrder *o = s->bord;
  for (unsigned k = s->ng; k-- > 0;) {
    double *vk = v + B5 * k;
    for (unsigned e = o->lbeg[k]; e < o->lbeg[k + 1]; e++) {
      const double *L = s->Lb + BB * e, *vi = v + B5 * o->lrow[e];
      for (unsigned a = 0; a < B5; a++, L += B5) {
        const double t = vi[a];
        vk[0] -= L[0] * t, vk[1] -= L[1] * t, vk[2] -= L[2] * t, vk[3] -= L[3] * t, vk[4] -= L[4] * t;
      }
    }
    const double *Dk = s->Db + BB * k;
    vk[3] -= Dk[23] * vk[4];
    vk[2] -= Dk[22] * vk[4] + Dk[17] * vk[3];
    vk[1] -= Dk[21] * vk[4] + Dk[16] * vk[3] + Dk[11] * vk[2];
    vk[0] -= Dk[20] * vk[4] + Dk[15] * vk[3] + Dk[10] * vk[2] + Dk[5] * vk[1];
  }
}

static double dot5(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4];
}

/* the reduced problem as reduce() makes it (S, b', bounds, friction indices; Y, W = D^-1 Y and
 * z kept), by blocks; Y's row r is set only in the blocks of ymask[r] */
static int blk_reduce(stLcp *s, const double *A, unsigned skip, const double *bx, const double *lh,
                      const int *findex, unsigned nu, unsigned nb) {
  const stBlkOrder *o = s->bord;
  const unsigned ng = s->ng, *B = s->B;
  if (!bounded_rows(s, lh, findex, nu, nb)) return 0;
  double *Y = s->Y, *W = s->W;
  for (unsigned r = 0; r < nb; r++) { /* Y = L^-1 A_UB, a row of A_BU at a time */
    double *y = Y + (size_t)r * nu;
    const unsigned b = B[r];
    const double *Ab = A + (size_t)b * skip;
    uint64_t mask = 0;
    for (unsigned g = 0; g < ng; g++) {
      const unsigned k = o->pos[g], ag = s->ga0[g];
      double *yk = y + B5 * k;
      if (ag < b) memcpy(yk, Ab + ag, B5 * sizeof *yk);
      else
        for (unsigned a = 0; a < B5; a++) yk[a] = A[(size_t)(ag + a) * skip + b];
      const uint64_t nz = nzbits(yk) | nzbits(yk + 1) | nzbits(yk + 2) | nzbits(yk + 3) | nzbits(yk + 4);
      mask |= (uint64_t)(nz != 0) << k;
    }
    mask = blk_lsolve(s, y, mask);
    s->ymask[r] = mask;
    double *w = W + (size_t)r * nu;
    for (uint64_t m = mask; m; m &= m - 1) {
      const unsigned k = B5 * (unsigned)__builtin_ctzll(m);
      for (unsigned a = k; a < k + B5; a++) w[a] = y[a] * s->dinv[a];
    }
  }
  double *z = s->z, *v = s->v;
  for (unsigned g = 0; g < ng; g++) {
    double *zk = z + B5 * o->pos[g];
    for (unsigned a = 0; a < B5; a++) zk[a] = bx[2 * (s->ga0[g] + a)];
  }
  blk_lsolve(s, z, ng == 64 ? ~(uint64_t)0 : ((uint64_t)1 << ng) - 1);
  for (unsigned i = 0; i < nu; i++) v[i] = z[i] * s->dinv[i];
  const unsigned sb = pad(nb);
  for (unsigned r = 0; r < nb; r++) { /* S = A_BB - W^T Y over the blocks both rows have */
    const double *wr = W + (size_t)r * nu, *yr = Y + (size_t)r * nu;
    const double *Ar = A + (size_t)B[r] * skip;
    for (unsigned c = 0; c <= r; c++) {
      const double *yc = Y + (size_t)c * nu;
      double acc = 0.0;
      for (uint64_t m = s->ymask[r] & s->ymask[c]; m; m &= m - 1) {
        const unsigned k = B5 * (unsigned)__builtin_ctzll(m);
        acc += dot5(wr + k, yc + k);
      }
      const double a = (B[c] <= B[r] ? Ar[B[c]] : A[(size_t)B[c] * skip + B[r]]) - acc;
      s->S[(size_t)r * sb + c] = a;
      s->S[(size_t)c * sb + r] = a;
    }
    double acc = 0.0;
    for (uint64_t m = s->ymask[r]; m; m &= m - 1) {
      const unsigned k = B5 * (unsigned)__builtin_ctzll(m);
      acc += dot5(yr + k, v + k);
    }
    s->bx_b[2 * r] = bx[2 * B[r]] - acc;
    s->bx_b[2 * r + 1] = 0.0;
  }
  return 1;
}

/* x_U = A_UU^-1 (b_U - A_UB x_B) = P^T L^-T D^-1 (z - Y x_B); every x into bx */
static void blk_back(stLcp *s, double *bx, unsigned nu, unsigned nb) {
  const stBlkOrder *o = s->bord;
  double *v = s->v;
  memcpy(v, s->z, nu * sizeof *v);
  for (unsigned r = 0; r < nb; r++) {
    const double xr = s->bx_b[2 * r + 1];
    bx[2 * s->B[r] + 1] = xr;
    if (xr == 0.0) continue;
    const double *yr = s->Y + (size_t)r * nu;
    for (uint64_t m = s->ymask[r]; m; m &= m - 1) {
      const unsigned k = B5 * (unsigned)__builtin_ctzll(m);
      for (unsigned a = k; a < k + B5; a++) v[a] -= yr[a] * xr;
    }
  }
  for (unsigned i = 0; i < nu; i++) v[i] *= s->dinv[i];
  blk_ltsolve(s, v);
  for (unsigned g = 0; g < s->ng; g++) {
    const double *vk = v + B5 * o->pos[g];
    for (unsigned a = 0; a < B5; a++) bx[2 * (s->ga0[g] + a) + 1] = vk[a];
  }
}

/* ---- dynamics.lcp = warm: the reduced LCP solved directly ---------------------------------- */

/* ODE's Dantzig solver (lcp.cpp) drives the bounded rows in one at a time with the friction rows
 * (findex >= 0) last; when it reaches the first of them it fixes their bounds, +-|hi| times
 * their normal's force at that moment, and never changes them again. At that moment the rows
 * before it satisfy their own LCP with the friction rows at 0, and at the end all rows satisfy
 * theirs with those bounds. S is positive definite, so each of the two box LCPs has one
 * solution: ODE's result is (1) the solution of the LCP of the rows without a friction index,
 * friction at 0, then (2) the solution of the whole LCP with the friction bounds from (1) (0 when
 * the normal's force is 0: those rows stay at 0, as in ODE). Each is found here by guessing which
 * rows are clamped and which sit at a bound (the last sub-step's answer for the row of the same
 * kind and rank), solving the clamped rows' equations directly and checking the rest: x within
 * the bounds, w of the right sign at a bound, to 1e-9 of the terms' size (rounding; a wrong
 * guess misses by far more). Rows that fail switch sides (block principal pivoting, Judice and
 * Pires 1994) for a few rounds; should that not settle, ODE's Dantzig solves S as in block. */

enum { RS_C = 0, RS_LO, RS_HI, RS_ZERO }; /* clamped, at lo, at hi, fixed at 0 (lo = hi = 0) */
enum { WARM_ROUNDS = 8, WARM_TRIES = 3 };
#define WARM_TOL 1e-9

static ST_THREAD_LOCAL int g_force_fallback; /* st__lcp_force_fallback */

void st__lcp_force_fallback(int on) { g_force_fallback = on; }

/* The box LCP of rows[0..nr) (the other rows' x are 0): S x = b + w, lo <= x <= hi, from the
 * statuses in rs. x into xd. Returns the rounds taken, 0 when it did not settle. Every row that
 * fails its check switches sides while that lowers the count of failing rows (or did within the
 * last WARM_TRIES rounds); else only the last failing one does (Murty's rule, which ends on a
 * positive definite S), as Judice and Pires (1994) safeguard block principal pivoting. */
static int bpp(stLcp *s, unsigned nb, const unsigned *rows, unsigned nr, const double *lo,
               const double *hi) {
  const unsigned sb = pad(nb);
  const double *S = s->S;
  double *x = s->xd, *F = s->F, *rhs = s->rhs, *dinvc = s->dinvc;
  unsigned char *rs = s->rs;
  unsigned *cl = s->cl;
  unsigned best = nr + 1;
  int tries = WARM_TRIES;
  for (int round = 1; round <= WARM_ROUNDS; round++) {
    unsigned nc = 0;
    for (unsigned q = 0; q < nr; q++) {
      const unsigned i = rows[q];
      if (rs[i] == RS_LO && lo[i] == -dInfinity) rs[i] = RS_C; /* no such bound */
      if (rs[i] == RS_HI && hi[i] == dInfinity) rs[i] = RS_C;
      if (rs[i] == RS_C) cl[nc++] = i;
      else x[i] = rs[i] == RS_LO ? lo[i] : hi[i];
    }
    /* S_CC x_C = b_C - S_CN x_N: LDL^T of S_CC (dense, positive definite) */
    unsigned nn = 0; /* the rows at a nonzero bound, after the clamped ones in cl */
    for (unsigned q = 0; q < nr; q++)
      if (rs[rows[q]] != RS_C && x[rows[q]] != 0.0) cl[nc + nn++] = rows[q];
    for (unsigned a = 0; a < nc; a++) {
      const double *Sa = S + (size_t)cl[a] * sb;
      double acc = s->bx_b[2 * cl[a]];
      for (unsigned q = nc; q < nc + nn; q++) acc -= Sa[cl[q]] * x[cl[q]];
      rhs[a] = acc;
      double *Fa = F + (size_t)a * nc;
      for (unsigned b = 0; b <= a; b++) Fa[b] = Sa[cl[b]];
    }
    /* right-looking, a column at a time: the updates run along rows (no chain of sums) */
    double *col = s->wcol;
    for (unsigned k = 0; k < nc; k++) {
      const double d = F[(size_t)k * nc + k];
      if (!(d > 0.0) || !isfinite(d)) return 0;
      const double inv = 1.0 / d;
      dinvc[k] = inv;
      for (unsigned i = k + 1; i < nc; i++) col[i] = F[(size_t)i * nc + k];
      for (unsigned i = k + 1; i < nc; i++) {
        double *Fi = F + (size_t)i * nc;
        const double l = col[i] * inv;
        for (unsigned j = k + 1; j <= i; j++) Fi[j] -= l * col[j];
        Fi[k] = l;
      }
    }
    for (unsigned a = 0; a < nc; a++) { /* L y = rhs, row by row */
      const double *Fa = F + (size_t)a * nc;
      double acc = rhs[a];
      for (unsigned b = 0; b < a; b++) acc -= Fa[b] * rhs[b];
      rhs[a] = acc;
    }
    for (unsigned a = 0; a < nc; a++) rhs[a] *= dinvc[a];
    for (unsigned b = nc; b-- > 1;) { /* L^T x = y, a finished x_b out of the rows above */
      const double *Fb = F + (size_t)b * nc, xb = rhs[b];
      for (unsigned a = 0; a < b; a++) rhs[a] -= Fb[a] * xb;
    }
    for (unsigned a = 0; a < nc; a++) x[cl[a]] = rhs[a];
    /* the check: each failing row's new side in cl (a list, as the statuses stay for now) */
    unsigned nbad = 0;
    for (unsigned q = 0; q < nr; q++) {
      const unsigned i = rows[q];
      const double xi = x[i];
      if (!isfinite(xi)) return 0;
      unsigned char to = RS_C;
      if (rs[i] == RS_C) {
        const double tol = WARM_TOL * (fabs(xi) + fabs(s->bx_b[2 * i]) / S[(size_t)i * sb + i]);
        if (xi < lo[i] - tol) to = RS_LO;
        else if (xi > hi[i] + tol) to = RS_HI;
        else continue;
      } else {
        const double *Si = S + (size_t)i * sb;
        double w = -s->bx_b[2 * i], size = fabs(w);
        for (unsigned j = 0; j < nb; j++) {
          if (x[j] == 0.0) continue;
          const double t = Si[j] * x[j];
          w += t;
          size += fabs(t);
        }
        if (rs[i] == RS_LO ? w >= -WARM_TOL * size : w <= WARM_TOL * size) continue;
      }
      cl[nbad++] = i | (unsigned)to << 24;
    }
    if (!nbad) return round;
    if (nbad < best) best = nbad, tries = WARM_TRIES;
    else if (tries > 0) tries--;
    else cl[0] = cl[nbad - 1], nbad = 1; /* Murty: the last one alone */
    for (unsigned q = 0; q < nbad; q++) rs[cl[q] & 0xffffff] = (unsigned char)(cl[q] >> 24);
  }
  return 0;
}

/* a bounded row's kind (friction, lo 0, hi infinite, lo infinite) for the warm start's memory */
static unsigned char row_kind(double lo, double hi, int f) {
  return (unsigned char)((f >= 0) | (lo == 0.0) << 1 | (hi == dInfinity) << 2 |
                         (lo == -dInfinity) << 3);
}

/* the reduced problem in s (S, bx_b, lh_b, findex_b) solved directly: x into bx_b; 1 when it
 * settled, else 0 (S, bx_b's b, lh_b untouched: for ODE's Dantzig) */
static int warm_solve(stLcp *s, unsigned nb) {
  unsigned char cnt[WARM_KINDS] = {0};
  unsigned *rows = s->posb; /* free after the reduction */
  double *x = s->xd;
  unsigned nr = 0, nfr = 0;
  for (unsigned r = 0; r < nb; r++) {
    const double lo = s->lh_b[2 * r], hi = s->lh_b[2 * r + 1];
    const unsigned char k = row_kind(lo, hi, s->findex_b[r]);
    s->kind[r] = k;
    s->rank[r] = cnt[k] < 255 ? cnt[k]++ : 255;
    x[r] = 0.0;
    const unsigned char h = s->rank[r] < WARM_RANKS ? s->hist[0][k][s->rank[r]] : 0;
    if (s->findex_b[r] >= 0) {
      nfr++;
          continue; /* outside phase 1: 0 */
    }
    s->lo2[r] = lo, s->hi2[r] = hi;
    if (lo == 0.0 && hi == 0.0) { /* never anything but 0 in ODE */
      s->rs[r] = RS_ZERO;
      continue;
    }
    s->rs[r] = h ? (unsigned char)(h - 1) : RS_C;
    rows[nr++] = r;
  }
  s->p1_ok = 0;
  int rounds = bpp(s, nb, rows, nr, s->lo2, s->hi2);
  if (!rounds) return 0;
  int total = rounds;
  for (unsigned q = 0; q < nr; q++) {
    const unsigned r = rows[q];
    if (s->rank[r] < WARM_RANKS) s->hist[0][s->kind[r]][s->rank[r]] = (unsigned char)(s->rs[r] + 1);
  }
  s->p1_ok = 1;
  if (nfr) { /* phase 2: the friction bounds from phase 1's normal forces, as ODE sets them */
    nr = 0;
    for (unsigned r = 0; r < nb; r++) {
      const int f = s->findex_b[r];
      if (f >= 0) {
        const double wf = x[f], h = s->lh_b[2 * r + 1];
        s->hi2[r] = wf == 0.0 ? 0.0 : fabs(h * wf);
        s->lo2[r] = -s->hi2[r];
        x[r] = 0.0;
        if (wf == 0.0) {
          s->rs[r] = RS_ZERO;
          continue;
        }
        const unsigned char hh = s->rank[r] < WARM_RANKS ? s->hist[1][s->kind[r]][s->rank[r]] : 0;
        s->rs[r] = hh ? (unsigned char)(hh - 1) : RS_C;
      } else if (s->rs[r] == RS_ZERO) continue;
      else if (s->rank[r] < WARM_RANKS && s->hist[1][s->kind[r]][s->rank[r]])
        s->rs[r] = (unsigned char)(s->hist[1][s->kind[r]][s->rank[r]] - 1); /* last phase 2's */
      rows[nr++] = r;
    }
    rounds = bpp(s, nb, rows, nr, s->lo2, s->hi2);
    if (!rounds) return 0;
    total += rounds;
    for (unsigned q = 0; q < nr; q++) {
      const unsigned r = rows[q];
      if (s->rank[r] < WARM_RANKS) s->hist[1][s->kind[r]][s->rank[r]] = (unsigned char)(s->rs[r] + 1);
    }
  }
  for (unsigned r = 0; r < nb; r++) s->bx_b[2 * r + 1] = x[r];
  s->st.rounds += total;
  return 1;
}

/* after ODE's Dantzig solved S: its answer's statuses as the next guess (ODE leaves a row in N
 * exactly at its bound; a friction row's bound is phase 1's, +-|hi| times the normal's force
 * then: known when phase 1 settled here, else guessed from the final force; to 1e-6) */
static void warm_remember(stLcp *s, unsigned nb) {
  unsigned char cnt[WARM_KINDS] = {0};
  for (unsigned r = 0; r < nb; r++) {
    const double lo = s->lh0[2 * r], hi = s->lh0[2 * r + 1], x = s->bx_b[2 * r + 1];
    const int f = s->f0[r];
    const unsigned char k = row_kind(lo, hi, f), q = cnt[k] < 255 ? cnt[k]++ : 255;
    if (q >= WARM_RANKS) continue;
    unsigned char st = RS_C;
    if (f >= 0) { /* the bound: phase 1's when it settled, else from the final normal force */
      const double b = s->p1_ok ? s->hi2[r] : fabs(hi * s->bx_b[2 * f + 1]);
      if (b > 0.0 && fabs(fabs(x) - b) <= 1e-6 * b) st = x > 0 ? RS_HI : RS_LO;
      s->hist[1][k][q] = (unsigned char)(st + 1);
      continue;
    }
    if (x == lo) st = RS_LO;
    else if (x == hi) st = RS_HI;
    s->hist[0][k][q] = s->hist[1][k][q] = (unsigned char)(st + 1);
  }
}

/* the problem by the block reduction (1), or 0 when it does not apply (nothing written) */
static int solve_block(stLcp *s, void *arena, unsigned n, const double *A, double *bx,
                       unsigned nub, const double *lh, const int *findex) {
  if (!reserve(s, n)) return 0;
  unsigned nu, nb;
  split_rows(s, n, nub, lh, findex, &nu, &nb);
  if (nu < 2 || !blk_groups(s, nu)) return 0;
  const unsigned skip = pad(n);
  blk_pattern(s, A, skip);
  s->bord = blk_ordering(s);
  if (!blk_factor(s, A, skip)) return 0;
  if (!blk_reduce(s, A, skip, bx, lh, findex, nu, nb)) return 0;
  if (nb) {
    if (s->mode == ST_DYN_LCP_WARM && !g_force_fallback && warm_solve(s, nb)) s->st.direct++;
    else {
      const int warm = s->mode == ST_DYN_LCP_WARM;
      if (warm) { /* ODE's solver permutes them in place */
        s->st.fallbacks++;
        memcpy(s->lh0, s->lh_b, 2 * nb * sizeof *s->lh0);
        memcpy(s->f0, s->findex_b, nb * sizeof *s->f0);
      }
      if (g_force_fallback) s->p1_ok = 0;
      /* (as in solve_reduced: a warning of ODE's on S stands, the world redoes the sub-step) */
      ode_lcp()(arena, nb, s->S, s->bx_b, NULL, 0, s->lh_b, s->findex_b);
      if (warm) warm_remember(s, nb);
    }
  }
  blk_back(s, bx, nu, nb);
  s->st.reduced++;
  s->st.rows += n;
  s->st.unbounded += nu;
  return 1;
}

/* the problem by the world's variant (1), or 0 when it does not apply (nothing written) */
static int solve_variant(stLcp *s, void *arena, unsigned n, const double *A, double *bx,
                         unsigned nub, const double *lh, const int *findex) {
  if (s->mode == ST_DYN_LCP_BLOCK || s->mode == ST_DYN_LCP_WARM) {
    if (solve_block(s, arena, n, A, bx, nub, lh, findex)) return 1;
    /* more than BLK_MAX blocks, or a pivot the blocks' rounding made not positive: schur's */
  }
  return solve_reduced(s, arena, n, A, bx, nub, lh, findex);
}

/* check mode: the reference's solution (ODE's, or schur's: ST_LCP_CHECK_*) kept, the world's
 * variant's on copies compared with it */
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
  const int reduced = solve_variant(s, arena, n, s->copyA, s->copybx, nub, s->copylh,
                                    findex ? s->copyf : NULL);
  int warned = st__ode_messages() != msgs;
  st__ode_messages_rewind(msgs);
  if (g_check == ST_LCP_CHECK_SCHUR) { /* the step goes on with schur's solution */
    const unsigned long m0 = st__ode_messages();
    const stLcpStats keep = s->st; /* the statistics stay the variant's */
    if (w || !solve_reduced(s, arena, n, A, bx, nub, lh, findex))
      ode_lcp()(arena, n, A, bx, w, nub, lh, findex);
    s->st = keep;
    warned |= st__ode_messages() != m0;
  } else
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
    if (!w && solve_variant(s, arena, n, A, bx, nub, lh, findex)) return;
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
