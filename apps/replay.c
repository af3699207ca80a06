/* SPDX-License-Identifier: MIT
 * replay: runs one trial of a saved genotype and writes its per-step trace (SPEC §9).
 *
 *   replay GENOME CONFIG --trial K [--out trace.csv] [--exact] [--stage simple|main]
 *          [--generation G] [--index I] [--force OUT=VALUE[@STEP]]... [--set section.key=value]...
 *
 * Primitive stages: K = 0..15 (primitive K/4: reach, open, grasp, move; posture and object
 * position K%4). Integrated stage (a config with stage.stages = integrated): K = 0..
 * integrated.trials-1 (type K%4); the trial hears and is scored as that generation's plan says
 * (generation 0: the first generation's variant).
 * The genotypes are of network.arch's architecture: base for the primitive stages' runs, A or B
 * for the integrated stage's; an A or B genotype also replays the primitive trials (without
 * the secondary input).
 * --generation picks the trials' random offsets; --index the genotype of GENOME (a number, or
 * "last"). Without --index: in a file of per-generation bests (evolve's best.genome, whose
 * records carry "# generation G") the record of generation G, or the last record and its
 * generation when --generation is not given either; otherwise the first genotype (the best in
 * population.genome) with generation 0. Prints the genotype chosen and a one-line summary.
 * --exact prints the trace's reals with 17 significant digits (they read back bit for bit: for
 * comparing runs, and the golden results of tests/check_golden.sh) instead of 9.
 * --force overrides network output OUT (0..11 the DOF of SPEC §3, 12 focus) with VALUE (0..1)
 * from step STEP on (default 0): what the individual would do with, e.g., its thumb opposed.
 * --rollin FILE [--rollin-index I] (a main-prim config with stage.handover_rollin = elite, a
 * hand-over trial K = 16..27; required there, refused elsewhere): the genotype of FILE whose
 * base network acts the roll-in, the generation's elite (its genotype 0), as evolve had it.
 * Without --rollin-index: in a file of per-generation bests, the record of generation G - 1
 * (the GA copies the previous generation's best to genotype 0; not so at a stage's first
 * generation, nor at generation 0, whose elite is the initial population's first genotype:
 * give that file); otherwise its first genotype (a checkpoint's population is the generation's
 * own, genotype 0 its elite). Forced outputs apply to the individual, which acts from the
 * hand-over on.
 *
 * --posteval TEST (integration, robustness, generalisation) replays trial K of that
 * post-evaluation's table instead (posteval's trial numbering, its random streams: the trial
 * posteval ran; CONFIG as given to posteval, --caretaker as its generalisation variant), and
 * prints the words heard and how it ended, as posteval's trials.csv has them.
 * --shapes FILE writes the collision shapes (st_world_shapes: every robot geometry, the ball,
 * the table, the target) of the state after the chosen steps' actions, one CSV row per shape:
 * step,kind,owner,type,sx,sy,sz,px,py,pz,r00..r22 (docs/PROTOCOL.md, "Robot pictures"). The
 * steps: --at LIST (step numbers and "last", the trial's last step, comma-separated) and/or
 * --shapes-every N (steps 0, N, 2N, ... and the last); every step without either.
 * --html FILE writes one self-contained page that plays the trial in 3D beside its trace (the
 * shapes of every step, the words, the linguistic outputs, touch, d_r, d_g, lifted, S, P) and
 * its summary, three.js inlined from --three DIR, $SELFTALK_THREE_DIR or Debian's libjs-three
 * (trial_page.h; docs/PROTOCOL.md, "Trial pages").
 *
 * The trace has one row per step: joints, palm, object, target, touch, focus, the linguistic
 * inputs, S, P, events, the fitness quantities, then the caretaker's word given at the step
 * (-1 none; in primitive trials the trial's word), the self-talk label produced at the step (a
 * type A network; -1 otherwise), the four linguistic outputs (type A) and the four
 * hidden-linguistic values (type B), empty where the network has none. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "trial_page.h"
#include "selftalk/integrated.h"
#include "selftalk/posteval.h"
#include "selftalk/trialkind.h"
#include "selftalk/trace.h"
#include "selftalk/trial.h"
#include "selftalk/world.h"

static const char *prog = "replay";

#define MAX_FORCE 32
#define MAX_AT 256
#define MAX_STEP 100000 /* far beyond any trial; keeps the step an int */

