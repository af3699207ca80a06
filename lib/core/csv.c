/* SPDX-License-Identifier: MIT
 * The results files' CSV (selftalk/csv.h): one schema per file, its writer and its validated
 * reader. Core: no simulator. */
#include "selftalk/csv.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "core/readers.h"
#include "selftalk/io.h"

/* ---- lines ---- */

char *st__lines_next(stLines *t) {
  if (t->pos >= t->len) return NULL;
  char *s = t->text + t->pos, *nl = memchr(s, '\n', t->len - t->pos);
  const size_t n = nl ? (size_t)(nl - s) : t->len - t->pos;
  t->pos += n + 1;
  t->lineno++;
  s[n] = 0;
  size_t e = n;
  while (e > 0 && strchr(" \t\r\v\f", s[e - 1])) s[--e] = 0;
  while (*s == ' ' || *s == '\t') s++;
  return s;
}

char *st__lines_content(stLines *t) {
  char *s;
  while ((s = st__lines_next(t)) && (!*s || *s == '#')) {
  }
  return s;
}

/* ---- writing ---- */

static const void *field_at(const void *row, const stCsvColumn *c) {
  return (const char *)row + c->offset;
}

static int int_at(const void *row, const stCsvColumn *c) {
  int v;
  memcpy(&v, field_at(row, c), sizeof v);
  return v;
}

static double real_at(const void *row, const stCsvColumn *c) {
  double v;
  memcpy(&v, field_at(row, c), sizeof v);
  return v;
}

/* one field as written, into buf as snprintf */
static int field_text(const stCsvColumn *c, const void *row, char *buf, size_t n) {
  switch (c->kind) {
    case ST_CSV_INT: return snprintf(buf, n, "%d", int_at(row, c));
    case ST_CSV_REAL: return snprintf(buf, n, "%.17g", real_at(row, c));
    case ST_CSV_CHOICE: return snprintf(buf, n, "%s", c->choice_name(int_at(row, c)));
    default: return snprintf(buf, n, "%s", (const char *)field_at(row, c));
  }
}

/* appends to buf[0..n) at *k as snprintf would (the length counted beyond n) */
static void put(char *buf, size_t n, int *k, int len, const char *text) {
  if ((size_t)*k < n) snprintf(buf + *k, n - (size_t)*k, "%s", text);
  *k += len;
}

int st_csv_header_text(const stCsvSchema *s, char *buf, size_t n) {
  ST_ASSERT(s && (buf || n == 0));
  int k = 0;
  if (n) buf[0] = 0;
  for (int i = 0; i < s->ncols; i++) {
    if (i) put(buf, n, &k, 1, ",");
    put(buf, n, &k, (int)strlen(s->col[i].name), s->col[i].name);
  }
  put(buf, n, &k, 1, "\n");
  return k;
}

int st_csv_row_text(const stCsvSchema *s, const void *row, char *buf, size_t n) {
  ST_ASSERT(s && row && (buf || n == 0));
  int k = 0;
  if (n) buf[0] = 0;
  for (int i = 0; i < s->ncols; i++) {
    if (i) put(buf, n, &k, 1, ",");
    k += field_text(&s->col[i], row, (size_t)k < n ? buf + k : NULL, (size_t)k < n ? n - (size_t)k : 0);
  }
  put(buf, n, &k, 1, "\n");
  return k;
}

int st_csv_write_header(FILE *f, const stCsvSchema *s) {
  ST_ASSERT(f && s);
  for (int i = 0; i < s->ncols; i++)
    if (fprintf(f, "%s%s", i ? "," : "", s->col[i].name) < 0) return -1;
  return fputc('\n', f) == EOF ? -1 : 0;
}

int st_csv_write_row(FILE *f, const stCsvSchema *s, const void *row) {
  ST_ASSERT(f && s && row);
  for (int i = 0; i < s->ncols; i++) {
    char small[64];
    const int len = field_text(&s->col[i], row, small, sizeof small);
    if (i && fputc(',', f) == EOF) return -1;
    if ((size_t)len < sizeof small) {
      if (fputs(small, f) == EOF) return -1;
    } else if (fprintf(f, "%s", (const char *)field_at(row, &s->col[i])) < 0) {
      return -1; /* a long name or text: only those exceed the buffer */
    }
  }
  return fputc('\n', f) == EOF ? -1 : 0;
}

/* ---- reading ---- */

typedef struct reader {
  const stCsvSchema *s;
  const char *name;
  const void *ctx;
  stLines t;
  char *err;
  size_t errsz;
} reader;

/* the schema's read columns, comma-separated */
static void read_names(const stCsvSchema *s, char *buf, size_t n) {
  buf[0] = 0;
  for (int i = 0; i < s->nread; i++)
    snprintf(buf + strlen(buf), n - strlen(buf), "%s%s", i ? "," : "", s->col[i].name);
}

