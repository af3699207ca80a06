/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>

#include "selftalk/config.h"
#include "test_util.h"

/* the defaults are the thesis protocol (SPEC §4-§5) */
static void test_config_defaults(void) {
  stConfig c;
  st_config_default(&c);
  CU_ASSERT_EQUAL(c.ga_population, 100);
  CU_ASSERT_EQUAL(c.ga_elites, 10);
  CU_ASSERT_EQUAL(c.ga_parents, 20);
  CU_ASSERT_DOUBLE_EQUAL(c.ga_mutation_rate, 0.005, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.ga_mutation_rate_integrated, 0.04, 0.0);
  CU_ASSERT_EQUAL(c.ga_success_genotypes, 5);
  CU_ASSERT_EQUAL(c.ga_max_generations, 1500);
  CU_ASSERT_EQUAL(c.ga_integrated_generations, 100);
  CU_ASSERT_DOUBLE_EQUAL(c.network_lambda, 1.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_gamma_a, 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_gamma_b, 10.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_focus_scale, 20.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_focus_threshold, 0.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_linguistic_input, 10.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.network_secondary_input, 10.0, 0.0);
  CU_ASSERT_EQUAL(c.network_typeb_init_gene, 32768);
  CU_ASSERT_EQUAL(c.network_arch, 0);
  /* SPEC §1-§3, §6, §8 */
  CU_ASSERT_DOUBLE_EQUAL(c.robot_torso_min_deg, -10.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.robot_torso_max_deg, 40.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.robot_alpha_kinematic, 37.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.robot_alpha_dynamic, 100.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.robot_max_velocity_deg, 40.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.robot_control_dt, 0.05, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_table_top_z, -0.08, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_table_x_max - c.scene_table_x_min, 0.50, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_table_y_max - c.scene_table_y_min, 0.80, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_object_radius, 0.035, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_object_mass, 0.2, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_object_base_radius, 0.0175, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_target_z - c.scene_table_top_z, 0.25, 1e-15);
  CU_ASSERT_DOUBLE_EQUAL(c.scene_target_radius, 0.06, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.fitness_reach_height, 0.095, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.fitness_move_free, 0.02, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.fitness_move_max, 2.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.postures_reach_clearance, 0.15, 0.0);
  CU_ASSERT_EQUAL(st_config_validate(&c, NULL, 0), ST_OK);
}

