/* SPDX-License-Identifier: MIT
 * Mann-Whitney U and quantiles (selftalk/stats.h). Core: libm only. */
#include "selftalk/stats.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "core/readers.h"
#include "selftalk/io.h"

stMwuDef st_mwu_default_def(void) {
  stMwuDef d = {20, 0.5};
  return d;
}

static stStatus check_def(const stMwuDef *d, char *err, size_t errsz) {
  if (d->exact_max_n < 0 || d->exact_max_n > ST_MWU_EXACT_LIMIT)
    return st__errf(err, errsz, "mann-whitney: exact_max_n %d (expected 0..%d)", d->exact_max_n,
                    ST_MWU_EXACT_LIMIT), ST_ERR_RANGE;
  if (!(d->continuity >= 0.0 && d->continuity <= 0.5))
    return st__errf(err, errsz, "mann-whitney: continuity %g (expected 0..0.5)", d->continuity),
           ST_ERR_RANGE;
  return ST_OK;
}

/* what: "sample A", "quartiles", ... */
static stStatus check_sample(const char *what, const double *x, int n, char *err, size_t errsz) {
  if (n < 1) return st__errf(err, errsz, "%s: no values (expected at least 1)", what), ST_ERR_ARG;
  for (int i = 0; i < n; i++)
    if (!isfinite(x[i]))
      return st__errf(err, errsz, "%s: value %d is %g (expected a finite number)", what, i, x[i]),
             ST_ERR_RANGE;
  return ST_OK;
}

/* ---- exact distribution ---- */

/* f[j][k], k <= kmax, for the current i: the arrangements of i values of A and j of B (no ties)
 * with U_A = k. Mann & Whitney (1947): f(i, j, k) = f(i - 1, j, k - j) + f(i, j - 1, k), the
 * largest value being A's (it beats all j of B) or B's. Returns the row of n_b, or NULL. */
static double *exact_counts(int n_a, int n_b, int kmax) {
  const size_t w = (size_t)kmax + 1;
  double *f = calloc((size_t)(n_b + 1) * w, sizeof *f);
  if (!f) return NULL;
  for (int j = 0; j <= n_b; j++) f[j * w] = 1.0; /* i = 0: U = 0 */
  for (int i = 1; i <= n_a; i++)
    for (int j = 1; j <= n_b; j++) /* j = 0 stays U = 0 */
      for (int k = kmax; k >= 0; k--) /* f[j][k - j] is still row i - 1 */
        f[j * w + k] = (k >= j ? f[j * w + k - j] : 0.0) + f[(j - 1) * w + k];
  return f;
}

stStatus st_mwu_exact_p(int n_a, int n_b, double u, double *p, char *err, size_t errsz) {
  ST_ASSERT(p);
  if (n_a < 1 || n_b < 1 || n_a > ST_MWU_EXACT_LIMIT || n_b > ST_MWU_EXACT_LIMIT)
    return st__errf(err, errsz, "mann-whitney exact: sizes %d and %d (expected 1..%d each)", n_a,
                    n_b, ST_MWU_EXACT_LIMIT), ST_ERR_RANGE;
  const int mn = n_a * n_b, kmax = mn / 2;
  if (!(u >= 0.0 && u <= mn))
    return st__errf(err, errsz, "mann-whitney exact: U %g (expected 0..%d)", u, mn), ST_ERR_RANGE;
  double *f = exact_counts(n_a, n_b, kmax);
  if (!f) return st__errf(err, errsz, "mann-whitney exact: out of memory"), ST_ERR_NOMEM;
  const double *dist = f + (size_t)n_b * ((size_t)kmax + 1);
  const int k = (int)floor(fmin(u, mn - u)); /* <= kmax */
  double below = 0.0, half = 0.0;              /* P(U <= k), P(U <= kmax) unnormalised */
  for (int i = 0; i <= kmax; i++) {
    half += dist[i];
    if (i == k) below = half;
  }
  /* symmetry: the counts of kmax + 1 .. mn mirror 0 .. mn - kmax - 1 */
  const double total = 2.0 * half - (mn % 2 == 0 ? dist[kmax] : 0.0);
  free(f);
  *p = fmin(1.0, 2.0 * below / total);
  return ST_OK;
}

