/* SPDX-License-Identifier: MIT
 * libselftalk: the experiment configuration.
 *
 * Configs are the experiment: every number of the protocol is a key of ST_CONFIG_KEYS below,
 * with the thesis's value as default. The one table drives the struct, the defaults, the INI
 * parser, validation, st_config_write() (the resolved config saved beside every run) and the
 * key reference (st_config_help()).
 *
 * INI files: "[section]" lines and "key = value" lines; '#' and ';' start comments. Errors
 * read "FILE:LINE: key 'section.key': problem (expected ...)". Owns nothing on the heap. */
#ifndef SELFTALK_CONFIG_H
#define SELFTALK_CONFIG_H

#include <stdint.h>
#include <stdio.h>

#include "selftalk/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_CONFIG_STR_MAX 256

/* What a key is: its tier (st_config_key_tier, from ST_CONFIG_TIERS below the table).
 * --help-config and config.ini group the keys by tier, and a run's keys away from their
 * defaults in every tier but RUN are how it departs from the thesis's protocol
 * (tools/run_report.py, tools/replicate_report.py's report.md). */
typedef enum stConfigTier {
  ST_TIER_PROTOCOL = 0, /* the thesis's protocol, and our decision where it leaves one open
                           (docs/PROTOCOL.md): the defaults are that protocol */
  ST_TIER_RUN,          /* what one run of the protocol is: its seed, stages, starting
                           populations, condition (Table 2.1); runs differ in them within it */
  ST_TIER_EXTENSION,    /* ours, not the thesis's (the chain stage's trials, palm-down and drawn
                           starts): off at their defaults */
  ST_TIER_DIAGNOSTIC,   /* for looking into a result, not for results */
  ST_TIER_SPEED,        /* how fast, not what: the same results, or the same up to rounding */
  ST_TIER_COUNT
} stConfigTier;

/* The key table. Each row: section, key, default, then
 *   INT / REAL: min, max, help     BOOL: help
 *   ENUM: choices "a|b|c" (the field holds the index), help     STR: help */
