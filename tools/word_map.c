/* SPDX-License-Identifier: MIT
 * word_map: what a talking (type A) network would say at each step of an integrated trial had
 * it heard another word, its state and senses unchanged: how much of its self talk is a map of
 * the last word alone. A diagnostic (issue 47 item 4: why ST runs stall saying one word, or two
 * in turn; docs/notebook/study.md), not part of the protocol.
 *
 *   build/word_map CONFIG GENOME [--trial T] [--generation G] [--index I] [--steps]
 *                  [--set section.key=value]...
 *
 * Replays trial T (default 0) of the integrated stage as evolution ran it at generation G
 * (default: the genotype's own, as ./apps/replay) for genotype I of GENOME (default: the last).
 * Before each step's action the network's state is copied and stepped once more for every word
 * it could hear instead (none, reach, open, grasp, move: the inputs of that step with only the
 * linguistic ones changed); the real step then goes on as recorded. With --steps, one line per
 * step:
 *   step S heard H said L if N R O G M
 * (H, L: the word heard and the label said, - for none; N R O G M: the label it would have
 * said hearing nothing, reach, open, grasp, move). Then, for each word w that can be heard:
 *   map W -> L (K of N steps, C changes)
 * L the label said most often on hearing w (ties: the lowest), K the steps at which it is the
 * one said, N the steps simulated, C the steps at which, hearing w, it would say another label
 * than at the step before (what the body's course changes); then
 *   word matters at F of N steps
 * F: the steps at which the five words heard would not all give one label. A network whose
 * words follow the body: few F, C > 0 (a label per phase); one caught in its own words: the
 * maps make a cycle (o -> g, g -> o) and C = 0; one deaf to both: one label, F and C near 0.
 * Exit 0, or 2 with the reason. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "selftalk/selftalk.h"

#define NHEAR (ST_NET_NLING + 1) /* none, then the four words */
static const char LETTER[] = "-rogm";

static void die(const char *fmt, const char *a) {
  fprintf(stderr, "word_map: ");
  fprintf(stderr, fmt, a);
  fprintf(stderr, "\n");
  exit(2);
}

/* the network controller, with each step's counterfactual labels before its real step */
typedef struct mapCtl {
  stNetController inner; /* the network's controller: its state, reset and real steps */
  stController net;
  double scale; /* input value of a heard word (network.linguistic_input) */
  int nsteps, cap;
  int (*would)[NHEAR]; /* [step][h]: label said hearing h - 1 (h = 0: nothing) */
  int *heard, *said;
} mapCtl;

static void map_reset(void *self, const stEpisodeSpec *e) {
  mapCtl *m = self;
  m->net.reset(m->net.self, e);
  m->nsteps = 0;
}

/* the word in a step's linguistic inputs: the one set, -1 when none is */
static int heard_in(const double *in) {
  for (int w = 0; w < ST_NET_NLING; w++)
    if (in[ST_NET_IN_LING + w] != 0.0) return w;
  return -1;
}

static void map_act(void *self, const stWorld *w, const stQuantities *q, const double *in, int step,
                    double *out) {
  mapCtl *m = self;
  const int n = st_net_ninputs(m->inner.net->arch);
  double alt[ST_NET_NIN + 1]; /* type A: the base network's inputs and the secondary one */
  if (m->nsteps >= m->cap || n > (int)(sizeof alt / sizeof alt[0]))
    die("%s", "more steps or inputs than the config's network and trial have");
  for (int h = 0; h < NHEAR; h++) {
    memcpy(alt, in, (size_t)n * sizeof *alt);
    st_net_label_input(h - 1, m->scale, alt + ST_NET_IN_LING);
    stNetState s = m->inner.state;
    st_net_step(m->inner.net, &s, alt, NULL);
    m->would[m->nsteps][h] = st_net_selftalk_label(&s);
  }
  m->net.act(m->net.self, w, q, in, step, out);
  m->heard[m->nsteps] = heard_in(in);
  m->said[m->nsteps] = st_net_selftalk_label(&m->inner.state);
  m->nsteps++;
}

