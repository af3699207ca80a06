/* SPDX-License-Identifier: MIT
 * Fuzz target: the trial page writer of replay --html (apps/trial_page.c, included: the app's own
 * code). The input is NUL-separated fields: the title (the genotype's file name), replay's
 * summary line, robot.touch_links, the three.js directory, a shape's owner (a URDF link), the
 * text of three.min.js and of OrbitControls.js. Property: whatever the names, the page has
 * exactly the template's elements and comments - the title's text holds no '<', the data no
 * '<', '>' or '&' and every name decodes back from it, the comments heading three.js end where
 * they are meant to and hold no '<' - and an inlined three.js that script_breaker accepts holds
 * no "</script" (in any case) and no "<!--". Also built with cc as build/page_check, which runs
 * it over tests/fuzz/seeds/page/ in tests/check_html.sh. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdint.h>

#include "app_common.h"
#include "app_shim.h"
#include "../../apps/trial_page.c"

enum { F_TITLE, F_LINE, F_LINKS, F_DIR, F_OWNER, F_THREE, F_ORBIT, NFIELDS };

static char *g_field[NFIELDS];

static size_t count_ci(const char *s, const char *needle) {
  size_t n = 0, k = strlen(needle);
  for (; *s; s++) {
    size_t i = 0;
    while (i < k && s[i] && tolower((unsigned char)s[i]) == needle[i]) i++;
    n += i == k;
  }
  return n;
}

/* what a name reads as in the data: non-ASCII bytes as '?' (the page is ASCII) */
static void plain(const char *s, char *out) {
  for (; *s; s++) *out++ = (unsigned char)*s < 0x80 ? *s : '?';
  *out = 0;
}

/* the JSON string after key in text, decoded into out (the writer's escapes only); 0 if absent */
static int json_string(const char *text, const char *key, char *out) {
  const char *p = strstr(text, key);
  if (!p || p[strlen(key)] != '"') return 0;
  for (p += strlen(key) + 1; *p != '"'; p++) {
    if (!*p) return 0;
    if (*p != '\\') *out++ = *p;
    else if (p[1] == '"' || p[1] == '\\') *out++ = *++p;
    else if (p[1] == 'u') {
      unsigned v;
      if (sscanf(p + 2, "%4x", &v) != 1) return 0;
      *out++ = (char)v, p += 5;
    } else return 0;
  }
  *out = 0;
  return 1;
}

/* the comment heading an inlined three.js file, from *p: it must end ("* /") just before the
 * file's text, and hold no '<'; *p moves past the file */