/* splits a line at commas in place; the number of fields, or -1 (err set) */
static int split(reader *r, char *s, char **field) {
  if (strchr(s, '"')) {
    st__errf(r->err, r->errsz, "%s:%d: a quoted field (expected plain comma-separated values)",
             r->name, r->t.lineno);
    return -1;
  }
  int n = 0;
  for (;;) {
    if (n == ST_CSV_MAX_FIELDS) {
      st__errf(r->err, r->errsz, "%s:%d: more than %d fields", r->name, r->t.lineno,
               ST_CSV_MAX_FIELDS);
      return -1;
    }
    field[n++] = s;
    char *c = strchr(s, ',');
    if (!c) return n;
    *c = 0;
    s = c + 1;
  }
}

static stStatus check_header(reader *r, char *line) {
  char *f[ST_CSV_MAX_FIELDS], want[1024];
  const int n = line ? split(r, line, f) : 0;
  if (n < 0) return ST_ERR_PARSE;
  int ok = n >= r->s->nread;
  for (int i = 0; ok && i < r->s->nread; i++) ok = !strcmp(f[i], r->s->col[i].name);
  if (ok) return ST_OK;
  read_names(r->s, want, sizeof want);
  return st__errf(r->err, r->errsz, "%s:%d: %s (expected the header %s, further columns ignored)",
                  r->name, r->t.lineno, line ? "not the header" : "no header", want), ST_ERR_PARSE;
}

/* "A, B or C": the names of a choice column's values */
static void choice_list(const stCsvColumn *c, char *buf, size_t n) {
  buf[0] = 0;
  for (int i = 0; i < c->nchoices; i++)
    snprintf(buf + strlen(buf), n - strlen(buf), "%s%s",
             !i ? "" : i == c->nchoices - 1 ? " or " : ", ", c->choice_name(c->choices[i]));
}

static stStatus parse_field(reader *r, const stCsvColumn *c, const char *s, char *row) {
  char *at = row + c->offset;
  switch (c->kind) {
    case ST_CSV_NAME:
      if (!*s || strlen(s) >= ST_CSV_NAME_LEN || strpbrk(s, " \t|"))
        return st__errf(r->err, r->errsz, "%s:%d: %s '%s' (expected a name of 1..%d characters "
                        "without blanks or |)", r->name, r->t.lineno, c->name, s,
                        ST_CSV_NAME_LEN - 1), ST_ERR_PARSE;
      memcpy(at, s, strlen(s) + 1);
      return ST_OK;
    case ST_CSV_TEXT:
      if (strlen(s) >= c->size)
        return st__errf(r->err, r->errsz, "%s:%d: %s '%.40s...' (expected at most %d "
                        "characters)", r->name, r->t.lineno, c->name, s, (int)c->size - 1),
               ST_ERR_PARSE;
      memcpy(at, s, strlen(s) + 1);
      return ST_OK;
    case ST_CSV_CHOICE: {
      int v = -1, found = 0;
      for (int i = 0; i < c->nchoices && !found; i++)
        if (!strcmp(s, c->choice_name(c->choices[i]))) v = c->choices[i], found = 1;
      if (!found) {
        char list[256];
        choice_list(c, list, sizeof list);
        return st__errf(r->err, r->errsz, "%s:%d: %s '%s' (expected %s)", r->name, r->t.lineno,
                        c->name, s, list), ST_ERR_PARSE;
      }
      memcpy(at, &v, sizeof v);
      return ST_OK;
    }
    case ST_CSV_REAL: {
      char *end;
      errno = 0;
      const double x = strtod(s, &end);
      if (end == s || *end || errno == ERANGE || !isfinite(x))
        return st__errf(r->err, r->errsz, "%s:%d: %s '%s' (expected a finite number)", r->name,
                        r->t.lineno, c->name, s), ST_ERR_PARSE;
      memcpy(at, &x, sizeof x);
      return ST_OK;
    }
    default: {
      char *end;
      errno = 0;
      const long x = strtol(s, &end, 10);
      if (end == s || *end || errno || x < c->lo || x > INT_MAX)
        return st__errf(r->err, r->errsz, "%s:%d: %s '%s' (expected an integer >= %d)", r->name,
                        r->t.lineno, c->name, s, c->lo), ST_ERR_PARSE;
      const int v = (int)x;
      memcpy(at, &v, sizeof v);
      return ST_OK;
    }
  }
}

