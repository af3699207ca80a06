/* SPDX-License-Identifier: MIT
 * replay --html (trial_page.h): the trial's shapes and trace as compact JSON inside the page
 * template, with three.js inlined. The data's layout is docs/PROTOCOL.md's "Trial pages"; the
 * page's script (tools/trial_page.html) is its only reader. */
#include "trial_page.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/fitness.h"
#include "selftalk/io.h"
#include "selftalk/world.h"

/* tools/trial_page.html as bytes (the Makefile writes the .inc with od): compiled in, so an
 * installed replay needs no data file of its own */
static const unsigned char TEMPLATE[] = {
#include "trial_page.inc"
    0};

/* fixed-point units of the data: positions and distances in 0.1 mm, unit quaternions and
 * S, P in 1e-4, linguistic values in 1e-3 (far below what a picture or a bar shows) */
#define POS_SCALE 1e4
#define QUAT_SCALE 1e4
#define VAL_SCALE 1e3
#define MAX_FIXED 1e9 /* larger magnitudes (a diverged simulation) are clamped */
#define POSE_N 7      /* x, y, z, qx, qy, qz, qw */

typedef struct stepRec {
  int heard, word, label, source, event, touching, lifted;
  int touch; /* bit i: touch sensor i */
  long d_r, d_g, d_m, S, P;
  long ling[ST_NET_NLING];
} stepRec;

struct trialPage {
  const char *prog, *path;
  char three_dir[1024];
  char *three, *orbit; /* the two three.js files, NUL-terminated */
  char revision[16];
  char touch_links[ST_CONFIG_STR_MAX]; /* the touch sensors' links, comma-separated */
  double dt;
  int n;               /* shapes per step */
  stShape *buf;
  char (*owner)[64];   /* the shapes' owners, kinds, types and sizes: those of step 0 */
  int *kind, *type;
  double (*size)[3];
  long *pose;          /* steps x n x POSE_N */
  stepRec *rec;
  long steps, cap;
  int ling;            /* 0 none, 1 type A's linguistic outputs, 2 type B's hidden-linguistic */
  long clamped;        /* non-finite or huge values clamped */
};

/* ---- a growable text buffer -------------------------------------------------------------- */

typedef struct sbuf {
  char *s;
  size_t len, cap;
  const char *prog;
} sbuf;

static void sb_grow(sbuf *b, size_t more) {
  if (b->len + more + 1 <= b->cap) return;
  size_t cap = b->cap ? b->cap : 4096;
  while (cap < b->len + more + 1) cap *= 2;
  char *s = realloc(b->s, cap);
  if (!s) app_die(b->prog, "out of memory");
  b->s = s;
  b->cap = cap;
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void sb_printf(sbuf *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) app_die(b->prog, "cannot format the page");
  sb_grow(b, (size_t)n);
  va_start(ap, fmt);
  vsnprintf(b->s + b->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  b->len += (size_t)n;
}

static void sb_put(sbuf *b, const char *s, size_t n) {
  sb_grow(b, n);
  memcpy(b->s + b->len, s, n);
  b->len += n;
  b->s[b->len] = 0;
}

static void sb_append(sbuf *b, const char *s) { sb_put(b, s, strlen(s)); }

/* The one place where text from outside (link names, paths, the genotype's file name) enters
 * the page, escaped for where it lands: a browser must never read it as markup or code.
 *  - PAGE_HTML: element text or an attribute value (&, <, >, ", ' as entities);
 *  - PAGE_JSON: a JSON string in the data's <script> element (<, > and & as \u escapes, so no
 *    data can end the element; the page's script puts it in the page as text, never as markup);
 *  - PAGE_COMMENT: inside a JavaScript comment in a <script> element: every byte but a few
 *    plain ones %-escaped, so neither "* /" nor "</script" nor "<!--" can occur.
 * Non-ASCII bytes become '?' (HTML, JSON) or %XX (comment), control bytes '?', \u escapes or %XX:
 * the page is ASCII, and the checksum the page recomputes over the data reads it as written. */
typedef enum pageContext { PAGE_HTML, PAGE_JSON, PAGE_COMMENT } pageContext;

static void sb_escaped(sbuf *b, pageContext ctx, const char *s) {
  if (ctx == PAGE_JSON) sb_printf(b, "\"");
  for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
    const int plain = *c >= 0x20 && *c < 0x7f;
    if (ctx == PAGE_COMMENT) {
      if (isalnum(*c) || (*c && strchr(" ._/+,:=@~-", *c))) sb_printf(b, "%c", *c);
      else sb_printf(b, "%%%02X", *c);
    } else if (ctx == PAGE_HTML) {
      if (*c == '&') sb_printf(b, "&amp;");
      else if (*c == '<') sb_printf(b, "&lt;");
      else if (*c == '>') sb_printf(b, "&gt;");
      else if (*c == '"') sb_printf(b, "&quot;");
      else if (*c == '\'') sb_printf(b, "&#39;");
      else sb_printf(b, "%c", plain ? *c : '?');
    } else {
      if (*c == '"' || *c == '\\') sb_printf(b, "\\%c", *c);
      else if (*c < 0x20 || *c == '<' || *c == '>' || *c == '&') sb_printf(b, "\\u%04x", *c);
      else sb_printf(b, "%c", *c < 0x80 ? *c : '?');
    }
  }
  if (ctx == PAGE_JSON) sb_printf(b, "\"");
}

