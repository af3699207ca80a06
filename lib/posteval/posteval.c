/* SPDX-License-Identifier: MIT
 * The post-evaluations' tables, words, conditions, exclusion rule and one trial
 * (selftalk/posteval.h). The inputs and the parallel run are in postrun.c, the files' writers
 * and readers in postcsv.c. */
#include <math.h>
#include <string.h>

#include "core/internal.h"
#include "posteval/journal.h"
#include "selftalk/posteval.h"

/* ---- the tests, one row each ---- */

static int integration_trials(const stConfig *c) { return c->posteval_integration_trials; }
static int robustness_trials(const stConfig *c) { return c->posteval_robustness_trials; }
static int grid_trials(const stConfig *c) {
  const int cells = c->posteval_generalisation_cells;
  return cells * cells * ST_NPOSTURE * c->posteval_generalisation_repetitions;
}
static int integrated_steps(const stConfig *c) { return c->integrated_steps; }
static int generalisation_steps(const stConfig *c) { return c->posteval_generalisation_steps; }

/* thesis 2.10.1-2.10.3 and SPEC 11-12, in stPostTest order */
static const stPostTestInfo g_tests[ST_POST_NTESTS] = {
    /* integration: the primitive runs' best under the caretaker; no words as its variant */
    {ST_CONFIG_INTEGRATION_TEST, 0, 1, ST_POST_NO_WORDS, 1, 0, integration_trials,
     integrated_steps},
    /* robustness: the integrated runs, their own autonomous words, fresh offsets; no variant */
    {ST_CONFIG_ROBUSTNESS_TEST, 0, 0, ST_POST_OWN_WORDS, 0, 0, robustness_trials,
     integrated_steps},
    /* generalisation: the grid, the runs that succeeded autonomously; the caretaker variant */
    {ST_CONFIG_GENERALISATION_TEST, 1, 0, ST_POST_CARETAKER, 0, 1, grid_trials,
     generalisation_steps},
};

/* the variants: their label suffix (st_post_condition), and why each belongs to its test */
static const struct {
  const char *name, *suffix, *why;
} g_variants[] = {
    {"own words", "", ""},
    {"caretaker", "0", "ST-CT0, ST0; the integration test always hears the caretaker"},
    {"no-words", "-nowords",
     "robustness and generalisation already hear the condition's autonomous words"},
};
#define NVARIANTS (int)(sizeof g_variants / sizeof g_variants[0])

const stPostTestInfo *st_post_test_info(stPostTest t) {
  return (int)t >= 0 && t < ST_POST_NTESTS ? &g_tests[t] : NULL;
}

unsigned st_post_test_reader(stPostTest t) {
  const stPostTestInfo *info = st_post_test_info(t);
  return info ? info->reader : 0u;
}

/* ---- the trial tables ---- */

void st_post_def_from_config(const stConfig *c, stPostTest test, stPostDef *d) {
  ST_ASSERT(c && d);
  memset(d, 0, sizeof *d);
  d->test = test;
  d->seed = st_config_rng_seed(c);
  d->cells = c->posteval_generalisation_cells;
  d->cell_size = c->posteval_generalisation_cell_size;
  d->center[0] = c->scene_object_center_x;
  d->center[1] = c->scene_object_center_y;
  d->offset = c->posteval_generalisation_offset;
  d->repetitions = c->posteval_generalisation_repetitions;
  const stPostTestInfo *info = st_post_test_info(test);
  ST_ASSERT(info);
  d->trials = info->trials(c);
  d->steps = info->steps(c);
}

void st_post_cell_center(const stPostDef *d, int cell, double xy[2]) {
  ST_ASSERT(d && xy);
  ST_ASSERT(cell >= 0 && cell < d->cells * d->cells);
  const double mid = 0.5 * (d->cells - 1);
  xy[0] = d->center[0] + (cell / d->cells - mid) * d->cell_size; /* row: along x */
  xy[1] = d->center[1] + (cell % d->cells - mid) * d->cell_size; /* column: along y */
}