/* one row's line: its fields, then the schema's check */
static stStatus parse_row(reader *r, char *line, char *row) {
  char *f[ST_CSV_MAX_FIELDS];
  const int n = split(r, line, f);
  if (n < 0) return ST_ERR_PARSE;
  if (n < r->s->nread) {
    char want[1024];
    read_names(r->s, want, sizeof want);
    return st__errf(r->err, r->errsz, "%s:%d: %d fields (expected at least %d: %s)", r->name,
                    r->t.lineno, n, r->s->nread, want), ST_ERR_PARSE;
  }
  memset(row, 0, r->s->row_size);
  for (int i = 0; i < r->s->nread; i++) {
    stStatus st = parse_field(r, &r->s->col[i], f[i], row);
    if (st) return st;
  }
  char msg[1024];
  if (r->s->check && r->s->check(row, r->ctx, msg, sizeof msg))
    return st__errf(r->err, r->errsz, "%s:%d: %s", r->name, r->t.lineno, msg), ST_ERR_PARSE;
  return ST_OK;
}

int st_csv_compare(const stCsvSchema *s, int nkey, const void *a, const void *b) {
  ST_ASSERT(s && a && b && nkey <= s->nkey);
  for (int i = 0; i < nkey; i++) {
    const stCsvColumn *c = &s->col[i];
    int d;
    if (c->kind == ST_CSV_NAME) {
      d = strcmp(field_at(a, c), field_at(b, c));
    } else {
      const int x = int_at(a, c), y = int_at(b, c);
      d = (x > y) - (x < y);
    }
    if (d) return d;
  }
  return 0;
}

const void *st_csv_row(const stCsvRows *rows, int i) {
  ST_ASSERT(rows && i >= 0 && i < rows->n);
  return rows->data + rows->schema->row_size * (size_t)i;
}

const void *st_csv_sorted(const stCsvRows *rows, int k) {
  ST_ASSERT(rows && k >= 0 && k < rows->n);
  return st_csv_row(rows, rows->order[k]);
}

/* rows i and j by key, then by index: a total order, so the sort's result is the one order */
static int by_key(const stCsvRows *rs, int i, int j) {
  const int c = st_csv_compare(rs->schema, rs->schema->nkey, st_csv_row(rs, i), st_csv_row(rs, j));
  return c ? c : (i > j) - (i < j);
}

/* merge sort of a[0..n) (O(n log n); qsort has no context to pass the rows in) */
static void sort_order(const stCsvRows *rs, int *a, int *tmp, int n) {
  if (n < 2) return;
  const int h = n / 2;
  sort_order(rs, a, tmp, h);
  sort_order(rs, a + h, tmp, n - h);
  int i = 0, j = h, k = 0;
  while (i < h && j < n) tmp[k++] = by_key(rs, a[i], a[j]) <= 0 ? a[i++] : a[j++];
  while (i < h) tmp[k++] = a[i++];
  while (j < n) tmp[k++] = a[j++];
  memcpy(a, tmp, (size_t)n * sizeof *a);
}

/* "test T condition C run R individual I": a row's key in words */
static void key_words(const stCsvSchema *s, const void *row, char *buf, size_t n) {
  buf[0] = 0;
  for (int i = 0; i < s->nkey; i++) {
    const stCsvColumn *c = &s->col[i];
    char v[64];
    field_text(c, row, v, sizeof v);
    snprintf(buf + strlen(buf), n - strlen(buf), "%s%s %s", i ? " " : "", c->name, v);
  }
}

/* the rows' order by key; a key twice is refused at its second line */
static stStatus order_rows(reader *r, stCsvRows *rs) {
  rs->order = malloc((size_t)rs->n * sizeof *rs->order);
  int *tmp = malloc((size_t)rs->n * sizeof *tmp);
  if (!rs->order || !tmp) {
    free(tmp);
    return st__errf(r->err, r->errsz, "%s: out of memory", r->name), ST_ERR_NOMEM;
  }
  for (int i = 0; i < rs->n; i++) rs->order[i] = i;
  sort_order(rs, rs->order, tmp, rs->n);
  free(tmp);
  for (int i = 1; i < rs->n; i++) {
    const int a = rs->order[i - 1], b = rs->order[i];
    if (st_csv_compare(r->s, r->s->nkey, st_csv_row(rs, a), st_csv_row(rs, b))) continue;
    char what[256];
    key_words(r->s, st_csv_row(rs, b), what, sizeof what);
    return st__errf(r->err, r->errsz, "%s:%d: %s twice (first at line %d; expected each once)",
                    r->name, rs->line[b], what, rs->line[a]), ST_ERR_PARSE;
  }
  return ST_OK;
}

