/* SPDX-License-Identifier: MIT
 * libselftalk: the 16 initial postures of the primitive stages (thesis §2.5.3, SPEC §8) -
 * four per primitive; posture k of a primitive is used with object position k (and target
 * k mod 2). The integrated stage and the post-evaluations start from the four reach postures.
 *
 * Postures are computed, deterministically, by inverse kinematics (selftalk/ik.h) from the
 * scene's object positions, from fixed start postures; nothing random is involved and the
 * result depends only on the robot and the scene (st_posture_varied builds an open or grasp
 * posture from a drawn variation instead: postures.vary_starts). Each call allocates a kinematic stWorld
 * (contact checks) and frees it before returning: call these at run or trial set-up, not in
 * a control loop (st_postures_all computes the 16 once).
 *
 * How each is built (the numbers are the postures.* keys, selftalk/config.h; defaults here):
 *   reach  k: the palm centre is placed (position only) at a fixed offset from the centre of
 *             the four object positions, from four different start postures; torso yaw and
 *             pitch at 0 degrees, thumb and fingers fully extended. Palm >= 0.15 m from every
 *             object position, above the table, touching nothing.
 *   open   k=0,1: palm down 1.5 cm above the ball top, its centre 2 cm behind the ball along
 *             the fingers, thumb half opposed, thumb and fingers partly closed (0.15 / 0.35)
 *             around the ball without touching it ("almost grasping").
 *   open   k=2,3: palm down, centred 4 cm above the ball top, hand almost closed (flexion 0.8).
 *   grasp  k: palm down, centred 3 cm above the ball top; fingers extended (k=0,1) or
 *             partly flexed (0.25, k=2,3).
 *   move   k: palm down on the ball top (1 mm contact), ball centre 3.5 cm ahead of the palm
 *             centre, thumb opposed 0.8; the thumb, then the fingers, close until they touch
 *             the ball (the thumb; 3 fingertips), on a 0.01 grid, then squeeze by 0.02 more.
 *             In kinematic mode the check asks for >= 3 touch sensors on the object and
 *             d_g < 0.03 m; the SPEC §8 property that the object stays 3 s in the hand with
 *             frozen finger commands needs dynamic mode and is verified there. */
#ifndef SELFTALK_POSTURES_H
#define SELFTALK_POSTURES_H

#include "selftalk/study.h" /* the primitives: ST_PRIM_*, st_primitive_name */
#include "selftalk/rng.h"
#include "selftalk/robot.h"
#include "selftalk/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ST_NPOSTURE 4 /* postures per primitive (= object positions) */


/* Initial posture k (0..3) of a primitive (ST_PRIM_*), for object position k of the scene:
 * fills qhat[12] (SPEC §3 order). Fails with ST_ERR_ARG on a bad primitive or k, ST_ERR_RANGE
 * when the inverse kinematics cannot reach the posture's target or the result fails
 * st_posture_check (both possible only with a scene or robot far from the defaults); err
 * names the posture and the reason. */
ST_API stStatus st_posture(const stRobot *robot, const stScene *scene, int primitive, int k,
                    double qhat[ST_NDOF], char *err, size_t errsz);

/* A variation of an open or grasp start (postures.vary_starts): the palm moved by (dx, dy) m
 * along its own x (towards the fingers) and y axes, its normal tilted by `tilt` rad from
 * straight down towards the horizontal direction at angle `azimuth` rad from world +x, and the
 * inverse kinematics started from torso pitch, wrist pronation and wrist pitch ik_deg (deg). */
typedef struct stPostureVariation {
  double dx, dy;
  double tilt, azimuth;
  double ik_deg[3];
  int open_high; /* open k=0,1 built as k=2,3 (palm a few cm above, hand almost closed) */
} stPostureVariation;

/* The variation that changes nothing: st_posture_varied then gives st_posture's result. */
ST_API void st_posture_variation_none(const stScene *scene, stPostureVariation *v);

/* Draws a variation from the scene's postures.vary_* ranges: the offset uniform in a disc of
 * radius vary_offset, the tilt angle uniform in [0, vary_tilt] and its direction uniform, each
 * IK start angle uniform between the ik_* key and its vary_* key; open_high is
 * postures.vary_open_high (not drawn: the stream is the same either way). */
ST_API void st_posture_variation_draw(const stScene *scene, stRng *rng, stPostureVariation *v);

/* Open or grasp posture k built with variation v, checked as st_posture checks: ST_ERR_RANGE
 * with the reason in err when the IK misses or the SPEC §8 properties fail; ST_ERR_ARG for
 * another primitive (reach starts are far from the object and move starts hold it: neither
 * is varied this way). */
ST_API stStatus st_posture_varied(const stRobot *robot, const stScene *scene, int primitive, int k,
                           const stPostureVariation *v, double qhat[ST_NDOF], char *err,
                           size_t errsz);

/* All 16 postures: qhat[primitive][k]. */
ST_API stStatus st_postures_all(const stRobot *robot, const stScene *scene,
                         double qhat[ST_NPRIM][ST_NPOSTURE][ST_NDOF], char *err, size_t errsz);

/* Steps a bang-bang controller needs, in kinematic mode, to bring the palm centre from qhat
 * to within fitness.success_dist (0.03 m) of the reach point above object position k: each
 * DOF is driven at full speed towards an inverse-kinematics solution of the reach point, and
 * held once within 0.02 of it. A lower bound on what an evolved controller needs; -1 when not
 * reached within max_steps. */
ST_API int st_posture_reach_steps(const stRobot *robot, const stScene *scene, int k,
                           const double qhat[ST_NDOF], int max_steps);

/* 1 when qhat has the SPEC §8 properties of posture k of a primitive (object at scene
 * position k), else 0 with the first failed property in why (nullable). Reach postures are
 * also checked to be distinct from the other three reach postures st_posture computes. */
ST_API int st_posture_check(const stRobot *robot, const stScene *scene, int primitive, int k,
                     const double qhat[ST_NDOF], char *why, size_t n);

#ifdef __cplusplus
}
#endif

#endif