static void sb_json(sbuf *b, const char *s) { sb_escaped(b, PAGE_JSON, s); }

/* ---- reading three.js ------------------------------------------------------------------ */

/* where text inlined in a <script> element would end it early ("</script", in any case, as the
 * HTML parser reads it) or switch the parser into its escaped states ("<!--"); NULL: nowhere */
static const char *script_breaker(const char *text) {
  for (const char *c = text; *c; c++) {
    if (*c != '<') continue;
    if (!strncmp(c, "<!--", 4)) return c;
    if (c[1] != '/') continue;
    int k = 0;
    while (k < 6 && c[2 + k] && tolower((unsigned char)c[2 + k]) == "script"[k]) k++;
    if (k == 6) return c;
  }
  return NULL;
}

static char *read_lib(trialPage *pg, const char *rel) {
  char path[1100], err[1024];
  snprintf(path, sizeof path, "%s/%s", pg->three_dir, rel);
  char *text;
  size_t len;
  if (st_text_read(path, ST_FILE_MAX, &text, &len, err, sizeof err))
    app_die(pg->prog, "--html: %s (three.js: Debian's libjs-three, `apt-get install libjs-three` "
            "or `make deps`; or give --three DIR or %s=DIR, a directory holding three.min.js and "
            "examples/js/controls/OrbitControls.js)", err, TRIAL_PAGE_THREE_ENV);
  const char *bad = script_breaker(text);
  if (bad) app_die(pg->prog, "--html: %s holds '%.8s' (cannot be inlined in a page)", path, bad);
  return text;
}

trialPage *trial_page_open(const char *prog, const char *path, const char *three_dir,
                           const stProtocol *p) {
  trialPage *pg = calloc(1, sizeof *pg);
  if (!pg) app_die(prog, "out of memory");
  pg->prog = prog;
  pg->path = path;
  if (!three_dir) three_dir = getenv(TRIAL_PAGE_THREE_ENV);
  if (!three_dir || !*three_dir) three_dir = TRIAL_PAGE_THREE_DIR;
  snprintf(pg->three_dir, sizeof pg->three_dir, "%s", three_dir);
  pg->three = read_lib(pg, "three.min.js");
  pg->orbit = read_lib(pg, "examples/js/controls/OrbitControls.js");
  const char *rev = strstr(pg->three, "REVISION=\"");
  if (!rev || sscanf(rev + 10, "%15[0-9a-z]", pg->revision) != 1)
    app_die(prog, "--html: %s/three.min.js has no REVISION (expected three.js's minified build)",
            pg->three_dir);
  char err[1024];
  stAtomicFile af; /* fail now, not after the trial, when the page cannot be written */
  if (st_atomic_open(&af, path, err, sizeof err)) app_die(prog, "--html: %s", err);
  st_atomic_abort(&af);
  stWorld *w = NULL;
  if (st_world_create(p->robot, &p->scene, &w, err, sizeof err)) app_die(prog, "%s", err);
  pg->n = st_world_shapes(w, NULL, 0);
  st_world_destroy(w);
  const size_t n = (size_t)pg->n;
  pg->buf = calloc(n, sizeof *pg->buf);
  pg->owner = calloc(n, sizeof *pg->owner);
  pg->kind = calloc(n, sizeof *pg->kind);
  pg->type = calloc(n, sizeof *pg->type);
  pg->size = calloc(n, sizeof *pg->size);
  if (!pg->buf || !pg->owner || !pg->kind || !pg->type || !pg->size) app_die(prog, "out of memory");
  pg->dt = p->cfg.robot_control_dt;
  snprintf(pg->touch_links, sizeof pg->touch_links, "%s", p->cfg.robot_touch_links);
  return pg;
}