/* --force OUT=VALUE[@STEP] */
static stForce force_arg(const char *v) {
  stForce f = {0, 0.0, 0};
  char *end;
  long out = strtol(v, &end, 10);
  int ok = end != v && *end == '=';
  if (ok) {
    const char *s = end + 1;
    f.value = strtod(s, &end);
    ok = end != s;
  }
  long from = 0;
  if (ok && *end == '@') {
    const char *s = end + 1;
    from = strtol(s, &end, 10);
    ok = end != s;
  }
  if (!ok || *end)
    app_die(prog, "--force '%s': expected OUT=VALUE or OUT=VALUE@STEP (e.g. 9=1@20)", v);
  if (out < 0 || out > ST_NET_OUT_FOCUS)
    app_die(prog, "--force '%s': output %ld (expected 0..%d: the 12 DOF, then focus)", v, out,
            ST_NET_OUT_FOCUS);
  if (!(f.value >= 0.0 && f.value <= 1.0))
    app_die(prog, "--force '%s': value %g (expected 0..1)", v, f.value);
  if (from < 0 || from > MAX_STEP)
    app_die(prog, "--force '%s': step %ld (expected 0..%d)", v, from, MAX_STEP);
  f.output = (int)out;
  f.from_step = (int)from;
  return f;
}

/* --shapes FILE: the shapes of the chosen steps */
typedef struct shapesOut {
  FILE *f;
  const char *path;
  int every;           /* --shapes-every N (0: none) */
  int at[MAX_AT], nat; /* --at's step numbers */
  int last;            /* the trial's last step too */
  stShape *buf;        /* the shapes of the latest step traced */
  int n;               /* shapes per step */
  int buf_step;        /* the step in buf, -1 none */
  int written;         /* the last step written, -1 none */
  int nwritten;        /* steps written */
  int digits;
} shapesOut;

typedef struct traceCtx {
  stTraceCsv csv;    /* --out: csv.f NULL without it; csv.digits 9, or 17 with --exact */
  shapesOut *shapes; /* NULL without --shapes */
  trialPage *page;   /* NULL without --html */
  trialPageSummary sum; /* the trial's summary for the page (title and line below) */
  char title[1024], line[2048];
} traceCtx;

/* --at LIST: step numbers and "last", comma-separated */
static void at_arg(shapesOut *so, const char *v) {
  const char *s = v;
  for (;;) {
    char *end;
    if (!strncmp(s, "last", 4) && (s[4] == ',' || !s[4])) {
      so->last = 1;
      end = (char *)s + 4;
    } else {
      const long x = strtol(s, &end, 10);
      if (*s < '0' || *s > '9' || (*end && *end != ',') || x > MAX_STEP)
        app_die(prog, "--at '%s': expected step numbers 0..%d and 'last', comma-separated (e.g. "
                "0,40,last)", v, MAX_STEP);
      if (so->nat == MAX_AT) app_die(prog, "--at '%s': at most %d steps", v, MAX_AT);
      so->at[so->nat++] = (int)x;
    }
    if (!*end) return;
    s = end + 1;
  }
}

static void shapes_header(FILE *f) {
  fprintf(f, "step,kind,owner,type,sx,sy,sz,px,py,pz,r00,r01,r02,r10,r11,r12,r20,r21,r22\n");
}

/* the file and a buffer of a world's shapes (counted on a world of the protocol's robot) */
static shapesOut *shapes_open(shapesOut *so, const stProtocol *p, int digits) {
  char err[1024];
  stWorld *w = NULL;
  if (st_world_create(p->robot, &p->scene, &w, err, sizeof err)) app_die(prog, "%s", err);
  so->n = st_world_shapes(w, NULL, 0);
  st_world_destroy(w);
  so->buf = calloc((size_t)so->n, sizeof *so->buf);
  if (!so->buf) app_die(prog, "out of memory");
  so->digits = digits;
  if (!(so->f = fopen(so->path, "w"))) app_die(prog, "%s: cannot write", so->path);
  shapes_header(so->f);
  return so;
}

