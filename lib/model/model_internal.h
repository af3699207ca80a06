/* SPDX-License-Identifier: MIT
 * libselftalk: internals of the robot model shared by lib/model/model.c, the URDF importer
 * (lib/model/model_urdf.cpp) and the URDF fuzz target; not installed. */
#ifndef SELFTALK_MODEL_INTERNAL_H
#define SELFTALK_MODEL_INTERNAL_H

#include "selftalk/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Allocates a model whose struct and every array live in ONE zeroed allocation (buffer_),
 * sized for the given counts (each >= 0; nbody >= 1). Arrays of length 0 get a valid but
 * non-dereferenceable pointer. Defaults: body_parent -1, jnt_type ST_JOINT_FIXED, jnt_rot and
 * geom_rot identity, jnt_mimic -1, jnt_mimic_mult 1, everything else 0 / empty names.
 * Returns NULL on a bad count or when out of memory; free with st_model_destroy. */
stModel *st__model_alloc(int nbody, int ngeom, int nvert, int ntri);

/* Splits a config value "a, b,c" into at most max names (spaces around a name dropped);
 * returns how many names the list has (possibly more than max), -1 if one is empty or too
 * long (st__list_item: the lists of every config key are read alike). */
int st__split_names(const char *list, char names[][ST_NAME_MAX], int max);

/* st_model_load_urdf's importer (the readers' pattern, core/readers.h: st_file_read, then
 * this, which the unit tests and tests/fuzz/fuzz_urdf.c call directly): URDF text; relative
 * mesh paths are taken from dir. */
stStatus st__model_parse_urdf(const char *name, const char *dir, const char *text, size_t len,
                              stModel **model, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