/* ---- recording --------------------------------------------------------------------------- */

static long fixed(trialPage *pg, double x, double scale) {
  double v = x * scale;
  if (!(v >= -MAX_FIXED && v <= MAX_FIXED)) {
    pg->clamped++;
    v = isnan(v) ? 0.0 : v > 0 ? MAX_FIXED : -MAX_FIXED;
  }
  return lround(v);
}

/* the unit quaternion (x, y, z, w) of a rotation matrix (row-major); the largest of the four
 * terms is taken from the diagonal, so the division is never by a small number */
static void quaternion(const double *R, double q[4]) {
  const double tr = R[0] + R[4] + R[8];
  if (tr > 0) {
    const double s = 2.0 * sqrt(tr + 1.0);
    q[3] = 0.25 * s, q[0] = (R[7] - R[5]) / s, q[1] = (R[2] - R[6]) / s, q[2] = (R[3] - R[1]) / s;
  } else if (R[0] > R[4] && R[0] > R[8]) {
    const double s = 2.0 * sqrt(1.0 + R[0] - R[4] - R[8]);
    q[3] = (R[7] - R[5]) / s, q[0] = 0.25 * s, q[1] = (R[1] + R[3]) / s, q[2] = (R[2] + R[6]) / s;
  } else if (R[4] > R[8]) {
    const double s = 2.0 * sqrt(1.0 + R[4] - R[0] - R[8]);
    q[3] = (R[2] - R[6]) / s, q[0] = (R[1] + R[3]) / s, q[1] = 0.25 * s, q[2] = (R[5] + R[7]) / s;
  } else {
    const double s = 2.0 * sqrt(1.0 + R[8] - R[0] - R[4]);
    q[3] = (R[3] - R[1]) / s, q[0] = (R[2] + R[6]) / s, q[1] = (R[5] + R[7]) / s, q[2] = 0.25 * s;
  }
}