void st_post_trial_layout(const stPostDef *d, int i, stPostTrial *t) {
  ST_ASSERT(d && t);
  ST_ASSERT(i >= 0 && i < d->trials);
  memset(t, 0, sizeof *t);
  t->index = i;
  t->steps = d->steps;
  if (st_post_test_info(d->test)->grid) { /* a cell of the grid with each posture */
    const int per_cell = ST_NPOSTURE * d->repetitions;
    t->type = -1;
    t->cell = i / per_cell;
    t->posture = i % per_cell / d->repetitions;
    t->repetition = i % d->repetitions;
    t->target = ST_TARGET_GENERAL;
  } else { /* integration, robustness: the integrated stage's types */
    const int k = i % ST_NPOSTURE;
    t->type = t->posture = k;
    t->cell = -1;
    t->repetition = i / ST_NPOSTURE;
    t->target = k % 2;
  }
}

/* integration, robustness: fresh offsets */
static void trained_trial(const stScene *s, stRng *rng, stPostTrial *t) {
  st_scene_object(s, t->type, 1, rng, t->obj);       /* x/y offset, */
  st_scene_target(s, t->target, rng, t->target_pos); /* then the target's x/y/z */
}

/* generalisation: the cell's centre with an offset, the one target */
static void grid_trial(const stPostDef *d, const stScene *s, stRng *rng, stPostTrial *t) {
  double xy[2];
  st_post_cell_center(d, t->cell, xy);
  t->obj[0] = xy[0] + st_rng_range(rng, -d->offset, d->offset);
  t->obj[1] = xy[1] + st_rng_range(rng, -d->offset, d->offset);
  t->obj[2] = s->obj_rest_z;
  st_scene_target(s, ST_TARGET_GENERAL, NULL, t->target_pos); /* "always kept the same" */
}

void st_post_trial(const stPostDef *d, const stScene *s, int i, stPostTrial *t) {
  ST_ASSERT(d && s && t);
  st_post_trial_layout(d, i, t);
  stRng rng = st_rng_keyed(d->seed, ST_RNG_POSTEVAL, (uint64_t)d->test, 0, (uint64_t)i);
  t->solver_key = st_rng_keyed(d->seed, ST_RNG_POSTEVAL_SOLVER, (uint64_t)d->test, 0, (uint64_t)i).key;
  if (st_post_test_info(d->test)->grid) grid_trial(d, s, &rng, t);
  else trained_trial(s, &rng, t);
}

void st_post_episode(const stProtocol *p, const stPostTrial *t, stEpisodeSpec *e) {
  ST_ASSERT(p && t && e);
  ST_ASSERT(t->posture >= 0 && t->posture < ST_NPOSTURE);
  memset(e, 0, sizeof *e);
  e->dynamic = 1;
  memcpy(e->qhat0, p->posture[ST_PRIM_REACH][t->posture], sizeof e->qhat0);
  memcpy(e->obj, t->obj, sizeof e->obj);
  memcpy(e->target, t->target_pos, sizeof e->target);
  e->steps = t->steps;
  e->table_off_step = -1; /* the object-table collision stays on, as in the integrated stage */
  e->seed_key = t->solver_key;
}

/* ---- words, conditions, exclusion ---- */