int main(int argc, char **argv) {
  static const char usage[] =
      "usage: word_map CONFIG GENOME [--trial T] [--generation G] [--index I] [--steps] "
      "[--set section.key=value]...";
  const char *config = NULL, *genome = NULL;
  const char **sets = calloc((size_t)argc, sizeof *sets);
  int nsets = 0, trial = 0, generation = -1, index = -1, steps = 0;
  if (!sets) die("%s", "out of memory");
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    char *end = NULL;
    if ((!strcmp(a, "--trial") || !strcmp(a, "--generation") || !strcmp(a, "--index")) &&
        i + 1 < argc) {
      const long v = strtol(argv[++i], &end, 10);
      if (end == argv[i] || *end || v < 0 || v > 1000000) die("'%s': expected a number >= 0", argv[i]);
      *(a[2] == 't' ? &trial : a[2] == 'g' ? &generation : &index) = (int)v;
    } else if (!strcmp(a, "--steps")) steps = 1;
    else if (!strcmp(a, "--set") && i + 1 < argc) sets[nsets++] = argv[++i];
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      printf("%s\n", usage);
      return 0;
    } else if (a[0] == '-') die("unknown or incomplete option '%s'", a);
    else if (!config) config = a;
    else if (!genome) genome = a;
    else die("unexpected argument '%s'", a);
  }
  if (!config || !genome) die("%s", usage);
  char err[1024];
  stConfig cfg;
  st_config_default(&cfg);
  if (st_config_load(config, &cfg, err, sizeof err)) die("%s", err);
  if (nsets && st_config_set_all(&cfg, sets, nsets, err, sizeof err)) die("%s", err);
  if (cfg.stage_stages != ST_STAGES_INTEGRATED || cfg.network_arch != ST_ARCH_A)
    die("%s: expected an integrated stage's config with a talking network (stage.stages = "
        "integrated, network.arch = A)", config);
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) die("%s", err);
  stIntegratedDef def;
  st_integrated_def_from_config(&p->cfg, &def);
  if (trial >= def.trials) die("--trial: expected 0..integrated.trials - 1 (%s)", config);
  stGenomeSet set;
  if (st_genome_set_read(genome, st_arch_ngenes(ST_ARCH_A), &set, err, sizeof err)) die("%s", err);
  if (index < 0) index = set.count - 1;
  if (index >= set.count) die("--index: past the last genotype of %s", genome);
  if (generation < 0) generation = set.generation[index] >= 0 ? set.generation[index] : 0;
  stNetParams np;
  if (st_net_decode(&p->net, ST_ARCH_A, &set.genome[index], &np, err, sizeof err)) die("%s", err);
  st_genome_set_free(&set);

  mapCtl m = {.scale = cfg.network_linguistic_input, .cap = cfg.integrated_steps};
  m.would = calloc((size_t)m.cap, sizeof *m.would);
  m.heard = calloc((size_t)m.cap, sizeof *m.heard);
  m.said = calloc((size_t)m.cap, sizeof *m.said);
  if (!m.would || !m.heard || !m.said) die("%s", "out of memory");
  m.net = st_net_controller(&m.inner, &np, NULL, 0);
  const stController ctl = {map_reset, map_act, m.net.ninputs, &m, m.net.noutputs, m.net.talks,
                            NULL};
  const stIntPlan plan = st_integrated_plan(&def, generation, trial);
  stEpisodeSpec e;
  st_int_trial(p, &def, generation, index, trial, &e);
  stWorkspace ws = {NULL, NULL, NULL};
  stIntTrialResult r;
  if (st_int_run_with(p, &def, &ws, &e, &ctl, &plan, &r, NULL, NULL, NULL, err, sizeof err))
    die("%s", err);
  st_workspace_free(&ws);

  printf("genotype %d of %s, trial %d of generation %d (words %s): success %d, %d steps\n", index,
         genome, trial, generation, st_word_source_name(plan.words), r.success, m.nsteps);
  for (int t = 0; steps && t < m.nsteps; t++) {
    printf("step %d heard %c said %c if", t, LETTER[m.heard[t] + 1], LETTER[m.said[t] + 1]);
    for (int h = 0; h < NHEAR; h++) printf(" %c", LETTER[m.would[t][h] + 1]);
    printf("\n");
  }
  for (int h = 0; h < NHEAR; h++) {
    int count[ST_NET_NLING] = {0}, best = 0, changes = 0;
    for (int t = 0; t < m.nsteps; t++) {
      count[m.would[t][h]]++;
      changes += t > 0 && m.would[t][h] != m.would[t - 1][h];
    }
    for (int l = 1; l < ST_NET_NLING; l++)
      if (count[l] > count[best]) best = l;
    printf("map %c -> %c (%d of %d steps, %d changes)\n", LETTER[h], LETTER[best + 1], count[best],
           m.nsteps, changes);
  }
  int matters = 0;
  for (int t = 0; t < m.nsteps; t++)
    for (int h = 1; h < NHEAR; h++)
      if (m.would[t][h] != m.would[t][0]) {
        matters++;
        break;
      }
  printf("word matters at %d of %d steps\n", matters, m.nsteps);
  free(m.would);
  free(m.heard);
  free(m.said);
  free(sets);
  st_protocol_destroy(p);
  return 0;
}