static void test_config_load_ok(void) {
  char path[256], err[512];
  st_test_write_tmp(path, sizeof path, ".cfg",
                    "# an experiment\n"
                    "[ga]\n"
                    "population = 50   # inline comment\n"
                    "mutation_rate = 0.01 ; another\n"
                    "\n"
                    "[network]\n"
                    "arch = b\n"
                    "[run]\n"
                    "seed=7\n");
  stConfig c;
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_load(path, &c, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(c.ga_population, 50);
  CU_ASSERT_DOUBLE_EQUAL(c.ga_mutation_rate, 0.01, 0.0);
  CU_ASSERT_EQUAL(c.network_arch, 2);
  CU_ASSERT_EQUAL(c.run_seed, 7);
  CU_ASSERT_EQUAL(c.ga_elites, 10); /* untouched keys keep their defaults */
  CU_ASSERT_STRING_EQUAL(st_config_enum_name("network", "arch", c.network_arch), "B");

  CU_ASSERT_EQUAL(st_config_set(&c, "ga.elites=12", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(c.ga_elites, 12);
}

/* the resolved config written out loads back to the same values */
static void test_config_roundtrip(void) {
  stConfig a, b;
  st_config_default(&a);
  a.ga_mutation_rate = 0.1 + 0.2; /* not representable in few digits */
  a.network_arch = 1;
  a.run_seed = 123456;
  char path[256], err[512];
  st_test_write_tmp(path, sizeof path, ".cfg", "");
  FILE *f = fopen(path, "w");
  CU_ASSERT_EQUAL(st_config_write(f, &a), 0);
  fclose(f);
  st_config_default(&b);
  CU_ASSERT_EQUAL_FATAL(st_config_load(path, &b, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(memcmp(&a, &b, sizeof a), 0);
}

static void expect_error(const char *text, stStatus want, const char *needle) {
  char path[256], err[1024];
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  stConfig c;
  st_config_default(&c);
  stStatus st = st_config_load(path, &c, err, sizeof err);
  CU_ASSERT_EQUAL(st, want);
  if (st != want) fprintf(stderr, "\n  status %d for: %s\n", st, err);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, needle);
}

static void test_config_errors(void) {
  expect_error("[ga]\npopulation = 10\n[robot_arm]\n", ST_ERR_PARSE,
               ":3: section [robot_arm]: unknown section (expected one of run, network, ga, robot,");
  expect_error("[ga]\npopsize = 10\n", ST_ERR_PARSE,
               ":2: key 'ga.popsize': unknown key (expected one of population, elites,");
  expect_error("[ga]\nmutation_rate = abc\n", ST_ERR_PARSE,
               ":2: key 'ga.mutation_rate': 'abc' is not a number (expected a number in [0, 1])");
  expect_error("[ga]\n\nmutation_rate = 1.5\n", ST_ERR_RANGE,
               ":3: key 'ga.mutation_rate': 1.5 is out of range (expected a number in [0, 1])");
  expect_error("[ga]\npopulation = 10.5\n", ST_ERR_PARSE,
               ":2: key 'ga.population': '10.5' is not an integer (expected an integer in [2, 100000])");
  expect_error("[ga]\npopulation = 1e400\n", ST_ERR_PARSE, "'1e400' is not an integer");
  expect_error("[network]\nlambda = 1e400\n", ST_ERR_PARSE, "'1e400' is not a number");
  /* eq. 2.6 divides by open_h, eq. 2.7 by 1 - grasp_h: 0 and 1 would give infinite fitness */
  expect_error("[fitness]\nopen_h = 0\n", ST_ERR_RANGE,
               ":2: key 'fitness.open_h': 0 is out of range (expected a number in [0.01, 1])");
  expect_error("[fitness]\ngrasp_h = 1\n", ST_ERR_RANGE,
               ":2: key 'fitness.grasp_h': 1 is out of range (expected a number in [0, 0.99])");
  expect_error("[network]\narch = C\n", ST_ERR_RANGE,
               ":2: key 'network.arch': 'C' is not a valid choice (expected one of base|A|B)");
  expect_error("[ga]\nelites = 3\nelites = 4\n", ST_ERR_PARSE,
               ":3: key 'ga.elites': duplicate key (first set on line 2)");
  expect_error("[ga]\nelites = 3\nthis line has no equals sign\n", ST_ERR_PARSE,
               ":3: syntax error (expected '[section]' or 'key = value')");
  expect_error("seed = 3\n[run]\n", ST_ERR_PARSE,
               ":1: key 'seed': outside any section (expected a [section] line first)");
  expect_error("[ga]\nelites = 30\n\npopulation = 20\n", ST_ERR_RANGE,
               ":2: key 'ga.elites': 30 exceeds ga.population = 20 (expected elites <= population)");
  expect_error("[ga]\nelites = \n", ST_ERR_PARSE, ":2: key 'ga.elites': '' is not an integer");
  /* the trial kinds' rules (postures.vary_*, stage.handover*, stage.chain_*) are their rows',
   * checked after loading: tests/test_trialkind.c */
  expect_error("[stage]\nprimitives = reach,grasp,lift\n", ST_ERR_RANGE,
               ":2: key 'stage.primitives': 'reach,grasp,lift' is not a list of primitives "
               "(expected a comma-separated subset of reach,open,grasp,move)");
  expect_error("[stage]\n\nprimitives = grasp,,move\n", ST_ERR_PARSE,
               ":3: key 'stage.primitives': 'grasp,,move': item 2 of 3 is empty");

  stConfig c;
  char err[512];
  st_config_default(&c);
  CU_ASSERT_EQUAL(st_config_load("/nonexistent/run.cfg", &c, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, "/nonexistent/run.cfg: cannot open: No such file");
}

/* issue 48: inih drops what follows a section's ']' ("[ga] population = 999999999" ran with
 * the defaults), and a file of CR-only line endings was one line, every key lost: the first is
 * refused naming the line, the second read line by line (CR, LF and CRLF alike) */
static void test_config_strict_syntax(void) {
  expect_error("[ga] population = 999999999\n", ST_ERR_PARSE,
               ":1: section [ga]: 'population = 999999999' after its ']' (expected nothing but a "
               "comment there: a key goes on a line of its own)");
  expect_error("[run]\nseed = 3\n  [ga]]\n", ST_ERR_PARSE, ":3: section [ga]: ']' after its ']'");
  char path[256], err[512];
  stConfig c;
  static const char *const ok_files[] = {
      "[ga]   ; a comment\npopulation = 50\n[run] # another\nseed = 9\n",
      "[ga]\rpopulation = 50\r[run]\rseed = 9\r",         /* CR (old Mac) */
      "[ga]\r\npopulation = 50\r\n[run]\r\nseed = 9\r\n", /* CRLF */
      "[ga]\rpopulation = 50\n[run]\r\nseed = 9",           /* mixed, no last newline */
  };
  for (size_t i = 0; i < sizeof ok_files / sizeof ok_files[0]; i++) {
    st_test_write_tmp(path, sizeof path, ".cfg", ok_files[i]);
    st_config_default(&c);
    CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK);
    CU_ASSERT(c.ga_population == 50 && c.run_seed == 9);
  }
  /* lines counted at every ending */
  expect_error("[ga]\r\rpopulation = x\r", ST_ERR_PARSE, ":3: key 'ga.population': 'x' is not an integer");
  expect_error("[ga]\r\n\rpopulation = 999999999\r\n", ST_ERR_RANGE, ":3: key 'ga.population'");
}

/* issue 48: keys that would act on nothing in the run's solver or condition are refused, naming
 * the key's line; list items are validated alike in every list key */
static void test_config_keys_act(void) {
  /* quickstep's parameters with the direct solver (the default) */
  expect_error("[dynamics]\niterations = 40\n", ST_ERR_RANGE,
               ":2: key 'dynamics.iterations': it shapes quickstep's iterations, which "
               "dynamics.solver = step turns off (expected dynamics.solver = quickstep, or the key "
               "left out)");
  expect_error("[dynamics]\nsolver = step\nsor_w = 1.1\n", ST_ERR_RANGE,
               ":3: key 'dynamics.sor_w': it shapes quickstep's over-relaxation, which "
               "dynamics.solver = step turns off");
  {
    char path[256], err[512];
    stConfig c;
    st_config_default(&c);
    st_test_write_tmp(path, sizeof path, ".cfg", "[dynamics]\nsolver = quickstep\niterations = 40\nsor_w = 1.1\n");
    CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK);
    CU_ASSERT(c.dynamics_iterations == 40 && c.dynamics_sor_w == 1.1);
    st_config_default(&c); /* a config built in code: validate */
    c.dynamics_iterations = 40;
    CU_ASSERT_EQUAL(st_config_validate(&c, err, sizeof err), ST_ERR_RANGE);
    ST_ASSERT_CONTAINS(err, "key 'dynamics.iterations': it shapes quickstep's iterations");
  }
  /* the self-talk gate in conditions without self talk: CT and NI (Table 2.1) */
  static const char head[] = "[stage]\nstages = integrated\n[network]\narch = B\n[integrated]\n"
                             "fitness_even = integrated\n";
  char text[512];
  snprintf(text, sizeof text, "%swords_even = caretaker\nwords_odd = none\nselftalk_gate = move\n"
           "populations = x.genome\n", head);
  expect_error(text, ST_ERR_RANGE, ":9: key 'integrated.selftalk_gate': it holds self talk's "
               "words, and integrated.words_even = caretaker, words_odd = none give no self talk "
               "(expected selftalk in words_even or words_odd, or the key left out)");
  snprintf(text, sizeof text, "%sselftalk_gate = ahead\nwords_even = none\nwords_odd = none\n"
           "populations = x.genome\n", head);
  expect_error(text, ST_ERR_RANGE, ":7: key 'integrated.selftalk_gate': it holds self talk's words, "
               "and integrated.words_even = none, words_odd = none");
  {
    char path[256], err[512];
    stConfig c;
    st_config_default(&c);
    snprintf(text, sizeof text, "%spopulations = x.genome\nwords_even = caretaker\n"
             "words_odd = selftalk\nselftalk_gate = move\n",
             "[stage]\nstages = integrated\n[network]\narch = A\n[integrated]\n");
    st_test_write_tmp(path, sizeof path, ".cfg", text);
    CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK); /* ST-CT: acts */
    const char *ct[] = {"integrated.words_odd=caretaker"};
    CU_ASSERT_EQUAL(st_config_set_all(&c, ct, 1, err, sizeof err), ST_ERR_RANGE);
    ST_ASSERT_CONTAINS(err, "after the --set options: key 'integrated.selftalk_gate'");
  }
  /* empty list items, in every list key alike (some readers skipped them, others refused) */
  expect_error("[dynamics]\nadaptive_joints = l_elbow,,l_wrist_prosup\n", ST_ERR_PARSE,
               ":2: key 'dynamics.adaptive_joints': 'l_elbow,,l_wrist_prosup': item 2 of 3 is "
               "empty (expected comma-separated items, none empty)");
  expect_error("[dynamics]\nkinematic_joints = torso_pitch,torso_yaw,\n", ST_ERR_PARSE,
               ":2: key 'dynamics.kinematic_joints': 'torso_pitch,torso_yaw,': item 3 of 3 is empty");
  expect_error("[robot]\ntouch_links = ,l_index_3,l_middle_3,l_ring_3,l_little_3,l_hand\n", ST_ERR_PARSE,
               ":2: key 'robot.touch_links': ',l_index_3,l_middle_3,l_ring_3,l_little_3,l_hand': item 1 of 6 is empty");
  expect_error("[integrated]\npopulations = a.genome, ,b.genome\n", ST_ERR_PARSE,
               ":2: key 'integrated.populations': 'a.genome, ,b.genome': item 2 of 3 is empty");
  {
    char err[512];
    stConfig c;
    st_config_default(&c);
    CU_ASSERT_EQUAL(st_config_set(&c, "robot.tip_frames=a,,b", err, sizeof err), ST_ERR_PARSE);
    ST_ASSERT_CONTAINS(err, "--set robot.tip_frames=a,,b: key 'robot.tip_frames': 'a,,b': item 2 of 3 is empty");
    CU_ASSERT_EQUAL(st_config_set(&c, "dynamics.adaptive_joints=", err, sizeof err), ST_OK); /* none */
    CU_ASSERT_EQUAL(st_config_set(&c, "dynamics.kinematic_joints=torso_pitch, torso_yaw", err, sizeof err), ST_OK);
    snprintf(c.robot_dof_joints, sizeof c.robot_dof_joints, "a,b,,c");
    CU_ASSERT_EQUAL(st_config_validate(&c, err, sizeof err), ST_ERR_RANGE);
    ST_ASSERT_CONTAINS(err, "key 'robot.dof_joints': 'a,b,,c': item 3 of 4 is empty");
  }
}

/* issue 17: a NUL byte cuts a line short for inih (the rest would be silently dropped), and a
 * file that never ends must not fill the memory; both refused, nothing of them applied */
static void test_config_hostile_files(void) {
  static const char text[] = "[ga]\npopulation = 50\0 and junk\nelites = 3\n";
  char path[256], err[512];
  stConfig c;
  st_config_default(&c);
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".cfg", text, sizeof text - 1));
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, ":2: NUL byte at column 16 (expected a text file)");
  CU_ASSERT_EQUAL(c.ga_population, 100); /* the default: nothing of the file was applied */
  CU_ASSERT_EQUAL(st_config_load("/dev/zero", &c, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_STRING_EQUAL(err, "/dev/zero: larger than 64 MiB (expected an input file of at most "
                              "67108864 bytes)");
}

/* issue 17 (found by tests/fuzz/fuzz_config.c): a string value the config file a run writes
 * (config.ini) cannot hold as it is was accepted, and the resumed run found config.ini
 * differing: "populations =;eue" stored ";eue", written back as "populations = ;eue", which
 * reads as a comment */
static void test_config_unwritable_strings(void) {
  char path[256], err[512];
  stConfig c;
  st_config_default(&c);
  st_test_write_tmp(path, sizeof path, ".cfg", "[stage]\ninit_population =;x\n");
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, ":2: key 'stage.init_population': ';x': ';' at the start reads as a "
                          "comment in a config file (expected a value without one)");
  st_test_write_tmp(path, sizeof path, ".cfg", "[stage]\ninit_population =#x\n");
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT_EQUAL(st_config_set(&c, "robot.urdf=a ;b", err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "key 'robot.urdf': 'a ;b': ';' after a space reads as a comment");
  CU_ASSERT_EQUAL(st_config_set(&c, "robot.urdf=a\tb", err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "control character 0x09");
  CU_ASSERT_EQUAL(st_config_set(&c, "stage.primitives= reach", err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "white space around the value");
  CU_ASSERT_EQUAL(st_config_set(&c, "robot.urdf=a;b#c", err, sizeof err), ST_OK); /* no space: kept */
  /* lines: 198 characters, with or without the last newline (fuzz_config: a last line of 199
   * was accepted and, written back with its newline, refused); a value must fit a line as the
   * writer writes it, "name = value" ("init_population = " leaves 198 - 18 = 180) */
  char text[400], v[200];
  memset(v, 'v', sizeof v);
  snprintf(text, sizeof text, "[stage]\ninit_population=%.*s", 181, v); /* 197 characters */
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  st_config_default(&c);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, ":2: key 'stage.init_population': value of 181 characters too long for "
                          "a config line (expected at most 180: 'init_population = VALUE' must fit "
                          "the 198 characters of a line)");
  snprintf(text, sizeof text, "[stage]\ninit_population=%.*s", 180, v);
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK);
  snprintf(text, sizeof text, "[stage]\n# %.*s", 197, v); /* 199 characters, no newline */
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, ":2: line longer than 198 characters");
  snprintf(text, sizeof text, "[stage]\n# %.*s", 196, v); /* 198 characters */
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK);
  snprintf(text, sizeof text, "[stage]\n# %.*s\n", 196, v); /* the same with its newline */
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_OK);
  snprintf(text, sizeof text, "[stage]\n# %.*s\n", 197, v);
  st_test_write_tmp(path, sizeof path, ".cfg", text);
  CU_ASSERT_EQUAL(st_config_load(path, &c, err, sizeof err), ST_ERR_PARSE);
  /* a value set over a longer one is the same configuration as the value set alone (resume
   * compares configurations byte for byte) */
  stConfig a, b;
  st_config_default(&a);
  st_config_default(&b);
  CU_ASSERT_EQUAL(st_config_set(&a, "stage.init_population=a_long_file_name.genome", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_set(&a, "stage.init_population=s.genome", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_set(&b, "stage.init_population=s.genome", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(memcmp(&a, &b, sizeof a), 0);
}

static void test_config_set_errors(void) {
  stConfig c;
  char err[512];
  st_config_default(&c);
  CU_ASSERT_EQUAL(st_config_set(&c, "ga.nope=3", err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "--set ga.nope=3: key 'ga.nope': unknown key");
  CU_ASSERT_EQUAL(st_config_set(&c, "population=3", err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "malformed override (expected section.key=value)");
  CU_ASSERT_EQUAL(st_config_set(&c, "ga.population", err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT_EQUAL(st_config_set(&c, "ga.mutation_rate=-1", err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "key 'ga.mutation_rate': -1 is out of range");
  CU_ASSERT_EQUAL(st_config_set(&c, "ga.population=5", err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "key 'ga.elites': 10 exceeds ga.population = 5");
  /* several overrides: cross-key rules once at the end, in any order */
  st_config_default(&c);
  const char *sets[] = {"ga.population=4", "ga.elites=1", "ga.parents=2", "ga.success_genotypes=1"};
  CU_ASSERT_EQUAL(st_config_set_all(&c, sets, 4, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(c.ga_population, 4);
  CU_ASSERT_EQUAL(c.ga_elites, 1);
  st_config_default(&c);
  CU_ASSERT_EQUAL(st_config_set_all(&c, sets, 2, err, sizeof err), ST_ERR_RANGE); /* parents 20 */
  ST_ASSERT_CONTAINS(err, "after the --set options: key 'ga.parents': 20 exceeds ga.population = 4");
  const char *bad[] = {"ga.population=4", "ga.elites=x"};
  CU_ASSERT_EQUAL(st_config_set_all(&c, bad, 2, err, sizeof err), ST_ERR_PARSE);
  ST_ASSERT_CONTAINS(err, "--set ga.elites=x: key 'ga.elites': 'x' is not an integer");
  /* a config built in code is checked by validate */
  st_config_default(&c);
  c.network_lambda = -3;
  CU_ASSERT_EQUAL(st_config_validate(&c, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "key 'network.lambda': -3 is out of range");
}

static void test_config_table(void) {
  /* every key is findable, documented and has a default inside its own range */
  stConfig c;
  st_config_default(&c);
  for (int i = 0; i < st_config_nkeys(); i++) {
    const stConfigKey *k = st_config_key(i);
    CU_ASSERT_EQUAL(st_config_find(k->section, k->name), i);
    CU_ASSERT(k->help && strlen(k->help) > 10);
    if (k->type == ST_CFG_INT || k->type == ST_CFG_REAL)
      CU_ASSERT(k->def_num >= k->min && k->def_num <= k->max);
  }
  CU_ASSERT_EQUAL(st_config_find("ga", "nope"), -1);
  CU_ASSERT_PTR_NULL(st_config_key(-1));
}

/* which stages read a key: the primitive stages do not read the integrated stage's keys, nor
 * simple-prim (kinematic) the dynamic world's; a run refuses such a key unless it is at its
 * default (issue 13: no key silently ignored) */
static void test_config_stage_keys(void) {
  stConfig c;
  char err[512];
  st_config_default(&c);
  CU_ASSERT_EQUAL(st_config_run_stages(&c), ST_CONFIG_SIMPLE_PRIM); /* default: simple_prim */
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "stage.stages=main_prim", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_run_stages(&c), ST_CONFIG_MAIN_PRIM);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "stage.stages=prims", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_run_stages(&c), ST_CONFIG_SIMPLE_PRIM | ST_CONFIG_MAIN_PRIM);
  c.stage_stages = ST_STAGES_INTEGRATED; /* st_config_set would need its populations too */
  CU_ASSERT_EQUAL(st_config_run_stages(&c), ST_CONFIG_INTEGRATED);

  const unsigned S = ST_CONFIG_SIMPLE_PRIM, M = ST_CONFIG_MAIN_PRIM, I = ST_CONFIG_INTEGRATED;
  const unsigned PI = ST_CONFIG_INTEGRATION_TEST, PR = ST_CONFIG_ROBUSTNESS_TEST;
  const unsigned PG = ST_CONFIG_GENERALISATION_TEST, P = ST_CONFIG_POSTEVAL, E = S | M | I;
  const unsigned ALL = ST_CONFIG_ALL_STAGES;
  /* the integrated stage (lib/episode/integrated.c, intscore.c) reads eq. 2.12 inside eq. 2.14, the
   * object-moving penalty, fail_penalty and the dynamic world; not the grasp postures, the
   * harmonic mean or the object-touching penalty. The issue-12 hand's keys: the dynamic
   * world's and a grasp posture's. The post-evaluations (lib/posteval/posteval.c, postrun.c) read the
   * network, the dynamic world, the caretaker's conditions (integration, generalisation),
   * integrated.steps (integration, robustness), the condition's words (robustness,
   * generalisation), no fitness and no GA key; the generalisation test has its own object
   * positions and target. */
  static const struct {
    const char *section, *name;
    unsigned stages;
  } rows[] = {
      {"network", "arch", I | P}, {"network", "typeb_init_gene", I}, {"network", "gamma_a", I | P},
      {"network", "lambda", ALL}, {"ga", "mutation_rate_integrated", I},
      {"ga", "integrated_generations", I}, {"ga", "mutation_rate", S | M},
      {"ga", "population", E}, {"dynamics", "gravity", M | I | P}, {"stage", "simple_steps", S},
      {"stage", "init_population", S | M | PI}, {"stage", "stages", E | PI},
      {"fitness", "move_touch", M | I}, {"fitness", "move_free", M | I},
      {"fitness", "fail_penalty", M | I}, {"fitness", "reach_hold_steps", M},
      {"fitness", "fp_min", S | M}, {"fitness", "penalty_object", S | M},
      {"fitness", "penalty_table", E}, {"fitness", "open_h", E | PI | PG},
      {"fitness", "reach_height", ALL}, {"scene", "target_offset", E | PI | PR},
      {"scene", "target_radius", ALL}, {"scene", "object_center_x", ALL},
      {"integrated", "steps", I | PI | PR}, {"integrated", "words_odd", I | PR | PG},
      {"integrated", "first_generation", I | PG}, {"integrated", "hold_steps", I},
      {"prediction", "window", I}, {"caretaker", "first_step", I | PI | PG},
      {"dynamics", "kinematic_joints", M | I | P}, {"dynamics", "table_friction", M | I | P},
      {"postures", "grasp_partial_thumb_flex", S | M}, {"postures", "reach_clearance", ALL},
      {"posteval", "integration_top", PI}, {"posteval", "robustness_trials", PR},
      {"posteval", "generalisation_target_y", PG}, {"robot", "alpha_dynamic", M | I | P},
      {"stage", "handover", M}, {"stage", "handover_rollin_steps", M}, {"stage", "chain_trials", M},
      {"stage", "handover_rollin", M},
  };
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    const unsigned got = st_config_key_stages(st_config_find(rows[i].section, rows[i].name));
    if (got != rows[i].stages)
      fprintf(stderr, "%s.%s: stages %u (expected %u)\n", rows[i].section, rows[i].name, got,
              rows[i].stages);
    CU_ASSERT_EQUAL(got, rows[i].stages);
  }
  /* every row of the table names a real key: 31 single keys (network 5, robot 1, scene 6,
   * stage 19) plus the ga, caretaker, integrated, prediction, dynamics and posteval sections,
   * the fitness section but reach_height, and the open, grasp and move postures, counted here
   * from the key table itself */
  int restricted = 0, whole = 0;
  for (int i = 0; i < st_config_nkeys(); i++) {
    const stConfigKey *k = st_config_key(i);
    restricted += st_config_key_stages(i) != ST_CONFIG_ALL_STAGES;
    whole += !strcmp(k->section, "ga") || !strcmp(k->section, "caretaker") ||
             !strcmp(k->section, "integrated") || !strcmp(k->section, "prediction") ||
             !strcmp(k->section, "dynamics") || !strcmp(k->section, "posteval") ||
             (!strcmp(k->section, "fitness") && strcmp(k->name, "reach_height")) ||
             (!strcmp(k->section, "postures") && strncmp(k->name, "reach_", 6));
  }
  CU_ASSERT_EQUAL(restricted, 31 + whole);

  /* defaults pass every combination of stages */
  st_config_default(&c);
  for (unsigned st = 1; st <= ST_CONFIG_ALL_STAGES; st++)
    CU_ASSERT_EQUAL(st_config_check_stages(&c, st, err, sizeof err), ST_OK);
  /* the integrated stage's keys: refused by the primitive stages, accepted by it */
  static const char *const integrated[][2] = {
      {"network.arch=A", "key 'network.arch': A is read only by the integrated stage and the "
                         "integration, robustness and generalisation tests, which this run "
                         "(simple-prim and main-prim) does not have: the primitive stages "
                         "evolve the base network"},
      {"network.typeb_init_gene=1", "key 'network.typeb_init_gene': 1 is read only by the integrated stage"},
      {"ga.mutation_rate_integrated=0.05", "key 'ga.mutation_rate_integrated': 0.05 is read only by "
                                            "the integrated stage"},
      {"ga.integrated_generations=7", "key 'ga.integrated_generations': 7 is read only by the integrated stage"},
      {"caretaker.first_step=2", "key 'caretaker.first_step': 2 is read only by the integrated "
                                 "stage and the integration and generalisation tests"},
      {"integrated.steps=30", "key 'integrated.steps': 30 is read only by the integrated stage "
                              "and the integration and robustness tests"},
      {"prediction.window=10", "key 'prediction.window': 10 is read only by the integrated stage"},
      {"network.gamma_b=7", "key 'network.gamma_b': 7 is read only by the integrated stage and "
                            "the integration, robustness and generalisation tests"},
  };
  for (size_t i = 0; i < sizeof integrated / sizeof integrated[0]; i++) {
    st_config_default(&c);
    CU_ASSERT_EQUAL_FATAL(st_config_set(&c, integrated[i][0], err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, S | M, err, sizeof err), ST_ERR_ARG);
    ST_ASSERT_CONTAINS(err, integrated[i][1]);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, I, err, sizeof err), ST_OK);
  }
  /* stage-specific keys of the primitive stages */
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "dynamics.gravity=5", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, S, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'dynamics.gravity': 5 is read only by the main-prim and integrated "
                          "stages and the integration, robustness and generalisation tests, which "
                          "this run (simple-prim) does not have: simple-prim runs in kinematic mode "
                          "(expected the default, 9.81)");
  CU_ASSERT_EQUAL(st_config_check_stages(&c, S | M, err, sizeof err), ST_OK);
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "stage.simple_steps=50", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, M, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'stage.simple_steps': 50 is read only by the simple-prim stage");
  CU_ASSERT_EQUAL(st_config_check_stages(&c, S, err, sizeof err), ST_OK);
  /* the primitive stages' keys: refused by the integrated stage, accepted by them */
  static const char *const primitive[][2] = {
      {"ga.max_generations=7", "key 'ga.max_generations': 7 is read only by the simple-prim and "
                               "main-prim stages, which this run (integrated) does not have"},
      {"ga.success_genotypes=2", "key 'ga.success_genotypes': 2 is read only by the simple-prim and main-prim stages"},
      {"ga.mutation_rate=0.01", "key 'ga.mutation_rate': 0.01 is read only by the simple-prim and main-prim stages"},
      {"stage.init_population=x.genome", "key 'stage.init_population': x.genome is read only by the "
                                         "simple-prim and main-prim stages and the integration test"},
      {"fitness.fp_min=0.01", "key 'fitness.fp_min': 0.01 is read only by the simple-prim and main-prim stages"},
      {"postures.grasp_partial_thumb_flex=0.1", "key 'postures.grasp_partial_thumb_flex': 0.1 is read "
                                                "only by the simple-prim and main-prim stages, which "
                                                "this run (integrated) does not have: the integrated "
                                                "stage starts every trial from the reach postures "
                                                "(expected the default, 0)"},
  };
  for (size_t i = 0; i < sizeof primitive / sizeof primitive[0]; i++) {
    st_config_default(&c);
    CU_ASSERT_EQUAL_FATAL(st_config_set(&c, primitive[i][0], err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, I, err, sizeof err), ST_ERR_ARG);
    ST_ASSERT_CONTAINS(err, primitive[i][1]);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, S | M, err, sizeof err), ST_OK);
  }
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "stage.main_move_steps=50", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, I, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'stage.main_move_steps': 50 is read only by the main-prim stage, "
                          "which this run (integrated) does not have");
  /* keys the integrated stage reads with main-prim: not refused by it */
  st_config_default(&c);
  const char *both[] = {"fitness.move_lift=0.2", "fitness.move_scale=0.2", "fitness.fail_penalty=2",
                        "dynamics.table_friction=0.5", "robot.alpha_dynamic=50"};
  CU_ASSERT_EQUAL_FATAL(st_config_set_all(&c, both, 5, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, I, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, M, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, S, err, sizeof err), ST_ERR_ARG);
  /* a key set to its default explicitly is not an error */
  st_config_default(&c);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "network.arch=base", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "ga.mutation_rate_integrated=0.04", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, S, err, sizeof err), ST_OK);
}

/* what st_config_write writes of c, or without c st_config_help's reference, into *buf (free
 * it) */
static void written(const stConfig *c, char **buf) {
  size_t len = 0;
  *buf = NULL;
  FILE *f = open_memstream(buf, &len);
  CU_ASSERT_PTR_NOT_NULL_FATAL(f);
  if (c) st_config_write(f, c);
  else st_config_help(f);
  fclose(f);
}

/* the post-evaluation tests are readers like the stages: their [posteval] keys are refused by
 * evolution runs and by the other tests, a key no test reads is refused by a test with the
 * post-evaluations' reason, and st_config_check_changes judges the --set options against the
 * config file (a run's config file may set keys of its own stages) */
static void test_config_posteval_keys(void) {
  stConfig c, file;
  char err[1024];
  const unsigned PI = ST_CONFIG_INTEGRATION_TEST, PR = ST_CONFIG_ROBUSTNESS_TEST;
  const unsigned PG = ST_CONFIG_GENERALISATION_TEST;
  st_config_default(&c);
  CU_ASSERT_EQUAL(c.posteval_integration_top, 10);
  CU_ASSERT_EQUAL(c.posteval_integration_trials, 40);
  CU_ASSERT_EQUAL(c.posteval_robustness_trials, 40);
  CU_ASSERT_EQUAL(c.posteval_generalisation_cells, 7);
  CU_ASSERT_DOUBLE_EQUAL(c.posteval_generalisation_cell_size, 0.05, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.posteval_generalisation_offset, 0.005, 0.0);
  CU_ASSERT_EQUAL(c.posteval_generalisation_repetitions, 10);
  CU_ASSERT_EQUAL(c.posteval_generalisation_steps, 300);
  CU_ASSERT_DOUBLE_EQUAL(c.posteval_generalisation_target_x, 0.25, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.posteval_generalisation_target_y, 0.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(c.posteval_generalisation_target_z, 0.17, 0.0);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "posteval.generalisation_cells=3", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, ST_CONFIG_INTEGRATED, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'posteval.generalisation_cells': 3 is read only by the "
                          "generalisation test, which this run (integrated) does not have: a "
                          "post-evaluation reads it, no evolution stage does (expected the default, 7)");
  CU_ASSERT_EQUAL(st_config_check_stages(&c, PG, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_stages(&c, PR, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "which this run (robustness test) does not have: it belongs to the "
                          "generalisation test (expected the default, 7)");
  /* keys the evolution stages read and no test does, with the tests' reasons; keys tests read */
  const struct {
    const char *set;
    unsigned stages;
    const char *msg;
  } refused[] = {
      {"ga.population=50", PR, "key 'ga.population': 50 is read only by the simple-prim, "
                               "main-prim and integrated stages, which this run (robustness "
                               "test) does not have: a post-evaluation runs no genetic algorithm"},
      {"fitness.fail_penalty=2", PI, "a post-evaluation records success and the step the target "
                                     "was reached, no fitness"},
      {"scene.target_offset=0.01", PG, "the generalisation test's target has no offset"},
      {"integrated.steps=60", PG, "the generalisation test's trials last posteval.generalisation_steps"},
      {"caretaker.grasp_touches=2", PR, "only the integration test and the generalisation "
                                        "test's caretaker variant hear the caretaker"},
      {"stage.primitives=grasp", PI, "a post-evaluation runs integrated trials"},
  }, read[] = {
      {"integrated.steps=60", PI, ""}, {"integrated.steps=60", PR, ""},
      {"caretaker.grasp_touches=2", PG, ""}, {"integrated.words_odd=none", PR, ""},
      {"dynamics.gravity=5", PR, ""}, {"network.gamma_a=2", PG, ""},
      {"scene.target_radius=0.05", PG, ""}, {"posteval.integration_top=2", PI, ""},
  };
  for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
    st_config_default(&c);
    CU_ASSERT_EQUAL_FATAL(st_config_set(&c, refused[i].set, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, refused[i].stages, err, sizeof err), ST_ERR_ARG);
    ST_ASSERT_CONTAINS(err, refused[i].msg);
  }
  /* ... and keys a test reads */
  for (size_t i = 0; i < sizeof read / sizeof read[0]; i++) {
    st_config_default(&c);
    CU_ASSERT_EQUAL_FATAL(st_config_set(&c, read[i].set, err, sizeof err), ST_OK);
    CU_ASSERT_EQUAL(st_config_check_stages(&c, read[i].stages, err, sizeof err), ST_OK);
  }
  /* changes against a config file: what the file sets for its own run is not an override */
  st_config_default(&file);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&file, "ga.population=50", err, sizeof err), ST_OK);
  c = file;
  CU_ASSERT_EQUAL(st_config_check_changes(&c, &file, "the config file's value", PR, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "posteval.robustness_trials=8", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_changes(&c, &file, "the config file's value", PR, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_changes(&c, &file, "the config file's value", PI, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'posteval.robustness_trials': 8 is read only by the robustness test, "
                          "which this run (integration test) does not have: it belongs to the "
                          "robustness test (expected the config file's value, 40)");
  CU_ASSERT_EQUAL_FATAL(st_config_set(&c, "ga.population=20", err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_changes(&c, &file, "the config file's value", PR, err, sizeof err), ST_ERR_ARG);
  ST_ASSERT_CONTAINS(err, "key 'ga.population': 20 is read only by the simple-prim, main-prim and "
                          "integrated stages, which this run (robustness test) does not have");
  ST_ASSERT_CONTAINS(err, "(expected the config file's value, 50)");
  /* the run's stages and a test together */
  CU_ASSERT_EQUAL(st_config_check_stages(&file, ST_CONFIG_INTEGRATED | PR, err, sizeof err), ST_OK);
  /* the key reference names the readers */
  char *buf;
  written(NULL, &buf);
  ST_ASSERT_CONTAINS(buf, "posteval.generalisation_cells (int, default 7; an integer in [1, 1000]); "
                          "read by the generalisation test only");
  ST_ASSERT_CONTAINS(buf, "caretaker.first_step (int, default 1; an integer in [0, 100000]); read by "
                          "the integrated stage and the integration and generalisation tests only");
  ST_ASSERT_CONTAINS(buf, "stage.simple_steps (int, default 60; an integer in [1, 100000]); read by "
                          "the simple-prim stage only");
  CU_ASSERT_PTR_NULL(strstr(buf, "fitness.reach_height (real, default 0.095; a number in [0, 1]); read"));
  free(buf);
}

/* every key has a tier; --help-config lists them tier by tier, each key once under its tier's
 * heading; config.ini groups each section's keys by tier under a comment, and reads back */
static void test_config_tiers(void) {
  int per[ST_TIER_COUNT] = {0};
  for (int i = 0; i < st_config_nkeys(); i++) {
    const stConfigKey *k = st_config_key(i);
    (void)k;
    const stConfigTier t = st_config_key_tier(i);
    CU_ASSERT_FATAL((int)t >= 0 && t < ST_TIER_COUNT);
    per[t]++;
  }
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("run", "seed")), ST_TIER_RUN);
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("run", "threads")), ST_TIER_SPEED);
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("stage", "primitives")), ST_TIER_DIAGNOSTIC);
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("stage", "handover_rollin")), ST_TIER_EXTENSION);
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("postures", "vary_draws")), ST_TIER_EXTENSION);
  CU_ASSERT_EQUAL(st_config_key_tier(st_config_find("fitness", "bonus")), ST_TIER_PROTOCOL);
  /* each entry of the fence names keys of the table */
  static const struct {
    const char *section, *name;
  } fence[] = {
#define ROW(t, s, k) {s, k},
      ST_CONFIG_TIERS(ROW)
#undef ROW
  };
  for (size_t r = 0; r < sizeof fence / sizeof fence[0]; r++) {
    const size_t n = strlen(fence[r].name);
    const int prefix = fence[r].name[n - 1] == '*';
    int hits = 0;
    for (int i = 0; i < st_config_nkeys(); i++) {
      const stConfigKey *k = st_config_key(i);
      hits += !strcmp(k->section, fence[r].section) &&
              (prefix ? !strncmp(k->name, fence[r].name, n - 1) : !strcmp(k->name, fence[r].name));
    }
    if (!hits) fprintf(stderr, "\n  fence entry %s.%s names no key\n", fence[r].section, fence[r].name);
    CU_ASSERT(hits > 0);
  }
  CU_ASSERT_STRING_EQUAL(st_config_tier_name(ST_TIER_EXTENSION), "extension");
  CU_ASSERT_STRING_EQUAL(st_config_tier_name(ST_TIER_COUNT), "?");
  char *buf, *ini;
  written(NULL, &buf);
  const char *at = buf;
  for (int t = 0; t < ST_TIER_COUNT; t++) {
    char head[64];
    snprintf(head, sizeof head, "==== %s: ", st_config_tier_name((stConfigTier)t));
    const char *h = strstr(buf, head);
    CU_ASSERT_FATAL(h != NULL && h >= at);
    at = h;
    /* its keys before the next heading */
    const char *next = strstr(h + 1, "\n==== ");
    int n = 0;
    for (int i = 0; i < st_config_nkeys(); i++) {
      const stConfigKey *k = st_config_key(i);
      char name[160];
      snprintf(name, sizeof name, "\n%s.%s (", k->section, k->name);
      const char *p = strstr(h, name);
      if (st_config_key_tier(i) == (stConfigTier)t) CU_ASSERT(p != NULL && (!next || p < next));
      n += p != NULL && (!next || p < next);
    }
    CU_ASSERT_EQUAL(n, per[t]);
  }
  free(buf);
  stConfig c;
  st_config_default(&c);
  c.stage_handover = 1;
  written(&c, &ini);
  const char *stage = strstr(ini, "\n[stage]\n");
  CU_ASSERT_PTR_NOT_NULL_FATAL(stage);
  const char *proto = strstr(stage, "# ---- protocol: "), *run = strstr(stage, "# ---- run: ");
  const char *ext = strstr(stage, "# ---- extension: "), *diag = strstr(stage, "# ---- diagnostic: ");
  const char *ho = strstr(stage, "\nhandover = true\n"), *steps = strstr(stage, "\nsimple_steps = 60\n");
  CU_ASSERT(proto && run && ext && diag && ho && steps);
  CU_ASSERT(proto < steps && steps < run && run < ext && ext < ho && ho < diag);
  free(ini);
}