static int at_step(const shapesOut *so, int step) {
  if (so->every > 0 && step % so->every == 0) return 1;
  for (int i = 0; i < so->nat; i++)
    if (so->at[i] == step) return 1;
  return so->every == 0 && so->nat == 0 && !so->last; /* neither: every step */
}

/* the shapes in so->buf as rows of step so->buf_step */
static void shapes_write(shapesOut *so) {
  for (int i = 0; i < so->n; i++) {
    const stShape *sh = &so->buf[i];
    fprintf(so->f, "%d,%s,%s,%s", so->buf_step, st_shape_kind_name(sh->kind), sh->owner,
            st_geom_type_name(sh->type));
    const double *v[3] = {sh->size, sh->pos, sh->R};
    const int len[3] = {3, 3, 9};
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < len[k]; j++) fprintf(so->f, ",%.*g", so->digits, v[k][j] + 0.0);
    fputc('\n', so->f);
  }
  so->written = so->buf_step;
  so->nwritten++;
}

static void shapes_step(shapesOut *so, const stWorld *w, int step) {
  st_world_shapes(w, so->buf, so->n);
  so->buf_step = step;
  if (at_step(so, step)) shapes_write(so);
}

/* after the trial: the last step (--at last, --shapes-every), the steps --at asked for that the
 * trial did not reach (a warning), the file closed */
static void shapes_finish(shapesOut *so) {
  if ((so->last || so->every > 0) && so->buf_step >= 0 && so->written != so->buf_step)
    shapes_write(so);
  for (int i = 0; i < so->nat; i++)
    if (so->at[i] > so->buf_step)
      fprintf(stderr, "replay: --at %d: the trial ended at step %d (no shapes for it)\n",
              so->at[i], so->buf_step);
  if (fclose(so->f) != 0) app_die(prog, "%s: write error", so->path);
  free(so->buf);
  fprintf(stderr, "replay: %s: %d shapes at each of %d steps\n", so->path, so->n, so->nwritten);
}

static void on_step(void *ctx, const stTraceStep *s) {
  const traceCtx *c = ctx;
  if (c->shapes) shapes_step(c->shapes, s->world, s->step);
  if (c->page) trial_page_step(c->page, s, c->csv.arch);
  if (c->csv.f) st_trace_csv_row(&c->csv, s);
}

/* the page's title: what main put there (the genotype), then what the trial is */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void page_summary(traceCtx *c, const char *fmt, ...) {
  const size_t n = strlen(c->title);
  if (n + 2 >= sizeof c->title) return;
  strcpy(c->title + n, ": ");
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(c->title + n + 2, sizeof c->title - n - 2, fmt, ap);
  va_end(ap);
}

/* a primitive trial and its share of F_p (the primitive's N_p spans its trials: four, eight
 * with main-prim's hand-over trials); traced
 * into trace->csv.f when not NULL */
