/* SPDX-License-Identifier: MIT
 * libselftalk: the statistics of the post-evaluation (thesis §2.10, §3; SPEC §11): the
 * two-tailed Mann-Whitney U test and the median and quartiles. Part of the core (libm only, no
 * simulator): ./apps/stats reads the post-evaluation CSVs and calls these.
 *
 * Conventions (docs/PROTOCOL.md, "Statistics"):
 * - U of sample A counts the pairs (a_i, b_j) with a_i > b_j, plus half the tied pairs (R's
 *   wilcox.test W, SciPy's U1). The thesis reports U = min(U_A, U_B).
 * - p is exact (the null distribution of U, counted) when the pooled values have no ties and
 *   both samples have at most def.exact_max_n (20) values; otherwise the normal approximation
 *   with the tie correction of the variance and a continuity correction of def.continuity (0.5):
 *   SciPy's mannwhitneyu(method="asymptotic", use_continuity=True).
 * - Quantiles are Hyndman & Fan's definition 7 (R's quantile() default, numpy's "linear"):
 *   linear interpolation between the order statistics at h = (n - 1) p. */
#ifndef SELFTALK_STATS_H
#define SELFTALK_STATS_H

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest def.exact_max_n: the exact distribution's table has (n_b + 1)(n_a n_b / 2 + 1)
 * doubles (0.5 MB at 50 and 50, R's own threshold). */
#define ST_MWU_EXACT_LIMIT 50

/* Definition of the test; st_mwu_default_def() gives SPEC §11's. */
typedef struct stMwuDef {
  int exact_max_n;   /* exact p when there are no ties and both samples have at most this many
                        values (20); 0..ST_MWU_EXACT_LIMIT, 0: always the normal approximation */
  double continuity; /* continuity correction of the normal approximation (0.5; 0: none) */
} stMwuDef;

ST_API stMwuDef st_mwu_default_def(void);

typedef enum stMwuMethod { ST_MWU_EXACT = 0, ST_MWU_NORMAL } stMwuMethod;

typedef struct stMwuResult {
  int n_a, n_b;
  double u_a;         /* pairs with a_i > b_j plus half the ties */
  double u_b;         /* n_a n_b - u_a */
  double u;           /* min(u_a, u_b) */
  double p;           /* two-tailed, in (0, 1] */
  double z;           /* normal approximation: (u_a - n_a n_b / 2, moved towards 0 by the
                         continuity correction) / sigma; 0 when p is exact */
  int ties;           /* pooled values that equal another value (0: no ties) */
  stMwuMethod method; /* how p was computed */
} stMwuResult;

/* The two-tailed Mann-Whitney U test of samples a (n_a values) and b (n_b values). Fails with
 * ST_ERR_ARG when a sample is empty, ST_ERR_RANGE on a non-finite value or a definition out of
 * range, ST_ERR_NOMEM. Nullable: def (the defaults). When every value is the same, sigma is 0:
 * p = 1, z = 0. */
ST_API stStatus st_mwu(const stMwuDef *def, const double *a, int n_a, const double *b, int n_b,
                stMwuResult *r, char *err, size_t errsz);

/* The exact two-tailed p of U = u (either U_A or U_B) for samples of n_a and n_b values without
 * ties: min(1, 2 P(U <= min(u, n_a n_b - u))), P counted by the recurrence of Mann & Whitney
 * (1947). Counts are exact integers in double while C(n_a + n_b, n_a) < 2^53 (both at most 25);
 * beyond, their relative error is below 1e-13. 1 <= n_a, n_b <= ST_MWU_EXACT_LIMIT, 0 <= u <=
 * n_a n_b (a fraction is rounded down: U has no fractions without ties). */
ST_API stStatus st_mwu_exact_p(int n_a, int n_b, double u, double *p, char *err, size_t errsz);

/* The p-quantile (0 <= p <= 1) of n >= 1 values sorted ascending: definition 7,
 * sorted[j] + (h - j)(sorted[j + 1] - sorted[j]) with h = (n - 1) p, j = floor(h). */
ST_API double st_quantile_sorted(const double *sorted, int n, double p);

typedef struct stQuartiles {
  int n;
  double min, q1, median, q3, max; /* quantiles 0, 0.25, 0.5, 0.75, 1 (definition 7) */
} stQuartiles;

/* The five-number summary of x (any order; x is not changed). Fails with ST_ERR_ARG when
 * n < 1, ST_ERR_RANGE on a non-finite value, ST_ERR_NOMEM. */
ST_API stStatus st_quartiles(const double *x, int n, stQuartiles *q, char *err, size_t errsz);

/* A file of one number per line (./apps/stats mwu, quartiles): lines are trimmed, blank lines
 * and lines starting with '#' skipped; each other line one finite number. *x (freed with
 * free()) holds the *n >= 1 numbers in file order. Read through the bounded reader (at most
 * ST_FILE_MAX bytes, no NUL byte). ST_ERR_IO, ST_ERR_PARSE ("FILE:LINE: 'x' is not a number
 * (expected one number per line)", "FILE: no numbers ..."), ST_ERR_NOMEM. */
ST_API stStatus st_numbers_read(const char *path, double **x, int *n, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