#define ST_CONFIG_KEYS(INT, REAL, BOOL, ENUM, STR)                                               \
  INT(run, seed, 1, 0, 2147483647, "run seed; keys every random stream (GA, trial offsets)")     \
  ENUM(run, rng_seed, 0, "plain|apart", "how run.seed keys the streams: plain, as a stream number is (seed a's stream b is seed b's stream a); apart, as seed + 2^32, no run's stream another's (PROTOCOL)") \
  INT(run, threads, 0, 0, 1024, "evaluation threads; 0 = one per core (results do not depend on it)") \
  ENUM(network, arch, 0, "base|A|B", "network architecture: base (primitive stages), A (self talk), B (hidden linguistic memory)") \
  REAL(network, lambda, 1.5, 0.01, 100.0, "sigmoid slope: sigma(x) = 1/(1+exp(-lambda x)) (thesis eq. 2.1)") \
  REAL(network, gamma_a, 1.0, 0.0, 1000.0, "gain of the type A linguistic output units (eq. 2.13)") \
  REAL(network, gamma_b, 10.0, 0.0, 1000.0, "gain of the type B hidden-linguistic units (eq. 2.13)") \
  REAL(network, focus_scale, 20.0, 0.0, 1000.0, "focus-vector input = (focus point - palm centre) in metres times this (thesis 2.3.5)") \
  REAL(network, focus_threshold, 0.5, 0.0, 1.0, "focus output below this selects the object, else the target (thesis 2.3.2)") \
  REAL(network, linguistic_input, 10.0, 0.0, 1000.0, "value of the linguistic input of the word being given (thesis 2.3.6)") \
  REAL(network, secondary_input, 10.0, 0.0, 1000.0, "value of the secondary input move-object-to-target while given (thesis 2.9.1)") \
  INT(network, typeb_init_gene, 32768, 0, 65535, "initial gene of the type B hidden-linguistic -> hidden block (32768: v = 1/65535, near zero)") \
  INT(ga, population, 100, 2, 100000, "genotypes per generation (thesis 2.4)")                   \
  INT(ga, elites, 10, 0, 100000, "best genotypes copied unchanged into the next generation")     \
  INT(ga, parents, 20, 1, 100000, "best genotypes that breed; children are assigned round-robin") \
  REAL(ga, mutation_rate, 0.005, 0.0, 1.0, "bit-flip probability per mutable bit, primitive stages") \
  REAL(ga, mutation_rate_integrated, 0.04, 0.0, 1.0, "bit-flip probability per mutable (new) bit, integrated stage") \
  INT(ga, success_genotypes, 5, 1, 100000, "primitive stages end when this many genotypes succeed in every trial") \
  INT(ga, max_generations, 1500, 1, 10000000, "primitive stages (both together) stop after this many generations") \
  INT(ga, integrated_generations, 100, 1, 10000000, "generations of the integrated stage")      \
  STR(robot, urdf, "data/icub_left_arm.urdf", "robot model (URDF); relative paths are from the working directory") \
  STR(robot, dof_joints, "torso_yaw,torso_pitch,l_shoulder_pitch,l_shoulder_roll,l_shoulder_yaw,l_elbow,l_wrist_prosup,l_wrist_pitch,l_wrist_yaw,l_thumb_oppose,l_thumb_proximal,l_index_proximal", "the 12 actuated DOF in SPEC order: the master joint of each (coupled joints mimic it)") \
  STR(robot, touch_links, "l_thumb_3,l_index_3,l_middle_3,l_ring_3,l_little_3,l_hand", "links of the 6 touch sensors: thumb, index, middle, ring, little fingertip, palm") \
  STR(robot, tip_frames, "l_thumb_tip,l_index_tip,l_middle_tip,l_ring_tip,l_little_tip", "fingertip points: thumb, index, middle, ring, little") \
  STR(robot, palm_frame, "l_palm_center", "frame at the centre of the palm's inner surface, +z = outward palm normal") \
  STR(robot, arm_first_link, "l_shoulder_1", "first link of the arm: it and its descendants are the arm and hand (table penalty, touch)") \
  REAL(robot, torso_min_deg, -10.0, -90.0, 90.0, "lower limit of torso yaw and pitch (thesis 2.2), degrees") \
  REAL(robot, torso_max_deg, 40.0, -90.0, 90.0, "upper limit of torso yaw and pitch (thesis 2.2), degrees") \
  REAL(robot, alpha_kinematic, 37.0, 0.0, 10000.0, "joint velocity = alpha (y - qhat) degrees/s, kinematic mode (thesis 2.3.1)") \
  REAL(robot, alpha_dynamic, 100.0, 0.0, 10000.0, "joint velocity = alpha (y - qhat) degrees/s, dynamic mode (thesis 2.3.1)") \
  REAL(robot, max_velocity_deg, 40.0, 0.0, 1000.0, "joint speed limit, degrees/s (thesis 2.3.1)") \
  REAL(robot, control_dt, 0.05, 0.001, 1.0, "control step, seconds (thesis 2.1: 20 steps = 1 s)") \
  REAL(scene, table_top_z, -0.08, -1.0, 1.0, "height of the table top in the world frame (waist = 0), m") \
  REAL(scene, table_x_min, 0.10, -2.0, 2.0, "table near edge, m (50 cm deep)") \
  REAL(scene, table_x_max, 0.60, -2.0, 2.0, "table far edge, m") \
  REAL(scene, table_y_min, -0.30, -2.0, 2.0, "table right edge, m (80 cm wide)") \
  REAL(scene, table_y_max, 0.50, -2.0, 2.0, "table left edge, m") \
  REAL(scene, table_thickness, 0.03, 0.001, 1.0, "table top thickness, m") \
  REAL(scene, object_radius, 0.035, 0.001, 0.5, "object sphere radius, m (7 cm diameter, thesis 2.5.1)") \
  REAL(scene, object_mass, 0.2, 0.001, 10.0, "object mass, kg") \
  REAL(scene, object_base_radius, 0.0175, 0.0, 0.5, "flattened base: cylinder radius, m (3.5 cm diameter)") \
  REAL(scene, object_base_height, 0.015, 0.0, 0.5, "flattened base: cylinder height, m; its bottom is flush with the sphere's lowest point") \
  REAL(scene, object_center_x, 0.30, -2.0, 2.0, "centre of the four object positions, x, m (30 cm in front)") \
  REAL(scene, object_center_y, 0.10, -2.0, 2.0, "centre of the four object positions, y, m (10 cm to the left)") \
  REAL(scene, object_spacing, 0.10, 0.0, 1.0, "object positions lie this far front/back/left/right of the centre, m") \
  REAL(scene, object_offset, 0.02, 0.0, 0.5, "uniform offset on x and y of the object in trials that start with reach, m") \
  REAL(scene, target_x, 0.25, -2.0, 2.0, "targets: x, m (25 cm in front)") \
  REAL(scene, target_y, 0.10, -2.0, 2.0, "targets: T0 at +y, T1 at -y, m") \
  REAL(scene, target_z, 0.17, -2.0, 2.0, "targets: z, m (25 cm above the table)") \
  REAL(scene, target_offset, 0.02, 0.0, 0.5, "uniform offset on x, y and z of the target every trial, m") \
  REAL(scene, target_radius, 0.06, 0.0, 1.0, "the target is reached when the object centre is this close, m") \
  REAL(fitness, reach_height, 0.095, 0.0, 1.0, "d_r is measured to the point this far above the object centre, m (6 cm above the sphere)") \
  REAL(fitness, penalty_table, 1.0, 0.0, 100.0, "penalty per step with any arm or hand part on the table") \
  REAL(fitness, penalty_object, 1.0, 0.0, 100.0, "penalty per step with any robot part on the object") \
  REAL(fitness, move_free, 0.02, 0.0, 1.0, "object displacement below this is not penalised, m") \
  REAL(fitness, move_scale, 0.1, 0.0001, 10.0, "object-moving penalty = displacement / this (in decimetres), m") \
  REAL(fitness, move_max, 2.0, 0.0, 100.0, "object-moving penalty cap per step") \
  REAL(fitness, focus_weight, 0.2, 0.0, 1.0, "eq. 2.4: S = w f_f + (1 - w) s_p when the focus is correct, w f_f otherwise") \
  REAL(fitness, decay, 10.0, 0.0, 1000.0, "distance terms are exp(-decay d) (eq. 2.5-2.8, 2.12), 1/m") \
  REAL(fitness, open_h, 0.7, 0.01, 1.0, "open: openness the step fitness peaks at and the success needs (h > this; eq. 2.6)") \
  REAL(fitness, grasp_h, 0.4, 0.0, 0.99, "grasp: openness the step fitness peaks at and the success needs (h < this; eq. 2.7)") \
  REAL(fitness, success_dist, 0.03, 0.0, 1.0, "reach/open (d_r), grasp (d_g), simplified move (d_mhat) succeed below this, m") \
  REAL(fitness, palm_down, 0.9, 0.0, 1.0, "open and grasp success need p above this") \
  REAL(fitness, bonus, 10.0, 0.0, 1000.0, "bonus per successful trial (eq. 2.3)") \
  REAL(fitness, scale, 100.0, 0.0, 10000.0, "F_p = B_p + scale / N_p * sum(S - P) (eq. 2.3)") \
  REAL(fitness, fp_min, 0.001, 1e-9, 1.0, "each F_p is clamped to at least this before the harmonic mean (SPEC 7)") \
  REAL(fitness, fail_penalty, 4.0, 0.0, 100.0, "a trial ended early by failure scores S = 0, P = this for every remaining step") \
  INT(fitness, reach_hold_steps, 20, 0, 100000, "main-prim reach ends with success this many steps after the reach point was first reached") \
  REAL(fitness, move_touch, 0.1, 0.0, 1.0, "eq. 2.12: step fitness while touching the object") \
  REAL(fitness, move_lift, 0.1, 0.0, 1.0, "eq. 2.12: step fitness while the object is lifted") \
  REAL(fitness, move_lift_dist, 0.8, 0.0, 1.0, "eq. 2.12: weight of exp(-decay d_m) while lifted") \
  ENUM(stage, stages, 0, "simple_prim|main_prim|prims|integrated", "what evolve runs: simple-prim, main-prim, both in sequence (thesis 2.7-2.8), or the integrated stage (2.9)") \
  STR(stage, init_population, "", "population file to start from (main_prim); empty: random genotypes") \
  STR(stage, primitives, "reach,open,grasp,move", "primitives whose 4 trials are evaluated, comma-separated; F is the harmonic mean over these (diagnostic: the thesis evaluates all four)") \
  INT(stage, simple_steps, 60, 1, 100000, "simple-prim trial length, control steps (3 s)") \
  INT(stage, main_reach_steps, 100, 1, 100000, "main-prim reach trial length (5 s)") \
  INT(stage, main_open_steps, 60, 1, 100000, "main-prim open trial length (3 s)") \
  INT(stage, main_grasp_steps, 80, 1, 100000, "main-prim grasp trial length (4 s)") \
  INT(stage, main_move_steps, 70, 1, 100000, "main-prim move trial length (3.5 s)") \
  INT(stage, grasp_table_off_step, 40, 0, 100000, "main-prim grasp: object-table collision off after this many steps") \
  INT(stage, move_table_off_step, 10, 0, 100000, "main-prim move: object-table collision off after this many steps") \
  BOOL(stage, handover, 0, "main-prim adds 12 hand-over trials: open, grasp, move from where the caretaker hands over to each in the individual's own chain (SPEC 12, docs/PROTOCOL.md; not the thesis's); false: its 16") \
  INT(stage, chain_trials, 0, 0, 32, "main-prim adds this many chained trials (the integrated stage's table, the caretaker's words) scored by eq. 2.14 into F_chain (SPEC 12; 0: the thesis)") \
  ENUM(stage, chain_combine, 0, "harmonic|sum", "how F_chain joins main-prim's F: harmonic, a 5th term of the harmonic mean; sum, added to the harmonic mean of the four F_p, weighted by chain_gate (docs/PROTOCOL.md)") \
  REAL(stage, chain_gate, 0.0, 0.0, 64.0, "chain_combine = sum: F_chain is weighted by (fixed trials solved / fixed trials evaluated, 16 with every primitive)^chain_gate, so that selection keeps the thesis's 16 trials solved; 0: unweighted") \
  ENUM(stage, chain_complete, 0, "all|fixed_chained", "what a genotype solves to count towards ga.success_genotypes with chained trials: all, every trial; fixed_chained, the fixed and the chained ones") \
  REAL(stage, chain_progress, 0.0, 0.0, 1000.0, "F_chain adds this times the mean of how far the caretaker got in the chained trials (reach 0 .. move 3): a shaping term, not the thesis's (docs/PROTOCOL.md); 0: eq. 2.14 alone") \
  BOOL(stage, handover_fallback, 0, "a hand-over trial whose chain never hands over: true, runs from the fixed posture; false, scores 0 over its length (a fallback it solves would reward a chain that breaks)") \
  ENUM(stage, handover_rollin, 0, "self|elite", "who acts a hand-over trial's roll-in: self, the individual's own chain; elite, the base network of genotype 0 (the previous generation's best) for every individual (docs/PROTOCOL.md)") \
  INT(stage, handover_rollin_steps, 170, 1, 100000, "hand-over trials: the caretaker must hand over within this many steps of the chain (integrated.steps 240 less main-prim move's 70); else see handover_fallback") \
  INT(caretaker, grasp_touches, 3, 1, 6, "the caretaker considers a grasp done when this many touch sensors touch the object (thesis 2.9.3)") \
  INT(caretaker, first_step, 1, 0, 100000, "first step at which the caretaker speaks (never at step 0, thesis 2.9.3)") \
  STR(integrated, populations, "", "integrated stage: primitive-stage population files (612 genes, best first), comma-separated; each item may be a glob pattern (expanded in sorted order)") \
  INT(integrated, top, 10, 1, 100000, "integrated stage: genotypes taken from the top of each population file (thesis 2.4: the top 10 of each of the 10 runs)") \
  ENUM(integrated, words_even, 1, "none|caretaker|selftalk", "what even trials (0, 2, 4, 6) hear: no words, the caretaker, or self talk (Table 2.1)") \
  ENUM(integrated, words_odd, 2, "none|caretaker|selftalk", "what odd trials hear (Table 2.1)") \
  ENUM(integrated, fitness_even, 1, "integrated|prediction", "fitness of even trials: integrated behaviour (eq. 2.14) or prediction (eq. 2.15-2.24; caretaker trials of a type A network) (Table 2.1)") \
  ENUM(integrated, fitness_odd, 0, "integrated|prediction", "fitness of odd trials (Table 2.1)") \
  BOOL(integrated, first_generation, 1, "the first generation hears the caretaker in every trial, scored by the integrated fitness with bonuses x first_bonus_factor (thesis 2.9.4.1: all conditions but NI)") \
  REAL(integrated, first_bonus_factor, 10.0, 0.0, 1000.0, "bonus multiplier of the first generation's integrated fitness (thesis 2.9.4.1)") \
  INT(integrated, trials, 8, 1, 32, "trials per individual; trial i has type k (integrated.trial_order): reach posture k, object position k, target k mod 2 (thesis 2.9, SPEC 10)") \
  ENUM(integrated, trial_order, 0, "mod4|pairs", "trial i's type k: i mod 4 (mod4), or (i div 2) mod 4, each type once in each parity (pairs); the thesis allows both (SPEC 13)") \
  INT(integrated, steps, 240, 1, 100000, "integrated trial length, control steps (12 s)") \
  INT(integrated, hold_steps, 20, 0, 100000, "a trial ends (S = 1 for the rest) when the object was within the target radius while lifted more than this many steps ago and is still lifted") \
  INT(integrated, focus_bonus_steps, 3, 1, 100000, "bonus when the object is lifted with the focus on the target for this many consecutive steps (thesis 2.9.4.1)") \
  ENUM(integrated, selftalk_gate, 0, "none|move|ahead", "diagnostic, not the thesis: self talk heard as said (none); *move* heard as *grasp* until the grasp holds (move); a word ahead of the caretaker's heard as his (ahead) (PROTOCOL)") \
  ENUM(integrated, fail_end, 0, "penalty|exact|runout", "object fell: penalty ends the trial (S 0, P fitness.fail_penalty after); exact ends it once the rest cannot change its result; runout never (PROTOCOL, Speed)") \
  INT(prediction, window, 20, 1, 100000, "steps looked back before a switch of the caretaker's word (eq. 2.18, 2.20)") \
  INT(prediction, bonus_window, 5, 0, 100000, "a switch predicted fewer than this many steps early earns the bonus (eq. 2.23)") \
  REAL(postures, reach_clearance, 0.15, 0.0, 2.0, "reach start: palm centre at least this far from every object position, m (SPEC 8)") \
  INT(postures, reach_max_steps, 40, 1, 100000, "reach start: a bang-bang IK controller in kinematic mode reaches the reach point within this many steps (2 s of the 3 s trial: thesis 2.7, enough time from every start) ") \
  BOOL(postures, reach_palm_down, 0, "reach start: the palm also turned to face the table (p > 0.85), so a reach keeping it arrives opened and open can be jumped (thesis 3.1.1); off: position only (PROTOCOL.md)") \
  REAL(postures, open_near_ball_x, 0.02, -0.2, 0.2, "open k=0,1: ball centre ahead of the palm centre along the fingers, m") \
  REAL(postures, open_near_gap, 0.015, -0.1, 0.3, "open k=0,1: palm above the ball top, m (hand around the ball, almost grasping)") \
  REAL(postures, open_near_oppose, 0.5, 0.0, 1.0, "open k=0,1: thumb opposition, normalised") \
  REAL(postures, open_near_thumb, 0.15, 0.0, 1.0, "open k=0,1: thumb flexion, normalised") \
  REAL(postures, open_near_fingers, 0.35, 0.0, 1.0, "open k=0,1: finger flexion, normalised") \
  REAL(postures, open_high_gap, 0.04, 0.0, 0.3, "open k=2,3: palm centred this far above the ball top, m") \
  REAL(postures, open_high_oppose, 0.5, 0.0, 1.0, "open k=2,3: thumb opposition, normalised") \
  REAL(postures, open_high_flex, 0.8, 0.0, 1.0, "open k=2,3: thumb and finger flexion (hand almost closed), normalised") \
  REAL(postures, grasp_gap, 0.03, 0.0, 0.3, "grasp: palm down, this far above the ball top, m") \
  REAL(postures, grasp_ball_x, 0.0, -0.2, 0.2, "grasp: ball centre ahead of the palm centre along the fingers, m (0: palm centred over the ball; the move posture holds it at move_ball_x)") \
  REAL(postures, grasp_oppose, 0.9, 0.0, 1.0, "grasp k=0,1: thumb opposition (fingers fully extended)") \
  REAL(postures, grasp_partial_oppose, 0.5, 0.0, 1.0, "grasp k=2,3: thumb opposition") \
  REAL(postures, grasp_partial_flex, 0.25, 0.0, 1.0, "grasp k=2,3: finger flexion (partly extended)") \
  REAL(postures, grasp_partial_thumb_flex, 0.0, 0.0, 1.0, "grasp k=2,3: thumb flexion (the thesis gives only the fingers)") \
  REAL(postures, move_ball_x, 0.035, -0.2, 0.2, "move: ball centre ahead of the palm centre along the fingers, m (0.035: the thumb closes below the equator, so the grasp holds in dynamic mode)") \
  REAL(postures, move_gap, -0.001, -0.05, 0.1, "move: palm above the ball top, m (negative: pressing on it)") \
  REAL(postures, move_oppose, 0.8, 0.0, 1.0, "move: thumb opposition, normalised (0.8: holds the ball for 3 s in dynamic mode; 0.5 let it fall)") \
  REAL(postures, move_squeeze, 0.02, 0.0, 1.0, "move: extra flexion after the thumb and fingers first touch the ball (grip)") \
  INT(postures, move_min_fingers, 3, 1, 4, "move: fingers close until this many fingertips (besides the thumb) touch the ball") \
  REAL(postures, ik_torso_pitch, 0.0, -22.0, 70.0, "open, grasp, move: torso pitch the inverse kinematics starts from, deg (it keeps close to it: the solution is the arm configuration near this start)") \
  REAL(postures, ik_wrist_prosup, 80.0, -90.0, 90.0, "open, grasp, move: wrist pronation-supination the inverse kinematics starts from, deg") \
  REAL(postures, ik_wrist_pitch, -30.0, -90.0, 0.0, "open, grasp, move: wrist pitch the inverse kinematics starts from, deg") \
  BOOL(postures, vary_starts, 0, "open and grasp trials of the primitive stages start from postures drawn per generation and trial (docs/PROTOCOL.md, Varied starts); false: the fixed postures") \
  ENUM(postures, vary_trials, 0, "replace|extra", "vary_starts: replace, the open and grasp trials start from drawn postures; extra, they keep theirs and main-prim has 8 trials more from drawn ones (PROTOCOL.md)") \
  INT(postures, vary_replace_generations, 0, 0, 1000000, "vary_trials = extra: main-prim's first N generations run as replace, no genotype completing (PROTOCOL.md); 0: extra from the first") \
  REAL(postures, vary_offset, 0.02, 0.0, 0.1, "vary_starts: the palm moves horizontally, in its own frame, by up to this, m (uniform in a disc; the reach trials' object offset is +-2 cm)") \
  REAL(postures, vary_tilt, 20.0, 0.0, 45.0, "vary_starts: the palm normal tilts from straight down by up to this, deg (angle uniform, direction uniform)") \
  REAL(postures, vary_torso_pitch, 20.0, -22.0, 70.0, "vary_starts: the IK start's torso pitch is uniform between ik_torso_pitch and this, deg") \
  REAL(postures, vary_wrist_prosup, 0.0, -90.0, 90.0, "vary_starts: the IK start's wrist pronation-supination is uniform between ik_wrist_prosup and this, deg") \
  REAL(postures, vary_wrist_pitch, -45.0, -90.0, 0.0, "vary_starts: the IK start's wrist pitch is uniform between ik_wrist_pitch and this, deg") \
  BOOL(postures, vary_open_high, 0, "vary_starts: open's drawn starts at k=0,1 are built as k=2,3's (palm a few cm above the ball, hand almost closed): open earns its success everywhere (PROTOCOL.md)") \
  INT(postures, vary_draws, 20, 1, 1000, "vary_starts: draws per trial until one has the SPEC 8 properties; when none has, the trial starts from the fixed posture") \
  ST_CONFIG_DYNAMICS_KEYS(INT, REAL, BOOL, ENUM, STR)                                             \
  ST__CONFIG_POSTEVAL_KEYS(INT, REAL, BOOL, ENUM, STR)