static void replay_primitive(const stProtocol *p, stStage stage, int generation, int index,
                             int trial, const stNetParams *np, const stNetParams *rollin,
                             const stForce *force, int nforce, traceCtx *trace) {
  stTrialSpec t;
  st_trial_spec(p, stage, generation, trial, &t);
  if (t.start_draws)
    fprintf(stderr, "replay: postures.vary_starts: the %s start drawn for generation %d (draw %d)\n",
            st_primitive_name(t.primitive), generation, t.start_draws);
  trace->csv.arch = np->arch;
  stWorkspace ws = {NULL, NULL, NULL};
  stTrialResult r;
  char err[1024];
  const uint64_t key = st_trial_seed_key(p, generation, index, trial);
  const stTraceFn fn = trace->csv.f || trace->shapes || trace->page ? on_step : NULL;
  /* the individual (its outputs forced), and with a roll-in the elite acting until the
   * hand-over */
  if (st_force_check(force, nforce, err, sizeof err)) app_die(prog, "%s", err);
  stNetController nc, rc;
  stRollinController roll;
  stController ctl = st_net_controller(&nc, np, force, nforce);
  if (rollin) {
    const stController individual = ctl, elite = st_net_controller(&rc, rollin, NULL, 0);
    if (st_rollin_controller(&roll, &elite, &individual, &ctl, err, sizeof err))
      app_die(prog, "--rollin: %s", err);
  }
  if (st_trial_run(p, &ws, &t, &ctl, key, &r, fn, trace, err, sizeof err)) app_die(prog, "%s", err);
  st_workspace_free(&ws);
  long n_p = 0; /* the primitive's trials, hand-over trials included */
  for (int i = 0; i < st_stage_trials(p, stage); i++) {
    stTrialSpec o;
    st_trial_spec(p, stage, generation, i, &o);
    if (o.primitive == t.primitive) n_p += o.steps;
  }
  const int handover = t.kind == ST_TRIAL_HANDOVER;
  if (handover)
    fprintf(stderr, "replay: hand-over trial: %s\n",
            r.handover_step >= 0           ? "handed over at the step below"
            : p->cfg.stage_handover_fallback ? "no hand-over: the fixed-posture fallback ran (the "
                                               "trace holds both)"
                                             : "no hand-over: the trial scores nothing");
  double share = (r.success ? p->fitness.bonus : 0.0) + p->fitness.scale / (double)n_p * (r.sum_s - r.sum_p);
  char ho[48] = "";
  if (handover) snprintf(ho, sizeof ho, " handover_step=%d", r.handover_step);
  snprintf(trace->line, sizeof trace->line, "trial %d %s %s k=%d success=%d steps=%ld/%d end=%s "
           "first_success_step=%d sum_S=%.6f sum_P=%.6f F_contribution=%.6f%s", trial,
           st_stage_name(stage), st_primitive_name(t.primitive), t.k, r.success, r.steps_run,
           t.steps, st_trial_end_name((stTrialEnd)r.end), r.success_step, r.sum_s, r.sum_p, share, ho);
  printf("%s\n", trace->line);
  page_summary(trace, "%s trial %d (%s, posture %d)", st_stage_name(stage), trial,
               st_primitive_name(t.primitive), t.k);
  trace->sum = (trialPageSummary){trace->title, trace->line, r.success, st_trial_end_name((stTrialEnd)r.end), 1,
                                  r.success ? p->fitness.bonus : 0.0, r.steps_run, t.steps};
}

/* an integrated trial: what it heard, how it ended, its bonus and points (eq. 2.14) and, for a
 * prediction trial, its prediction score (whether or not its object reached the target) */

/* integrated.fail_end other than penalty, appended to a trial's line (the default's line stays
 * as it was): with exact, end=failure before the last step is the exact early end (the object
 * out of reach for good, nothing left to change the result; sum_P then holds the object-moving
 * penalty every remaining step was certain to pay) */
static void fail_end_note(const stProtocol *p, char *ln, size_t lz) {
  const size_t n = strlen(ln);
  if (p->cfg.integrated_fail_end != ST_FAIL_END_PENALTY && n < lz)
    snprintf(ln + n, lz - n, " fail_end=%s",
             st_config_enum_name("integrated", "fail_end", p->cfg.integrated_fail_end));
}

