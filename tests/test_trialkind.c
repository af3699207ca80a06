/* SPDX-License-Identifier: MIT
 * The table of trial kinds (selftalk/trialkind.h): its rows against ST_TRIAL_KINDS, the trial
 * indices they give, which kinds an evaluation has, and the kinds' cross-key rules, which a
 * program checks after loading a config (st_trial_kinds_check), naming the file's line. */
#include <string.h>

#include "selftalk/config.h"
#include "selftalk/trial.h"
#include "selftalk/trialkind.h"
#include "test_util.h"

/* every row is the line of ST_TRIAL_KINDS it stands for, and the indexed kinds' ranges follow
 * each other: fixed 0..15, hand-over 16..27, varied 28..35 */
static void test_kind_rows(void) {
  static const struct {
    stTrialKind kind;
    const char *name;
    int max, indexed;
  } want[] = {
#define ROW(E, name, max, indexed) {ST_TRIAL_##E, #name, max, indexed},
      ST_TRIAL_KINDS(ROW)
#undef ROW
  };
  CU_ASSERT_EQUAL_FATAL((int)(sizeof want / sizeof want[0]), ST_TRIAL_KIND_COUNT);
  int first = 0;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    CU_ASSERT_EQUAL(d->kind, want[k].kind);
    CU_ASSERT_STRING_EQUAL(d->name, want[k].name);
    CU_ASSERT(d->max == want[k].max && d->indexed == want[k].indexed);
    CU_ASSERT(d->max > 0 && d->max <= ST_TRIAL_KIND_MAX && d->title && d->trial_column);
    CU_ASSERT_PTR_NOT_NULL(d->count);
    /* an indexed kind makes specs; a block kind evaluates */
    CU_ASSERT(d->indexed ? d->spec && d->primitive && d->seed_key && !d->evaluate : d->evaluate != NULL);
    if (d->switch_key) { /* a key of the key table, and its family's keys too; all ours */
      const char *dot = strchr(d->switch_key, '.');
      char section[32];
      snprintf(section, sizeof section, "%.*s", (int)(dot - d->switch_key), d->switch_key);
      const int sw = st_config_find(section, dot + 1);
      CU_ASSERT_FATAL(sw >= 0);
      CU_ASSERT_EQUAL(st_config_key_tier(sw), ST_TIER_EXTENSION);
      CU_ASSERT(!d->family || !strncmp(d->family, section, strlen(section)));
      for (int i = 0; d->family && i < st_config_nkeys(); i++) {
        const stConfigKey *ck = st_config_key(i);
        if (!strcmp(ck->section, section) && !strncmp(ck->name, d->family + strlen(section) + 1,
                                                      strlen(d->family + strlen(section) + 1)))
          CU_ASSERT_EQUAL(st_config_key_tier(i), ST_TIER_EXTENSION);
      }
    }
    if (!d->indexed) continue;
    CU_ASSERT_EQUAL(st_trial_kind_first((stTrialKind)k), first);
    for (int j = 0; j < d->max; j++) CU_ASSERT_EQUAL(st_trial_kind(first + j), (stTrialKind)k);
    first += d->max;
  }
  CU_ASSERT_EQUAL(first, ST_MAIN_TRIALS_MAX);
  CU_ASSERT_EQUAL(st_trial_kind_first(ST_TRIAL_HANDOVER), ST_PRIM_TRIALS);
  CU_ASSERT_EQUAL(st_trial_kind_first(ST_TRIAL_VARIED), ST_PRIM_TRIALS + ST_TRIAL_MAX_HANDOVER);
  /* stage.chain_trials can ask for no more chained trials than their row holds */
  CU_ASSERT_EQUAL(st_config_key(st_config_find("stage", "chain_trials"))->max, ST_TRIAL_MAX_CHAINED);
}

