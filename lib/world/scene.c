/* SPDX-License-Identifier: MIT */
#include "selftalk/scene.h"

#include <string.h>

#include "core/internal.h"

void st_scene_from_config(const stConfig *c, stScene *s) {
  ST_ASSERT(c && s);
  memset(s, 0, sizeof *s);
  s->table_top_z = c->scene_table_top_z;
  s->table_lo[0] = c->scene_table_x_min;
  s->table_lo[1] = c->scene_table_y_min;
  s->table_lo[2] = c->scene_table_top_z - c->scene_table_thickness;
  s->table_hi[0] = c->scene_table_x_max;
  s->table_hi[1] = c->scene_table_y_max;
  s->table_hi[2] = c->scene_table_top_z;
  s->obj_radius = c->scene_object_radius;
  s->obj_mass = c->scene_object_mass;
  s->base_radius = c->scene_object_base_radius;
  s->base_height = c->scene_object_base_height;
  s->obj_rest_z = c->scene_table_top_z + c->scene_object_radius;
  /* front, back, left, right of the centre (SPEC §2: P0..P3) */
  static const double dir[ST_NOBJPOS][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int k = 0; k < ST_NOBJPOS; k++) {
    s->obj_pos[k][0] = c->scene_object_center_x + dir[k][0] * c->scene_object_spacing;
    s->obj_pos[k][1] = c->scene_object_center_y + dir[k][1] * c->scene_object_spacing;
    s->obj_pos[k][2] = s->obj_rest_z;
  }
  for (int k = 0; k < 2; k++) {
    s->target[k][0] = c->scene_target_x;
    s->target[k][1] = k == 0 ? c->scene_target_y : -c->scene_target_y;
    s->target[k][2] = c->scene_target_z;
  }
  /* the generalisation test's, "in between the two trained ones" (thesis 2.10.3) */
  s->target[ST_TARGET_GENERAL][0] = c->posteval_generalisation_target_x;
  s->target[ST_TARGET_GENERAL][1] = c->posteval_generalisation_target_y;
  s->target[ST_TARGET_GENERAL][2] = c->posteval_generalisation_target_z;
  s->obj_offset = c->scene_object_offset;
  s->target_offset = c->scene_target_offset;
  s->target_radius = c->scene_target_radius;
  s->posture.reach_clearance = c->postures_reach_clearance;
  s->posture.open_near_ball_x = c->postures_open_near_ball_x;
  s->posture.open_near_gap = c->postures_open_near_gap;
  s->posture.open_near_oppose = c->postures_open_near_oppose;
  s->posture.open_near_thumb = c->postures_open_near_thumb;
  s->posture.open_near_fingers = c->postures_open_near_fingers;
  s->posture.open_high_gap = c->postures_open_high_gap;
  s->posture.open_high_oppose = c->postures_open_high_oppose;
  s->posture.open_high_flex = c->postures_open_high_flex;
  s->posture.grasp_gap = c->postures_grasp_gap;
  s->posture.grasp_ball_x = c->postures_grasp_ball_x;
  s->posture.grasp_oppose = c->postures_grasp_oppose;
  s->posture.grasp_partial_oppose = c->postures_grasp_partial_oppose;
  s->posture.grasp_partial_flex = c->postures_grasp_partial_flex;
  s->posture.grasp_partial_thumb_flex = c->postures_grasp_partial_thumb_flex;
  s->posture.move_ball_x = c->postures_move_ball_x;
  s->posture.move_gap = c->postures_move_gap;
  s->posture.move_oppose = c->postures_move_oppose;
  s->posture.move_squeeze = c->postures_move_squeeze;
  s->posture.move_min_fingers = c->postures_move_min_fingers;
  s->posture.ik_torso_pitch = c->postures_ik_torso_pitch;
  s->posture.ik_wrist_prosup = c->postures_ik_wrist_prosup;
  s->posture.ik_wrist_pitch = c->postures_ik_wrist_pitch;
  s->posture.vary_offset = c->postures_vary_offset;
  s->posture.vary_tilt = c->postures_vary_tilt;
  s->posture.vary_torso_pitch = c->postures_vary_torso_pitch;
  s->posture.vary_wrist_prosup = c->postures_vary_wrist_prosup;
  s->posture.vary_wrist_pitch = c->postures_vary_wrist_pitch;
  s->posture.vary_open_high = c->postures_vary_open_high;
  s->posture.reach_max_steps = c->postures_reach_max_steps;
  s->posture.reach_palm_down = c->postures_reach_palm_down;
  s->posture.reach_height = c->fitness_reach_height;
}

void st_scene_object(const stScene *s, int k, int with_offset, stRng *rng, double pos[3]) {
  ST_ASSERT(s && pos);
  ST_ASSERT(k >= 0 && (size_t)k < sizeof s->obj_pos / sizeof s->obj_pos[0]);
  ST_ASSERT(!with_offset || rng);
  memcpy(pos, s->obj_pos[k], sizeof s->obj_pos[k]);
  if (with_offset) {
    pos[0] += st_rng_range(rng, -s->obj_offset, s->obj_offset);
    pos[1] += st_rng_range(rng, -s->obj_offset, s->obj_offset);
  }
}

void st_scene_target(const stScene *s, int k, stRng *rng, double pos[3]) {
  ST_ASSERT(s && pos);
  ST_ASSERT(k >= 0 && (size_t)k < sizeof s->target / sizeof s->target[0]);
  memcpy(pos, s->target[k], sizeof s->target[k]);
  if (rng)
    for (int i = 0; i < 3; i++) pos[i] += st_rng_range(rng, -s->target_offset, s->target_offset);
}