void trial_page_step(trialPage *pg, const stTraceStep *s, stNetArch arch) {
  if (s->step != pg->steps)
    app_die(pg->prog, "--html: step %d traced after step %ld (expected every step in order)",
            s->step, pg->steps - 1);
  if (pg->steps == pg->cap) {
    pg->cap = pg->cap ? 2 * pg->cap : 256;
    long *pose = realloc(pg->pose, (size_t)pg->cap * (size_t)pg->n * POSE_N * sizeof *pose);
    stepRec *rec = realloc(pg->rec, (size_t)pg->cap * sizeof *rec);
    if (pose) pg->pose = pose;
    if (rec) pg->rec = rec;
    if (!pose || !rec) app_die(pg->prog, "out of memory");
  }
  st_world_shapes(s->world, pg->buf, pg->n);
  long *pose = pg->pose + (size_t)pg->steps * (size_t)pg->n * POSE_N;
  for (int i = 0; i < pg->n; i++, pose += POSE_N) {
    const stShape *sh = &pg->buf[i];
    if (pg->steps == 0) {
      snprintf(pg->owner[i], sizeof pg->owner[i], "%s", sh->owner);
      pg->kind[i] = (int)sh->kind;
      pg->type[i] = (int)sh->type;
      memcpy(pg->size[i], sh->size, sizeof sh->size);
    }
    double q[4];
    quaternion(sh->R, q);
    /* q and -q are the same turn: the one nearer the previous step keeps the deltas small */
    const long *prev = pg->steps ? pose - (size_t)pg->n * POSE_N : NULL;
    if (prev && prev[3] * q[0] + prev[4] * q[1] + prev[5] * q[2] + prev[6] * q[3] < 0)
      for (int k = 0; k < 4; k++) q[k] = -q[k];
    for (int k = 0; k < 3; k++) pose[k] = fixed(pg, sh->pos[k], POS_SCALE);
    for (int k = 0; k < 4; k++) pose[3 + k] = fixed(pg, q[k], QUAT_SCALE);
  }
  stepRec *r = &pg->rec[pg->steps++];
  const int given = st_word_source_given(s->source);
  r->heard = s->word;
  r->word = given ? s->word : -1; /* as the trace's caretaker_word */
  r->label = s->label;
  r->source = (int)s->source;
  r->event = s->event;
  r->touching = s->q->touching;
  r->lifted = s->q->lifted;
  r->touch = 0;
  for (int i = 0; i < ST_NTOUCH; i++) r->touch |= s->world->contacts.touch[i] ? 1 << i : 0;
  r->d_r = fixed(pg, s->q->d_r, POS_SCALE);
  r->d_g = fixed(pg, s->q->d_g, POS_SCALE);
  r->d_m = fixed(pg, s->q->d_m, POS_SCALE);
  r->S = fixed(pg, s->S, QUAT_SCALE);
  r->P = fixed(pg, s->P, QUAT_SCALE);
  /* the linguistic cluster, as the trace's lo_* (type A) and hl_* (type B) columns */
  const int has = s->nout >= ST_NET_MAX_OUT && (arch == ST_ARCH_A || arch == ST_ARCH_B);
  pg->ling = has ? (arch == ST_ARCH_A ? 1 : 2) : 0;
  for (int m = 0; m < ST_NET_NLING; m++)
    r->ling[m] = has ? fixed(pg, s->out[ST_NET_NOUT + m], VAL_SCALE) : 0;
}

/* ---- the data ---------------------------------------------------------------------------- */

/* a per-step column of the records as a JSON array */
#define COLUMN(b, pg, name, field)                                                             \
  do {                                                                                         \
    sb_printf(b, ",\"%s\":[", name);                                                           \
    for (long t_ = 0; t_ < (pg)->steps; t_++)                                                  \
      sb_printf(b, "%s%ld", t_ ? "," : "", (long)(pg)->rec[t_].field);                         \
    sb_printf(b, "]");                                                                         \
  } while (0)

/* one shape's poses: POSE_N numbers when it never moves (the table, the target, the torso),
 * else POSE_N per step, each step the difference from the step before (small integers) */
static void pose_json(sbuf *b, const trialPage *pg, int i) {
  const size_t stride = (size_t)pg->n * POSE_N;
  const long *p0 = pg->pose + (size_t)i * POSE_N;
  int moves = 0;
  for (long t = 1; t < pg->steps && !moves; t++)
    moves = memcmp(p0, p0 + (size_t)t * stride, POSE_N * sizeof *p0) != 0;
  sb_printf(b, "[");
  for (long t = 0; t < (moves ? pg->steps : 1); t++)
    for (int k = 0; k < POSE_N; k++) {
      const long v = p0[(size_t)t * stride + (size_t)k];
      sb_printf(b, "%s%ld", t || k ? "," : "", t ? v - p0[(size_t)(t - 1) * stride + (size_t)k] : v);
    }
  sb_printf(b, "]");
}

