/* SPDX-License-Identifier: MIT
 * The table of trial kinds (selftalk/trialkind.h): its rows, one per file in
 * lib/episode/trials/, and what goes through all of them. */
#include "selftalk/trialkind.h"

#include <string.h>

#include "core/internal.h"
#include "episode/trials/trials.h"

static const stTrialKindDef *const g_kinds[ST_TRIAL_KIND_COUNT] = {
#define ST__TRIAL_KIND_ROW(E, name, max, indexed) &st__trial_##name,
    ST_TRIAL_KINDS(ST__TRIAL_KIND_ROW)
#undef ST__TRIAL_KIND_ROW
};

/* every kind's trials fit its results and columns */
#define ST__TRIAL_KIND_FITS(E, name, max, indexed) &&(max) <= ST_TRIAL_KIND_MAX
typedef char st__trial_kinds_fit[(1 ST_TRIAL_KINDS(ST__TRIAL_KIND_FITS)) ? 1 : -1];
#undef ST__TRIAL_KIND_FITS

const stTrialKindDef *st_trial_kind_def(stTrialKind k) {
  ST_ASSERT((int)k >= 0 && k < ST_TRIAL_KIND_COUNT);
  return g_kinds[k];
}

int st_trial_kind_first(stTrialKind k) {
  ST_ASSERT((int)k >= 0 && k < ST_TRIAL_KIND_COUNT);
  int first = 0;
  for (int i = 0; i < (int)k; i++) first += g_kinds[i]->indexed ? g_kinds[i]->max : 0;
  return first;
}

stTrialKind st_trial_kind(int index) {
  ST_ASSERT(index >= 0 && index < ST_MAIN_TRIALS_MAX);
  int k = 0;
  for (int first = 0;; k++) {
    if (!g_kinds[k]->indexed) continue;
    if (index < first + g_kinds[k]->max) break;
    first += g_kinds[k]->max;
  }
  return (stTrialKind)k;
}

int st_trial_kind_count(const stConfig *cfg, stStage stage, stTrialKind k) {
  ST_ASSERT(cfg);
  ST_ASSERT(stage == ST_STAGE_SIMPLE || stage == ST_STAGE_MAIN);
  return st_trial_kind_def(k)->count(cfg, stage);
}

int st_trial_kind_runs(const stConfig *cfg, stStage stage, int generation, stTrialKind k) {
  ST_ASSERT(generation >= 0);
  const stTrialKindDef *d = st_trial_kind_def(k);
  return d->count(cfg, stage) > 0 && (!d->active || d->active(cfg, generation));
}

/* ---- the kinds' keys ---- */

int st__switched_family(const stConfig *c, int on, const char *family, const char *what,
                        const char *switch_key, const char *off, const char *on_value, char *msg,
                        size_t n) {
  if (on) return -1;
  const size_t ns = strcspn(family, ".");
  const char *prefix = family + ns + 1;
  stConfig d;
  st_config_default(&d);
  for (int i = 0; i < st_config_nkeys(); i++) {
    const stConfigKey *k = st_config_key(i);
    if (strlen(k->section) != ns || strncmp(k->section, family, ns) ||
        strncmp(k->name, prefix, strlen(prefix)) || !st_config_key_differs(c, &d, i))
      continue;
    snprintf(msg, n, "it shapes %s, which %s = %s turns off (expected %s %s, or the key left out)",
             what, switch_key, off, switch_key, on_value);
    return i;
  }
  return -1;
}

/* a kind's family, refused while its switch key is at its default: "false" and "= true" for a
 * switch, "0" and "> 0" for a count */
static int family_rule(const stTrialKindDef *d, const stConfig *c, char *msg, size_t n) {
  if (!d->family) return -1;
  const size_t ns = strcspn(d->switch_key, ".");
  char section[64];
  snprintf(section, sizeof section, "%.*s", (int)ns, d->switch_key);
  const int sw = st_config_find(section, d->switch_key + ns + 1);
  ST_ASSERT(sw >= 0);
  stConfig def;
  st_config_default(&def);
  const int is_bool = st_config_key(sw)->type == ST_CFG_BOOL;
  return st__switched_family(c, st_config_key_differs(c, &def, sw), d->family, d->shapes,
                             d->switch_key, is_bool ? "false" : "0", is_bool ? "= true" : "> 0",
                             msg, n);
}

stStatus st_trial_kinds_check(const stConfig *cfg, const char *path, char *err, size_t errsz) {
  ST_ASSERT(cfg);
  char msg[512];
  for (int k = 0; k < ST_TRIAL_KIND_COUNT; k++) {
    const stTrialKindDef *d = g_kinds[k];
    int key = family_rule(d, cfg, msg, sizeof msg);
    if (key < 0 && d->check) key = d->check(cfg, msg, sizeof msg);
    if (key < 0) continue;
    const stConfigKey *ck = st_config_key(key);
    const int line = path ? st_config_key_line(path, key) : 0;
    if (line > 0)
      st__errf(err, errsz, "%s:%d: key '%s.%s': %s", path, line, ck->section, ck->name, msg);
    else
      st__errf(err, errsz, "key '%s.%s': %s", ck->section, ck->name, msg);
    return ST_ERR_RANGE;
  }
  return ST_OK;
}