static void replay_integrated(const stProtocol *p, int generation, int index, int trial,
                              const stNetParams *np, traceCtx *trace) {
  stIntegratedDef def;
  st_integrated_def_from_config(&p->cfg, &def);
  if (trial >= def.trials) app_die(prog, "--trial %d: expected 0..%d", trial, def.trials - 1);
  trace->csv.arch = np->arch;
  stWorkspace ws = {NULL, NULL, NULL};
  stIntPlan plan;
  stIntTrialResult r;
  stPredScore pred;
  char err[1024];
  const stTraceFn fn = trace->csv.f || trace->shapes || trace->page ? on_step : NULL;
  if (st_int_trial_run(p, &def, &ws, generation, index, trial, np, &plan, &r, &pred, fn, trace,
                       err, sizeof err))
    app_die(prog, "%s", err);
  st_workspace_free(&ws);
  const double bonus = st_int_trial_bonus(&r, p->fitness.bonus, plan.bonus_factor);
  char *ln = trace->line;
  const size_t lz = sizeof trace->line;
  const int n = snprintf(ln, lz, "trial %d integrated k=%d words=%s fitness=%s success=%d "
                         "steps=%ld/%ld end=%s reached_step=%d sum_S=%.17g sum_P=%.17g "
                         "focus_bonus=%d move_bonus=%d bonus=%.17g points=%.17g", trial,
                         st_int_trial_type(p, trial), st_word_source_name(plan.words),
                         st_int_fitness_name(plan.fitness), r.success, r.steps_run, r.steps,
                         st_trial_end_name((stTrialEnd)r.end), r.reached_step, r.sum_s, r.sum_p, r.focus_bonus, r.success,
                         bonus, st_int_trial_points(&r));
  if (plan.fitness == ST_FIT_PREDICTION && n > 0 && (size_t)n < lz)
    snprintf(ln + n, lz - (size_t)n, " reached=%d F_step=%.17g F_switch=%.17g B_pred=%.17g",
             r.reached_step >= 0, pred.f_step, pred.f_switch, pred.b_pred);
  fail_end_note(p, ln, lz);
  printf("%s\n", ln);
  page_summary(trace, "integrated trial %d (posture %d, words: %s)", trial, st_int_trial_type(p, trial),
               st_word_source_name(plan.words));
  trace->sum = (trialPageSummary){trace->title, ln, r.success, st_trial_end_name((stTrialEnd)r.end), 1, bonus,
                                  r.steps_run, r.steps};
}

/* trial K of a post-evaluation (posteval's numbering and streams) */
static void replay_posteval(const stProtocol *p, stPostTest test, int caretaker, int trial,
                            const stNetParams *np, traceCtx *trace) {
  stPostDef pd;
  stIntegratedDef idef;
  st_post_def_from_config(&p->cfg, test, &pd);
  st_integrated_def_from_config(&p->cfg, &idef);
  if (trial >= pd.trials) app_die(prog, "--trial %d: the %s test has trials 0..%d", trial,
                                  st_post_test_name(test), pd.trials - 1);
  char err[1024];
  stWordSource words;
  if (st_post_words(&idef, test, caretaker, &words, err, sizeof err)) app_die(prog, "%s", err);
  stPostTrial t;
  st_post_trial(&pd, &p->scene, trial, &t);
  trace->csv.arch = np->arch;
  stWorkspace ws = {NULL, NULL, NULL};
  stNetController nc;
  const stController ctl = st_net_controller(&nc, np, NULL, 0);
  stPostResult r;
  const stTraceFn fn = trace->csv.f || trace->shapes || trace->page ? on_step : NULL;
  if (st_post_run_trial(p, &idef, &ws, &t, &ctl, words, &r, fn, trace, err, sizeof err))
    app_die(prog, "%s", err);
  st_workspace_free(&ws);
  snprintf(trace->line, sizeof trace->line, "trial %d %s type=%d cell=%d posture=%d "
           "repetition=%d words=%s heard=%s success=%d reached_step=%d steps=%d/%d end=%s "
           "open_jumped=%d", trial, st_post_test_name(test), t.type, t.cell, t.posture,
           t.repetition, st_word_source_name(words), r.heard, r.success, r.reached_step,
           r.steps_run, t.steps, st_trial_end_name((stTrialEnd)r.end), r.open_jumped);
  fail_end_note(p, trace->line, sizeof trace->line);
  printf("%s\n", trace->line);
  page_summary(trace, "%s test trial %d (posture %d, words: %s)", st_post_test_name(test), trial,
               t.posture, st_word_source_name(words));
  /* a post-evaluation trial succeeds or not: it earns no bonus */
  trace->sum = (trialPageSummary){trace->title, trace->line, r.success, st_trial_end_name((stTrialEnd)r.end), 0, 0.0,
                                  r.steps_run, t.steps};
}

