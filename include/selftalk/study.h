/* SPDX-License-Identifier: MIT
 * libselftalk: the study's named parts, counted and spelled here once: the four primitives
 * (whose words are the network's linguistic units and the prediction's words), the stages,
 * and the post-evaluation tests. In the simulator-free core, so the config reader, the
 * network and the simulator's layers all read the same names. */
#ifndef SELFTALK_STUDY_H
#define SELFTALK_STUDY_H

#include <stddef.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Primitives, in the order of the linguistic inputs (SPEC §4). */
enum { ST_PRIM_REACH = 0, ST_PRIM_OPEN, ST_PRIM_GRASP, ST_PRIM_MOVE, ST_NPRIM };

/* "reach", "open", "grasp", "move"; "?" for anything else. */
ST_API const char *st_primitive_name(int primitive);

/* The primitive named by the len characters at name, or -1. */
ST_API int st_primitive_parse(const char *name, size_t len);

/* The stages whose trials are scored per primitive. */
typedef enum stStage { ST_STAGE_SIMPLE = 0, ST_STAGE_MAIN, ST_STAGE_COUNT } stStage;

/* "simple-prim", "main-prim"; "?" for anything else. */
ST_API const char *st_stage_name(stStage stage);

/* The integrated stage (thesis §2.9), which is not an stStage: its trials are not per
 * primitive. */
#define ST_INTEGRATED_STAGE_NAME "integrated"

/* The post-evaluation tests (thesis §2.10). */
typedef enum stPostTest {
  ST_POST_INTEGRATION = 0,
  ST_POST_ROBUSTNESS,
  ST_POST_GENERALISATION,
  ST_POST_NTESTS
} stPostTest;

/* "integration", "robustness", "generalisation"; "?" for anything else. */
ST_API const char *st_post_test_name(stPostTest test);
/* The test named, or -1. */
ST_API int st_post_test_parse(const char *name);

#ifdef __cplusplus
}
#endif

#endif
