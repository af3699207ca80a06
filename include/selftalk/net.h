/* SPDX-License-Identifier: MIT
 * libselftalk: the controller network of SPEC §4 (thesis §2.3, §2.9.1).
 *
 * Model/data split as in MuJoCo: stNetParams is decoded once from a genotype, immutable and
 * shareable by any number of threads; stNetState holds the per-trial activations and the
 * leaky units' memory. Both are fixed-size values: no allocation anywhere in this module,
 * which depends on nothing but libm and the config key table of the core (link it into a robot
 * controller alone).
 *
 * Inputs (25, or 26 for types A and B): 0-11 proprioception, 12-17 touch, 18-20 focus
 * vector, 21-24 linguistic input (reach, open, grasp, move), 25 secondary linguistic input.
 * Outputs (13): 0-11 desired normalised joint positions, 12 focus (< 0.5 object).
 * Types A and B add 4 linguistic values (emitted values of the leaky cluster). */
#ifndef SELFTALK_NET_H
#define SELFTALK_NET_H

#include "selftalk/base.h"
#include "selftalk/config.h"
#include "selftalk/genome.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Protocol constants of the network: keys network.lambda, gamma_a, gamma_b. */
typedef struct stNetDef {
  double lambda;  /* sigmoid slope: sigma(x) = 1 / (1 + exp(-lambda x)) */
  double gamma_a; /* gain of type A linguistic outputs */
  double gamma_b; /* gain of type B hidden-linguistic units */
} stNetDef;

/* The network keys of cfg. */
ST_API stNetDef st_net_def_from_config(const stConfig *cfg);
/* The keys' defaults (the thesis's values, from the key table). */
ST_API stNetDef st_net_default_def(void);

/* Parameters decoded from a genotype (weights in [-1, 1], decays in [0, 1]). */
typedef struct stNetParams {
  stNetArch arch;
  double lambda;
  double gamma;                                /* gain of the linguistic cluster */
  double w_ih[ST_NET_NHID][ST_NET_NIN];        /* input -> hidden */
  double bias[ST_NET_NHID];                    /* hidden bias (subtracted) */
  double w_ho[ST_NET_NOUT][ST_NET_NHID];       /* hidden -> output */
  double w_fo[ST_NET_NDIRECT][ST_NET_NFOCUS];  /* focus input -> torso/arm output */
  double w_hl[ST_NET_NLING][ST_NET_NHID];      /* hidden -> linguistic cluster */
  double w_ll[ST_NET_NLING][ST_NET_NLING];     /* [m][n]: emitted n at t-1 -> m */
  double delta[ST_NET_NLING];                  /* decay factor */
  double w_sl[ST_NET_NLING];                   /* secondary input -> linguistic cluster */
  double w_lh[ST_NET_NHID][ST_NET_NLING];      /* hidden linguistic -> hidden (type B) */
} stNetParams;

/* Per-trial state. */
typedef struct stNetState {
  double hidden[ST_NET_NHID];
  double out[ST_NET_NOUT];
  double ling_u[ST_NET_NLING];    /* internal state u(t) of the leaky units */
  double ling_emit[ST_NET_NLING]; /* emitted value gamma * u(t) */
  long t;                         /* steps taken since reset */
} stNetState;

/* Inputs and outputs of an architecture: 25/13 (base), 26/17 (A, B; outputs include the 4
 * linguistic values). */
ST_API int st_net_ninputs(stNetArch arch);
ST_API int st_net_noutputs(stNetArch arch);

/* Decodes a genotype. Fails with ST_ERR_ARG (message in err) when the genotype's gene count
 * is not the architecture's. Nullable: def (thesis defaults). */
ST_API stStatus st_net_decode(const stNetDef *def, stNetArch arch, const stGenome *g, stNetParams *p,
                       char *err, size_t errsz);

/* Starts a trial: leaky units at u(-1) = 0, nothing emitted. */
ST_API void st_net_reset(const stNetParams *p, stNetState *s);

/* One control step. in holds st_net_ninputs(arch) values; out receives
 * st_net_noutputs(arch) values (nullable: read s->out / s->ling_emit instead). */
ST_API void st_net_step(const stNetParams *p, stNetState *s, const double *in, double *out);

/* The logistic function with slope lambda. */
ST_API double st_net_sigmoid(double lambda, double x);

/* Self talk (type A): the label produced this step, the argmax of the linguistic values
 * (ties: lowest index), 0 reach, 1 open, 2 grasp, 3 move. */
ST_API int st_net_selftalk_label(const stNetState *s);

/* Linguistic inputs for a heard label: one-hot times scale, or all zero when label < 0. */
ST_API void st_net_label_input(int label, double scale, double in4[ST_NET_NLING]);

#ifdef __cplusplus
}
#endif

#endif