/* which kinds an evaluation has, by stage, switch and generation */
static void test_kind_counts(void) {
  stConfig c;
  st_config_default(&c);
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const int fixed = k == ST_TRIAL_FIXED ? ST_PRIM_TRIALS : 0;
    CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_SIMPLE, (stTrialKind)k), fixed);
    CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_MAIN, (stTrialKind)k), fixed);
  }
  c.stage_stages = ST_STAGES_MAIN;
  c.stage_handover = 1, c.stage_chain_trials = 5;
  c.postures_vary_starts = 1, c.postures_vary_trials = ST_VARY_EXTRA;
  c.postures_vary_replace_generations = 3;
  CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_MAIN, ST_TRIAL_HANDOVER), ST_TRIAL_MAX_HANDOVER);
  CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_MAIN, ST_TRIAL_CHAINED), 5);
  CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_MAIN, ST_TRIAL_VARIED), ST_TRIAL_MAX_VARIED);
  CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_SIMPLE, ST_TRIAL_HANDOVER), 0);
  CU_ASSERT_EQUAL(st_trial_kind_count(&c, ST_STAGE_SIMPLE, ST_TRIAL_CHAINED), 0);
  /* the varied trials run once the generations that replace are over */
  CU_ASSERT(!st_trial_kind_runs(&c, ST_STAGE_MAIN, 2, ST_TRIAL_VARIED));
  CU_ASSERT(st_trial_kind_runs(&c, ST_STAGE_MAIN, 3, ST_TRIAL_VARIED));
  CU_ASSERT(st_trial_kind_runs(&c, ST_STAGE_MAIN, 0, ST_TRIAL_HANDOVER));
  CU_ASSERT(!st_trial_kind_runs(&c, ST_STAGE_SIMPLE, 0, ST_TRIAL_HANDOVER));
  CU_ASSERT_EQUAL(st_trial_kinds_check(&c, NULL, NULL, 0), ST_OK);
}

/* a config file refused by the kinds' rules (it loads: core knows no kind), naming its line */
static void expect_kind_error(const char *text, stStatus want, const char *needle) {
  char path[256], err[1024] = "";
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  stConfig c;
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_load(path, &c, err, sizeof err), ST_OK);
  const stStatus st = st_trial_kinds_check(&c, path, err, sizeof err);
  CU_ASSERT_EQUAL(st, want);
  if (st != want) fprintf(stderr, "\n  status %d for: %s\n", st, err);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, needle);
}

