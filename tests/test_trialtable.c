/* SPDX-License-Identifier: MIT
 * The trial table (selftalk/trial.h): a generation's trials built once hold what st_trial_spec
 * gives, and an evaluation on a workspace that holds another generation's table, or another
 * protocol's, equals one on a fresh workspace. */
#include <string.h>

#include "selftalk/trial.h"
#include "test_util.h"

static stProtocol *protocol(int seed) {
  stConfig c;
  char err[512];
  st_config_default(&c);
  c.run_seed = seed;
  c.postures_vary_starts = 1; /* the starts that cost inverse kinematics */
  stProtocol *p = NULL;
  if (st_protocol_create(&c, &p, err, sizeof err)) fprintf(stderr, "\n  %s\n", err);
  return p;
}

static void test_table_holds_the_specs(void) {
  stProtocol *p = protocol(5);
  CU_ASSERT_PTR_NOT_NULL_FATAL(p);
  static stTrialTable tab;
  st_trial_table(p, ST_STAGE_MAIN, 3, &tab);
  CU_ASSERT_EQUAL(tab.n, st_stage_trials(p, ST_STAGE_MAIN));
  for (int i = 0; i < tab.n; i++) {
    stTrialSpec t;
    st_trial_spec(p, ST_STAGE_MAIN, 3, i, &t);
    CU_ASSERT(memcmp(&t, &tab.t[i], sizeof t) == 0);
  }
  st_protocol_destroy(p);
}

static void net_of(int seed, stNetParams *np) {
  stRng rng = st_rng_keyed((uint64_t)seed, ST_RNG_INIT, 0, 1, 0);
  stGenome g;
  st_genome_random(&g, ST_GENES_BASE, &rng);
  CU_ASSERT_EQUAL(st_net_decode(NULL, ST_ARCH_BASE, &g, np, NULL, 0), ST_OK);
}

static void test_warm_equals_cold(void) {
  stProtocol *a = protocol(5), *b = protocol(6);
  CU_ASSERT_PTR_NOT_NULL_FATAL(a);
  CU_ASSERT_PTR_NOT_NULL_FATAL(b);
  stNetParams np;
  net_of(9, &np);
  char err[512];
  stWorkspace warm = {NULL, NULL, NULL};
  stEvaluation e_warm, e_cold;
  memset(&e_warm, 0, sizeof e_warm);
  memset(&e_cold, 0, sizeof e_cold);
  /* the warm workspace holds generation 1 of protocol a, then is asked for generation 2 and
   * for protocol b's generation 2 */
  CU_ASSERT_EQUAL(st_stage_evaluate(a, &warm, ST_STAGE_SIMPLE, 1, 0, &np, NULL, &e_warm, err, sizeof err), ST_OK);
  const stProtocol *order[2] = {a, b};
  for (int k = 0; k < 2; k++) {
    stWorkspace cold = {NULL, NULL, NULL};
    CU_ASSERT_EQUAL(st_stage_evaluate(order[k], &warm, ST_STAGE_SIMPLE, 2, 3, &np, NULL, &e_warm, err,
                                      sizeof err), ST_OK);
    CU_ASSERT_EQUAL(st_stage_evaluate(order[k], &cold, ST_STAGE_SIMPLE, 2, 3, &np, NULL, &e_cold, err,
                                      sizeof err), ST_OK);
    CU_ASSERT(memcmp(&e_warm, &e_cold, sizeof e_warm) == 0);
    st_workspace_free(&cold);
  }
  st_workspace_free(&warm);
  st_protocol_destroy(a);
  st_protocol_destroy(b);
}

void st_suite_trialtable(void) {
  ST_ADD_SUITE("trialtable");
  ST_ADD_TEST(test_table_holds_the_specs);
  ST_ADD_TEST(test_warm_equals_cold);
}