static void data_json(sbuf *b, const trialPage *pg, const trialPageSummary *sum) {
  sb_printf(b, "{\"format\":\"selftalk-trial-page 1\",\"title\":");
  sb_json(b, sum->title);
  sb_printf(b, ",\"dt\":%.17g,\"steps\":%ld,\"units\":{\"pos\":%g,\"quat\":%g,\"val\":%g},"
            "\"words\":[", pg->dt, pg->steps, 1 / POS_SCALE, 1 / QUAT_SCALE, 1 / VAL_SCALE);
  for (int w = 0; w < ST_NPRIM; w++) sb_printf(b, "%s\"%s\"", w ? "," : "", st_primitive_name(w));
  sb_printf(b, "],\"sources\":[");
  for (int k = 0; k < ST_WORDS_COUNT; k++) sb_printf(b, "%s\"%s\"", k ? "," : "", st_word_source_name((stWordSource)k));
  sb_printf(b, "],\"touch_links\":");
  sb_json(b, pg->touch_links);
  sb_printf(b, ",\"summary\":{\"line\":");
  sb_json(b, sum->line);
  sb_printf(b, ",\"success\":%d,\"end\":", sum->success);
  sb_json(b, sum->end);
  if (sum->has_bonus) sb_printf(b, ",\"bonus\":%.17g", sum->bonus);
  else sb_printf(b, ",\"bonus\":null");
  sb_printf(b, ",\"steps_run\":%ld,\"steps\":%ld},\n\"shapes\":[", sum->steps_run, sum->steps);
  for (int i = 0; i < pg->n; i++) {
    sb_printf(b, "%s\n{\"kind\":\"%s\",\"owner\":", i ? "," : "", st_shape_kind_name(pg->kind[i]));
    sb_json(b, pg->owner[i]);
    sb_printf(b, ",\"type\":\"%s\",\"size\":[%.6g,%.6g,%.6g],\"pose\":",
              st_geom_type_name(pg->type[i]), pg->size[i][0], pg->size[i][1], pg->size[i][2]);
    pose_json(b, pg, i);
    sb_printf(b, "}");
  }
  sb_printf(b, "],\n\"trace\":{\"ling\":\"%s\"", pg->ling == 1 ? "outputs" : pg->ling == 2 ? "hidden" : "none");
  COLUMN(b, pg, "heard", heard);
  COLUMN(b, pg, "word", word);
  COLUMN(b, pg, "label", label);
  COLUMN(b, pg, "source", source);
  COLUMN(b, pg, "event", event);
  COLUMN(b, pg, "touch", touch);
  COLUMN(b, pg, "touching", touching);
  COLUMN(b, pg, "lifted", lifted);
  COLUMN(b, pg, "d_r", d_r);
  COLUMN(b, pg, "d_g", d_g);
  COLUMN(b, pg, "d_m", d_m);
  COLUMN(b, pg, "S", S);
  COLUMN(b, pg, "P", P);
  sb_printf(b, ",\"lingvals\":[");
  for (long t = 0; pg->ling && t < pg->steps; t++)
    for (int m = 0; m < ST_NET_NLING; m++) sb_printf(b, "%s%ld", t || m ? "," : "", pg->rec[t].ling[m]);
  sb_printf(b, "]}}\n");
}

/* 32-bit FNV-1a: the page recomputes it over the data element's text, so a damaged or cut page
 * says so instead of drawing garbage */
static uint32_t fnv1a(const char *s, size_t len) {
  uint32_t h = 2166136261u;
  for (size_t i = 0; i < len; i++) h = (h ^ (unsigned char)s[i]) * 16777619u;
  return h;
}

/* ---- the page ---------------------------------------------------------------------------- */

static const char *const MIT =
    "Permission is hereby granted, free of charge, to any person obtaining a copy of this software "
    "and associated documentation files (the \"Software\"), to deal in the Software without "
    "restriction, including without limitation the rights to use, copy, modify, merge, publish, "
    "distribute, sublicense, and/or sell copies of the Software, and to permit persons to whom the "
    "Software is furnished to do so, subject to the following conditions:\n *\n * The above "
    "copyright notice and this permission notice shall be included in all copies or substantial "
    "portions of the Software.\n *\n * THE SOFTWARE IS PROVIDED \"AS IS\", WITHOUT WARRANTY OF "
    "ANY KIND, EXPRESS OR IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, "
    "FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR "
    "COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION "
    "OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION WITH THE SOFTWARE OR "
    "THE USE OR OTHER DEALINGS IN THE SOFTWARE.";

/* the two three.js files, each in its <script> element headed by a comment with the licence
 * and where it was read from (the directory as PAGE_COMMENT: a name holding "* /" or "</script"
 * stays inside the comment) */