/* The [dynamics] keys, a block of the table of their own: the dynamic world's definition
 * (stDynDef, selftalk/world.h) is generated from it, field by key. */
#define ST_CONFIG_DYNAMICS_KEYS(INT, REAL, BOOL, ENUM, STR)                                      \
  ENUM(dynamics, solver, 1, "quickstep|step", "ODE stepper: quickstep (iterative; its constraint shuffling uses a per-thread generator seeded per trial) or step (direct, slower)") \
  REAL(dynamics, substep, 0.01, 0.0005, 0.05, "physics sub-step, s (control step / substep must be an integer)") \
  INT(dynamics, iterations, 20, 1, 1000, "quickstep solver iterations per sub-step") \
  REAL(dynamics, gravity, 9.81, 0.0, 100.0, "gravity, m/s^2 (downwards)") \
  REAL(dynamics, friction, 2.0, 0.0, 100.0, "Coulomb friction coefficient of the robot's contacts (silicone-skinned hand; data/README.md §3b)") \
  REAL(dynamics, table_friction, 1.0, 0.0, 100.0, "Coulomb friction coefficient of the object on the table and the floor") \
  REAL(dynamics, erp, 0.2, 0.0, 1.0, "error reduction parameter of joints and contacts") \
  REAL(dynamics, cfm, 1e-5, 0.0, 1.0, "constraint force mixing of joints and contacts") \
  INT(dynamics, max_contacts, 4, 1, 64, "contact points generated per colliding geometry pair") \
  REAL(dynamics, effort_scale, 1.0, 0.0, 1000.0, "joint motor torque limit = URDF effort times this") \
  REAL(dynamics, fall_margin, 0.0, 0.0, 1.0, "the object has fallen under the table when its centre is this far below the table top, m") \
  REAL(dynamics, contact_erp, 0.2, 0.0, 1.0, "error reduction parameter of contacts (soft ERP)") \
  REAL(dynamics, contact_cfm, 1e-4, 0.0, 1.0, "constraint force mixing of contacts (soft CFM; iCub_SIM 1e-4)") \
  REAL(dynamics, surface_layer, 0.001, 0.0, 0.1, "contact depth allowed without correction, m (iCub_SIM 0.001)") \
  REAL(dynamics, sor_w, 1.3, 0.1, 2.0, "quickstep successive over-relaxation factor (ODE default 1.3)") \
  REAL(dynamics, floor_z, -0.6, -100.0, 0.0, "floor plane that catches a dropped object, world z, m (iCub_SIM ground: 0.5976 m below the waist)") \
  REAL(dynamics, unstable_speed, 50.0, 0.001, 1e6, "a body whose centre moves faster than this makes the world unstable (trial failed), m/s") \
  REAL(dynamics, unstable_spin, 1000.0, 0.001, 1e6, "a body spinning faster than this makes the world unstable, rad/s") \
  REAL(dynamics, limit_tolerance_deg, 10.0, 0.0, 180.0, "a joint beyond its range by more than this makes the world unstable, degrees (impacts can push the weak wrist joints a few degrees past their stops)") \
  REAL(dynamics, stop_margin_deg, 0.5, 0.0, 28.0, "joint stops sit this far outside the qhat range, degrees, so that a servo holding the end of its range never rests on a stop") \
  REAL(dynamics, fudge_factor, 0.001, 0.0, 1.0, "ODE joint fudge factor: fraction of the motor torque applied explicitly when a powered joint leaves a stop (1 kicks 10 g phalanges)") \
  STR(dynamics, kinematic_joints, "torso_pitch,torso_yaw,l_shoulder_pitch,l_shoulder_roll,l_shoulder_yaw", "first joints of the chain that follow the servo law exactly in dynamic mode, their links kinematic bodies (PROTOCOL, Dynamic mode); empty: all bounded-torque motors") \
  BOOL(dynamics, free_motion, 1, "1: while no robot part can reach the table or the object within a sub-step, the robot moves kinematically (its servos cannot saturate) and ODE steps the object alone") \
  REAL(dynamics, contact_margin, 0.03, 0.0, 1.0, "free motion ends when a robot part comes this close to the table or the object, m (>= the distance a part moves in one sub-step)") \
  BOOL(dynamics, motor_active_set, 0, "1 (solver step): unsaturated hinge motors enter the LCP unbounded, checked after the step, redone bounded if one saturates: the same solution up to rounding (PROTOCOL, Speed)") \
  STR(dynamics, adaptive_joints, "", "the hinges after kinematic_joints, in chain order, that are exact servos while the torque they need stays within adaptive_limit of theirs, else motors (PROTOCOL, Speed); empty: none") \
  REAL(dynamics, adaptive_limit, 0.5, 0.01, 1.0, "adaptive_joints: an exact servo needing more than this times its motor's torque limit becomes a motor again, and a servo again below half of it") \
  ENUM(dynamics, lcp, 0, "dense|schur|block|warm", "solver step: dense, ODE's Dantzig on the whole LCP; schur, joint rows eliminated first; block, by joint blocks; warm, block and the rest solved from the last active set (PROTOCOL, Speed)") \
  /* DYNAMICS_KEYS_END: the dynamic-world engineer adds [dynamics] rows above this line */