static void test_kind_rules(void) {
  /* a postures.vary_* key without the drawn starts would do nothing */
  expect_kind_error("[postures]\nvary_draws = 5\n\nvary_tilt = 10\n", ST_ERR_RANGE,
               ":4: key 'postures.vary_tilt': it shapes the drawn starts, which "
               "postures.vary_starts = false turns off (expected postures.vary_starts = true, or "
               "the key left out)");
  expect_kind_error("[postures]\nvary_open_high = true\n", ST_ERR_RANGE,
               ":2: key 'postures.vary_open_high': it shapes the drawn starts");
  {
    char path[256], e[1024];
    st_test_write_tmp(path, sizeof path, ".cfg", "[postures]\nvary_tilt = 10\nvary_starts = true\n");
    stConfig v;
    st_config_default(&v);
    CU_ASSERT_EQUAL(st_config_load(path, &v, e, sizeof e), ST_OK);
    CU_ASSERT_EQUAL(st_trial_kinds_check(&v, path, e, sizeof e), ST_OK);
    CU_ASSERT(v.postures_vary_starts == 1 && v.postures_vary_tilt == 10.0);
  }
  /* the completion rule of chained trials needs them */
  expect_kind_error("[stage]\nchain_complete = fixed_chained\n", ST_ERR_RANGE,
               ":2: key 'stage.chain_complete': it shapes the chained trials, which "
               "stage.chain_trials = 0 turns off");
  /* the varied trials are main-prim's: refused without the drawn starts, or in simple-prim */
  expect_kind_error("[postures]\nvary_trials = extra\n", ST_ERR_RANGE,
               ":2: key 'postures.vary_trials': it shapes the drawn starts, which "
               "postures.vary_starts = false turns off (expected postures.vary_starts = true, or "
               "the key left out)");
  expect_kind_error("[postures]\nvary_starts = true\nvary_trials = extra\n", ST_ERR_RANGE,
               ":3: key 'postures.vary_trials': extra adds main-prim trials, and stage.stages = "
               "simple_prim runs another stage (expected stage.stages = main_prim, or "
               "postures.vary_trials = replace)");
  expect_kind_error("[stage]\nstages = prims\n[postures]\nvary_starts = true\nvary_trials = extra\n",
               ST_ERR_RANGE, ":5: key 'postures.vary_trials': extra adds main-prim trials, and "
               "stage.stages = prims runs another stage (expected stage.stages = main_prim, or "
               "postures.vary_trials = replace)");
  /* replace before extra: refused without the drawn starts, and with replace throughout */
  expect_kind_error("[postures]\nvary_replace_generations = 40\n", ST_ERR_RANGE,
               ":2: key 'postures.vary_replace_generations': it shapes the drawn starts, which "
               "postures.vary_starts = false turns off");
  expect_kind_error("[stage]\nstages = main_prim\n[postures]\nvary_starts = true\n"
               "vary_replace_generations = 40\n", ST_ERR_RANGE,
               ":5: key 'postures.vary_replace_generations': 40 generations of replace before "
               "extra, and postures.vary_trials = replace replaces throughout (expected "
               "postures.vary_trials = extra, or the key left out)");
  /* keys that would act on nothing: hand-over trials or drawn starts of primitives
   * stage.primitives leaves out, a stop rule that cannot fire (a replace schedule as long as
   * the cap is not refused, issue 48: the cap only ends a run, --generations sets it) */
  expect_kind_error("[stage]\nstages = main_prim\nprimitives = reach\nhandover = true\n",
               ST_ERR_RANGE, ":4: key 'stage.handover': the hand-over trials are open's, grasp's "
               "and move's, and stage.primitives = reach evaluates none of them");
  expect_kind_error("[stage]\nstages = main_prim\nprimitives = reach,move\n[postures]\n"
               "vary_starts = true\n", ST_ERR_RANGE, ":5: key 'postures.vary_starts': the drawn "
               "starts are open's and grasp's, and stage.primitives = reach,move evaluates neither");
  expect_kind_error("[stage]\nstages = main_prim\nchain_trials = 8\nchain_complete = fixed_chained\n"
               "[postures]\nvary_starts = true\n", ST_ERR_RANGE,
               ":4: key 'stage.chain_complete': fixed_chained completes a genotype only when it "
               "solves the 16 from their fixed starts, and postures.vary_trials = replace draws");
  {
    /* the nearest accepted: move's hand-over trials alone; grasp's drawn starts alone;
     * fixed_chained with extra; a replace schedule the cap ends first */
    stConfig v;
    char e[512] = "";
    st_config_default(&v);
    const char *const set[] = {"ga.max_generations=40", "stage.stages=main_prim",
                               "stage.primitives=grasp,move", "stage.handover=true",
                               "stage.chain_trials=8", "stage.chain_complete=fixed_chained",
                               "postures.vary_starts=true", "postures.vary_trials=extra",
                               "postures.vary_replace_generations=40"};
    CU_ASSERT_EQUAL(st_config_set_all(&v, set, (int)(sizeof set / sizeof set[0]), e, sizeof e),
                    ST_OK);
    CU_ASSERT_EQUAL(st_trial_kinds_check(&v, NULL, e, sizeof e), ST_OK);
    if (e[0]) fprintf(stderr, "%s\n", e);
  }
  /* without the file: the key alone */
  stConfig c;
  char err[512] = "";
  st_config_default(&c);
  c.stage_handover_fallback = 1;
  CU_ASSERT_EQUAL(st_trial_kinds_check(&c, NULL, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_EQUAL(strncmp(err, "key 'stage.handover_fallback': it shapes the hand-over trials", 61), 0);
}

void st_suite_trialkind(void) {
  ST_ADD_SUITE("trialkind");
  ST_ADD_TEST(test_kind_rows);
  ST_ADD_TEST(test_kind_counts);
  ST_ADD_TEST(test_kind_rules);
}
