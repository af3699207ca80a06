/* SPDX-License-Identifier: MIT
 * libselftalk: the results files' CSV (docs/PROTOCOL.md, "Post-evaluation files"). A file's
 * columns are one table, an stCsvSchema over a row struct, which its writer and its validated
 * reader both go through: a column is added in one place (trials.csv, summary.csv:
 * selftalk/postcsv.h; fitness.csv: selftalk/fitnesscsv.h; tools/csvschema.py is generated from
 * them by tools/csvschema.c). Core: no simulator.
 *
 * The format: a header line, then one row per line; comma-separated, no quoting. Written: every
 * column of the schema, integers %d, reals %.17g (they read back bit for bit), names and text as
 * they are. Read (st_csv_read): lines are trimmed, blank lines and lines starting with '#' are
 * skipped; the header must start with the schema's first `nread` columns in order (further
 * columns are ignored: older files have only those, and the file has room for additions); a
 * row has at least those fields, each checked by its kind, then by the schema's own check; a
 * quoted field, a second header or a row whose key (the first `nkey` columns) was given before
 * are refused. Errors name FILE:LINE and what was expected. */
#ifndef SELFTALK_CSV_H
#define SELFTALK_CSV_H

#include <stddef.h>
#include <stdio.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_CSV_NAME_LEN 32     /* a name read has 1..ST_CSV_NAME_LEN - 1 characters */
#define ST_CSV_MAX_FIELDS 256  /* fields of a line read, at most */

typedef enum stCsvKind {
  ST_CSV_NAME = 0, /* char[size]; read: 1..31 characters without blanks or '|' */
  ST_CSV_INT,      /* int; read: a decimal integer lo..INT_MAX */
  ST_CSV_REAL,     /* double; read: a finite number */
  ST_CSV_TEXT,     /* char[size], possibly empty */
  ST_CSV_CHOICE    /* int, written as choice_name(value); read: the name of one of choices */
} stCsvKind;

typedef struct stCsvColumn {
  const char *name;
  stCsvKind kind;
  size_t offset;                         /* of the field in the row struct */
  size_t size;                           /* NAME, TEXT: the field's bytes */
  int lo;                                /* INT: the smallest value read */
  const char *(*choice_name)(int value); /* CHOICE */
  const int *choices;                    /* CHOICE: the values a reader takes */
  int nchoices;
} stCsvColumn;

/* Columns of a row struct T (C99 initializers of stCsvColumn). */
#define ST_CSV_COL_NAME(T, field, name) \
  {name, ST_CSV_NAME, offsetof(T, field), sizeof(((T *)0)->field), 0, NULL, NULL, 0}
#define ST_CSV_COL_TEXT(T, field, name) \
  {name, ST_CSV_TEXT, offsetof(T, field), sizeof(((T *)0)->field), 0, NULL, NULL, 0}
#define ST_CSV_COL_INT(T, field, name, lo) \
  {name, ST_CSV_INT, offsetof(T, field), sizeof(int), lo, NULL, NULL, 0}
#define ST_CSV_COL_REAL(T, field, name) \
  {name, ST_CSV_REAL, offsetof(T, field), sizeof(double), 0, NULL, NULL, 0}
#define ST_CSV_COL_CHOICE(T, field, name, namefn, values, nvalues) \
  {name, ST_CSV_CHOICE, offsetof(T, field), sizeof(int), 0, namefn, values, nvalues}

/* A row's checks beyond its fields' (nullable in the schema): 0, or nonzero with what is wrong
 * in msg (without FILE:LINE, which the reader puts before it). ctx: st_csv_read's. */
typedef int (*stCsvCheck)(const void *row, const void *ctx, char *msg, size_t msgsz);

typedef struct stCsvSchema {
  const char *file;        /* the file's usual name, "trials.csv" */
  const stCsvColumn *col;
  int ncols;               /* the columns written */
  int nread;               /* the first nread columns are read and checked */
  int nkey;                /* the first nkey columns (NAME or INT) identify a row */
  size_t row_size;         /* sizeof the row struct */
  stCsvCheck check;        /* nullable */
} stCsvSchema;

/* ---- writing ---- */

/* The header line, or a row's line (with its newline), into buf as snprintf does: returns the
 * length of the whole line (>= n when it was cut). */
ST_API int st_csv_header_text(const stCsvSchema *s, char *buf, size_t n);
ST_API int st_csv_row_text(const stCsvSchema *s, const void *row, char *buf, size_t n);

/* The same onto f; 0, or -1 on a write error. */
ST_API int st_csv_write_header(FILE *f, const stCsvSchema *s);
ST_API int st_csv_write_row(FILE *f, const stCsvSchema *s, const void *row);

/* ---- reading ---- */

/* The rows of a file read: data holds n rows of schema->row_size bytes in file order (each
 * field of the first nread columns filled, the others 0), line each row's line, order the rows
 * by key (the first nkey columns; no two equal); name the file's name as given, so that what
 * is found in the rows later names FILE:LINE too. */
typedef struct stCsvRows {
  const stCsvSchema *schema;
  char *data;
  int n;
  int *line;
  int *order;
  char *name;
} stCsvRows;

/* Reads and checks a whole file (the bounded reader: at most ST_FILE_MAX bytes, no NUL byte);
 * ctx goes to schema->check. At least one row. ST_ERR_IO (the file), ST_ERR_PARSE (its text,
 * "FILE:LINE: ... (expected ...)"), ST_ERR_NOMEM. On failure rows is empty. */
ST_API stStatus st_csv_read(const char *path, const stCsvSchema *s, const void *ctx, stCsvRows *rows,
                     char *err, size_t errsz);

ST_API void st_csv_rows_free(stCsvRows *rows);

/* Row i in file order; row k in key order. */
ST_API const void *st_csv_row(const stCsvRows *rows, int i);
ST_API const void *st_csv_sorted(const stCsvRows *rows, int k);

/* Two rows of the schema by their first nkey columns (<0, 0, >0): names by strcmp, integers by
 * value. nkey <= s->nkey. */
ST_API int st_csv_compare(const stCsvSchema *s, int nkey, const void *a, const void *b);

/* A run of rows with the same first nkey columns: order[start..end), first the smallest row
 * index (the group's first line in the file). */
typedef struct stCsvGroup {
  int start, end, first;
} stCsvGroup;

/* The groups of the rows by their first nkey columns, in key order (O(n)); *groups freed with
 * free(). ST_ERR_NOMEM. */
ST_API stStatus st_csv_groups(const stCsvRows *rows, int nkey, stCsvGroup **groups, int *ngroups,
                       char *err, size_t errsz);

/* The group whose rows have the first nkey columns of row, by binary search; NULL for none. */
ST_API const stCsvGroup *st_csv_group_find(const stCsvRows *rows, int nkey, const stCsvGroup *groups,
                                    int ngroups, const void *row);

#ifdef __cplusplus
}
#endif

#endif
