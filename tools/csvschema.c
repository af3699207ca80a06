/* SPDX-License-Identifier: MIT
 * csvschema: prints tools/csvschema.py, the results files' columns for the Python tools, from
 * the library's column tables (selftalk/postcsv.h, selftalk/fitnesscsv.h), so that the tools
 * take their column names from the one definition the writers and readers use.
 *
 *   build/csvschema > tools/csvschema.py
 *   build/csvschema --fitness-header INTEGRATED TRIALS [KIND=N]...
 *
 * tests/check_tools.sh fails while the committed file differs from what this prints; the
 * second form prints a layout's fitness.csv header (st_fitness_csv), against which the check
 * tries csvschema.fitness_columns. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/fitnesscsv.h"
#include "selftalk/postcsv.h"
#include "selftalk/trialkind.h"

/* the kinds of tools/figlib.py's read_csv */
static const char *py_kind(stCsvKind k) {
  switch (k) {
    case ST_CSV_INT: return "int";
    case ST_CSV_REAL: return "float";
    case ST_CSV_TEXT: return "text";
    default: return "str"; /* a name, a choice: never empty */
  }
}

static void columns(const char *var, const stCsvSchema *s) {
  printf("\n# %s (./apps/posteval): the first %s_READ are what every such file has and what\n"
         "# ./apps/stats reads\n%s = {\n", s->file, var, var);
  for (int i = 0; i < s->ncols; i++) printf("    \"%s\": \"%s\",\n", s->col[i].name, py_kind(s->col[i].kind));
  printf("}\n%s_READ = %d\n", var, s->nread);
}

static const char *stages_of(unsigned stages) {
  return stages == (ST_FITNESS_PRIMITIVE | ST_FITNESS_INTEGRATED) ? "(\"primitive\", \"integrated\")"
         : stages == ST_FITNESS_INTEGRATED                       ? "(\"integrated\",)"
                                                                 : "(\"primitive\",)";
}

/* fitness.csv: the table's columns, then each trial kind's (its rows, selftalk/trialkind.h) */
static void fitness(void) {
  int n;
  const stFitnessColumn *c = st_fitness_columns(&n);
  printf("\n# fitness.csv (./apps/evolve): every column a run's file may have, in file order, as\n"
         "# (name, the runs that have it, the trial kind it belongs to or None, one per trial: a name\n"
         "# with %%d, from 0); the primitive stages' trials are their kinds' columns\n"
         "FITNESS_COLUMNS = [\n");
  for (int i = 0; i < n; i++)
    printf("    (\"%s\", %s, None, %s),\n", c[i].col.name, stages_of(c[i].stages),
           c[i].per_trial ? "True" : "False");
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (d->column.name)
      printf("    (\"%s\", (\"primitive\",), \"%s\", False),\n", d->column.name, d->name);
    printf("    (\"%s\", (\"primitive\",), \"%s\", True),\n", d->trial_column, d->name);
  }
  printf("]\n# {name: kind} of those columns\nFITNESS = {\n");
  for (int i = 0; i < n; i++) printf("    \"%s\": \"%s\",\n", c[i].col.name, py_kind(c[i].col.kind));
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (d->column.name) printf("    \"%s\": \"%s\",\n", d->column.name, py_kind(d->column.kind));
    if (strcmp(d->trial_column, ST_TRIAL_COLUMN)) printf("    \"%s\": \"int\",\n", d->trial_column);
  }
  printf("}\n# the primitive stages' kinds of trials (selftalk/trialkind.h), in column order: the most\n"
         "# trials of each\nTRIAL_KINDS = {\n");
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++)
    printf("    \"%s\": %d,\n", st_trial_kind_def((stTrialKind)k)->name,
           st_trial_kind_def((stTrialKind)k)->max);
  printf("}\n");
}

/* a layout's header, as evolve writes it: INTEGRATED TRIALS [KIND=N]... (primitive: TRIALS the
 * fixed trials, the other kinds none unless given) */