stStatus st_post_words(const stIntegratedDef *idef, stPostTest test, stPostVariant variant,
                       stWordSource *w, char *err, size_t errsz) {
  const stPostTestInfo *info = st_post_test_info(test);
  ST_ASSERT(info && idef && w);
  if ((int)variant < 0 || (int)variant >= NVARIANTS)
    return st__errf(err, errsz, "post-evaluation variant %d (expected 0..%d)", (int)variant,
                    NVARIANTS - 1), ST_ERR_ARG;
  if (variant != ST_POST_OWN_WORDS && variant != info->variant) {
    int owner = 0; /* the test whose variant it is */
    while (owner < ST_POST_NTESTS && g_tests[owner].variant != variant) owner++;
    return st__errf(err, errsz, "the %s variant belongs to the %s test (%s)",
                    g_variants[variant].name, st_post_test_name((stPostTest)owner),
                    g_variants[variant].why), ST_ERR_ARG;
  }
  if (variant == ST_POST_NO_WORDS) {
    *w = ST_WORDS_NONE;
    return ST_OK;
  }
  if (info->own_caretaker || variant == ST_POST_CARETAKER) {
    *w = ST_WORDS_CARETAKER;
    return ST_OK;
  }
  /* the words of the condition's autonomous trials (Table 2.1: the odd ones, or all) */
  for (int parity = 1; parity >= 0; parity--)
    if (idef->words[parity] != ST_WORDS_CARETAKER) {
      *w = idef->words[parity];
      return ST_OK;
    }
  return st__errf(err, errsz, "key 'integrated.words_odd': caretaker, and words_even too: the "
                  "condition has no autonomous trials to test (expected none or selftalk)"),
         ST_ERR_ARG;
}

/* Table 2.1: network.arch, words even / odd, fitness even / odd, first_generation */
static const struct {
  const char *name;
  int arch, words[2], fitness[2], first;
} g_conditions[] = {
    {"ST-CT", ST_ARCH_A, {ST_CFG_WORDS_CARETAKER, ST_CFG_WORDS_SELFTALK},
     {ST_CFG_FIT_PREDICTION, ST_CFG_FIT_INTEGRATED}, 1},
    {"ST", ST_ARCH_A, {ST_CFG_WORDS_SELFTALK, ST_CFG_WORDS_SELFTALK},
     {ST_CFG_FIT_INTEGRATED, ST_CFG_FIT_INTEGRATED}, 1},
    {"CT", ST_ARCH_B, {ST_CFG_WORDS_CARETAKER, ST_CFG_WORDS_NONE},
     {ST_CFG_FIT_INTEGRATED, ST_CFG_FIT_INTEGRATED}, 1},
    {"NI", ST_ARCH_B, {ST_CFG_WORDS_NONE, ST_CFG_WORDS_NONE},
     {ST_CFG_FIT_INTEGRATED, ST_CFG_FIT_INTEGRATED}, 0},
};

static const char *table21_name(const stConfig *c) {
  for (size_t i = 0; i < sizeof g_conditions / sizeof g_conditions[0]; i++) {
    const int same = c->network_arch == g_conditions[i].arch &&
                     c->integrated_words_even == g_conditions[i].words[0] &&
                     c->integrated_words_odd == g_conditions[i].words[1] &&
                     c->integrated_fitness_even == g_conditions[i].fitness[0] &&
                     c->integrated_fitness_odd == g_conditions[i].fitness[1] &&
                     c->integrated_first_generation == g_conditions[i].first;
    if (same) return g_conditions[i].name;
  }
  return "custom";
}

/* the primitive run's kind (thesis 3.1, Fig. 3.3): main-prim from random genotypes is the
 * non-incremental approach; after simple-prim (prims, or main-prim from its population) the
 * incremental one */
static const char *prims_name(const stConfig *c) {
  switch (c->stage_stages) {
    case ST_STAGES_PRIMS: return "incremental";
    case ST_STAGES_MAIN: return c->stage_init_population[0] ? "incremental" : "nonincremental";
    default: return st_config_enum_name("stage", "stages", c->stage_stages);
  }
}

void st_post_condition(const stConfig *c, stPostTest test, stPostVariant variant, char *buf,
                       size_t n) {
  const stPostTestInfo *info = st_post_test_info(test);
  ST_ASSERT(info && (int)variant >= 0 && (int)variant < NVARIANTS);
  snprintf(buf, n, "%s%s", info->populations ? prims_name(c) : table21_name(c),
           g_variants[variant].suffix);
}