static void header(const char **p, const char *lib) {
  if (strncmp(*p, "<script>\n/*", 11)) abort();
  const char *end = strstr(*p + 11, "*/");
  if (!end || memchr(*p + 11, '<', (size_t)(end - *p - 11))) abort();
  if (end[2] != '\n' || strncmp(end + 3, lib, strlen(lib))) abort(); /* closed early */
  *p = end + 3 + strlen(lib);
  if (strncmp(*p, "\n</script>\n", 11)) abort();
  *p += 11;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *in = (const char *)data, *end = in + size;
  for (int f = 0; f < NFIELDS; f++) {
    const char *stop = in < end ? memchr(in, 0, (size_t)(end - in)) : NULL;
    const size_t n = in < end ? (size_t)((stop ? stop : end) - in) : 0;
    g_field[f] = calloc(n + 1, 1);
    if (!g_field[f]) abort();
    memcpy(g_field[f], in, n);
    in += n + 1;
  }
  g_input = (const char *)data, g_input_len = size;
  if (setjmp(g_die)) { /* the writer refuses nothing it is given here */
    shim_free_all();
    abort();
  }

  /* three.js as read_lib takes it: refused when it would break out of its element */
  for (int f = F_THREE; f <= F_ORBIT; f++)
    if (!script_breaker(g_field[f]) &&
        (count_ci(g_field[f], "</script") || strstr(g_field[f], "<!--")))
      abort();
  const int libs_ok = !script_breaker(g_field[F_THREE]) && !script_breaker(g_field[F_ORBIT]);

  /* a page of one step with one shape: only the names come from the input */
  static stShape shape;
  static long pose[POSE_N];
  static stepRec rec;
  static char owner[1][64];
  static int kind, type;
  static double sz[1][3];
  trialPage pg = {0};
  pg.prog = "page_check";
  snprintf(pg.three_dir, sizeof pg.three_dir, "%s", g_field[F_DIR]);
  snprintf(pg.touch_links, sizeof pg.touch_links, "%s", g_field[F_LINKS]);
  snprintf(owner[0], sizeof owner[0], "%s", g_field[F_OWNER]);
  snprintf(pg.revision, sizeof pg.revision, "111");
  pg.three = g_field[F_THREE], pg.orbit = g_field[F_ORBIT];
  pg.n = 1, pg.buf = &shape, pg.owner = owner, pg.kind = &kind, pg.type = &type, pg.size = sz;
  pg.pose = pose, pg.rec = &rec, pg.steps = 1, pg.cap = 1, pg.dt = 0.05;
  const trialPageSummary sum = {g_field[F_TITLE], g_field[F_LINE], 1, "full", 1, 1.0, 1, 1};

  sbuf json = {NULL, 0, 0, "page_check"};
  data_json(&json, &pg, &sum);
  for (size_t i = 0; i < json.len; i++) {
    const unsigned char c = (unsigned char)json.s[i];
    if ((c < 0x20 && c != '\n') || c >= 0x80 || c == '<' || c == '>' || c == '&') abort();
  }
  char *want = malloc(size + 1), *got = malloc(size + 1);
  if (!want || !got) abort();
  static const struct { int f; const char *key; } NAMES[] = {
      {F_TITLE, "\"title\":"}, {F_LINKS, "\"touch_links\":"}, {F_LINE, "\"line\":"},
      {F_OWNER, "\"owner\":"}};
  for (size_t k = 0; k < sizeof NAMES / sizeof NAMES[0]; k++) {
    const char *v = NAMES[k].f == F_LINKS ? pg.touch_links : NAMES[k].f == F_OWNER ? owner[0]
                                                                                : g_field[NAMES[k].f];
    plain(v, want);
    if (!json_string(json.s, NAMES[k].key, got) || strcmp(want, got)) abort();
  }

  if (libs_ok) {
    sbuf page = {NULL, 0, 0, "page_check"};
    page_text(&page, &pg, &sum, &json);
    /* the template's own elements and comments, and no more */
    const char *tpl = (const char *)TEMPLATE;
    if (count_ci(page.s, "</script") != count_ci(tpl, "</script") + 2 + 1) abort();
    if (count_ci(page.s, "<!--") != count_ci(tpl, "<!--")) abort();
    const char *t0 = strstr(page.s, "<title>"), *t1 = t0 ? strstr(t0, "</title>") : NULL;
    if (!t1 || memchr(t0 + 7, '<', (size_t)(t1 - t0 - 7))) abort();
    for (const char *c = t0 + 7; c < t1; c++)
      if (*c == '"' || *c == '\'' || *c == '>' ||
          (*c == '&' && strncmp(c, "&amp;", 5) && strncmp(c, "&lt;", 4) &&
           strncmp(c, "&gt;", 4) && strncmp(c, "&quot;", 6) && strncmp(c, "&#39;", 5)))
        abort();
    const char *p = strstr(page.s, "<script>\n/* three.js r");
    if (!p) abort();
    header(&p, pg.three);
    header(&p, pg.orbit);
    free(page.s);
  }
  free(json.s), free(want), free(got);
  for (int f = 0; f < NFIELDS; f++) free(g_field[f]);
  if (shim_live()) abort(); /* the writer left something allocated */
  return 0;
}