/* without --index: see the header comment */
static int pick_index(const stGenomeSet *set, const char *genome, int generation) {
  int history = set->count > 0 && set->generation[0] >= 0;
  for (int k = 1; history && k < set->count; k++) history = set->generation[k] > set->generation[k - 1];
  if (!history) return 0;
  if (generation < 0) return set->count - 1;
  for (int k = 0; k < set->count; k++)
    if (set->generation[k] == generation) return k;
  app_die(prog, "--generation %d: %s has no genotype of that generation (it has %d..%d); "
          "give --index to replay another generation's genotype with these offsets",
          generation, genome, set->generation[0], set->generation[set->count - 1]);
}

/* the trial indices a primitive config's stage has: "0..15, 16..27 (hand-over trials), ..." */
static const char *trial_ranges(const stConfig *cfg, stStage stage) {
  static char buf[256];
  size_t m = 0;
  for (int k = 0; k < ST_TRIAL_KIND_COUNT && m < sizeof buf; k++) {
    const stTrialKindDef *d = st_trial_kind_def((stTrialKind)k);
    if (!d->indexed || !st_trial_kind_count(cfg, stage, d->kind)) continue;
    const int first = st_trial_kind_first(d->kind);
    const int w = k == ST_TRIAL_FIXED
                      ? snprintf(buf + m, sizeof buf - m, "%d..%d", first, first + d->max - 1)
                      : snprintf(buf + m, sizeof buf - m, ", %d..%d (%s)", first,
                                 first + d->max - 1, d->title);
    m += w > 0 ? (size_t)w : 0;
  }
  return buf;
}

