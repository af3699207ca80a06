/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/net.h"

stNetDef st_net_def_from_config(const stConfig *cfg) {
  ST_ASSERT(cfg);
  stNetDef d = {cfg->network_lambda, cfg->network_gamma_a, cfg->network_gamma_b};
  return d;
}

stNetDef st_net_default_def(void) {
  stConfig c;
  st_config_default(&c);
  return st_net_def_from_config(&c);
}

int st_net_ninputs(stNetArch arch) { return arch == ST_ARCH_BASE ? ST_NET_NIN : ST_NET_NIN + 1; }

int st_net_noutputs(stNetArch arch) {
  return arch == ST_ARCH_BASE ? ST_NET_NOUT : ST_NET_NOUT + ST_NET_NLING;
}

double st_net_sigmoid(double lambda, double x) { return 1.0 / (1.0 + exp(-lambda * x)); }

stStatus st_net_decode(const stNetDef *def, stNetArch arch, const stGenome *g, stNetParams *p,
                       char *err, size_t errsz) {
  ST_ASSERT(g && p);
  stNetDef d = def ? *def : st_net_default_def();
  int want = st_arch_ngenes(arch);
  if (!want) {
    st__errf(err, errsz, "unknown network architecture %d", (int)arch);
    return ST_ERR_ARG;
  }
  if (g->ngenes != want) {
    st__errf(err, errsz, "genotype has %d genes (expected %d for architecture %s)", g->ngenes, want,
             st_arch_name(arch));
    return ST_ERR_ARG;
  }
  memset(p, 0, sizeof *p);
  p->arch = arch;
  p->lambda = d.lambda;
  p->gamma = arch == ST_ARCH_A ? d.gamma_a : d.gamma_b;
  const uint16_t *u = g->gene;
  for (int h = 0; h < ST_NET_NHID; h++) {
    for (int i = 0; i < ST_NET_NIN; i++) p->w_ih[h][i] = st_gene_value(u[ST_GENE_IH(h, i)]);
    p->bias[h] = st_gene_value(u[ST_GENE_BIAS(h)]);
  }
  for (int k = 0; k < ST_NET_NOUT; k++)
    for (int h = 0; h < ST_NET_NHID; h++) p->w_ho[k][h] = st_gene_value(u[ST_GENE_HO(k, h)]);
  for (int k = 0; k < ST_NET_NDIRECT; k++)
    for (int f = 0; f < ST_NET_NFOCUS; f++) p->w_fo[k][f] = st_gene_value(u[ST_GENE_FO(k, f)]);
  if (arch == ST_ARCH_BASE) return ST_OK;
  for (int m = 0; m < ST_NET_NLING; m++) {
    for (int h = 0; h < ST_NET_NHID; h++) p->w_hl[m][h] = st_gene_value(u[ST_GENE_HL(m, h)]);
    for (int n = 0; n < ST_NET_NLING; n++) p->w_ll[m][n] = st_gene_value(u[ST_GENE_LL(m, n)]);
    p->delta[m] = (st_gene_value(u[ST_GENE_DECAY(m)]) + 1.0) / 2.0;
    p->w_sl[m] = st_gene_value(u[ST_GENE_SL(m)]);
  }
  if (arch == ST_ARCH_B)
    for (int h = 0; h < ST_NET_NHID; h++)
      for (int m = 0; m < ST_NET_NLING; m++) p->w_lh[h][m] = st_gene_value(u[ST_GENE_LH(h, m)]);
  return ST_OK;
}

void st_net_reset(const stNetParams *p, stNetState *s) {
  ST_ASSERT(p && s);
  (void)p;
  memset(s, 0, sizeof *s);
}

void st_net_step(const stNetParams *p, stNetState *s, const double *in, double *out) {
  ST_ASSERT(p && s && in);
  const double lam = p->lambda;
  /* hidden layer: inputs at t and, in type B, the hidden-linguistic values emitted at t-1 */
  for (int h = 0; h < ST_NET_NHID; h++) {
    double a = -p->bias[h];
    for (int i = 0; i < ST_NET_NIN; i++) a += p->w_ih[h][i] * in[i];
    if (p->arch == ST_ARCH_B)
      for (int m = 0; m < ST_NET_NLING; m++) a += p->w_lh[h][m] * s->ling_emit[m];
    s->hidden[h] = st_net_sigmoid(lam, a);
  }
  /* outputs: hidden at t plus the direct focus links to the torso and arm */
  for (int k = 0; k < ST_NET_NOUT; k++) {
    double a = 0.0;
    for (int h = 0; h < ST_NET_NHID; h++) a += p->w_ho[k][h] * s->hidden[h];
    if (k < ST_NET_NDIRECT)
      for (int f = 0; f < ST_NET_NFOCUS; f++) a += p->w_fo[k][f] * in[ST_NET_IN_FOCUS + f];
    s->out[k] = st_net_sigmoid(lam, a);
  }
  /* leaky linguistic cluster (eq. 2.13): every unit reads the emitted values of t-1 */
  if (p->arch != ST_ARCH_BASE) {
    double o[ST_NET_NLING];
    for (int m = 0; m < ST_NET_NLING; m++) {
      double a = p->w_sl[m] * in[ST_NET_IN_SECONDARY];
      for (int h = 0; h < ST_NET_NHID; h++) a += p->w_hl[m][h] * s->hidden[h];
      for (int n = 0; n < ST_NET_NLING; n++) a += p->w_ll[m][n] * s->ling_emit[n];
      o[m] = st_net_sigmoid(lam, a);
    }
    for (int m = 0; m < ST_NET_NLING; m++) {
      s->ling_u[m] = p->delta[m] * o[m] + (1.0 - p->delta[m]) * s->ling_u[m];
      s->ling_emit[m] = p->gamma * s->ling_u[m];
    }
  }
  s->t++;
  if (out) {
    memcpy(out, s->out, sizeof s->out);
    if (p->arch != ST_ARCH_BASE) memcpy(out + ST_NET_NOUT, s->ling_emit, sizeof s->ling_emit);
  }
}

int st_net_selftalk_label(const stNetState *s) {
  ST_ASSERT(s);
  int best = 0;
  for (int m = 1; m < ST_NET_NLING; m++)
    if (s->ling_emit[m] > s->ling_emit[best]) best = m;
  return best;
}

void st_net_label_input(int label, double scale, double in4[ST_NET_NLING]) {
  ST_ASSERT(label >= -1 && label < ST_NET_NLING);
  ST_ASSERT(in4);
  for (int m = 0; m < ST_NET_NLING; m++) in4[m] = m == label ? scale : 0.0;
}