/* the text (NUL-terminated at len, ours to change) into rows */
static stStatus parse_text(reader *r, char *text, size_t len, stCsvRows *rs) {
  r->t.text = text, r->t.len = len;
  stStatus st = check_header(r, st__lines_content(&r->t));
  int cap = 0;
  for (char *s; !st && (s = st__lines_content(&r->t));) {
    if (rs->n == cap) {
      cap = 2 * cap + 256;
      char *d = realloc(rs->data, (size_t)cap * r->s->row_size);
      if (d) rs->data = d;
      int *l = realloc(rs->line, (size_t)cap * sizeof *rs->line);
      if (l) rs->line = l;
      if (!d || !l) {
        st = ST_ERR_NOMEM;
        st__errf(r->err, r->errsz, "%s: out of memory", r->name);
        break;
      }
    }
    rs->line[rs->n] = r->t.lineno;
    st = parse_row(r, s, rs->data + r->s->row_size * (size_t)rs->n);
    if (!st) rs->n++;
  }
  if (!st && !rs->n)
    st = (st__errf(r->err, r->errsz, "%s: no rows after the header", r->name), ST_ERR_PARSE);
  if (!st) st = order_rows(r, rs);
  return st;
}

/* a reader's state for st__text_parse / st__text_read_parse */
typedef struct parsing {
  reader r;
  stCsvRows *rows;
} parsing;

static stStatus parse_cb(const char *name, char *text, size_t len, void *ctx, char *err,
                         size_t errsz) {
  parsing *p = ctx;
  (void)name, (void)err, (void)errsz; /* in p->r */
  return parse_text(&p->r, text, len, p->rows);
}

static stStatus parsing_init(parsing *p, const char *name, const stCsvSchema *s,
                             const void *ctx, stCsvRows *rs, char *err, size_t errsz) {
  ST_ASSERT(s && s->col && s->nkey <= s->nread && s->nread <= s->ncols);
  for (int i = 0; i < s->nread; i++) /* a name read fits its field */
    ST_ASSERT(s->col[i].kind != ST_CSV_NAME || s->col[i].size >= ST_CSV_NAME_LEN);
  memset(p, 0, sizeof *p);
  p->r.s = s, p->r.name = name, p->r.ctx = ctx, p->r.err = err, p->r.errsz = errsz;
  p->rows = rs;
  memset(rs, 0, sizeof *rs);
  rs->schema = s;
  const size_t n = strlen(name) + 1;
  if (!(rs->name = malloc(n))) return st__errf(err, errsz, "%s: out of memory", name), ST_ERR_NOMEM;
  memcpy(rs->name, name, n);
  return ST_OK;
}

stStatus st__csv_parse(const char *name, const char *text, size_t len, const stCsvSchema *s,
                       const void *ctx, stCsvRows *rows, char *err, size_t errsz) {
  ST_ASSERT(name && (text || len == 0) && rows);
  parsing p;
  stStatus st = parsing_init(&p, name, s, ctx, rows, err, errsz);
  if (!st) st = st__text_parse(name, text, len, parse_cb, &p, err, errsz);
  if (st) st_csv_rows_free(rows);
  return st;
}

stStatus st_csv_read(const char *path, const stCsvSchema *s, const void *ctx, stCsvRows *rows,
                     char *err, size_t errsz) {
  ST_ASSERT(path && rows);
  parsing p;
  stStatus st = parsing_init(&p, path, s, ctx, rows, err, errsz);
  if (!st) st = st__text_read_parse(path, parse_cb, &p, err, errsz);
  if (st) st_csv_rows_free(rows);
  return st;
}

void st_csv_rows_free(stCsvRows *rows) {
  if (!rows) return;
  free(rows->data);
  free(rows->line);
  free(rows->order);
  free(rows->name);
  rows->data = NULL, rows->line = rows->order = NULL, rows->name = NULL;
  rows->n = 0;
}

/* ---- groups ---- */

stStatus st_csv_groups(const stCsvRows *rs, int nkey, stCsvGroup **groups, int *ng, char *err,
                       size_t errsz) {
  ST_ASSERT(rs && groups && ng && nkey <= rs->schema->nkey);
  *ng = 0;
  stCsvGroup *g = *groups = malloc(((size_t)rs->n + 1) * sizeof *g);
  if (!g) return st__errf(err, errsz, "out of memory"), ST_ERR_NOMEM;
  for (int i = 0; i < rs->n;) {
    stCsvGroup *x = &g[(*ng)++];
    x->start = i, x->first = rs->order[i];
    const void *r0 = st_csv_sorted(rs, i);
    while (i < rs->n && !st_csv_compare(rs->schema, nkey, st_csv_sorted(rs, i), r0)) {
      x->first = rs->order[i] < x->first ? rs->order[i] : x->first;
      i++;
    }
    x->end = i;
  }
  return ST_OK;
}

const stCsvGroup *st_csv_group_find(const stCsvRows *rs, int nkey, const stCsvGroup *g, int ng,
                                    const void *row) {
  ST_ASSERT(rs && row && (g || ng == 0));
  int lo = 0, hi = ng;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    const int c = st_csv_compare(rs->schema, nkey, st_csv_sorted(rs, g[mid].start), row);
    if (!c) return &g[mid];
    if (c < 0) lo = mid + 1;
    else hi = mid;
  }
  return NULL;
}
