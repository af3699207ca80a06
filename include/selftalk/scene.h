/* SPDX-License-Identifier: MIT
 * libselftalk: the scene of thesis §2.5 / SPEC §2 - table, object (sphere with a flattened
 * base), the four object positions and the targets, with their random offsets. A plain value
 * built from the [scene] keys; read-only afterwards. */
#ifndef SELFTALK_SCENE_H
#define SELFTALK_SCENE_H

#include "selftalk/config.h"
#include "selftalk/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_NOBJPOS 4 /* P0 front, P1 back, P2 left, P3 right of the centre */
#define ST_TARGET_GENERAL 2 /* target index of the generalisation test, between T0 and T1 */

/* How the initial postures are built (keys postures.*; see selftalk/postures.h). */
typedef struct stPostureDef {
  double reach_clearance;
  double open_near_ball_x;
  double open_near_gap;
  double open_near_oppose;
  double open_near_thumb;
  double open_near_fingers;
  double open_high_gap;
  double open_high_oppose;
  double open_high_flex;
  double grasp_gap;
  double grasp_ball_x;
  double grasp_oppose;
  double grasp_partial_oppose;
  double grasp_partial_flex;
  double grasp_partial_thumb_flex;
  double move_ball_x;
  double move_gap;
  double move_oppose;
  double move_squeeze;
  int move_min_fingers;
  double ik_torso_pitch, ik_wrist_prosup, ik_wrist_pitch; /* IK start of open, grasp, move, deg */
  double vary_offset, vary_tilt;                          /* postures.vary_*: m, deg */
  double vary_torso_pitch, vary_wrist_prosup, vary_wrist_pitch; /* the IK start's other end, deg */
  int vary_open_high; /* postures.vary_open_high: drawn open starts are all of k=2,3's kind */
  int reach_max_steps;
  int reach_palm_down; /* postures.reach_palm_down: the reach starts' palm faces the table too */
  double reach_height; /* fitness.reach_height: the reach point above the object centre */
} stPostureDef;

typedef struct stScene {
  double table_lo[3], table_hi[3]; /* table-top box, world frame */
  double table_top_z;
  double obj_radius, obj_mass, base_radius, base_height;
  double obj_rest_z;               /* sphere centre resting on the table */
  double obj_pos[ST_NOBJPOS][3];   /* resting object positions (sphere centres) */
  double target[3][3];             /* T0, T1, the generalisation test's target (keys
                                      posteval.generalisation_target_*) */
  double obj_offset, target_offset, target_radius;
  stPostureDef posture;            /* initial postures (SPEC §8) */
} stScene;

ST_API void st_scene_from_config(const stConfig *cfg, stScene *scene);

/* Object position k (0..3); with_offset adds the uniform x/y offset of reach trials. Nullable:
 * rng when with_offset is 0. */
ST_API void st_scene_object(const stScene *s, int k, int with_offset, stRng *rng, double pos[3]);

/* Target k (0, 1 or ST_TARGET_GENERAL) with its uniform x/y/z offset drawn from rng (nullable:
 * no offset). */
ST_API void st_scene_target(const stScene *s, int k, stRng *rng, double pos[3]);

#ifdef __cplusplus
}
#endif

#endif
