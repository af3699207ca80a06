/* SPDX-License-Identifier: MIT
 * The caretaker's word sequence on a synthetic trajectory (thesis §2.9.3). */
#include "selftalk/caretaker.h"
#include "test_util.h"

/* a default caretaker and an empty state */
static void setup(stFitnessDef *d, stCaretaker *c, stQuantities *q, stContacts *k) {
  stConfig cfg;
  st_config_default(&cfg);
  st_fitness_def_from_config(&cfg, d);
  st_caretaker_init(c, &cfg);
  memset(q, 0, sizeof *q);
  memset(k, 0, sizeof *k);
}

static void test_caretaker_sequence(void) {
  stFitnessDef d;
  stCaretaker c;
  stQuantities q;
  stContacts k;
  setup(&d, &c, &q, &k);
  q.d_r = 0.2;
  q.h = 1.0;
  q.p = 0.5;
  /* silent at step 0, then reach */
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 0, &q, &k), -1);
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 1, &q, &k), ST_PRIM_REACH);
  /* reach done (d_r < 0.03) but the palm not down: open */
  q.d_r = 0.02;
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 2, &q, &k), ST_PRIM_OPEN);
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 3, &q, &k), ST_PRIM_OPEN);
  /* palm down with the hand open: grasp */
  q.p = 0.95;
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 4, &q, &k), ST_PRIM_GRASP);
  /* two touches are not a grasp, three are */
  k.touch_object[0] = k.touch_object[5] = 1;
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 5, &q, &k), ST_PRIM_GRASP);
  k.touch_object[1] = 1;
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 6, &q, &k), ST_PRIM_MOVE);
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 7, &q, &k), ST_PRIM_MOVE); /* move stays */
  CU_ASSERT_EQUAL(c.switch_step[ST_PRIM_OPEN], 2);
  CU_ASSERT_EQUAL(c.given[ST_PRIM_OPEN], 2);
  CU_ASSERT_EQUAL(c.given[ST_PRIM_MOVE], 2);
}

/* open is jumped when its condition already holds as reach ends */
static void test_caretaker_jump(void) {
  stFitnessDef d;
  stCaretaker c;
  stQuantities q;
  stContacts k;
  setup(&d, &c, &q, &k);
  q.d_r = 0.2;
  q.h = 0.9;
  q.p = 0.95;
  st_caretaker_word(&c, &d, 0, &q, &k);
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 1, &q, &k), ST_PRIM_REACH);
  q.d_r = 0.01;
  CU_ASSERT_EQUAL(st_caretaker_word(&c, &d, 2, &q, &k), ST_PRIM_GRASP);
  CU_ASSERT_EQUAL(c.switch_step[ST_PRIM_OPEN], -1); /* never given */
  CU_ASSERT_EQUAL(c.given[ST_PRIM_OPEN], 0);
}

void st_suite_caretaker(void) {
  ST_ADD_SUITE("caretaker");
  ST_ADD_TEST(test_caretaker_sequence);
  ST_ADD_TEST(test_caretaker_jump);
}
