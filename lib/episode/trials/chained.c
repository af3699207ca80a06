/* SPDX-License-Identifier: MIT
 * The chained trials (selftalk/trialkind.h; stage.chain_trials, SPEC 12, docs/PROTOCOL.md
 * "Hand-over trials and chained trials"; not the thesis's): main-prim runs the integrated
 * stage's trials with the caretaker's words (st_chain_def_from_config), scored by eq. 2.14 plus
 * stage.chain_progress times how far the caretaker got; that F_chain joins the fitness as a term
 * of the harmonic mean or, weighted, added to it (stage.chain_combine). They count among the
 * trials that completing the stage needs solved. */
#include <math.h>

#include "core/internal.h"
#include "episode/trials/trials.h"
#include "selftalk/integrated.h"

static int chained_count(const stConfig *cfg, stStage stage) {
  return stage == ST_STAGE_MAIN ? cfg->stage_chain_trials : 0;
}

static stStatus chained_evaluate(const stProtocol *p, stWorkspace *ws, int generation,
                                 int individual, const stNetParams *net, stKindEvaluation *r,
                                 char *err, size_t errsz) {
  stIntegratedDef def;
  st_chain_def_from_config(&p->cfg, &def);
  stIntEvaluation ie;
  stStatus st = st_int_evaluate(p, &def, ws, generation, individual, net, &ie, err, errsz);
  if (st) return st;
  r->fitness = ie.fitness + p->cfg.stage_chain_progress * ie.progress;
  r->trials = ie.ntrials;
  r->successes = ie.successes;
  r->unstable = ie.unstable;
  for (int i = 0; i < ie.ntrials; i++) r->success[i] = ie.success[i];
  return ST_OK;
}

/* stage.chain_combine = sum: F_chain's weight, (fixed trials solved / fixed trials)^chain_gate,
 * so that a chain bought with a fixed trial costs more than it earns (chain_gate 0: 1) */
static double chain_weight(const stProtocol *p, const stEvaluation *e) {
  int fixed = 0, solved = 0;
  for (int k = 0; k < ST_NPRIM; k++) fixed += (p->primitives >> k & 1u) ? ST_NPOSTURE : 0;
  for (int i = 0; i < ST_PRIM_TRIALS; i++) solved += e->kind[ST_TRIAL_FIXED].success[i];
  return fixed ? pow((double)solved / fixed, p->cfg.stage_chain_gate) : 1.0;
}

static void chained_fitness(const stProtocol *p, const stEvaluation *e, double *terms, int *n,
                            double *added) {
  const double f_chain = e->kind[ST_TRIAL_CHAINED].fitness;
  if (p->cfg.stage_chain_combine == ST_CHAIN_HARMONIC) terms[(*n)++] = f_chain;
  else *added += chain_weight(p, e) * f_chain;
}

static int chained_note(const stEvaluation *e, char *buf, size_t n) {
  const stKindEvaluation *r = &e->kind[ST_TRIAL_CHAINED];
  return r->trials ? snprintf(buf, n, " (chained %d/%d, F_chain %.1f)", r->successes, r->trials,
                              r->fitness)
                   : 0;
}

/* chain_gate weighs the summed F_chain only; fixed_chained counts only genotypes solving the 16
 * from their fixed starts */
static int chained_check(const stConfig *c, char *msg, size_t n) {
  int k = st__switched_family(c, c->stage_chain_combine == ST_CHAIN_SUM, "stage.chain_gate",
                              "the summed F_chain", "stage.chain_combine", "harmonic", "= sum",
                              msg, n);
  if (k >= 0) return k;
  if (c->postures_vary_starts && c->postures_vary_trials == ST_VARY_REPLACE &&
      c->stage_chain_trials > 0 && c->stage_chain_complete == ST_CHAIN_COMPLETE_FIXED_CHAINED) {
    snprintf(msg, n, "fixed_chained completes a genotype only when it solves the 16 from their "
             "fixed starts, and postures.vary_trials = replace draws open's and grasp's in every "
             "generation, so the stage could never complete (expected postures.vary_trials = "
             "extra, or stage.chain_complete = all)");
    return st_config_find("stage", "chain_complete");
  }
  return -1;
}

/* the row: what it is and its keys; its fitness.csv columns; its streams; its hooks */
const stTrialKindDef st__trial_chained = {
    ST__TRIAL_KIND(CHAINED, chained), .title = "chained trials",
    .switch_key = "stage.chain_trials", .family = "stage.chain_", .shapes = "the chained trials",
    .column = ST_CSV_COL_REAL(stKindEvaluation, fitness, "best_F_chain"),
    .trial_column = "best_c%d",
    .offsets = ST_RNG_INTEGRATED, .solver = ST_RNG_SOLVER,
    .count = chained_count, .evaluate = chained_evaluate, .fitness = chained_fitness,
    .note = chained_note, .check = chained_check,
};
