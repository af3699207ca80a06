/* SPDX-License-Identifier: MIT
 * posteval: the post-evaluations of thesis §2.10 (SPEC §11, selftalk/posteval.h).
 *
 *   posteval integration    CONFIG POPULATION... [--no-words] [options]   (configs/prims.cfg)
 *   posteval robustness     CONFIG RUNDIR...     [options]   (configs/integrated_<cond>.cfg)
 *   posteval generalisation CONFIG RUNDIR...     [--caretaker] [options]
 *   options: [--out DIR] [--threads N] [--condition NAME] [--resume] [--journal-every S]
 *            [--set section.key=value]...
 *            [--help-config]
 *
 * integration: the top posteval.integration_top (10) genotypes of each population file (or
 * primitive run directory: population.genome, else its checkpoint), posteval.integration_trials
 * (40) caretaker-guided trials each. robustness: the best of the last generation of each
 * integrated run directory, posteval.robustness_trials (40) autonomous trials. generalisation:
 * the same individuals on the 7 x 7 grid x 4 postures x 10 repetitions, 300 steps; an individual
 * with no autonomous success in its last training generation scores 0 without being run;
 * --caretaker runs every individual with the caretaker's words (ST-CT0, ST0); --no-words runs
 * the integration test's trials with no words (SPEC 12: primitives that stay word-driven should
 * rarely chain without them).
 * Writes DIR/trials.csv, DIR/summary.csv and DIR/config.ini atomically (default DIR
 * runs/posteval/TEST-CONDITION); progress on stderr. The files are the same for any --threads.
 * The trials done are journalled in DIR/posteval.journal every --journal-every S seconds (30;
 * 0: after every trial): --resume continues a killed test from there to the same files; a
 * directory with a journal is refused without --resume. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/posteval.h"

static const char *prog = "posteval";

static void usage(FILE *f) {
  fprintf(f, "usage: posteval integration CONFIG POPULATION... [--no-words] [options]\n"
             "       posteval robustness CONFIG RUNDIR... [options]\n"
             "       posteval generalisation CONFIG RUNDIR... [--caretaker] [options]\n"
             "options: [--out DIR] [--threads N] [--condition NAME] [--resume] [--journal-every S]\n"
             "         [--set section.key=value]...\n"
             "         [--help-config]\n");
}

#define MAX_INPUTS 1024

typedef struct cli {
  appConfigArgs ca;
  const char *test, *out, *condition;
  const char *inputs[MAX_INPUTS];
  int ninputs, threads, resume;
  stPostVariant variant;
  double journal_seconds;
} cli;

/* a positional argument: the test, the config (unless --config), then the inputs */
static void positional(cli *c, const char *a) {
  if (!c->test) c->test = a;
  else if (!c->ca.config_path) c->ca.config_path = a;
  else if (c->ninputs < MAX_INPUTS) c->inputs[c->ninputs++] = a;
  else app_die(prog, "more than %d inputs", MAX_INPUTS);
}

static void parse(cli *c, int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&c->ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--out") && i + 1 < argc) c->out = argv[++i];
    else if (!strcmp(a, "--threads") && i + 1 < argc) c->threads = app_int_arg(prog, a, argv[++i], 1);
    else if (!strcmp(a, "--condition") && i + 1 < argc) c->condition = argv[++i];
    else if (!strcmp(a, "--caretaker")) c->variant = ST_POST_CARETAKER;
    else if (!strcmp(a, "--no-words")) c->variant = ST_POST_NO_WORDS;
    else if (!strcmp(a, "--resume")) c->resume = 1;
    else if (!strcmp(a, "--journal-every") && i + 1 < argc) {
      char *end;
      c->journal_seconds = strtod(argv[++i], &end);
      if (end == argv[i] || *end || !(c->journal_seconds >= 0.0 && c->journal_seconds <= 86400.0))
        app_die(prog, "--journal-every '%s': expected seconds, 0 to 86400 (0: after every trial)",
                argv[i]);
      if (c->journal_seconds == 0.0) c->journal_seconds = -1.0; /* the library's "every trial" */
    }
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) usage(stdout), exit(0);
    else if (a[0] == '-' && a[1]) {
      usage(stderr);
      app_die(prog, "unknown or incomplete option '%s'", a);
    } else positional(c, a);
  }
  if (!c->test || !c->ca.config_path || !c->ninputs) {
    usage(stderr);
    app_die(prog, "missing %s", !c->test ? "TEST" : !c->ca.config_path ? "CONFIG" : "inputs");
  }
}

int main(int argc, char **argv) {
  cli c;
  memset(&c, 0, sizeof c);
  parse(&c, argc, argv);
  const int test = st_post_test_parse(c.test);
  if (test < 0) app_die(prog, "test '%s' (expected integration, robustness or generalisation)", c.test);
  /* the config file alone (the --set options are checked against it), then with them */
  appConfigArgs file_args = c.ca;
  file_args.nsets = 0;
  stConfig file_cfg, cfg;
  app_config_resolve(&file_args, &file_cfg, prog);
  app_config_resolve(&c.ca, &cfg, prog);
  char cond[64], dir[1024];
  if (!c.out) {
    if (c.condition) snprintf(cond, sizeof cond, "%s", c.condition);
    else st_post_condition(&cfg, (stPostTest)test, c.variant, cond, sizeof cond);
    snprintf(dir, sizeof dir, "runs/posteval/%s-%s", c.test, cond);
    c.out = dir;
  }
  const stPostRunDef def = {&cfg, &file_cfg, (stPostTest)test, c.inputs, c.ninputs, c.variant,
                            c.condition, c.out, c.threads, stderr, c.resume, c.journal_seconds};
  char err[2048];
  if (st_post_run(&def, err, sizeof err)) app_die(prog, "%s", err);
  return 0;
}