#define ST__CONFIG_POSTEVAL_KEYS(INT, REAL, BOOL, ENUM, STR)                                     \
  INT(posteval, integration_top, 10, 1, 100000, "integration test: genotypes taken from the top of each primitive run's population (thesis 2.10.1: the top 10)") \
  INT(posteval, integration_trials, 40, 1, 100000, "integration test: caretaker-guided trials per genotype; trial i has type k = i mod 4: reach posture k, object position k, target k mod 2, fresh offsets (thesis 2.10.1)") \
  INT(posteval, robustness_trials, 40, 1, 100000, "robustness test: autonomous trials per individual, types as the integration test's (thesis 2.10.2)") \
  INT(posteval, generalisation_cells, 7, 1, 1000, "generalisation test: cells of the grid along x and along y (thesis 2.10.3: 7 x 7), centred on scene.object_center_x/y") \
  REAL(posteval, generalisation_cell_size, 0.05, 0.001, 1.0, "generalisation test: side of a cell, m (7 x 5 cm = 35 cm)") \
  REAL(posteval, generalisation_offset, 0.005, 0.0, 0.5, "generalisation test: uniform offset on x and y of the object around its cell centre, m (+-0.5 cm)") \
  INT(posteval, generalisation_repetitions, 10, 1, 100000, "generalisation test: trials of each cell with each reach posture (thesis 2.10.3: 10)") \
  INT(posteval, generalisation_steps, 300, 1, 100000, "generalisation test: trial length, control steps (15 s)") \
  REAL(posteval, generalisation_target_x, 0.25, -2.0, 2.0, "generalisation test: target x, m, the same in every trial (no offset), between T0 and T1") \
  REAL(posteval, generalisation_target_y, 0.0, -2.0, 2.0, "generalisation test: target y, m (0: between T0 and T1)") \
  REAL(posteval, generalisation_target_z, 0.17, -2.0, 2.0, "generalisation test: target z, m (25 cm above the table)")

