/* SPDX-License-Identifier: MIT */
#include "selftalk/study.h"

#include "core/internal.h"

#include <string.h>

static const char *const g_primitives[ST_NPRIM] = {"reach", "open", "grasp", "move"};
static const char *const g_stages[ST_STAGE_COUNT] = {"simple-prim", "main-prim"};
static const char *const g_tests[ST_POST_NTESTS] = {"integration", "robustness", "generalisation"};

const char *st_primitive_name(int p) { return p >= 0 && p < ST_NPRIM ? g_primitives[p] : "?"; }

int st_primitive_parse(const char *name, size_t len) {
  ST_ASSERT(name);
  for (int p = 0; p < ST_NPRIM; p++)
    if (len == strlen(g_primitives[p]) && !strncmp(name, g_primitives[p], len)) return p;
  return -1;
}

const char *st_stage_name(stStage s) {
  return (int)s >= 0 && s < ST_STAGE_COUNT ? g_stages[s] : "?";
}

const char *st_post_test_name(stPostTest t) {
  return (int)t >= 0 && t < ST_POST_NTESTS ? g_tests[t] : "?";
}

int st_post_test_parse(const char *name) {
  ST_ASSERT(name);
  for (int t = 0; t < ST_POST_NTESTS; t++)
    if (!strcmp(name, g_tests[t])) return t;
  return -1;
}