/* ---- ranks ---- */

typedef struct pooled {
  double v;
  int from_a;
} pooled;

static int cmp_pooled(const void *x, const void *y) {
  const double a = ((const pooled *)x)->v, b = ((const pooled *)y)->v;
  return (a > b) - (a < b);
}

/* sorts the pooled values; u_a from A's mid-rank sum, the tie term sum(t^3 - t) and the
 * number of tied values */
static void rank(pooled *v, int n, int n_a, stMwuResult *r, double *tie_term) {
  qsort(v, (size_t)n, sizeof *v, cmp_pooled);
  double rank_a = 0.0;
  *tie_term = 0.0;
  r->ties = 0;
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && v[j].v == v[i].v) j++;
    const double t = j - i, mid = 0.5 * (i + 1 + j); /* ranks i+1 .. j */
    for (int k = i; k < j; k++) rank_a += v[k].from_a ? mid : 0.0;
    if (t > 1) *tie_term += t * t * t - t, r->ties += (int)t;
    i = j;
  }
  r->u_a = rank_a - 0.5 * n_a * (n_a + 1.0);
}

/* the normal approximation with the tie and continuity corrections (SciPy's asymptotic p) */
static void normal_p(const stMwuDef *d, double tie_term, stMwuResult *r) {
  const double n = r->n_a + r->n_b, mu = 0.5 * r->n_a * r->n_b;
  const double var = r->n_a * (double)r->n_b / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
  r->method = ST_MWU_NORMAL;
  if (!(var > 0.0)) { /* every value the same */
    r->z = 0.0, r->p = 1.0;
    return;
  }
  const double dev = r->u_a - mu, z = fmax(0.0, fabs(dev) - d->continuity) / sqrt(var);
  r->z = dev < 0.0 ? -z : z;
  r->p = erfc(z * 0.70710678118654752440); /* 2 (1 - Phi(z)) <= 1: z >= 0 */
}

stStatus st_mwu(const stMwuDef *def, const double *a, int n_a, const double *b, int n_b,
                stMwuResult *r, char *err, size_t errsz) {
  ST_ASSERT(r);
  const stMwuDef d = def ? *def : st_mwu_default_def();
  stStatus st = check_def(&d, err, errsz);
  if (!st) st = check_sample("mann-whitney: sample A", a, n_a, err, errsz);
  if (!st) st = check_sample("mann-whitney: sample B", b, n_b, err, errsz);
  if (st) return st;
  pooled *v = malloc(sizeof *v * ((size_t)n_a + (size_t)n_b));
  if (!v) return st__errf(err, errsz, "mann-whitney: out of memory"), ST_ERR_NOMEM;
  for (int i = 0; i < n_a; i++) v[i].v = a[i], v[i].from_a = 1;
  for (int i = 0; i < n_b; i++) v[n_a + i].v = b[i], v[n_a + i].from_a = 0;
  memset(r, 0, sizeof *r);
  r->n_a = n_a, r->n_b = n_b;
  double tie_term;
  rank(v, n_a + n_b, n_a, r, &tie_term);
  free(v);
  r->u_b = (double)n_a * n_b - r->u_a;
  r->u = fmin(r->u_a, r->u_b);
  if (r->ties || n_a > d.exact_max_n || n_b > d.exact_max_n) {
    normal_p(&d, tie_term, r);
    return ST_OK;
  }
  r->method = ST_MWU_EXACT;
  return st_mwu_exact_p(n_a, n_b, r->u, &r->p, err, errsz);
}

/* ---- quantiles ---- */