/* The fence (MuJoCo lists its experimental flags apart, under "experimental"): every key that
 * is not the thesis's protocol, by tier; a key not named here is ST_TIER_PROTOCOL. Each entry:
 * tier, section, key or "prefix_*" (every key of the section whose name starts with prefix_).
 * tests/test_config.c checks that each entry names keys of the table. */
#define ST_CONFIG_TIERS(X)                                                                       \
  /* what one run is within the protocol: seed, stages, starting populations, condition */       \
  X(RUN, "run", "seed") X(RUN, "network", "arch") X(RUN, "stage", "stages")                       \
  X(RUN, "stage", "init_population") X(RUN, "integrated", "populations")                          \
  X(RUN, "integrated", "words_*") X(RUN, "integrated", "fitness_*")                               \
  X(RUN, "integrated", "first_generation")                                                        \
  /* ours: the chain stage's trials, drawn and palm-down starts, seeds kept apart */          \
  X(EXTENSION, "stage", "handover*") X(EXTENSION, "stage", "chain_*")                             \
  X(EXTENSION, "postures", "vary_*") X(EXTENSION, "postures", "reach_palm_down")                  \
  X(EXTENSION, "run", "rng_seed")                                                                 \
  /* for looking into a result */                                                                 \
  X(DIAGNOSTIC, "stage", "primitives") X(DIAGNOSTIC, "integrated", "selftalk_gate")               \
  /* how fast, not what */                                                                        \
  X(SPEED, "run", "threads") X(SPEED, "dynamics", "free_motion")                                  \
  X(SPEED, "dynamics", "contact_margin") X(SPEED, "dynamics", "motor_active_set")                 \
  X(SPEED, "dynamics", "adaptive_*") X(SPEED, "dynamics", "lcp")