/* ranges live in the key table: code that builds its definitions checks them there */
static void test_config_check_number(void) {
  char err[256];
  CU_ASSERT_EQUAL(st_config_check_number("ga", "population", 2, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_number("ga", "population", 1, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "ga.population: 1 is out of range (expected an integer in [2, 100000])");
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "gravity", 100, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "gravity", 101, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "dynamics.gravity: 101 is out of range (expected a number in [0, 100])");
  CU_ASSERT_EQUAL(st_config_check_number("robot", "urdf", 1, err, sizeof err), ST_ERR_ARG);
  /* a BOOL takes 0 and 1, an ENUM its choices' indices */
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "free_motion", 1, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "free_motion", 2, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "lcp", 1, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "lcp", 3, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "lcp", 4, err, sizeof err), ST_ERR_RANGE);
  ST_ASSERT_CONTAINS(err, "dynamics.lcp: 4 is out of range (expected one of dense|schur|block|warm)");
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "lcp", -1, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_EQUAL(st_config_check_number("dynamics", "lcp", 0.5, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_EQUAL(st_config_check_number("ga", "nope", 1, err, sizeof err), ST_ERR_ARG);
}

void st_suite_config(void) {
  ST_ADD_SUITE("config");
  ST_ADD_TEST(test_config_defaults);
  ST_ADD_TEST(test_config_load_ok);
  ST_ADD_TEST(test_config_roundtrip);
  ST_ADD_TEST(test_config_errors);
  ST_ADD_TEST(test_config_strict_syntax);
  ST_ADD_TEST(test_config_keys_act);
  ST_ADD_TEST(test_config_hostile_files);
  ST_ADD_TEST(test_config_unwritable_strings);
  ST_ADD_TEST(test_config_set_errors);
  ST_ADD_TEST(test_config_table);
  ST_ADD_TEST(test_config_stage_keys);
  ST_ADD_TEST(test_config_posteval_keys);
  ST_ADD_TEST(test_config_check_number);
  ST_ADD_TEST(test_config_tiers);
}
