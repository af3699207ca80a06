/* SPDX-License-Identifier: MIT
 * The bounded reader every input file goes through (selftalk/io.h): content, the size limit,
 * devices that never end, directories, and NUL bytes in text (issue 17). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "selftalk/io.h"
#include "test_util.h"

static void test_io_read(void) {
  char path[256], err[512] = "";
  char *data = (char *)&data; /* must be reset */
  size_t len = 99;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".txt", "0123456789"));
  /* exactly the limit: read whole and NUL-terminated */
  CU_ASSERT_EQUAL_FATAL(st_file_read(path, 10, &data, &len, err, sizeof err), ST_OK);
  CU_ASSERT_EQUAL(len, 10);
  CU_ASSERT_STRING_EQUAL(data, "0123456789");
  free(data);
  /* one byte over the limit: refused, nothing handed back */
  data = (char *)&data;
  CU_ASSERT_EQUAL(st_file_read(path, 9, &data, &len, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_PTR_NULL(data);
  CU_ASSERT_EQUAL(len, 0);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, ": larger than 9 bytes (expected an input file of at most 9 bytes)");
  /* an empty file is a file */
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".txt", ""));
  CU_ASSERT_EQUAL_FATAL(st_file_read(path, 10, &data, &len, err, sizeof err), ST_OK);
  CU_ASSERT(len == 0 && data[0] == 0);
  free(data);
}

/* a file larger than the buffer's first guess grows it, up to the byte */
static void test_io_read_large(void) {
  const size_t n = 300000;
  char *big = malloc(n), path[256], err[256];
  for (size_t i = 0; i < n; i++) big[i] = (char)('a' + i % 26);
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".txt", big, n));
  char *data;
  size_t len;
  CU_ASSERT_EQUAL_FATAL(st_file_read(path, n, &data, &len, err, sizeof err), ST_OK);
  CU_ASSERT(len == n && !memcmp(data, big, n) && data[n] == 0);
  free(data);
  CU_ASSERT_EQUAL(st_file_read(path, n - 1, &data, &len, err, sizeof err), ST_ERR_RANGE);
  free(big);
}

/* /dev/zero never ends: refused at the limit (64 MiB), not read until memory runs out;
 * a directory, and a missing file, are refused with the system's reason */
static void test_io_read_refusals(void) {
  char *data, err[512], dir[256];
  size_t len;
  CU_ASSERT_EQUAL(st_file_read("/dev/zero", ST_FILE_MAX, &data, &len, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_STRING_EQUAL(err, "/dev/zero: larger than 64 MiB (expected an input file of at most "
                              "67108864 bytes)");
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  CU_ASSERT_EQUAL(st_file_read(dir, ST_FILE_MAX, &data, &len, err, sizeof err), ST_ERR_IO);
  ST_ASSERT_CONTAINS(err, ": cannot read: Is a directory");
  CU_ASSERT_EQUAL(st_file_read("/nonexistent/f", 10, &data, &len, err, sizeof err), ST_ERR_IO);
  CU_ASSERT_STRING_EQUAL(err, "/nonexistent/f: cannot open: No such file or directory");
}

static int exists(const char *dir, const char *name) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return access(p, F_OK) == 0;
}

/* st_atomic_clean removes what killed writers of one file left ("<file>.tmp.<pid>"), not this
 * process's own temporary, not other files' and not names that only look alike */
static void test_io_atomic_clean(void) {
  char dir[256], own[64], path[320];
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  snprintf(own, sizeof own, "f.csv.tmp.%ld", (long)getpid());
  const char *names[] = {"f.csv", "f.csv.tmp.12", "f.csv.tmp.999999", own, "f.csv.tmp.",
                         "f.csv.tmp.1x", "f.csv.tmpx.3", "g.csv.tmp.12", "xf.csv.tmp.12"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    FILE *f = fopen(path, "w");
    CU_ASSERT_PTR_NOT_NULL_FATAL(f);
    fclose(f);
  }
  snprintf(path, sizeof path, "%s/f.csv", dir);
  CU_ASSERT_EQUAL(st_atomic_clean(path), 2);
  CU_ASSERT(!exists(dir, "f.csv.tmp.12") && !exists(dir, "f.csv.tmp.999999"));
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (strcmp(names[i], "f.csv.tmp.12") && strcmp(names[i], "f.csv.tmp.999999"))
      CU_ASSERT(exists(dir, names[i]));
  CU_ASSERT_EQUAL(st_atomic_clean(path), 0);
  CU_ASSERT_EQUAL(st_atomic_clean("/nonexistent/dir/f.csv"), -1);
}

static void test_io_text_check(void) {
  char err[256] = "";
  CU_ASSERT_EQUAL(st_text_check("t", "ab\ncd", 5, err, sizeof err), ST_OK);
  /* the NUL is the 3rd character of line 2 */
  CU_ASSERT_EQUAL(st_text_check("t", "ab\ncd\0e\n", 8, err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT_STRING_EQUAL(err, "t:2: NUL byte at column 3 (expected a text file)");
  CU_ASSERT_EQUAL(st_text_check("t", "\0", 1, err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT_STRING_EQUAL(err, "t:1: NUL byte at column 1 (expected a text file)");
}

/* st_text_read: the bounded reader, then the NUL check, with their messages */
static void test_io_text_read(void) {
  char path[256], err[256] = "", *text = NULL;
  size_t len = 0;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".txt", "a\nb\n", 4));
  CU_ASSERT_EQUAL_FATAL(st_text_read(path, 10, &text, &len, err, sizeof err), ST_OK);
  CU_ASSERT(len == 4 && !strcmp(text, "a\nb\n"));
  free(text);
  CU_ASSERT_EQUAL(st_text_read(path, 3, &text, &len, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT(text == NULL && len == 0);
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".txt", "a\nb\0\n", 4));
  CU_ASSERT_EQUAL(st_text_read(path, 10, &text, &len, err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT(text == NULL && len == 0);
  ST_ASSERT_CONTAINS(err, ":2: NUL byte at column 2 (expected a text file)");
}

void st_suite_io(void) {
  ST_ADD_SUITE("io");
  ST_ADD_TEST(test_io_read);
  ST_ADD_TEST(test_io_read_large);
  ST_ADD_TEST(test_io_read_refusals);
  ST_ADD_TEST(test_io_atomic_clean);
  ST_ADD_TEST(test_io_text_check);
  ST_ADD_TEST(test_io_text_read);
}