/* The configuration: one field per key, named section_key. */
#define ST__CFG_INT(s, k, d, lo, hi, h) int s##_##k;
#define ST__CFG_REAL(s, k, d, lo, hi, h) double s##_##k;
#define ST__CFG_BOOL(s, k, d, h) int s##_##k;
#define ST__CFG_ENUM(s, k, d, ch, h) int s##_##k;
#define ST__CFG_STR(s, k, d, h) char s##_##k[ST_CONFIG_STR_MAX];
typedef struct stConfig {
  ST_CONFIG_KEYS(ST__CFG_INT, ST__CFG_REAL, ST__CFG_BOOL, ST__CFG_ENUM, ST__CFG_STR)
} stConfig;
#undef ST__CFG_INT
#undef ST__CFG_REAL
#undef ST__CFG_BOOL
#undef ST__CFG_ENUM
#undef ST__CFG_STR

typedef enum stConfigType {
  ST_CFG_INT,
  ST_CFG_REAL,
  ST_CFG_BOOL,
  ST_CFG_ENUM,
  ST_CFG_STR,
  ST_CFG_TYPE_COUNT
} stConfigType;

/* Description of one key (read-only; from st_config_key()). */
typedef struct stConfigKey {
  const char *section;
  const char *name;
  stConfigType type;
  double min, max;     /* INT, REAL */
  double def_num;      /* INT, REAL, BOOL, ENUM (index) */
  const char *def_str; /* STR */
  const char *choices; /* ENUM: "a|b|c" */
  const char *help;
  size_t offset;       /* of the field in stConfig */
} stConfigKey;