static void libs(sbuf *b, const trialPage *pg) {
  /* Debian's three.min.js carries no notice of its own: the upstream licence goes with it */
  sb_printf(b, "<script>\n/* three.js r%s, read from ", pg->revision);
  sb_escaped(b, PAGE_COMMENT, pg->three_dir);
  sb_printf(b, "/three.min.js (Debian's libjs-three) and inlined unchanged.\n * Copyright (c) "
            "2010-2019 three.js authors. The MIT License:\n * %s */\n", MIT);
  sb_append(b, pg->three);
  sb_printf(b, "\n</script>\n<script>\n/* OrbitControls of three.js r%s (", pg->revision);
  sb_escaped(b, PAGE_COMMENT, pg->three_dir);
  sb_printf(b, "/examples/js/controls/OrbitControls.js), inlined unchanged; the licence above. "
            "*/\n");
  sb_append(b, pg->orbit);
  sb_printf(b, "\n</script>\n");
}

/* the page: the template with its three marks replaced by the title, three.js and the data */
static void page_text(sbuf *out, const trialPage *pg, const trialPageSummary *sum,
                      const sbuf *data) {
  const char *t = (const char *)TEMPLATE;
  int seen[3] = {0, 0, 0};
  static const char *const NAMES[3] = {"TITLE", "LIBS", "DATA"};
  for (const char *m; (m = strstr(t, "@@"));) {
    sb_put(out, t, (size_t)(m - t));
    const char *end = strstr(m + 2, "@@");
    int k = 0;
    while (k < 3 && !(end && (size_t)(end - m - 2) == strlen(NAMES[k]) &&
                      !strncmp(m + 2, NAMES[k], strlen(NAMES[k]))))
      k++;
    if (k == 3) app_die(pg->prog, "--html: the page template has '%.20s' (expected @@TITLE@@, "
                        "@@LIBS@@, @@DATA@@)", m);
    seen[k]++;
    if (k == 0) sb_escaped(out, PAGE_HTML, sum->title);
    else if (k == 1) libs(out, pg);
    else {
      sb_printf(out, "<script type=\"application/json\" id=\"trial-data\" data-fnv=\"%08x\">",
                (unsigned)fnv1a(data->s, data->len));
      sb_put(out, data->s, data->len);
      sb_printf(out, "</script>");
    }
    t = end + 2;
  }
  sb_append(out, t);
  if (seen[0] != 1 || seen[1] != 1 || seen[2] != 1)
    app_die(pg->prog, "--html: the page template has @@TITLE@@ %d, @@LIBS@@ %d, @@DATA@@ %d "
            "times (expected once each)", seen[0], seen[1], seen[2]);
}

void trial_page_finish(trialPage *pg, const trialPageSummary *sum) {
  if (pg->steps == 0) app_die(pg->prog, "--html: the trial ran no step");
  sbuf data = {NULL, 0, 0, pg->prog};
  data_json(&data, pg, sum);
  sbuf page = {NULL, 0, 0, pg->prog};
  page_text(&page, pg, sum, &data);
  char err[1024];
  stAtomicFile af;
  if (st_atomic_open(&af, pg->path, err, sizeof err)) app_die(pg->prog, "--html: %s", err);
  fwrite(page.s, 1, page.len, af.f);
  if (ferror(af.f)) {
    st_atomic_abort(&af);
    app_die(pg->prog, "--html: %s: write error", pg->path);
  }
  const long size = (long)page.len;
  if (st_atomic_commit(&af, err, sizeof err)) app_die(pg->prog, "--html: %s", err);
  if (pg->clamped)
    fprintf(stderr, "replay: --html: %ld non-finite or huge values clamped (a diverged "
            "simulation)\n", pg->clamped);
  fprintf(stderr, "replay: %s: a page of %ld steps, %d shapes, %ld bytes (data %zu)\n", pg->path,
          pg->steps, pg->n, size, data.len);
  free(data.s);
  free(page.s);
  free(pg->three);
  free(pg->orbit);
  free(pg->buf);
  free(pg->owner);
  free(pg->kind);
  free(pg->type);
  free(pg->size);
  free(pg->pose);
  free(pg->rec);
  free(pg);
}
