/* SPDX-License-Identifier: MIT
 * The journal of an unfinished post-evaluation (journal.h). One line per trial done, in unit
 * order; every field an integer except the words heard, so the resumed files are the same. */
#include "posteval/journal.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/io.h"

#define MAGIC "# selftalk posteval journal 1"
#define COLUMNS "unit,success,reached_step,steps_run,end,unstable,open_jumped,heard"
#define LINE_MAX_LEN 256
#define STEP_MAX 1000000 /* far beyond any trial length */

/* ---- fingerprint (FNV-1a, 64 bit) ---- */

static uint64_t fnv(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

static uint64_t fnv_int(uint64_t h, long v) {
  char buf[32];
  return fnv(h, buf, (size_t)snprintf(buf, sizeof buf, "%ld;", v));
}

static uint64_t fnv_str(uint64_t h, const char *s) { return fnv(h, s, strlen(s) + 1); }

/* the configuration: its keys that differ from their defaults, each as config.ini writes it
 * ("[section]" and "name = value"). Not the comments, the version line or keys at their
 * defaults: a new key, a reworded description or a new release leave a half-done test
 * resumable (what the library's code does is not fingerprinted, here as in evolve's resume) */
static uint64_t fnv_config(uint64_t h, const stConfig *cfg) {
  stConfig def;
  st_config_default(&def);
  char text[ST_CONFIG_STR_MAX + 160], value[ST_CONFIG_STR_MAX + 32];
  for (int i = 0; i < st_config_nkeys(); i++) {
    if (!st_config_key_differs(cfg, &def, i)) continue;
    const stConfigKey *k = st_config_key(i);
    st_config_format(cfg, i, value, sizeof value);
    snprintf(text, sizeof text, "[%s]\n", k->section);
    h = fnv_str(h, text);
    snprintf(text, sizeof text, "%s = %s\n", k->name, value);
    h = fnv_str(h, text);
  }
  return h;
}

/* 8 bytes, least significant first: the same fingerprint on any byte order */
static uint64_t fnv_u64(uint64_t h, uint64_t v) {
  unsigned char b[8];
  for (int i = 0; i < 8; i++) b[i] = (unsigned char)(v >> (8 * i));
  return fnv(h, b, sizeof b);
}

static uint64_t fnv_reals(uint64_t h, const double *v, size_t n) {
  for (size_t i = 0; i < n; i++) {
    uint64_t bits;
    memcpy(&bits, &v[i], sizeof bits);
    h = fnv_u64(h, bits);
  }
  return h;
}

static uint64_t fnv_ints(uint64_t h, const int *v, size_t n) {
  for (size_t i = 0; i < n; i++) h = fnv_u64(h, (uint64_t)(int64_t)v[i]);
  return h;
}

/* the robot model: everything the importer took from the URDF and its meshes (issue 48: a
 * URDF changed in place, under the same robot.urdf, made another test's journal resumable).
 * What the file holds that the model does not (comments, visual elements) changes no result */
static uint64_t fnv_model(uint64_t h, const stModel *m) {
  const size_t nb = (size_t)m->nbody, ng = (size_t)m->ngeom;
  h = fnv_ints(h, (const int[]){m->nbody, m->ngeom, m->nvert, m->ntri}, 4);
  for (size_t b = 0; b < nb; b++) h = fnv_str(fnv_str(h, m->body_name[b]), m->jnt_name[b]);
  h = fnv_ints(h, m->body_parent, nb);
  h = fnv_reals(h, m->body_mass, nb);
  h = fnv_reals(h, m->body_com[0], 3 * nb);
  h = fnv_reals(h, m->body_inertia[0], 9 * nb);
  h = fnv_ints(h, m->jnt_type, nb);
  h = fnv_reals(h, m->jnt_pos[0], 3 * nb);
  h = fnv_reals(h, m->jnt_rot[0], 9 * nb);
  h = fnv_reals(h, m->jnt_axis[0], 3 * nb);
  h = fnv_reals(h, m->jnt_range[0], 2 * nb);
  h = fnv_reals(h, m->jnt_effort, nb);
  h = fnv_reals(h, m->jnt_velocity, nb);
  h = fnv_ints(h, m->jnt_mimic, nb);
  h = fnv_reals(h, m->jnt_mimic_mult, nb);
  h = fnv_reals(h, m->jnt_mimic_offset, nb);
  h = fnv_ints(h, m->geom_body, ng);
  h = fnv_ints(h, m->geom_type, ng);
  h = fnv_reals(h, m->geom_size[0], 3 * ng);
  h = fnv_reals(h, m->geom_pos[0], 3 * ng);
  h = fnv_reals(h, m->geom_rot[0], 9 * ng);
  h = fnv_ints(h, m->geom_vert0, ng);
  h = fnv_ints(h, m->geom_nvert, ng);
  h = fnv_ints(h, m->geom_tri0, ng);
  h = fnv_ints(h, m->geom_ntri, ng);
  if (m->nvert) h = fnv_reals(h, m->mesh_vert[0], 3 * (size_t)m->nvert);
  if (m->ntri) h = fnv_ints(h, m->mesh_tri[0], 3 * (size_t)m->ntri);
  return h;
}

uint64_t st__post_fingerprint(const stConfig *cfg, const stModel *model, stPostTest test,
                              int variant, const char *condition, const stPostIndividual *ind,
                              int nind) {
  uint64_t h = 14695981039346656037ull;
  h = fnv_config(h, cfg);
  if (model) h = fnv_model(h, model);
  h = fnv_int(h, test);
  h = fnv_int(h, variant);
  h = fnv_str(h, condition);
  h = fnv_int(h, nind);
  for (int i = 0; i < nind; i++) {
    const stPostIndividual *d = &ind[i];
    h = fnv_int(h, d->run);
    h = fnv_str(h, d->run_label);
    h = fnv_int(h, d->rank);
    h = fnv_int(h, d->generation);
    h = fnv_int(h, d->excluded);
    h = fnv_int(h, d->genome.ngenes);
    for (int g = 0; g < d->genome.ngenes; g++) h = fnv_int(h, d->genome.gene[g]);
  }
  return h;
}

/* ---- writing ---- */

stStatus st__post_journal_write(const char *path, uint64_t fingerprint, long units,
                                const uint8_t *done, const stPostResult *res, char *err,
                                size_t errsz) {
  stAtomicFile af;
  stStatus st = st_atomic_open(&af, path, err, errsz);
  if (st) return st;
  int rc = fprintf(af.f, MAGIC "\n# fingerprint %016" PRIx64 "\n# units %ld\n" COLUMNS "\n",
                   fingerprint, units) < 0;
  for (long u = 0; u < units && !rc; u++) {
    if (!done[u]) continue;
    const stPostResult *r = &res[u];
    rc = fprintf(af.f, "%ld,%d,%d,%d,%d,%d,%d,%s\n", u, r->success, r->reached_step, r->steps_run,
                 (int)r->end, r->unstable, r->open_jumped, r->heard) < 0;
  }
  if (rc) {
    st_atomic_abort(&af);
    return st__errf(err, errsz, "%s: cannot write", path), ST_ERR_IO;
  }
  return st_atomic_commit(&af, err, errsz);
}

/* ---- reading ---- */

/* an integer field in [lo, hi], ended by ',' (advances *s past it) */
static int field(const char **s, long lo, long hi, long *v) {
  char *end;
  const char *p = *s;
  if (!((*p >= '0' && *p <= '9') || *p == '-')) return 0;
  long x = strtol(p, &end, 10);
  if (end == p || *end != ',' || x < lo || x > hi) return 0;
  *v = x;
  *s = end + 1;
  return 1;
}

/* the words heard: letters r, o, g, m (no repeat in a row), at most ST_POST_HEARD_MAX, then
 * an optional '+' */
static int heard_ok(const char *h) {
  size_t n = strlen(h);
  if (n > 0 && h[n - 1] == '+') n--;
  if (n > ST_POST_HEARD_MAX || (h[n] == '+' && n < ST_POST_HEARD_MAX)) return 0;
  for (size_t i = 0; i < n; i++)
    if (!h[i] || !strchr("rogm", h[i]) || (i > 0 && h[i] == h[i - 1])) return 0;
  return 1;
}

/* one trial line of a trial of `steps` steps into res[u]; NULL, or what is wrong with it. A
 * line must be one posteval writes (st_post_run_trial): the fields in their ranges, and
 * together what a trial can give. */
static const char *parse_line(const char *line, long units, int steps, long *unit,
                              stPostResult *r) {
  const char *s = line;
  long u, v[6];
  static const long lo[6] = {0, -1, 1, 0, 0, 0}, hi[6] = {1, STEP_MAX, STEP_MAX, 3, 1, 1};
  if (!field(&s, 0, units - 1, &u)) return "not a trial line";
  for (int i = 0; i < 6; i++)
    if (!field(&s, lo[i], hi[i], &v[i])) return "not a trial line";
  if (strlen(s) > ST_POST_HEARD_MAX + 1 || !heard_ok(s)) return "not a trial line";
  const long success = v[0], reached = v[1], run = v[2], end = v[3], unstable = v[4];
  if (end != ST_END_FULL && end != ST_END_SUCCESS && end != ST_END_FAILURE)
    return "an end posteval never writes (expected 0 full, 1 success or 2 failure)";
  if (run > steps) return "more steps run than the trial has";
  /* a success has its step, ended the trial there (its last step), and ended so */
  if ((success == 1) != (reached >= 0) || (success == 1) != (end == ST_END_SUCCESS) ||
      (reached >= 0 && reached != run - 1))
    return "success, reached_step, steps_run and end disagree (expected success 1 with "
           "end 1 and reached_step = steps_run - 1, or success 0 with reached_step -1)";
  if (end == ST_END_FULL && run != steps)
    return "end full before the trial's last step (expected steps_run = the trial's length)";
  /* the simulation giving up ends a trial as a failure (or on the step it succeeded) */
  if (unstable && end == ST_END_FULL) return "unstable with end full (expected end 2 failure)";
  if (v[5] != st__post_open_jumped(s))
    return "open_jumped disagrees with the words heard (expected 1 exactly when grasp or move "
           "was heard but never open)";
  memset(r, 0, sizeof *r);
  r->success = (int)success;
  r->reached_step = (int)reached;
  r->steps_run = (int)run;
  r->end = (stTrialEnd)end;
  r->unstable = (int)unstable;
  r->open_jumped = (int)v[5];
  strcpy(r->heard, s);
  *unit = u;
  return NULL;
}

/* the journal's text (read whole through the bounded reader), line by line */
typedef struct jtext {
  const char *p, *end;
} jtext;

/* a line without its newline into buf; 0 at the end, -1 when too long or without newline */
static int get_line(jtext *t, char *buf, size_t n) {
  buf[0] = 0;
  const char *line;
  size_t len;
  int newline;
  if (!st__text_line(&t->p, t->end, &line, &len, &newline)) return 0;
  if (!newline || len + 1 >= n) return -1;
  memcpy(buf, line, len);
  buf[len] = 0;
  return 1;
}

static stStatus header(jtext *f, const char *path, uint64_t fingerprint, long units, char *err,
                       size_t errsz) {
  char line[LINE_MAX_LEN], want[64];
  if (get_line(f, line, sizeof line) != 1 || strcmp(line, MAGIC))
    return st__errf(err, errsz, "%s:1: not a posteval journal (expected '" MAGIC "')", path),
           ST_ERR_PARSE;
  snprintf(want, sizeof want, "# fingerprint %016" PRIx64, fingerprint);
  if (get_line(f, line, sizeof line) != 1 || strcmp(line, want))
    return st__errf(err, errsz, "%s:2: '%s' belongs to another test: the configuration, the "
                    "inputs or the condition changed (expected '%s'; remove the journal to "
                    "start again)", path, line, want), ST_ERR_ARG;
  snprintf(want, sizeof want, "# units %ld", units);
  if (get_line(f, line, sizeof line) != 1 || strcmp(line, want))
    return st__errf(err, errsz, "%s:3: '%s' (expected '%s')", path, line, want), ST_ERR_PARSE;
  if (get_line(f, line, sizeof line) != 1 || strcmp(line, COLUMNS))
    return st__errf(err, errsz, "%s:4: expected the columns '" COLUMNS "'", path), ST_ERR_PARSE;
  return ST_OK;
}

stStatus st__post_journal_parse(const char *path, const char *text, size_t len,
                                uint64_t fingerprint, long units, int steps, uint8_t *done,
                                stPostResult *res, long *ndone, char *err, size_t errsz) {
  memset(done, 0, (size_t)units);
  memset(res, 0, (size_t)units * sizeof *res);
  *ndone = 0;
  stStatus st = st_text_check(path, text, len, err, errsz);
  if (st) return st;
  jtext f = {text, text + len};
  st = header(&f, path, fingerprint, units, err, errsz);
  char line[LINE_MAX_LEN];
  int rc;
  for (long n = 5; !st && (rc = get_line(&f, line, sizeof line)) != 0; n++) {
    long u;
    stPostResult r;
    const char *why = rc < 0 ? "not a trial line" : parse_line(line, units, steps, &u, &r);
    if (why)
      st = (st__errf(err, errsz, "%s:%ld: %s (expected %s with unit 0..%ld, success 0/1, its "
                     "step, the steps run 1..%d, end 0/1/2, unstable 0/1, open_jumped 0/1, the "
                     "words heard)", path, n, why, COLUMNS, units - 1, steps), ST_ERR_PARSE);
    else if (done[u])
      st = (st__errf(err, errsz, "%s:%ld: unit %ld twice", path, n, u), ST_ERR_PARSE);
    else {
      done[u] = 1;
      res[u] = r;
      (*ndone)++;
    }
  }
  return st;
}

stStatus st__post_journal_read(const char *path, uint64_t fingerprint, long units, int steps,
                               uint8_t *done, stPostResult *res, long *ndone, char *err,
                               size_t errsz) {
  memset(done, 0, (size_t)units);
  memset(res, 0, (size_t)units * sizeof *res);
  *ndone = 0;
  /* through the bounded reader (selftalk/io.h), at most what a journal of `units` can hold
   * (4 header lines and a line per unit), NUL bytes refused */
  const size_t lines = (size_t)units + 4;
  const size_t max = lines > ST_FILE_MAX / LINE_MAX_LEN ? ST_FILE_MAX : lines * LINE_MAX_LEN;
  char *text;
  size_t len;
  stStatus st = st_text_read(path, max, &text, &len, err, errsz);
  if (st) return st;
  st = st__post_journal_parse(path, text, len, fingerprint, units, steps, done, res, ndone, err,
                              errsz);
  free(text);
  return st;
}
