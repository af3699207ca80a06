/* SPDX-License-Identifier: MIT
 * Network tests: expected values are worked out by hand from thesis eq. 2.1 / 2.13 with
 * lambda = 1.5 (literals computed with a calculator, not with this library). */
#include <math.h>

#include "selftalk/net.h"
#include "test_util.h"

static void zero_params(stNetParams *p, stNetArch arch, double gamma) {
  memset(p, 0, sizeof *p);
  p->arch = arch;
  p->lambda = 1.5;
  p->gamma = gamma;
}

static void test_gene_decoding(void) {
  CU_ASSERT_DOUBLE_EQUAL(st_gene_value(0), -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_gene_value(65535), 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(st_gene_value(32768), 1.0 / 65535.0, 1e-18);
  CU_ASSERT_DOUBLE_EQUAL(st_gene_value(32767), -1.0 / 65535.0, 1e-18);
  /* bit order: bit 0 is the most significant bit of gene 0 */
  stGenome g;
  memset(&g, 0, sizeof g);
  g.ngenes = 2;
  g.gene[0] = 0x8001;
  CU_ASSERT_EQUAL(st_genome_bit(&g, 0), 1);
  CU_ASSERT_EQUAL(st_genome_bit(&g, 1), 0);
  CU_ASSERT_EQUAL(st_genome_bit(&g, 15), 1);
  st_genome_flip_bit(&g, 16);
  CU_ASSERT_EQUAL(g.gene[1], 0x8000);
}

/* SPEC §4 table: first and last index of every block */
static void test_gene_layout(void) {
  CU_ASSERT_EQUAL(ST_GENE_IH(0, 0), 0);
  CU_ASSERT_EQUAL(ST_GENE_IH(14, 24), 374);
  CU_ASSERT_EQUAL(ST_GENE_HO(0, 0), 375);
  CU_ASSERT_EQUAL(ST_GENE_HO(12, 14), 569);
  CU_ASSERT_EQUAL(ST_GENE_FO(0, 0), 570);
  CU_ASSERT_EQUAL(ST_GENE_FO(8, 2), 596);
  CU_ASSERT_EQUAL(ST_GENE_BIAS(0), 597);
  CU_ASSERT_EQUAL(ST_GENE_BIAS(14), 611);
  CU_ASSERT_EQUAL(ST_GENE_HL(0, 0), 612);
  CU_ASSERT_EQUAL(ST_GENE_HL(3, 14), 671);
  CU_ASSERT_EQUAL(ST_GENE_LL(0, 0), 672);
  CU_ASSERT_EQUAL(ST_GENE_LL(3, 3), 687);
  CU_ASSERT_EQUAL(ST_GENE_DECAY(0), 688);
  CU_ASSERT_EQUAL(ST_GENE_SL(3), 695);
  CU_ASSERT_EQUAL(ST_GENE_LH(0, 0), 696);
  CU_ASSERT_EQUAL(ST_GENE_LH(14, 3), 755);
  CU_ASSERT_EQUAL(st_arch_ngenes(ST_ARCH_BASE), 612);
  CU_ASSERT_EQUAL(st_arch_ngenes(ST_ARCH_A), 696);
  CU_ASSERT_EQUAL(st_arch_ngenes(ST_ARCH_B), 756);

  /* decoding reads each weight from its own gene: mark one gene per block */
  stGenome g;
  memset(&g, 0, sizeof g);
  g.ngenes = 756;
  for (int i = 0; i < 756; i++) g.gene[i] = 32768;
  g.gene[2 * 25 + 7] = 65535;  /* input 7 -> hidden 2 */
  g.gene[375 + 4 * 15 + 9] = 0; /* hidden 9 -> output 4 */
  g.gene[570 + 5 * 3 + 2] = 65535; /* focus 2 -> output 5 */
  g.gene[597 + 11] = 0;        /* bias 11 */
  g.gene[612 + 1 * 15 + 3] = 65535; /* hidden 3 -> linguistic 1 */
  g.gene[672 + 2 * 4 + 0] = 0;  /* linguistic 0 -> 2 */
  g.gene[688 + 3] = 65535;      /* decay of unit 3 -> delta 1 */
  g.gene[692 + 2] = 0;          /* secondary -> unit 2 */
  g.gene[696 + 6 * 4 + 1] = 65535; /* hidden-linguistic 1 -> hidden 6 */
  stNetParams p;
  CU_ASSERT_EQUAL(st_net_decode(NULL, ST_ARCH_B, &g, &p, NULL, 0), ST_OK);
  CU_ASSERT_DOUBLE_EQUAL(p.w_ih[2][7], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_ih[7][2], 1.0 / 65535.0, 1e-18);
  CU_ASSERT_DOUBLE_EQUAL(p.w_ho[4][9], -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_fo[5][2], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.bias[11], -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_hl[1][3], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_ll[2][0], -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_ll[0][2], 1.0 / 65535.0, 1e-18);
  CU_ASSERT_DOUBLE_EQUAL(p.delta[3], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.delta[0], 0.5 + 0.5 / 65535.0, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(p.w_sl[2], -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.w_lh[6][1], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(p.gamma, 10.0, 0.0);

  char err[256];
  g.ngenes = 612;
  CU_ASSERT_EQUAL(st_net_decode(NULL, ST_ARCH_A, &g, &p, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "612 genes (expected 696 for architecture A)");
}

/* base network: H0 = sigma(-0.5 + 1*1) = sigma(0.5); out3 = sigma(2 H0); out4 = sigma(-1 * 2)
 * through the direct focus link; every other unit sees 0 and gives sigma(0) = 0.5 */
static void test_forward_pass(void) {
  stNetParams p;
  zero_params(&p, ST_ARCH_BASE, 0);
  p.w_ih[0][0] = 1.0;
  p.bias[0] = 0.5;
  p.w_ho[3][0] = 2.0;
  p.w_fo[4][1] = -1.0;
  double in[25] = {0}, out[13];
  in[0] = 1.0;
  in[19] = 2.0;
  stNetState s;
  st_net_reset(&p, &s);
  st_net_step(&p, &s, in, out);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[0], 0.679178699175393, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[1], 0.5, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(out[3], 0.8846821396341815, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(out[4], 0.04742587317756678, 1e-15);
  for (int k = 0; k < 13; k++)
    if (k != 3 && k != 4) CU_ASSERT_DOUBLE_EQUAL(out[k], 0.5, 1e-15);
  /* the focus link reaches outputs 0..8 only: a focus weight row beyond 8 does not exist,
   * so driving the focus input changes outputs 9..12 not at all */
  in[18] = 5.0;
  st_net_step(&p, &s, in, out);
  for (int k = 9; k < 13; k++) CU_ASSERT_DOUBLE_EQUAL(out[k], 0.5, 1e-15);
  CU_ASSERT_EQUAL(st_net_ninputs(ST_ARCH_BASE), 25);
  CU_ASSERT_EQUAL(st_net_noutputs(ST_ARCH_B), 17);
}

/* a leaky unit driven by a constant O = sigma(2) (secondary input 2, weight 1) with
 * delta = 0.25 follows u(t) = O (1 - 0.75^(t+1)) from u(-1) = 0 */
static void test_leaky_unit(void) {
  stNetParams p;
  zero_params(&p, ST_ARCH_A, 1.0);
  p.w_sl[0] = 1.0;
  p.delta[0] = 0.25;
  p.delta[1] = 1.0;
  p.w_ll[1][0] = 1.0; /* unit 0's emitted value at t-1 drives unit 1 */
  double in[26] = {0}, out[17];
  in[25] = 2.0;
  const double O = 0.9525741268224334;
  stNetState s;
  st_net_reset(&p, &s);
  double prev_emit0 = 0.0;
  for (int t = 0; t < 6; t++) {
    st_net_step(&p, &s, in, out);
    double u = O * (1.0 - pow(0.75, t + 1));
    CU_ASSERT_DOUBLE_EQUAL(out[13], u, 1e-14);
    CU_ASSERT_DOUBLE_EQUAL(s.ling_u[0], u, 1e-14);
    /* unit 1: delta 1, so u1(t) = sigma(e0(t-1)) */
    CU_ASSERT_DOUBLE_EQUAL(out[14], 1.0 / (1.0 + exp(-1.5 * prev_emit0)), 1e-14);
    prev_emit0 = out[13];
  }
  /* type A's cluster does not feed the hidden layer */
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[0], 0.5, 1e-15);
  /* after 6 steps u0 = O (1 - 0.75^6) = 0.7830 beats u1 = sigma(0.7265) = 0.7481 */
  CU_ASSERT_EQUAL(st_net_selftalk_label(&s), 0);
  stNetState tie;
  memset(&tie, 0, sizeof tie);
  CU_ASSERT_EQUAL(st_net_selftalk_label(&tie), 0);
  tie.ling_emit[0] = 0.1;
  tie.ling_emit[1] = 0.7;
  tie.ling_emit[2] = 0.7; /* tie between 1 and 2: the lower index wins */
  tie.ling_emit[3] = 0.2;
  CU_ASSERT_EQUAL(st_net_selftalk_label(&tie), 1);
  double li[4];
  st_net_label_input(2, 10.0, li);
  CU_ASSERT(li[0] == 0 && li[1] == 0 && li[2] == 10.0 && li[3] == 0);
  st_net_label_input(-1, 10.0, li);
  CU_ASSERT(li[0] == 0 && li[1] == 0 && li[2] == 0 && li[3] == 0);
}

/* type B: hidden-linguistic unit 1 (delta 1, gamma 10) driven by the secondary input feeds
 * hidden 2 one step later: e1(0) = 10 sigma(1); H2(1) = sigma(e1(0)); out0 = sigma(H2) */
static void test_typeb_feedback(void) {
  stNetParams p;
  zero_params(&p, ST_ARCH_B, 10.0);
  p.w_sl[1] = 1.0;
  p.delta[1] = 1.0;
  p.w_lh[2][1] = 1.0;
  p.w_ho[0][2] = 1.0;
  double in[26] = {0}, out[17];
  in[25] = 1.0;
  stNetState s;
  st_net_reset(&p, &s);
  st_net_step(&p, &s, in, out);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[2], 0.5, 1e-15); /* nothing emitted before t = 0 */
  CU_ASSERT_DOUBLE_EQUAL(out[14], 8.175744761936436, 1e-13);
  st_net_step(&p, &s, in, out);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[2], 0.9999952796228803, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(out[0], 0.8175734201500192, 1e-15);
  /* the same weights in a type A network do nothing to the hidden layer */
  p.arch = ST_ARCH_A;
  st_net_reset(&p, &s);
  st_net_step(&p, &s, in, out);
  st_net_step(&p, &s, in, out);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[2], 0.5, 1e-15);
}

/* the network's constants come from the key table: the thesis's values by default (eq. 2.1:
 * lambda 1.5; eq. 2.13: gamma 1 for type A, 10 for type B), the config's when set */
static void test_net_def_from_config(void) {
  stNetDef d = st_net_default_def();
  CU_ASSERT_DOUBLE_EQUAL(d.lambda, 1.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(d.gamma_a, 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(d.gamma_b, 10.0, 0.0);
  stConfig c;
  char err[256];
  st_config_default(&c);
  const char *sets[] = {"network.lambda=2.5", "network.gamma_a=3", "network.gamma_b=7"};
  CU_ASSERT_EQUAL_FATAL(st_config_set_all(&c, sets, 3, err, sizeof err), ST_OK);
  d = st_net_def_from_config(&c);
  CU_ASSERT_DOUBLE_EQUAL(d.lambda, 2.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(d.gamma_a, 3.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(d.gamma_b, 7.0, 0.0);
  /* decoding with it: all-zero genes give weights -1, so with the zero input of step 0 every
   * hidden unit sees -bias = +1: sigma(2.5 * 1) = 1 / (1 + e^-2.5) = 0.9241418199787566 */
  stGenome g;
  memset(&g, 0, sizeof g);
  g.ngenes = 612;
  stNetParams p;
  CU_ASSERT_EQUAL_FATAL(st_net_decode(&d, ST_ARCH_BASE, &g, &p, err, sizeof err), ST_OK);
  double in[25] = {0}, out[13];
  stNetState s;
  st_net_reset(&p, &s);
  st_net_step(&p, &s, in, out);
  CU_ASSERT_DOUBLE_EQUAL(s.hidden[0], 0.9241418199787566, 1e-15);
}

void st_suite_net(void) {
  ST_ADD_SUITE("net");
  ST_ADD_TEST(test_gene_decoding);
  ST_ADD_TEST(test_gene_layout);
  ST_ADD_TEST(test_forward_pass);
  ST_ADD_TEST(test_leaky_unit);
  ST_ADD_TEST(test_typeb_feedback);
  ST_ADD_TEST(test_net_def_from_config);
}