/* The tier of key i (0 <= i < st_config_nkeys()): the fence's (ST_CONFIG_TIERS), else
 * ST_TIER_PROTOCOL. */
ST_API stConfigTier st_config_key_tier(int i);

/* "protocol", "run", "extension", "diagnostic", "speed"; "?" for anything else. */
ST_API const char *st_config_tier_name(stConfigTier tier);

/* Number of keys and key i (0 <= i < st_config_nkeys()). */
ST_API int st_config_nkeys(void);
ST_API const stConfigKey *st_config_key(int i);

/* Whether key i (0 <= i < st_config_nkeys()) of cfg differs from base's, and its value as
 * config.ini writes it (st_config_write: "%.17g" reals, enum names, true/false). */
ST_API int st_config_key_differs(const stConfig *cfg, const stConfig *base, int i);
ST_API void st_config_format(const stConfig *cfg, int i, char *buf, size_t n);

/* Index of "section.key" or -1. */
ST_API int st_config_find(const char *section, const char *name);

/* Fills every field with its default (the thesis protocol). */
ST_API void st_config_default(stConfig *cfg);

/* Reads an INI file over cfg (keys the file does not name keep their value: call
 * st_config_default first). Rejects a missing file, one larger than ST_FILE_MAX or holding a
 * NUL byte, unknown sections and keys, duplicate keys, malformed or out-of-range values, string
 * values a config file cannot hold as they are (a ';' or '#' at the start or after a space,
 * control characters, white space around them) and inconsistent combinations, naming file and
 * line. */
ST_API stStatus st_config_load(const char *path, stConfig *cfg, char *err, size_t errsz);

/* The line of config file `path` that sets key i ("name = value" under its section), 0 when
 * none does or the file cannot be read: where a check made after st_config_load (a layer
 * above core: selftalk/trialkind.h) finds the key it blames. */
ST_API int st_config_key_line(const char *path, int i);

/* Applies one "section.key=value" override and checks the cross-key rules. */
ST_API stStatus st_config_set(stConfig *cfg, const char *assignment, char *err, size_t errsz);

/* Applies n overrides in order (the --set options of every app), then checks the cross-key
 * rules once, so that e.g. ga.elites=1 and ga.population=4 are accepted in either order. */
ST_API stStatus st_config_set_all(stConfig *cfg, const char *const *assignments, int n, char *err,
                           size_t errsz);

/* Checks ranges and cross-key consistency of a config built in code. */
ST_API stStatus st_config_validate(const stConfig *cfg, char *err, size_t errsz);

/* Writes the config as a loadable INI file, every key with its help as a comment; in each
 * section the keys by tier, each tier's under a comment naming it. */
ST_API int st_config_write(FILE *f, const stConfig *cfg);

/* Writes the key reference (section, key, type, default, range, help), tier by tier. */
ST_API void st_config_help(FILE *f);

