/* SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include "selftalk/config.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/internal.h"
#include "selftalk/genome.h"
#include "selftalk/io.h"
#include "selftalk/study.h"
#include "core/readers.h"

/* ---- the key table, generated from ST_CONFIG_KEYS ---- */

#define K_INT(s, k, d, lo, hi, h) \
  {#s, #k, ST_CFG_INT, lo, hi, d, NULL, NULL, h, offsetof(stConfig, s##_##k)},
#define K_REAL(s, k, d, lo, hi, h) \
  {#s, #k, ST_CFG_REAL, lo, hi, d, NULL, NULL, h, offsetof(stConfig, s##_##k)},
#define K_BOOL(s, k, d, h) {#s, #k, ST_CFG_BOOL, 0, 1, d, NULL, NULL, h, offsetof(stConfig, s##_##k)},
#define K_ENUM(s, k, d, ch, h) {#s, #k, ST_CFG_ENUM, 0, 0, d, NULL, ch, h, offsetof(stConfig, s##_##k)},
#define K_STR(s, k, d, h) {#s, #k, ST_CFG_STR, 0, 0, 0, d, NULL, h, offsetof(stConfig, s##_##k)},
static const stConfigKey g_keys[] = {ST_CONFIG_KEYS(K_INT, K_REAL, K_BOOL, K_ENUM, K_STR)};
#define NKEYS ((int)(sizeof g_keys / sizeof g_keys[0]))
#define MAX_KEYS 512
/* C99 static assertion: the loader's per-key line table must hold every key */
typedef char st__keys_fit[NKEYS <= MAX_KEYS ? 1 : -1];

/* the tiers' names, and what each is, for config.ini's and --help-config's headings */
static const char *const g_tier_name[ST_TIER_COUNT] = {"protocol", "run", "extension",
                                                       "diagnostic", "speed"};
static const char *const g_tier_title[ST_TIER_COUNT] = {
    "the thesis's protocol, and our decisions where it leaves one open (docs/PROTOCOL.md)",
    "what one run is within the protocol: seed, stages, starting populations, condition",
    "ours, not the thesis's protocol (off at their defaults)",
    "for looking into a result, not for results",
    "the same results (or the same up to rounding), faster"};

/* the fence: the keys that are not the thesis's protocol (config.h, ST_CONFIG_TIERS) */
static const struct {
  stConfigTier tier;
  const char *section, *name; /* a key, or "prefix_*" */
} g_tier_keys[] = {
#define ST__TIER_ROW(t, s, k) {ST_TIER_##t, s, k},
    ST_CONFIG_TIERS(ST__TIER_ROW)
#undef ST__TIER_ROW
};

static int name_matches(const char *pattern, const char *name);

stConfigTier st_config_key_tier(int i) {
  ST_ASSERT(i >= 0 && i < NKEYS);
  for (size_t r = 0; r < sizeof g_tier_keys / sizeof g_tier_keys[0]; r++)
    if (!strcmp(g_tier_keys[r].section, g_keys[i].section) &&
        name_matches(g_tier_keys[r].name, g_keys[i].name))
      return g_tier_keys[r].tier;
  return ST_TIER_PROTOCOL;
}

const char *st_config_tier_name(stConfigTier tier) {
  return (int)tier >= 0 && tier < ST_TIER_COUNT ? g_tier_name[tier] : "?";
}

int st_config_nkeys(void) { return NKEYS; }
const stConfigKey *st_config_key(int i) { return i >= 0 && i < NKEYS ? &g_keys[i] : NULL; }

int st_config_find(const char *section, const char *name) {
  ST_ASSERT(section && name);
  for (int i = 0; i < NKEYS; i++)
    if (!strcmp(g_keys[i].section, section) && !strcmp(g_keys[i].name, name)) return i;
  return -1;
}

static int section_known(const char *section) {
  for (int i = 0; i < NKEYS; i++)
    if (!strcmp(g_keys[i].section, section)) return 1;
  return 0;
}

/* ---- keys only some stages read (config.h, "Which stages read which keys") ----
 * One row per key (name "*": every key of the section; "prefix_*": every key whose name starts
 * with prefix_) with the stages that read it and why the others do not; the first matching row
 * counts. Checked against the code that reads each key: trial.c (trial lengths, table
 * collision, early ends), fitness.c (eq. 2.12 and the penalty masks: the object-moving penalty
 * is main-prim's), intscore.c and integrated.c (the integrated stage: eq. 2.14 is built on
 * eq. 2.10-2.12, its penalty is table + object moving, its trials start from the reach postures
 * and keep the table, its failures pay fitness.fail_penalty), assemble.c, caretaker.c,
 * prediction.c, net.c (gamma: types A and B only), the dynamic world (main-prim, integrated).
 * The post-evaluations (posteval.c, thesis 2.10) run integrated trials from the reach postures
 * in the dynamic world and record success and the step the target was reached, no fitness: they
 * read the network, robot, scene and dynamics keys, the caretaker's conditions (integration
 * test, and the generalisation test's caretaker variant), integrated.steps (integration and
 * robustness trials), the condition's words (robustness, generalisation) and their own [posteval]
 * keys. post_why says why a post-evaluation does not read a key (NULL: why says it). */
#define S_ ST_CONFIG_SIMPLE_PRIM
#define M_ ST_CONFIG_MAIN_PRIM
#define I_ ST_CONFIG_INTEGRATED
#define PI_ ST_CONFIG_INTEGRATION_TEST
#define PR_ ST_CONFIG_ROBUSTNESS_TEST
#define PG_ ST_CONFIG_GENERALISATION_TEST
#define P_ ST_CONFIG_POSTEVAL
#define EVOLVE_ (S_ | M_ | I_)
static const char NO_FITNESS[] = "a post-evaluation records success and the step the target was "
                                 "reached, no fitness";
static const char NO_CARETAKER[] = "only the integration test and the generalisation test's "
                                   "caretaker variant hear the caretaker";
typedef struct stageKey {
  const char *section, *name;
  unsigned stages;
  const char *why;
  const char *post_why;
} stageKey;
static const stageKey g_stage_keys[] = {
    {"network", "arch", I_ | P_, "the primitive stages evolve the base network, which the "
                                 "integrated stage grows into type A or B (thesis 2.9.2)", NULL},
    {"network", "gamma_a", I_ | P_, "the primitive stages' base network has no linguistic units (eq. 2.13)", NULL},
    {"network", "gamma_b", I_ | P_, "the primitive stages' base network has no linguistic units (eq. 2.13)", NULL},
    {"network", "typeb_init_gene", I_, "it initialises the type B block of genotypes the integrated stage grows", NULL},
    {"network", "secondary_input", I_ | P_, "the primitive stages never give the secondary input", NULL},
    {"ga", "mutation_rate", S_ | M_, "the integrated stage mutates at ga.mutation_rate_integrated",
     "a post-evaluation runs no genetic algorithm"},
    {"ga", "mutation_rate_integrated", I_, "the primitive stages mutate at ga.mutation_rate",
     "a post-evaluation runs no genetic algorithm"},
    {"ga", "success_genotypes", S_ | M_, "it ends the primitive stages",
     "a post-evaluation runs no genetic algorithm"},
    {"ga", "max_generations", S_ | M_, "it limits the primitive stages (the integrated stage: "
                                       "ga.integrated_generations)",
     "a post-evaluation runs no genetic algorithm"},
    {"ga", "integrated_generations", I_, "it is the length of the integrated stage",
     "a post-evaluation runs no genetic algorithm"},
    {"ga", "*", EVOLVE_, "", "a post-evaluation runs no genetic algorithm"},
    {"robot", "alpha_dynamic", M_ | I_ | P_, "simple-prim runs in kinematic mode", NULL},
    {"scene", "object_spacing", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test places the object on its grid (posteval.generalisation_*)"},
    {"scene", "object_offset", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test offsets the object by posteval.generalisation_offset"},
    {"scene", "target_x", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test's target is posteval.generalisation_target_x/y/z"},
    {"scene", "target_y", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test's target is posteval.generalisation_target_x/y/z"},
    {"scene", "target_z", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test's target is posteval.generalisation_target_x/y/z"},
    {"scene", "target_offset", EVOLVE_ | PI_ | PR_, "",
     "the generalisation test's target has no offset (thesis 2.10.3: \"always kept the same\")"},
    {"stage", "stages", EVOLVE_ | PI_, "",
     "it names the condition of the integration test only (robustness and generalisation: the "
     "integrated configuration's words, Table 2.1)"},
    {"stage", "init_population", S_ | M_ | PI_, "the integrated stage starts from integrated.populations",
     "it names the condition of the integration test only (main_prim from random genotypes: "
     "nonincremental)"},
    {"stage", "primitives", S_ | M_, "the integrated stage's trials are not per primitive",
     "a post-evaluation runs integrated trials"},
    {"stage", "simple_steps", S_, "it is the length of simple-prim trials", "a post-evaluation runs integrated trials"},
    {"stage", "main_reach_steps", M_, "it is the length of main-prim reach trials", "a post-evaluation runs integrated trials"},
    {"stage", "main_open_steps", M_, "it is the length of main-prim open trials", "a post-evaluation runs integrated trials"},
    {"stage", "main_grasp_steps", M_, "it is the length of main-prim grasp trials", "a post-evaluation runs integrated trials"},
    {"stage", "main_move_steps", M_, "it is the length of main-prim move trials", "a post-evaluation runs integrated trials"},
    {"stage", "grasp_table_off_step", M_, "only main-prim grasp trials remove the table", "a post-evaluation runs integrated trials"},
    {"stage", "move_table_off_step", M_, "only main-prim move trials remove the table", "a post-evaluation runs integrated trials"},
    {"stage", "handover*", M_, "only main-prim has hand-over trials", "a post-evaluation runs integrated trials"},
    {"stage", "chain_*", M_, "only main-prim has chained trials", "a post-evaluation runs integrated trials"},
    {"fitness", "penalty_object", S_ | M_, "the integrated stage's penalty is the table's and the "
                                           "object-moving one (eq. 2.14)", NO_FITNESS},
    {"fitness", "fp_min", S_ | M_, "only the primitive stages take the harmonic mean of F_p", NO_FITNESS},
    {"fitness", "reach_hold_steps", M_, "only main-prim reach trials end early on success "
                                        "(integrated trials: integrated.hold_steps)", NO_FITNESS},
    {"fitness", "fail_penalty", M_ | I_, "simple-prim trials never end early on failure", NO_FITNESS},
    {"fitness", "move_touch", M_ | I_, "eq. 2.12 scores main-prim move trials and the integrated "
                                       "stage (simple-prim: eq. 2.8)", NO_FITNESS},
    {"fitness", "move_lift", M_ | I_, "eq. 2.12 scores main-prim move trials and the integrated "
                                      "stage (simple-prim: eq. 2.8)", NO_FITNESS},
    {"fitness", "move_lift_dist", M_ | I_, "eq. 2.12 scores main-prim move trials and the "
                                           "integrated stage (simple-prim: eq. 2.8)", NO_FITNESS},
    {"fitness", "move_free", M_ | I_, "simple-prim has no object-moving penalty", NO_FITNESS},
    {"fitness", "move_scale", M_ | I_, "simple-prim has no object-moving penalty", NO_FITNESS},
    {"fitness", "move_max", M_ | I_, "simple-prim has no object-moving penalty", NO_FITNESS},
    /* the caretaker's conditions (caretaker.c: main-prim reach and open success) */
    {"fitness", "success_dist", EVOLVE_ | PI_ | PG_, "", NO_CARETAKER},
    {"fitness", "open_h", EVOLVE_ | PI_ | PG_, "", NO_CARETAKER},
    {"fitness", "palm_down", EVOLVE_ | PI_ | PG_, "", NO_CARETAKER},
    {"fitness", "reach_height", ST_CONFIG_ALL_STAGES, "", NULL}, /* the reach postures, d_r */
    {"fitness", "*", EVOLVE_, "", NO_FITNESS},
    {"postures", "open_*", S_ | M_, "the integrated stage starts every trial from the reach postures",
     "a post-evaluation starts every trial from the reach postures"},
    {"postures", "grasp_*", S_ | M_, "the integrated stage starts every trial from the reach postures",
     "a post-evaluation starts every trial from the reach postures"},
    {"postures", "move_*", S_ | M_, "the integrated stage starts every trial from the reach postures",
     "a post-evaluation starts every trial from the reach postures"},
    {"postures", "ik_*", S_ | M_, "the integrated stage starts every trial from the reach postures",
     "a post-evaluation starts every trial from the reach postures"},
    {"postures", "vary_*", S_ | M_, "the integrated stage starts every trial from the reach postures",
     "a post-evaluation starts every trial from the reach postures"},
    {"caretaker", "*", I_ | PI_ | PG_, "the caretaker speaks in the integrated stage only", NO_CARETAKER},
    {"integrated", "steps", I_ | PI_ | PR_, "it defines the integrated stage",
     "the generalisation test's trials last posteval.generalisation_steps"},
    {"integrated", "words_*", I_ | PR_ | PG_, "it defines the integrated stage",
     "the integration test always hears the caretaker"},
    {"integrated", "fail_end", I_ | P_, "the primitive stages' own trials end on failure by "
                                        "main-prim's rule (its chained trials read it: "
                                        "stage.chain_trials)", NULL},
    {"integrated", "selftalk_gate", I_ | PR_ | PG_, "it acts on self talk only",
     "the integration test always hears the caretaker"},
    {"integrated", "first_generation", I_ | PG_, "it defines the integrated stage",
     "only the generalisation test's exclusion rule reads the training's plan (which trials were "
     "autonomous in the last generation)"},
    {"integrated", "*", I_, "it defines the integrated stage",
     "a post-evaluation runs its own trials (posteval.*) to the first step in the target, with "
     "no fitness"},
    {"prediction", "*", I_, "the prediction fitness scores integrated trials only", NO_FITNESS},
    {"dynamics", "*", M_ | I_ | P_, "simple-prim runs in kinematic mode", NULL},
    {"posteval", "integration_*", PI_, "", "it belongs to the integration test"},
    {"posteval", "robustness_*", PR_, "", "it belongs to the robustness test"},
    {"posteval", "generalisation_*", PG_, "", "it belongs to the generalisation test"},
};
/* why the stages of a run do not read a key: the post-evaluations' reason where a row has one
 * and the run is one of them, else the evolution stages' reason ("" for rows only the
 * post-evaluations leave out) */
static const char *row_why(const struct stageKey *r, unsigned run) {
  if (r->post_why && (run & P_)) return r->post_why;
  return r->why[0] ? r->why : "a post-evaluation reads it, no evolution stage does";
}
/* the stages stage.stages names */
static const struct {
  const char *choice;
  unsigned stages;
} g_run_stages[] = {{"simple_prim", S_}, {"main_prim", M_}, {"prims", S_ | M_}, {"integrated", I_}};
#define NSTAGE_BITS 6
#define NEVOLVE_BITS 3 /* bits 0-2 are evolution stages, 3-5 post-evaluation tests */
/* the name of stage bit b: ST_CONFIG_SIMPLE_PRIM, _MAIN_PRIM, _INTEGRATED, then the tests */
static const char *stage_bit_name(int b) {
  return b < ST_STAGE_COUNT      ? st_stage_name((stStage)b)
         : b < NEVOLVE_BITS      ? ST_INTEGRATED_STAGE_NAME
                                 : st_post_test_name((stPostTest)(b - NEVOLVE_BITS));
}
#undef P_
#undef S_
#undef M_
#undef I_
#undef PI_
#undef PR_
#undef PG_
#undef EVOLVE_

/* a row's name: the key's name, "*" or a "prefix_*" */
static int name_matches(const char *pattern, const char *name) {
  const size_t n = strlen(pattern);
  if (n && pattern[n - 1] == '*') return !strncmp(pattern, name, n - 1);
  return !strcmp(pattern, name);
}

static const stageKey *stage_key(const stConfigKey *k) {
  for (size_t i = 0; i < sizeof g_stage_keys / sizeof g_stage_keys[0]; i++) {
    const stageKey *r = &g_stage_keys[i];
    if (!strcmp(r->section, k->section) && name_matches(r->name, k->name)) return r;
  }
  return NULL;
}

unsigned st_config_key_stages(int i) {
  const stConfigKey *k = st_config_key(i);
  const stageKey *r = k ? stage_key(k) : NULL;
  return r ? r->stages : ST_CONFIG_ALL_STAGES;
}

/* "x", "x and y", "x, y and z": the names of the set bits lo..hi-1 */
static void join_names(unsigned stages, int lo, int hi, char *buf, size_t n) {
  buf[0] = 0;
  int left = 0;
  for (int b = lo; b < hi; b++) left += (int)(stages >> b & 1u);
  for (int b = lo; b < hi; b++)
    if (stages >> b & 1u) {
      strncat(buf, stage_bit_name(b), n - strlen(buf) - 1);
      if (--left) strncat(buf, left == 1 ? " and " : ", ", n - strlen(buf) - 1);
    }
}

static int nbits(unsigned x) {
  int c = 0;
  for (; x; x &= x - 1) c++;
  return c;
}

/* "the simple-prim and main-prim stages", "the integrated stage and the robustness test",
 * "the integration and generalisation tests" */
static void readers_phrase(unsigned stages, char *buf, size_t n) {
  char ev[96], post[96];
  const unsigned evm = (1u << NEVOLVE_BITS) - 1u;
  join_names(stages, 0, NEVOLVE_BITS, ev, sizeof ev);
  join_names(stages, NEVOLVE_BITS, NSTAGE_BITS, post, sizeof post);
  const int ne = nbits(stages & evm), np = nbits(stages & ~evm);
  if (ne && np)
    snprintf(buf, n, "the %s stage%s and the %s test%s", ev, ne > 1 ? "s" : "", post, np > 1 ? "s" : "");
  else if (np) snprintf(buf, n, "the %s test%s", post, np > 1 ? "s" : "");
  else snprintf(buf, n, "the %s stage%s", ev, ne > 1 ? "s" : "");
}

/* what a run is: "simple-prim and main-prim", "robustness test", "integrated, robustness test" */
static void run_phrase(unsigned stages, char *buf, size_t n) {
  char ev[96], post[96];
  const unsigned evm = (1u << NEVOLVE_BITS) - 1u;
  join_names(stages, 0, NEVOLVE_BITS, ev, sizeof ev);
  join_names(stages, NEVOLVE_BITS, NSTAGE_BITS, post, sizeof post);
  const int np = nbits(stages & ~evm);
  snprintf(buf, n, "%s%s%s%s", ev, ev[0] && np ? ", " : "", post,
           np ? (np > 1 ? " tests" : " test") : "");
  if (!buf[0]) snprintf(buf, n, "no stage");
}

#define FIELD(cfg, k, T) ((T *)((char *)(cfg) + (k)->offset))
#define CFIELD(cfg, k, T) ((const T *)((const char *)(cfg) + (k)->offset))

/* i-th choice of "a|b|c" into buf; 0 on success */
static int choice_at(const char *choices, int i, char *buf, size_t n) {
  const char *p = choices;
  for (int c = 0; c < i; c++) {
    p = strchr(p, '|');
    if (!p) return -1;
    p++;
  }
  size_t len = strcspn(p, "|");
  if (len >= n) len = n - 1;
  memcpy(buf, p, len);
  buf[len] = 0;
  return 0;
}

const char *st_config_enum_name(const char *section, const char *name, int value) {
  ST_ASSERT(section && name);
  static char buf[64]; /* choices are static; one shared buffer is enough for messages */
  int i = st_config_find(section, name);
  if (i < 0 || g_keys[i].type != ST_CFG_ENUM || choice_at(g_keys[i].choices, value, buf, sizeof buf))
    return "?";
  return buf;
}

unsigned st_config_run_stages(const stConfig *cfg) {
  ST_ASSERT(cfg);
  const char *name = st_config_enum_name("stage", "stages", cfg->stage_stages);
  for (size_t i = 0; i < sizeof g_run_stages / sizeof g_run_stages[0]; i++)
    if (!strcmp(g_run_stages[i].choice, name)) return g_run_stages[i].stages;
  return 0;
}

void st_config_default(stConfig *cfg) {
  ST_ASSERT(cfg);
  memset(cfg, 0, sizeof *cfg);
  for (int i = 0; i < NKEYS; i++) {
    const stConfigKey *k = &g_keys[i];
    switch (k->type) {
      case ST_CFG_INT:
      case ST_CFG_BOOL:
      case ST_CFG_ENUM: *FIELD(cfg, k, int) = (int)k->def_num; break;
      case ST_CFG_REAL: *FIELD(cfg, k, double) = k->def_num; break;
      case ST_CFG_STR: st__strlcpy(FIELD(cfg, k, char), k->def_str, ST_CONFIG_STR_MAX); break;
      default: break;
    }
  }
}

/* what a key accepts, for messages */
static void expected(const stConfigKey *k, char *buf, size_t n) {
  switch (k->type) {
    case ST_CFG_INT: snprintf(buf, n, "an integer in [%.0f, %.0f]", k->min, k->max); break;
    case ST_CFG_REAL: snprintf(buf, n, "a number in [%g, %g]", k->min, k->max); break;
    case ST_CFG_BOOL: snprintf(buf, n, "true or false"); break;
    case ST_CFG_ENUM: snprintf(buf, n, "one of %s", k->choices); break;
    case ST_CFG_STR: snprintf(buf, n, "a string shorter than %d bytes", ST_CONFIG_STR_MAX); break;
    default: buf[0] = 0;
  }
}

/* a string value that a config file cannot hold as it is: st_config_write would write it and
 * the reader read back something else (a resumed run would find config.ini differing). Found
 * by tests/fuzz/fuzz_config.c: "populations =;eue" stored ";eue", written back as
 * "populations = ;eue", which reads as an empty value and a comment. Returns 1 with msg. */
static int str_unwritable(const char *v, char *msg, size_t n) {
  const size_t len = strlen(v);
  for (size_t i = 0; i < len; i++) {
    const unsigned char c = (unsigned char)v[i];
    if (c < 0x20 || c == 0x7f) {
      snprintf(msg, n, "control character 0x%02x in '%s' (expected printable text)", c, v);
      return 1;
    }
    if ((c == ';' || c == '#') && (i == 0 || isspace((unsigned char)v[i - 1]))) {
      snprintf(msg, n, "'%s': '%c' %s reads as a comment in a config file (expected a value "
               "without one)", v, c, i ? "after a space" : "at the start");
      return 1;
    }
  }
  if (len && (isspace((unsigned char)v[0]) || isspace((unsigned char)v[len - 1]))) {
    snprintf(msg, n, "'%s': white space around the value (expected none: a config file drops it)", v);
    return 1;
  }
  return 0;
}

/* the keys whose value is a comma-separated list: every item must be there ("a,,b", "a," and
 * ",a" were read as "a,b" by some readers and refused by others); an empty list is the key's
 * own business (dynamics.adaptive_joints: none) */
static int is_list_key(const stConfigKey *k) {
  static const char *const lists[] = {"robot.dof_joints", "robot.touch_links", "robot.tip_frames",
                                      "stage.primitives", "integrated.populations",
                                      "dynamics.kinematic_joints", "dynamics.adaptive_joints"};
  const size_t ns = strlen(k->section);
  for (size_t i = 0; i < sizeof lists / sizeof lists[0]; i++)
    if (!strncmp(lists[i], k->section, ns) && lists[i][ns] == '.' && !strcmp(lists[i] + ns + 1, k->name))
      return 1;
  return 0;
}

/* a list value with an empty item; returns 1 with msg */
static int list_bad(const char *v, char *msg, size_t n) {
  const int count = st__list_count(v);
  for (int i = 0; i < count; i++) {
    const char *item;
    size_t len;
    st__list_item(v, i, &item, &len);
    if (!len) {
      snprintf(msg, n, "'%s': item %d of %d is empty (expected comma-separated items, none empty)",
               v, i + 1, count);
      return 1;
    }
  }
  return 0;
}

/* parses value into cfg; on failure writes "problem (expected ...)" into msg */
static stStatus set_value(stConfig *cfg, const stConfigKey *k, const char *value, char *msg,
                          size_t n) {
  char exp[128];
  expected(k, exp, sizeof exp);
  switch (k->type) {
    case ST_CFG_INT: {
      int v;
      if (st__parse_int(value, &v)) {
        snprintf(msg, n, "'%s' is not an integer (expected %s)", value, exp);
        return ST_ERR_PARSE;
      }
      if (v < k->min || v > k->max) {
        snprintf(msg, n, "%d is out of range (expected %s)", v, exp);
        return ST_ERR_RANGE;
      }
      *FIELD(cfg, k, int) = v;
      return ST_OK;
    }
    case ST_CFG_REAL: {
      double v;
      if (st__parse_double(value, &v)) {
        snprintf(msg, n, "'%s' is not a number (expected %s)", value, exp);
        return ST_ERR_PARSE;
      }
      if (v < k->min || v > k->max) {
        snprintf(msg, n, "%g is out of range (expected %s)", v, exp);
        return ST_ERR_RANGE;
      }
      *FIELD(cfg, k, double) = v;
      return ST_OK;
    }
    case ST_CFG_BOOL: {
      static const char *yes[] = {"true", "yes", "on", "1"}, *no[] = {"false", "no", "off", "0"};
      for (int i = 0; i < 4; i++) {
        if (!strcasecmp(value, yes[i])) return *FIELD(cfg, k, int) = 1, ST_OK;
        if (!strcasecmp(value, no[i])) return *FIELD(cfg, k, int) = 0, ST_OK;
      }
      snprintf(msg, n, "'%s' is not a boolean (expected %s)", value, exp);
      return ST_ERR_PARSE;
    }
    case ST_CFG_ENUM: {
      char c[64];
      for (int i = 0; !choice_at(k->choices, i, c, sizeof c); i++)
        if (!strcasecmp(value, c)) return *FIELD(cfg, k, int) = i, ST_OK;
      snprintf(msg, n, "'%s' is not a valid choice (expected %s)", value, exp);
      return ST_ERR_RANGE;
    }
    case ST_CFG_STR:
      if (strlen(value) >= ST_CONFIG_STR_MAX) {
        snprintf(msg, n, "value too long (expected %s)", exp);
        return ST_ERR_RANGE;
      }
      if (str_unwritable(value, msg, n)) return ST_ERR_PARSE;
      if (is_list_key(k) && list_bad(value, msg, n)) return ST_ERR_PARSE;
      if (strlen(k->name) + 3 + strlen(value) > INI_MAX_LINE - 2) {
        snprintf(msg, n, "value of %zu characters too long for a config line (expected at most "
                 "%zu: '%s = VALUE' must fit the %d characters of a line)", strlen(value),
                 (size_t)(INI_MAX_LINE - 2) - 3 - strlen(k->name), k->name, INI_MAX_LINE - 2);
        return ST_ERR_RANGE;
      }
      /* the whole field: configs are compared with memcmp (resume) */
      memset(FIELD(cfg, k, char), 0, ST_CONFIG_STR_MAX);
      st__strlcpy(FIELD(cfg, k, char), value, ST_CONFIG_STR_MAX);
      return ST_OK;
    default: return ST_ERR_ARG;
  }
}

uint64_t st_config_rng_seed(const stConfig *cfg) {
  ST_ASSERT(cfg);
  const uint64_t seed = (uint64_t)cfg->run_seed; /* 0 .. 2^31 - 1: run.seed's range */
  return cfg->run_rng_seed == ST_RNG_SEED_APART ? seed + (UINT64_C(1) << 32) : seed;
}

unsigned st_config_primitive_mask(const stConfig *cfg) {
  ST_ASSERT(cfg);
  unsigned mask = 0;
  const char *s = cfg->stage_primitives;
  const int n = st__list_count(s);
  for (int i = 0; i < n; i++) {
    const char *item;
    size_t len;
    st__list_item(s, i, &item, &len);
    const int found = st_primitive_parse(item, len);
    if (found < 0) return 0; /* an unknown or empty name */
    mask |= 1u << found;
  }
  return mask;
}

/* the integrated stage's rules (Table 2.1): the network must have the cluster the words and
 * the fitness use; returns the key blamed or -1 */
static int check_integrated(const stConfig *c, char *msg, size_t n) {
  if (c->stage_stages != ST_STAGES_INTEGRATED) return -1;
  if (c->network_arch != ST_ARCH_A && c->network_arch != ST_ARCH_B) {
    snprintf(msg, n, "'base' cannot run the integrated stage (expected A or B)");
    return st_config_find("network", "arch");
  }
  const int words[2] = {c->integrated_words_even, c->integrated_words_odd};
  const int fit[2] = {c->integrated_fitness_even, c->integrated_fitness_odd};
  static const char *const parity[2] = {"even", "odd"};
  for (int k = 0; k < 2; k++) {
    char key[32];
    if (words[k] == ST_CFG_WORDS_SELFTALK && c->network_arch != ST_ARCH_A) {
      snprintf(msg, n, "self talk needs linguistic outputs (expected network.arch = A)");
      snprintf(key, sizeof key, "words_%s", parity[k]);
      return st_config_find("integrated", key);
    }
    if (fit[k] == ST_CFG_FIT_PREDICTION &&
        (words[k] != ST_CFG_WORDS_CARETAKER || c->network_arch != ST_ARCH_A)) {
      snprintf(msg, n, "the prediction fitness judges a type A network's outputs against the "
               "caretaker's words (expected integrated.words_%s = caretaker, network.arch = A)",
               parity[k]);
      snprintf(key, sizeof key, "fitness_%s", parity[k]);
      return st_config_find("integrated", key);
    }
    if (fit[k] == ST_CFG_FIT_PREDICTION && c->caretaker_first_step != 1) {
      snprintf(msg, n, "%d: the prediction fitness needs a word at every step after the first "
               "(expected 1)", c->caretaker_first_step);
      return st_config_find("caretaker", "first_step");
    }
  }
  if (!c->integrated_populations[0]) {
    snprintf(msg, n, "empty (expected the primitive-stage population files to start from)");
    return st_config_find("integrated", "populations");
  }
  /* the gate holds self talk's words: a condition without self talk (CT, NI) has none */
  if (c->integrated_selftalk_gate != ST_SELFTALK_GATE_NONE &&
      c->integrated_words_even != ST_CFG_WORDS_SELFTALK &&
      c->integrated_words_odd != ST_CFG_WORDS_SELFTALK) {
    char even[32], odd[32];
    choice_at(g_keys[st_config_find("integrated", "words_even")].choices,
              c->integrated_words_even, even, sizeof even);
    choice_at(g_keys[st_config_find("integrated", "words_odd")].choices,
              c->integrated_words_odd, odd, sizeof odd);
    snprintf(msg, n, "it holds self talk's words, and integrated.words_even = %s, words_odd = %s "
             "give no self talk (expected selftalk in words_even or words_odd, or the key left "
             "out)", even, odd);
    return st_config_find("integrated", "selftalk_gate");
  }
  return -1;
}

static int is_default(const stConfig *c, const stConfig *d, const stConfigKey *k);

/* quickstep's own parameters (dynamics.solver 0 = quickstep, its first choice): the direct
 * solver has no iterations and no over-relaxation, so changed under it they would do nothing */
static int check_quickstep_keys(const stConfig *c, char *msg, size_t n) {
  if (c->dynamics_solver == 0) return -1;
  stConfig d;
  st_config_default(&d);
  static const char *const names[2] = {"iterations", "sor_w"};
  static const char *const what[2] = {"quickstep's iterations", "quickstep's over-relaxation"};
  for (int j = 0; j < 2; j++) {
    const int i = st_config_find("dynamics", names[j]);
    if (is_default(c, &d, &g_keys[i])) continue;
    snprintf(msg, n, "it shapes %s, which dynamics.solver = step turns off (expected "
             "dynamics.solver = quickstep, or the key left out)", what[j]);
    return i;
  }
  return -1;
}

/* cross-key rules; returns the key index blamed and a message, or -1 */
static int check_rules(const stConfig *c, char *msg, size_t n) {
  /* the trial kinds' rules are their rows' (selftalk/trialkind.h: st_trial_kinds_check) */
  int k = check_integrated(c, msg, n);
  if (k >= 0) return k;
  if ((k = check_quickstep_keys(c, msg, n)) >= 0) return k;
  if (!st_config_primitive_mask(c)) {
    snprintf(msg, n, "'%s' is not a list of primitives (expected a comma-separated subset of "
             "reach,open,grasp,move)", c->stage_primitives);
    return st_config_find("stage", "primitives");
  }
  if (c->ga_elites > c->ga_population) {
    snprintf(msg, n, "%d exceeds ga.population = %d (expected elites <= population)", c->ga_elites,
             c->ga_population);
    return st_config_find("ga", "elites");
  }
  if (c->ga_parents > c->ga_population) {
    snprintf(msg, n, "%d exceeds ga.population = %d (expected parents <= population)",
             c->ga_parents, c->ga_population);
    return st_config_find("ga", "parents");
  }
  /* the primitive stages' termination; the integrated stage runs its generations */
  if (c->stage_stages != ST_STAGES_INTEGRATED && c->ga_success_genotypes > c->ga_population) {
    snprintf(msg, n, "%d exceeds ga.population = %d (expected success_genotypes <= population)",
             c->ga_success_genotypes, c->ga_population);
    return st_config_find("ga", "success_genotypes");
  }
  if (c->robot_torso_min_deg >= c->robot_torso_max_deg) {
    snprintf(msg, n, "%g is not below robot.torso_max_deg = %g (expected min < max)",
             c->robot_torso_min_deg, c->robot_torso_max_deg);
    return st_config_find("robot", "torso_min_deg");
  }
  if (c->scene_table_x_min >= c->scene_table_x_max) {
    snprintf(msg, n, "%g is not below scene.table_x_max = %g (expected min < max)",
             c->scene_table_x_min, c->scene_table_x_max);
    return st_config_find("scene", "table_x_min");
  }
  if (c->scene_table_y_min >= c->scene_table_y_max) {
    snprintf(msg, n, "%g is not below scene.table_y_max = %g (expected min < max)",
             c->scene_table_y_min, c->scene_table_y_max);
    return st_config_find("scene", "table_y_min");
  }
  if (c->scene_object_base_height > 2 * c->scene_object_radius) {
    snprintf(msg, n, "%g exceeds the object diameter %g (expected base inside the sphere's height)",
             c->scene_object_base_height, 2 * c->scene_object_radius);
    return st_config_find("scene", "object_base_height");
  }
  return -1;
}

/* range check of one already-stored value (configs built in code) */
static int check_range(const stConfig *c, const stConfigKey *k, char *msg, size_t n) {
  char exp[128];
  expected(k, exp, sizeof exp);
  if (k->type == ST_CFG_INT) {
    int v = *CFIELD(c, k, int);
    if (v < k->min || v > k->max) return snprintf(msg, n, "%d is out of range (expected %s)", v, exp), -1;
  } else if (k->type == ST_CFG_REAL) {
    double v = *CFIELD(c, k, double);
    if (!(v >= k->min && v <= k->max))
      return snprintf(msg, n, "%g is out of range (expected %s)", v, exp), -1;
  } else if (k->type == ST_CFG_ENUM) {
    char b[64];
    if (choice_at(k->choices, *CFIELD(c, k, int), b, sizeof b))
      return snprintf(msg, n, "choice %d does not exist (expected %s)", *CFIELD(c, k, int), exp), -1;
  } else if (k->type == ST_CFG_STR && is_list_key(k) && list_bad(CFIELD(c, k, char), msg, n)) {
    return -1;
  }
  return 0;
}

stStatus st_config_validate(const stConfig *cfg, char *err, size_t errsz) {
  ST_ASSERT(cfg);
  char msg[512];
  for (int i = 0; i < NKEYS; i++) {
    if (check_range(cfg, &g_keys[i], msg, sizeof msg)) {
      st__errf(err, errsz, "key '%s.%s': %s", g_keys[i].section, g_keys[i].name, msg);
      return ST_ERR_RANGE;
    }
  }
  int k = check_rules(cfg, msg, sizeof msg);
  if (k >= 0) {
    st__errf(err, errsz, "key '%s.%s': %s", g_keys[k].section, g_keys[k].name, msg);
    return ST_ERR_RANGE;
  }
  return ST_OK;
}

/* whether value is one key k takes: within an INT's or REAL's range, 0 or 1 for a BOOL (its
 * range), the index of a choice for an ENUM */
static int value_in_range(const stConfigKey *k, double value) {
  char c[64];
  if (k->type != ST_CFG_ENUM) return value >= k->min && value <= k->max;
  return value >= 0.0 && value < 64.0 && value == (int)value &&
         !choice_at(k->choices, (int)value, c, sizeof c);
}

stStatus st_config_check_number(const char *section, const char *name, double value, char *err,
                                size_t errsz) {
  ST_ASSERT(section && name);
  const int i = st_config_find(section, name);
  const stConfigKey *k = st_config_key(i);
  if (!k || k->type == ST_CFG_STR) {
    st__errf(err, errsz, "%s.%s: not a numeric key of the key table", section, name);
    return ST_ERR_ARG;
  }
  if (value_in_range(k, value)) return ST_OK;
  char exp[128];
  expected(k, exp, sizeof exp);
  st__errf(err, errsz, "%s.%s: %g is out of range (expected %s)", section, name, value, exp);
  return ST_ERR_RANGE;
}

static int is_default(const stConfig *c, const stConfig *d, const stConfigKey *k) {
  switch (k->type) {
    case ST_CFG_REAL: return *CFIELD(c, k, double) == *CFIELD(d, k, double);
    case ST_CFG_STR: return !strcmp(CFIELD(c, k, char), CFIELD(d, k, char));
    default: return *CFIELD(c, k, int) == *CFIELD(d, k, int);
  }
}

static void format_value(const stConfig *cfg, const stConfigKey *k, char *buf, size_t n);

/* the shortest text that reads back as v (0.005, not 0.0050000000000000001), for people */
static void short_real(double v, char *buf, size_t n) {
  for (int p = 6; p <= 17; p++) {
    snprintf(buf, n, "%.*g", p, v);
    if (strtod(buf, NULL) == v) return;
  }
}

/* readers that depend on another key's value: main-prim's hand-over trials (stage.handover)
 * and chained trials (stage.chain_trials) hear the caretaker; its chained trials are
 * integrated trials (their length, hold, focus bonus and failure end) */
static unsigned value_readers(const stConfig *cfg, const stConfigKey *k) {
  const int chain = cfg->stage_chain_trials > 0;
  if ((cfg->stage_handover || chain) && !strcmp(k->section, "caretaker")) return ST_CONFIG_MAIN_PRIM;
  if (chain && !strcmp(k->section, "integrated") &&
      (!strcmp(k->name, "steps") || !strcmp(k->name, "hold_steps") ||
       !strcmp(k->name, "focus_bonus_steps") || !strcmp(k->name, "fail_end")))
    return ST_CONFIG_MAIN_PRIM;
  return 0u;
}

stStatus st_config_check_changes(const stConfig *cfg, const stConfig *base, const char *base_name,
                                 unsigned stages, char *err, size_t errsz) {
  ST_ASSERT(cfg && base && base_name);
  for (int i = 0; i < NKEYS; i++) {
    const stConfigKey *k = &g_keys[i];
    const stageKey *r = stage_key(k);
    if (!r || ((r->stages | value_readers(cfg, k)) & stages) || is_default(cfg, base, k)) continue;
    char v[ST_CONFIG_STR_MAX + 32], bv[ST_CONFIG_STR_MAX + 32], readers[256], run[256];
    format_value(cfg, k, v, sizeof v);
    format_value(base, k, bv, sizeof bv);
    if (k->type == ST_CFG_REAL) {
      short_real(*CFIELD(cfg, k, double), v, sizeof v);
      short_real(*CFIELD(base, k, double), bv, sizeof bv);
    }
    readers_phrase(r->stages, readers, sizeof readers);
    run_phrase(stages, run, sizeof run);
    st__errf(err, errsz, "key '%s.%s': %s is read only by %s, which this run (%s) does not have: "
             "%s (expected %s, %s)", k->section, k->name, v, readers, run, row_why(r, stages),
             base_name, bv);
    return ST_ERR_ARG;
  }
  return ST_OK;
}

stStatus st_config_check_stages(const stConfig *cfg, unsigned stages, char *err, size_t errsz) {
  ST_ASSERT(cfg);
  stConfig d;
  st_config_default(&d);
  return st_config_check_changes(cfg, &d, "the default", stages, err, errsz);
}

/* ---- INI loading through inih ----
 * inih's handler gets no line number in Debian's build, so the file is fed through our own
 * reader, which counts lines, checks section names and strips '#' inline comments. */

typedef struct loader {
  const char *path;
  const char *text, *end; /* the unread rest of the text */
  stConfig *cfg;
  int lineno;
  int line_of[MAX_KEYS]; /* line where each key was set, 0 = not set */
  stStatus status;
  char msg[2048];
  char *buf;
  size_t cap;
} loader;

static void fail(loader *L, stStatus st, const char *fmt, const char *a, const char *b,
                 const char *c) {
  if (L->status) return; /* keep the first error */
  L->status = st;
  char tail[1200];
  snprintf(tail, sizeof tail, fmt, a, b, c);
  snprintf(L->msg, sizeof L->msg, "%s:%d: %s", L->path, L->lineno, tail);
}

/* the next line of the text into L->buf, ended by "\n" whatever ended it in the file: "\n",
 * "\r\n" or a lone "\r" (old Mac files: read as lines, not as one line whose keys inih would
 * never see); -1 at the end */
static int next_line(loader *L) {
  if (L->text >= L->end) return -1;
  const char *line = L->text;
  size_t len = 0;
  while (line + len < L->end && line[len] != '\n' && line[len] != '\r') len++;
  const char *e = line + len;
  const int newline = e < L->end;
  L->text = !newline ? e : e[0] == '\r' && e + 1 < L->end && e[1] == '\n' ? e + 2 : e + 1;
  const size_t n = len + (size_t)newline; /* with its newline */
  if (n + 1 > L->cap) {
    char *b = realloc(L->buf, n + 1);
    if (!b) {
      fail(L, ST_ERR_NOMEM, "out of memory%s%s%s", "", "", "");
      return -1;
    }
    L->buf = b;
    L->cap = n + 1;
  }
  memcpy(L->buf, line, len);
  if (newline) L->buf[len] = '\n';
  L->buf[n] = 0;
  return 0;
}

static char *reader(char *str, int num, void *stream) {
  loader *L = stream;
  if (L->status) return NULL; /* stop at the first error */
  if (next_line(L)) return NULL;
  L->lineno++;
  char *p = L->buf;
  /* '#' starts a comment at line start (inih) or after whitespace (here) */
  for (char *q = p + 1; *q; q++)
    if (*q == '#' && isspace((unsigned char)q[-1])) {
      *q = 0;
      break;
    }
  while (isspace((unsigned char)*p)) p++;
  if (*p == '[') {
    char name[128];
    size_t n = strcspn(p + 1, "]");
    if (p[1 + n] == ']' && n < sizeof name) {
      memcpy(name, p + 1, n);
      name[n] = 0;
      /* inih drops what follows ']': "[ga] population = 9" would lose the key */
      const char *rest = p + 2 + n;
      while (isspace((unsigned char)*rest)) rest++;
      if (*rest && *rest != ';' && *rest != '#') {
        char after[64];
        snprintf(after, sizeof after, "%.*s", (int)strcspn(rest, "\n"), rest);
        fail(L, ST_ERR_PARSE, "section [%s]: '%s' after its ']' (expected nothing but a comment "
             "there: a key goes on a line of its own)", name, after, "");
        return NULL;
      }
      if (!section_known(name)) {
        char known[256] = "";
        for (int i = 0; i < NKEYS; i++)
          if (i == 0 || strcmp(g_keys[i].section, g_keys[i - 1].section)) {
            if (known[0]) strncat(known, ", ", sizeof known - strlen(known) - 1);
            strncat(known, g_keys[i].section, sizeof known - strlen(known) - 1);
          }
        fail(L, ST_ERR_PARSE, "section [%s]: unknown section (expected one of %s)", name, known, "");
        return NULL;
      }
    }
  }
  /* num - 2 characters and the newline: the same for a last line without one (a line the
   * writer could not write back otherwise) */
  size_t len = strlen(L->buf);
  if (len && L->buf[len - 1] == '\n') len--;
  if (len + 2 > (size_t)num) {
    char lim[32];
    snprintf(lim, sizeof lim, "%d", num - 2);
    fail(L, ST_ERR_PARSE, "line longer than %s characters (expected a shorter line)%s%s", lim, "",
         "");
    return NULL;
  }
  strcpy(str, L->buf);
  return str;
}

static int handler(void *user, const char *section, const char *name, const char *value) {
  loader *L = user;
  if (!section[0]) {
    fail(L, ST_ERR_PARSE, "key '%s': outside any section (expected a [section] line first)%s%s",
         name, "", "");
    return 0;
  }
  char full[160];
  snprintf(full, sizeof full, "%s.%s", section, name);
  int i = st_config_find(section, name);
  if (i < 0) {
    char known[1024] = "";
    for (int j = 0; j < NKEYS; j++)
      if (!strcmp(g_keys[j].section, section)) {
        if (known[0]) strncat(known, ", ", sizeof known - strlen(known) - 1);
        strncat(known, g_keys[j].name, sizeof known - strlen(known) - 1);
      }
    fail(L, ST_ERR_PARSE, "key '%s': unknown key (expected one of %s)%s", full, known, "");
    return 0;
  }
  if (L->line_of[i]) {
    char first[32];
    snprintf(first, sizeof first, "%d", L->line_of[i]);
    fail(L, ST_ERR_PARSE, "key '%s': duplicate key (first set on line %s)%s", full, first, "");
    return 0;
  }
  char msg[512];
  stStatus st = set_value(L->cfg, &g_keys[i], value, msg, sizeof msg);
  if (st) {
    fail(L, st, "key '%s': %s%s", full, msg, "");
    return 0;
  }
  L->line_of[i] = L->lineno;
  return 1;
}

stStatus st__config_parse(const char *name, const char *text, size_t len, stConfig *cfg,
                          char *err, size_t errsz) {
  stStatus st = st_text_check(name, text, len, err, errsz);
  if (st) return st;
  loader L;
  memset(&L, 0, sizeof L);
  L.path = name;
  L.text = text;
  L.end = text + len;
  L.cfg = cfg;
  int r = ini_parse_stream(reader, &L, handler, &L);
  free(L.buf);
  if (!L.status && r > 0) {
    L.lineno = r;
    fail(&L, ST_ERR_PARSE, "syntax error (expected '[section]' or 'key = value')%s%s%s", "", "", "");
  }
  if (!L.status) {
    char msg[512];
    int k = check_rules(cfg, msg, sizeof msg);
    if (k >= 0) {
      L.lineno = L.line_of[k];
      fail(&L, ST_ERR_RANGE, "key '%s.%s': %s", g_keys[k].section, g_keys[k].name, msg);
    }
  }
  if (L.status) st__errf(err, errsz, "%s", L.msg);
  return L.status;
}

static stStatus parse_cb(const char *name, char *text, size_t len, void *cfg, char *err,
                         size_t errsz) {
  return st__config_parse(name, text, len, cfg, err, errsz);
}

stStatus st_config_load(const char *path, stConfig *cfg, char *err, size_t errsz) {
  ST_ASSERT(path && cfg);
  return st__text_read_parse(path, parse_cb, cfg, err, errsz);
}

int st_config_key_line(const char *path, int i) {
  ST_ASSERT(path);
  ST_ASSERT(i >= 0 && i < NKEYS);
  char *text;
  size_t len;
  char e[256];
  if (st_text_read(path, ST_FILE_MAX, &text, &len, e, sizeof e)) return 0;
  const char *rest = text, *line;
  size_t n;
  int lineno = 0, found = 0, in_section = 0;
  const size_t nk = strlen(g_keys[i].name), ns = strlen(g_keys[i].section);
  while (!found && st__text_line(&rest, text + len, &line, &n, NULL)) {
    lineno++;
    while (n && isspace((unsigned char)*line)) line++, n--;
    if (n && *line == '[') {
      in_section = n > ns + 1 && !strncmp(line + 1, g_keys[i].section, ns) && line[ns + 1] == ']';
      continue;
    }
    if (!in_section || n <= nk || strncmp(line, g_keys[i].name, nk)) continue;
    size_t k = nk;
    while (k < n && (line[k] == ' ' || line[k] == '\t')) k++;
    found = k < n && (line[k] == '=' || line[k] == ':');
  }
  free(text);
  return found ? lineno : 0;
}

static stStatus set_one(stConfig *cfg, const char *assignment, int cross, char *err, size_t errsz) {
  const char *eq = strchr(assignment, '=');
  const char *dot = strchr(assignment, '.');
  if (!eq || !dot || dot > eq) {
    st__errf(err, errsz, "--set %s: malformed override (expected section.key=value)", assignment);
    return ST_ERR_PARSE;
  }
  char section[64], name[128];
  size_t ns = (size_t)(dot - assignment), nk = (size_t)(eq - dot - 1);
  if (ns >= sizeof section || nk >= sizeof name) {
    st__errf(err, errsz, "--set %s: key too long", assignment);
    return ST_ERR_PARSE;
  }
  memcpy(section, assignment, ns);
  section[ns] = 0;
  memcpy(name, dot + 1, nk);
  name[nk] = 0;
  int i = st_config_find(section, name);
  if (i < 0) {
    st__errf(err, errsz, "--set %s: key '%s.%s': unknown key (see --help-config)", assignment,
             section, name);
    return ST_ERR_PARSE;
  }
  char msg[512];
  stStatus st = set_value(cfg, &g_keys[i], eq + 1, msg, sizeof msg);
  if (!st && cross) {
    int k = check_rules(cfg, msg, sizeof msg);
    if (k >= 0) st = ST_ERR_RANGE, i = k;
  }
  if (st) st__errf(err, errsz, "--set %s: key '%s.%s': %s", assignment, g_keys[i].section,
                   g_keys[i].name, msg);
  return st;
}

stStatus st_config_set(stConfig *cfg, const char *assignment, char *err, size_t errsz) {
  ST_ASSERT(cfg && assignment);
  return set_one(cfg, assignment, 1, err, errsz);
}

stStatus st_config_set_all(stConfig *cfg, const char *const *assignments, int n, char *err,
                           size_t errsz) {
  ST_ASSERT(cfg && n >= 0 && (assignments || n == 0));
  for (int i = 0; i < n; i++) {
    stStatus st = set_one(cfg, assignments[i], 0, err, errsz);
    if (st) return st;
  }
  /* cross-key rules once all overrides are in, so that their order does not matter */
  char msg[512];
  int k = check_rules(cfg, msg, sizeof msg);
  if (k >= 0) {
    st__errf(err, errsz, "after the --set options: key '%s.%s': %s", g_keys[k].section,
             g_keys[k].name, msg);
    return ST_ERR_RANGE;
  }
  return ST_OK;
}

int st_config_key_differs(const stConfig *cfg, const stConfig *base, int i) {
  ST_ASSERT(cfg && base);
  ST_ASSERT(i >= 0 && i < NKEYS);
  return !is_default(cfg, base, &g_keys[i]);
}

void st_config_format(const stConfig *cfg, int i, char *buf, size_t n) {
  ST_ASSERT(cfg && buf && n > 0);
  ST_ASSERT(i >= 0 && i < NKEYS);
  format_value(cfg, &g_keys[i], buf, n);
}

static void format_value(const stConfig *cfg, const stConfigKey *k, char *buf, size_t n) {
  switch (k->type) {
    case ST_CFG_INT: snprintf(buf, n, "%d", *CFIELD(cfg, k, int)); break;
    case ST_CFG_REAL: snprintf(buf, n, "%.17g", *CFIELD(cfg, k, double)); break;
    case ST_CFG_BOOL: snprintf(buf, n, "%s", *CFIELD(cfg, k, int) ? "true" : "false"); break;
    case ST_CFG_ENUM:
      if (choice_at(k->choices, *CFIELD(cfg, k, int), buf, n)) snprintf(buf, n, "?");
      break;
    case ST_CFG_STR: snprintf(buf, n, "%s", CFIELD(cfg, k, char)); break;
    default: buf[0] = 0;
  }
}

int st_config_write(FILE *f, const stConfig *cfg) {
  ST_ASSERT(f && cfg);
  fprintf(f, "# libselftalk %s resolved configuration\n", ST_VERSION_STRING);
  for (int first = 0; first < NKEYS;) {
    int end = first; /* the section: keys first..end-1 */
    while (end < NKEYS && !strcmp(g_keys[end].section, g_keys[first].section)) end++;
    fprintf(f, "\n[%s]\n", g_keys[first].section);
    for (int t = 0; t < ST_TIER_COUNT; t++) {
      int said = 0;
      for (int i = first; i < end; i++) {
        const stConfigKey *k = &g_keys[i];
        if (st_config_key_tier(i) != (stConfigTier)t) continue;
        if (!said++) fprintf(f, "# ---- %s: %s ----\n", g_tier_name[t], g_tier_title[t]);
        char v[ST_CONFIG_STR_MAX + 32];
        format_value(cfg, k, v, sizeof v);
        fprintf(f, "# %s\n%s = %s\n", k->help, k->name, v);
      }
    }
    first = end;
  }
  return ferror(f) ? -1 : 0;
}

/* one key of the reference: name, type, default, range, readers; help */
static void help_key(FILE *f, const stConfig *d, const stConfigKey *k) {
  static const char *tn[] = {"int", "real", "bool", "enum", "string"};
  char v[ST_CONFIG_STR_MAX + 32], exp[128];
  format_value(d, k, v, sizeof v);
  if (k->type == ST_CFG_REAL) short_real(*CFIELD(d, k, double), v, sizeof v);
  expected(k, exp, sizeof exp);
  const stageKey *r = stage_key(k);
  const int some = r && r->stages != ST_CONFIG_ALL_STAGES;
  char readers[160] = "";
  if (some) readers_phrase(r->stages, readers, sizeof readers);
  fprintf(f, "%s.%s (%s, default %s; %s)%s%s%s\n    %s\n", k->section, k->name, tn[k->type], v,
          exp, some ? "; read by " : "", readers, some ? " only" : "", k->help);
}

void st_config_help(FILE *f) {
  ST_ASSERT(f);
  stConfig d;
  st_config_default(&d);
  for (int t = 0; t < ST_TIER_COUNT; t++) {
    fprintf(f, "%s==== %s: %s ====\n", t ? "\n" : "", g_tier_name[t], g_tier_title[t]);
    for (int i = 0; i < NKEYS; i++)
      if (st_config_key_tier(i) == (stConfigTier)t) help_key(f, &d, &g_keys[i]);
  }
}