int st_post_excluded(const stIntegratedDef *idef, int generation, const uint8_t *success, int n) {
  ST_ASSERT(idef && n >= 0 && (n == 0 || success));
  for (int i = 0; i < n; i++)
    if (success[i] && st_integrated_plan(idef, generation, i).autonomous) return 0;
  return 1;
}

/* ---- one trial ---- */

/* the integrated scorer (its "reached": within the target radius while lifted), ended at the
 * first such step, plus the words heard */
typedef struct postScorer {
  stIntScorer is;
  stScorer inner;
  stIntTrialResult ir; /* the integrated scorer's result */
  stPostResult *r;
  int last_word;
  int len;
} postScorer;

static void post_begin(void *self) {
  postScorer *s = self;
  s->inner.begin(s->inner.self);
  s->last_word = -1;
  s->len = 0;
}

/* the word heard, appended when it differs from the last one heard */
static void hear(postScorer *s, int word) {
  static const char letter[ST_NPRIM] = {'r', 'o', 'g', 'm'};
  if (word < 0 || word >= ST_NPRIM || word == s->last_word) return;
  s->last_word = word;
  if (s->len < ST_POST_HEARD_MAX) s->r->heard[s->len] = letter[word];
  else s->r->heard[ST_POST_HEARD_MAX] = '+';
  s->len++;
}

static int post_step(void *self, stTraceStep *ts) {
  postScorer *s = self;
  hear(s, ts->word);
  const int event = s->inner.step(s->inner.self, ts);
  if (event < 0 && s->is.sc.r.reached_step >= 0) return ST_END_SUCCESS; /* decided */
  return event;
}

static void post_end(void *self, const stWorld *w) {
  postScorer *s = self;
  s->inner.end(s->inner.self, w);
  stPostResult *r = s->r;
  r->reached_step = s->ir.reached_step;
  r->steps_run = (int)s->ir.steps_run;
  r->success = s->ir.reached_step >= 0;
  r->unstable = s->ir.unstable;
  r->end = r->success ? ST_END_SUCCESS : s->ir.end;
  r->open_jumped = st__post_open_jumped(r->heard);
}

int st__post_open_jumped(const char *heard) {
  return !strchr(heard, 'o') && (strchr(heard, 'g') || strchr(heard, 'm'));
}

stStatus st_post_run_trial(const stProtocol *p, const stIntegratedDef *idef, stWorkspace *ws,
                           const stPostTrial *t, const stController *ctl, stWordSource words,
                           stPostResult *r, stTraceFn trace, void *ctx, char *err, size_t errsz) {
  ST_ASSERT(p && idef && ws && t && ctl && r);
  memset(r, 0, sizeof *r);
  stIntegratedDef def = *idef;
  def.steps = t->steps; /* the scorer fills the remainder of this length (unused here) */
  stEpisodeSpec e;
  st_post_episode(p, t, &e);
  const stWords w = st_int_words(p, words);
  postScorer ps;
  memset(&ps, 0, sizeof ps);
  ps.inner = st_int_scorer(&ps.is, p, &def, &ps.ir, NULL);
  ps.is.keep = ST_INT_KEEP_WORDS; /* no fitness: success, its step and the words heard */
  ps.r = r;
  const stScorer sc = {post_begin, post_step, post_end, &ps};
  return st_episode_run(p, ws, &e, ctl, &w, &sc, trace, ctx, err, errsz);
}

/* ---- results ---- */

void st_post_summarise(const stPostResult *r, int n, int excluded, stPostSummary *s) {
  ST_ASSERT(s && n >= 0 && (n == 0 || r));
  memset(s, 0, sizeof *s);
  s->trials = n;
  double steps = 0.0;
  for (int i = 0; i < n && !excluded; i++) {
    s->successes += r[i].success;
    s->open_jumps += r[i].open_jumped;
    s->unstable += r[i].unstable;
    if (r[i].success) steps += r[i].reached_step + 1;
  }
  s->mean_steps = s->successes ? steps / s->successes : NAN;
}