double st_quantile_sorted(const double *sorted, int n, double p) {
  ST_ASSERT(sorted && n > 0);
  ST_ASSERT(p >= 0.0 && p <= 1.0);
  const double h = (n - 1) * p;
  const int j = (int)floor(h);
  if (j >= n - 1) return sorted[n - 1];
  if (j < 0) return sorted[0];
  const double a = sorted[j], b = sorted[j + 1], f = h - j, d = b - a;
  /* a + f (b - a), the usual form (exact at f = 0); when b - a overflows (finite values of
   * opposite signs near DBL_MAX), the weighted mean, whose terms cannot */
  const double q = isfinite(d) ? a + f * d : (1.0 - f) * a + f * b;
  return fmin(fmax(q, a), b);
}

static int cmp_double(const void *x, const void *y) {
  const double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

stStatus st_quartiles(const double *x, int n, stQuartiles *q, char *err, size_t errsz) {
  ST_ASSERT(q);
  stStatus st = check_sample("quartiles", x, n, err, errsz);
  if (st) return st;
  double *s = malloc(sizeof *s * (size_t)n);
  if (!s) return st__errf(err, errsz, "quartiles: out of memory"), ST_ERR_NOMEM;
  memcpy(s, x, sizeof *s * (size_t)n);
  qsort(s, (size_t)n, sizeof *s, cmp_double);
  q->n = n;
  q->min = s[0], q->max = s[n - 1];
  q->q1 = st_quantile_sorted(s, n, 0.25);
  q->median = st_quantile_sorted(s, n, 0.5);
  q->q3 = st_quantile_sorted(s, n, 0.75);
  free(s);
  return ST_OK;
}

/* ---- files of numbers ---- */

/* the numbers of a text (NUL-terminated at len, ours to change) */
typedef struct numbers {
  double *x;
  int n;
} numbers;

static stStatus parse_numbers(const char *name, char *text, size_t len, void *ctx, char *err,
                              size_t errsz) {
  numbers *out = ctx;
  stLines t = {text, len, 0, 0};
  double *x = NULL;
  int n = 0, cap = 0;
  stStatus st = ST_OK;
  for (char *s; !st && (s = st__lines_content(&t));) {
    char *end;
    errno = 0;
    const double v = strtod(s, &end);
    if (end == s || *end)
      st = (st__errf(err, errsz, "%s:%d: '%s' is not a number (expected one number per line)",
                     name, t.lineno, s), ST_ERR_PARSE);
    else if (!isfinite(v) || errno == ERANGE)
      st = (st__errf(err, errsz, "%s:%d: '%s' is not finite (expected a finite number)", name,
                     t.lineno, s), ST_ERR_PARSE);
    else if (n == cap) {
      double *y = realloc(x, (size_t)(cap = 2 * cap + 64) * sizeof *x);
      if (y) x = y;
      else st = (st__errf(err, errsz, "%s: out of memory", name), ST_ERR_NOMEM);
    }
    if (!st) x[n++] = v;
  }
  if (!st && !n)
    st = (st__errf(err, errsz, "%s: no numbers (expected one number per line; blank lines and # "
                   "comments are skipped)", name), ST_ERR_PARSE);
  if (st) free(x), x = NULL, n = 0;
  out->x = x, out->n = n;
  return st;
}

stStatus st__numbers_parse(const char *name, const char *text, size_t len, double **x, int *n,
                           char *err, size_t errsz) {
  ST_ASSERT(name && (text || len == 0) && x && n);
  numbers out = {NULL, 0};
  stStatus st = st__text_parse(name, text, len, parse_numbers, &out, err, errsz);
  *x = out.x, *n = out.n;
  return st;
}

stStatus st_numbers_read(const char *path, double **x, int *n, char *err, size_t errsz) {
  ST_ASSERT(path && x && n);
  numbers out = {NULL, 0};
  stStatus st = st__text_read_parse(path, parse_numbers, &out, err, errsz);
  *x = out.x, *n = out.n;
  return st;
}