static int fitness_header(char **arg, int narg) {
  stFitnessLayout l;
  memset(&l, 0, sizeof l);
  l.integrated = atoi(arg[0]);
  const int trials = atoi(arg[1]);
  if (l.integrated) l.trials = trials;
  else l.kind_trials[ST_TRIAL_FIXED] = trials;
  for (int i = 2; i < narg; i++) {
    const char *eq = strchr(arg[i], '=');
    int k = 0;
    while (eq && k < ST_TRIAL_KIND_COUNT &&
           strncmp(arg[i], st_trial_kind_def((stTrialKind)k)->name, (size_t)(eq - arg[i])))
      k++;
    if (!eq || k == ST_TRIAL_KIND_COUNT) {
      fprintf(stderr, "csvschema: '%s': expected KIND=N of a trial kind\n", arg[i]);
      return 2;
    }
    l.kind_trials[k] = atoi(eq + 1);
  }
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++)
    if (l.kind_trials[k] < 0 || l.kind_trials[k] > st_trial_kind_def((stTrialKind)k)->max ||
        l.trials < 0 || l.trials > ST_INT_MAX_TRIALS) {
      fprintf(stderr, "csvschema: integrated trials 0..%d, each kind's up to its most\n",
              ST_INT_MAX_TRIALS);
      return 2;
    }
  stFitnessCsv c;
  st_fitness_csv(&l, &c);
  return st_csv_write_header(stdout, &c.schema) ? 1 : 0;
}

int main(int argc, char **argv) {
  if (argc >= 4 && !strcmp(argv[1], "--fitness-header")) return fitness_header(argv + 2, argc - 2);
  if (argc != 1) {
    fprintf(stderr, "usage: csvschema [--fitness-header INTEGRATED TRIALS [KIND=N]...]\n");
    return 2;
  }
  printf("# SPDX-License-Identifier: MIT\n"
         "# Generated by tools/csvschema.c from the library's column tables (lib/posteval/postcsv.c,\n"
         "# lib/run/fitnesscsv.c, the trial kinds' rows lib/episode/trials/): do not edit. After\n"
         "# changing a table: make build/csvschema && build/csvschema > tools/csvschema.py\n"
         "# (tests/check_tools.sh fails while they differ).\n"
         "\"\"\"The columns of the results files for the tools that read them: {name: kind} in file\n"
         "order, kinds as tools/figlib.py's read_csv takes them (\"str\" a name, never empty; \"int\";\n"
         "\"float\"; \"text\", possibly empty).\"\"\"\n");
  columns("TRIALS", st_post_trials_schema());
  columns("SUMMARY", st_post_summary_schema());
  fitness();
  printf("\n\ndef pick(columns, *names):\n"
         "    \"\"\"{name: kind} of the named columns of a file (TRIALS, SUMMARY, FITNESS); a name that\n"
         "    is not one of them raises KeyError, so a tool fails as soon as its names drift from the\n"
         "    library's\"\"\"\n"
         "    return {n: columns[n] for n in names}\n"
         "\n\n"
         "def fitness_columns(integrated, trials, kinds=None):\n"
         "    \"\"\"the header of a run's fitness.csv as ./apps/evolve writes it: the integrated stage's\n"
         "    columns with `trials` best_tI, or the primitive stages' with `trials` fixed trials and\n"
         "    kinds = {kind: trials} of its other kinds of trials (TRIAL_KINDS)\"\"\"\n"
         "    runs = \"integrated\" if integrated else \"primitive\"\n"
         "    count = dict(kinds or {}, fixed=trials)\n"
         "    out = []\n"
         "    for name, have, kind, per_trial in FITNESS_COLUMNS:\n"
         "        n = count.get(kind, 0) if kind else trials if per_trial else 1\n"
         "        if runs not in have or n == 0:\n"
         "            continue\n"
         "        out += [name %% t for t in range(n)] if per_trial else [name]\n"
         "    return out\n");
  return ferror(stdout) ? 1 : 0;
}