/* Primitives named by stage.primitives, as a bit mask: bit p set for primitive p in the order
 * reach, open, grasp, move (ST_PRIM_* of fitness.h). 0 if the list is empty or names anything
 * else (st_config_load and st_config_validate reject such a config). */
ST_API unsigned st_config_primitive_mask(const stConfig *cfg);

/* Values of stage.stages and of integrated.words_* / fitness_* (the order of their choices). */
enum { ST_STAGES_SIMPLE = 0, ST_STAGES_MAIN, ST_STAGES_PRIMS, ST_STAGES_INTEGRATED };
enum { ST_CFG_WORDS_NONE = 0, ST_CFG_WORDS_CARETAKER, ST_CFG_WORDS_SELFTALK };
enum { ST_CFG_FIT_INTEGRATED = 0, ST_CFG_FIT_PREDICTION };
/* run.rng_seed */
enum { ST_RNG_SEED_PLAIN = 0, ST_RNG_SEED_APART };
/* The seed every random stream of a run is keyed by (st_rng_keyed): run.seed, or with
 * run.rng_seed = apart run.seed + 2^32. st_rng_keyed mixes the seed as it mixes the stream's
 * number, and XORs the two: (seed a, stream b) and (seed b, stream a) have one key, and so have
 * (seed a, stream a) for every a. With plain, run seed 4's integrated offsets (stream 5) of
 * generation 0, trial 0 are run seed 5's new genes (stream 4) of individual 0, and run seed 4's
 * new genes are run seed 1's initial genotypes (stream 1). Stream numbers are below 2^32, so
 * with apart no two runs share a key. */
ST_API uint64_t st_config_rng_seed(const stConfig *cfg);
/* integrated.fail_end */
enum { ST_FAIL_END_PENALTY = 0, ST_FAIL_END_EXACT, ST_FAIL_END_RUNOUT };
/* integrated.trial_order */
enum { ST_TRIAL_ORDER_MOD4 = 0, ST_TRIAL_ORDER_PAIRS };
/* integrated.selftalk_gate */
enum { ST_SELFTALK_GATE_NONE = 0, ST_SELFTALK_GATE_MOVE, ST_SELFTALK_GATE_AHEAD };
/* stage.chain_combine */
enum { ST_CHAIN_HARMONIC = 0, ST_CHAIN_SUM };
/* stage.handover_rollin */
enum { ST_ROLLIN_SELF = 0, ST_ROLLIN_ELITE };
/* stage.chain_complete */
enum { ST_CHAIN_COMPLETE_ALL = 0, ST_CHAIN_COMPLETE_FIXED_CHAINED };
/* postures.vary_trials */
enum { ST_VARY_REPLACE = 0, ST_VARY_EXTRA };

/* Choice name of an ENUM key's value, e.g. st_config_enum_name("network", "arch", 1) = "A". */
ST_API const char *st_config_enum_name(const char *section, const char *name, int value);

/* Checks value against the range of the INT or REAL key section.name (the table is the one
 * place ranges live), or a BOOL's 0 and 1, or an ENUM's choice indices: ST_OK, or ST_ERR_RANGE
 * with "section.name: V is out of range (expected ...)". Code that builds its definitions
 * without a stConfig (the GA, the dynamic world) checks the fields that are keys with this. */
ST_API stStatus st_config_check_number(const char *section, const char *name, double value, char *err,
                                size_t errsz);

/* ---- Which stages read which keys ----
 * Most keys are read by every stage. Those that only some stages read are listed in lib/core/config.c
 * (stage_keys[]) with the stages that read them; an evolution run refuses a value other than
 * the default for a key none of its stages reads (a key acts or is refused, never silently
 * ignored). A stage that starts reading a key adds its bit to the key's row. The three
 * post-evaluation tests (thesis 2.10, selftalk/posteval.h) are readers like the stages. */
#define ST_CONFIG_SIMPLE_PRIM 1u /* the simple-prim stage (kinematic) */
#define ST_CONFIG_MAIN_PRIM 2u   /* the main-prim stage (dynamic) */
#define ST_CONFIG_INTEGRATED 4u  /* the integrated stage (thesis 2.9) */
#define ST_CONFIG_INTEGRATION_TEST 8u    /* post-evaluation: the integration test (2.10.1) */
#define ST_CONFIG_ROBUSTNESS_TEST 16u    /* post-evaluation: the robustness test (2.10.2) */
#define ST_CONFIG_GENERALISATION_TEST 32u /* post-evaluation: the generalisation test (2.10.3) */
#define ST_CONFIG_POSTEVAL 56u           /* the three tests */
#define ST_CONFIG_ALL_STAGES 63u

/* The stages (ST_CONFIG_* bits) that read key i; ST_CONFIG_ALL_STAGES for most keys. */
ST_API unsigned st_config_key_stages(int i);

/* The stages stage.stages names, as ST_CONFIG_* bits. */
ST_API unsigned st_config_run_stages(const stConfig *cfg);

/* Refuses (ST_ERR_ARG, naming the key, its value, the stages that read it and why) a key whose
 * value is not its default when none of `stages` reads it. */
ST_API stStatus st_config_check_stages(const stConfig *cfg, unsigned stages, char *err, size_t errsz);

/* The same against another configuration: refuses a key whose value differs from base's when
 * none of `stages` reads it; base_name says what base is in the message ("expected BASE_NAME,
 * VALUE"). A post-evaluation checks its --set options against the config file this way. */
ST_API stStatus st_config_check_changes(const stConfig *cfg, const stConfig *base, const char *base_name,
                                 unsigned stages, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