/* --rollin FILE: the elite that acts a hand-over trial's roll-in (see the header comment) */
static void read_rollin(const stProtocol *p, const char *file, int index, int index_last,
                        int generation, stNetParams *rollin) {
  char err[1024];
  stGenomeSet set;
  if (st_genome_set_read(file, st_arch_ngenes(ST_ARCH_BASE), &set, err, sizeof err))
    app_die(prog, "--rollin: %s (the elite is a base-network genotype)", err);
  if (index_last) index = set.count - 1;
  if (index >= set.count) app_die(prog, "--rollin-index %d: %s has %d genotypes", index, file, set.count);
  if (index < 0 && set.generation[0] >= 0 && generation == 0)
    app_die(prog, "--rollin %s: generation 0's elite is the initial population's first genotype, "
            "not a generation's best: give that file (or --rollin-index)", file);
  if (index < 0) index = pick_index(&set, file, generation - 1);
  fprintf(stderr, "replay: roll-in by genotype %d of %s (stage.handover_rollin = elite)\n", index,
          file);
  if (st_net_decode(&p->net, ST_ARCH_BASE, &set.genome[index], rollin, err, sizeof err))
    app_die(prog, "--rollin: %s", err);
  st_genome_set_free(&set);
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *genome = NULL, *out = NULL, *stage_name = NULL, *post_name = NULL, *html = NULL,
             *three = NULL, *rollin_file = NULL;
  int caretaker = 0, trial = -1, generation = -1, index = -1, index_last = 0, nforce = 0, digits = 9;
  int rollin_index = -1, rollin_last = 0;
  stForce force[MAX_FORCE];
  shapesOut so;
  memset(&so, 0, sizeof so);
  so.buf_step = so.written = -1;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    const char *a = argv[i];
    if (!strcmp(a, "--trial") && i + 1 < argc) trial = app_int_arg(prog, a, argv[++i], 0);
    else if (!strcmp(a, "--out") && i + 1 < argc) out = argv[++i];
    else if (!strcmp(a, "--force") && i + 1 < argc) {
      if (nforce == MAX_FORCE) app_die(prog, "--force: at most %d", MAX_FORCE);
      force[nforce++] = force_arg(argv[++i]);
    }
    else if (!strcmp(a, "--stage") && i + 1 < argc) stage_name = argv[++i];
    else if (!strcmp(a, "--posteval") && i + 1 < argc) post_name = argv[++i];
    else if (!strcmp(a, "--caretaker")) caretaker = 1;
    else if (!strcmp(a, "--shapes") && i + 1 < argc) so.path = argv[++i];
    else if (!strcmp(a, "--at") && i + 1 < argc) at_arg(&so, argv[++i]);
    else if (!strcmp(a, "--shapes-every") && i + 1 < argc) so.every = app_int_arg(prog, a, argv[++i], 1);
    else if (!strcmp(a, "--html") && i + 1 < argc) html = argv[++i];
    else if (!strcmp(a, "--three") && i + 1 < argc) three = argv[++i];
    else if (!strcmp(a, "--exact")) digits = 17;
    else if (!strcmp(a, "--generation") && i + 1 < argc) generation = app_int_arg(prog, a, argv[++i], 0);
    else if (!strcmp(a, "--index") && i + 1 < argc) {
      if (!strcmp(argv[++i], "last")) index_last = 1;
      else index = app_int_arg(prog, a, argv[i], 0);
    }
    else if (!strcmp(a, "--rollin") && i + 1 < argc) rollin_file = argv[++i];
    else if (!strcmp(a, "--rollin-index") && i + 1 < argc) {
      if (!strcmp(argv[++i], "last")) rollin_last = 1;
      else rollin_index = app_int_arg(prog, a, argv[i], 0);
    }
    else if (a[0] == '-' && a[1]) app_die(prog, "unknown or incomplete option '%s'", a);
    else if (!genome) genome = a;
    else if (!ca.config_path) ca.config_path = a;
    else app_die(prog, "unexpected argument '%s'", a);
  }
  if (!genome || !ca.config_path)
    app_die(prog, "usage: replay GENOME CONFIG --trial K [--out trace.csv] [--exact] "
                  "[--stage simple|main] [--generation G] [--index I] [--force OUT=VALUE[@STEP]]... "
                  "[--rollin FILE [--rollin-index I]] "
                  "[--posteval integration|robustness|generalisation [--caretaker]] "
                  "[--shapes FILE [--at STEP,...|last] [--shapes-every N]] [--html FILE [--three DIR]]");
  if (!so.path && (so.nat || so.last || so.every))
    app_die(prog, "--at and --shapes-every choose the steps of --shapes FILE: give --shapes");
  if (three && !html) app_die(prog, "--three DIR is where --html FILE finds three.js: give --html");
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  const int integrated = cfg.stage_stages == ST_STAGES_INTEGRATED;
  if (trial < 0) app_die(prog, "--trial K is required");
  const int post = post_name ? st_post_test_parse(post_name) : -1;
  if (post_name && post < 0)
    app_die(prog, "--posteval '%s': expected integration, robustness or generalisation", post_name);
  if (caretaker && (post < 0 || st_post_test_info((stPostTest)post)->variant != ST_POST_CARETAKER))
    app_die(prog, "--caretaker is the generalisation test's variant: give --posteval generalisation");
  if (post >= 0 && (stage_name || nforce))
    app_die(prog, "--posteval replays a post-evaluation trial: --stage and --force apply to primitive trials");
  if (integrated && (stage_name || nforce))
    app_die(prog, "%s is an integrated-stage config: --stage and --force apply to primitive trials",
            ca.config_path);
  stStage stage = cfg.stage_stages == ST_STAGES_MAIN ? ST_STAGE_MAIN : ST_STAGE_SIMPLE;
  if (post < 0 && !stage_name && cfg.stage_stages == ST_STAGES_PRIMS)
    app_die(prog, "%s runs simple-prim then main-prim: give --stage simple or --stage main",
            ca.config_path);
  if (stage_name) {
    if (!strcmp(stage_name, "simple")) stage = ST_STAGE_SIMPLE;
    else if (!strcmp(stage_name, "main")) stage = ST_STAGE_MAIN;
    else app_die(prog, "--stage '%s': expected simple or main", stage_name);
  }
  /* main-prim: the indexed kinds' trials after the 16 (selftalk/trialkind.h), where the config
   * has them */
  const int kind = trial >= 0 && trial < ST_MAIN_TRIALS_MAX ? (int)st_trial_kind(trial) : -1;
  if (post < 0 && !integrated && (kind < 0 || !st_trial_kind_count(&cfg, stage, (stTrialKind)kind)))
    app_die(prog, "--trial %d: expected %s", trial, trial_ranges(&cfg, stage));
  /* network.arch: an integrated-stage genotype (type A or B) replays primitive trials too */
  const stNetArch arch = (stNetArch)cfg.network_arch;
  char err[1024];
  stGenomeSet set;
  if (st_genome_set_read(genome, st_arch_ngenes(arch), &set, err, sizeof err))
    app_die(prog, "%s (network.arch = %s)", err, st_arch_name(arch));
  if (index_last) index = set.count - 1;
  if (index >= set.count) app_die(prog, "--index %d: %s has %d genotypes", index, genome, set.count);
  if (index < 0) index = pick_index(&set, genome, generation);
  if (generation < 0) generation = set.generation[index] >= 0 ? set.generation[index] : 0;
  if (post < 0 && !integrated && !st_trial_kind_runs(&cfg, stage, generation, (stTrialKind)kind))
    app_die(prog, "--trial %d: generation %d runs no %s (its open and grasp trials start from the "
            "drawn postures instead: postures.vary_replace_generations = %d); expected "
            "--generation %d or later", trial, generation, st_trial_kind_def((stTrialKind)kind)->title,
            cfg.postures_vary_replace_generations, cfg.postures_vary_replace_generations);
  fprintf(stderr, "replay: genotype %d of %s, trial offsets of generation %d\n", index, genome,
          generation);
  stProtocol *p = NULL;
  if (st_protocol_create(&cfg, &p, err, sizeof err)) app_die(prog, "%s", err);
  /* stage.handover_rollin = elite: a hand-over trial's roll-in is the elite's */
  const int elite_rollin = post < 0 && !integrated && st_stage_rollin_elite(p, stage) &&
                           kind == ST_TRIAL_HANDOVER;
  if (elite_rollin && !rollin_file)
    app_die(prog, "%s rolls hand-over trials in with the generation's elite (stage.handover_rollin "
            "= elite): give it with --rollin FILE (e.g. the run's best.genome: generation G - 1's "
            "best; or generation G's checkpoint, or at generation 0 the initial population: its "
            "genotype 0)", ca.config_path);
  if (!elite_rollin && (rollin_file || rollin_index >= 0 || rollin_last))
    app_die(prog, "--rollin names who rolls a hand-over trial in under stage.handover_rollin = "
            "elite: give a main-prim hand-over trial (%d..%d) of such a config",
            st_trial_kind_first(ST_TRIAL_HANDOVER),
            st_trial_kind_first(ST_TRIAL_HANDOVER) + ST_TRIAL_MAX_HANDOVER - 1);
  stNetParams np;
  if (st_net_decode(&p->net, arch, &set.genome[index], &np, err, sizeof err)) app_die(prog, "%s", err);
  st_genome_set_free(&set);
  stNetParams rollin;
  if (elite_rollin) read_rollin(p, rollin_file, rollin_index, rollin_last, generation, &rollin);
  static traceCtx trace; /* static: its summary buffers are large */
  trace.csv.arch = arch;
  trace.csv.digits = digits;
  if (out && !(trace.csv.f = fopen(out, "w"))) app_die(prog, "%s: cannot write", out);
  if (trace.csv.f) st_trace_csv_header(&trace.csv);
  if (so.path) trace.shapes = shapes_open(&so, p, digits);
  if (html) {
    trace.page = trial_page_open(prog, html, three, p);
    snprintf(trace.title, sizeof trace.title, "%s genotype %d", genome, index);
  }
  if (post >= 0) replay_posteval(p, (stPostTest)post, caretaker, trial, &np, &trace);
  else if (integrated) replay_integrated(p, generation, index, trial, &np, &trace);
  else replay_primitive(p, stage, generation, index, trial, &np, elite_rollin ? &rollin : NULL,
                        force, nforce, &trace);
  if (trace.csv.f && fclose(trace.csv.f) != 0) app_die(prog, "%s: write error", out);
  if (trace.shapes) shapes_finish(trace.shapes);
  if (trace.page) trial_page_finish(trace.page, &trace.sum);
  st_protocol_destroy(p);
  return 0;
}
