/* SPDX-License-Identifier: MIT
 * libselftalk: a hand-written controller (no evolution) that performs every primitive of the
 * main-prim stage (thesis §2.8) and the integrated sequence of §2.9.3 in dynamic mode. It is
 * the existence proof that the physics allows what evolution is asked to find: reach above the
 * object, open the hand palm down, grasp the 0.2 kg ball and hold it without the table, lift
 * it and carry it to a target.
 *
 * It implements the stController interface of selftalk/episode.h, beside the network's
 * (st_net_controller), and, like the evolved network, learns which primitive to perform from
 * the linguistic inputs (21-24: reach, open, grasp, move; none: it holds still). It reads the world (measured qhat, link poses, object centre,
 * target, touch sensors) and plans with the inverse kinematics of selftalk/ik.h: the palm
 * centre, or the point of the palm frame where the ball sits, plus the palm normal pointing
 * down. Under SPEC §3's law (velocity alpha (y - qhat) deg/s, clamped) a command
 * y = qhat + g (q_goal - qhat) / (1 - exp(-alpha dt / range)) closes a fraction g of the error
 * per step; thumb and fingers are commanded beyond their contact flexion, so that their
 * motors push with their bounded torque. In short (numbers and reasons: lib/episode/scripted.c and
 * docs/PROTOCOL.md, "Scripted controller"):
 *   reach: palm centre to the reach point, palm down, hand open, thumb beside the palm;
 *   open:  the same target; the palm rises slowly while the hand is still closed;
 *   grasp: the palm over the ball with the ball ahead along the fingers while the thumb turns
 *          to opposition behind it (its tip kept off the table and clear of the ball); then
 *          thumb and fingers close and are held a little beyond contact; the thumb keeps
 *          pushing the ball up into the palm (thumb behind/below, fingers in front);
 *   move:  keep the grip (a grasp still closing is finished first), lift the ball straight
 *          up, then move in joint space to the posture that puts the ball at the target with
 *          the palm down (IK from several starts, least cost plus motion). Focus output: target
 *          while moving, object otherwise.
 * State carries over from one primitive to the next (the integrated sequence): a grip made by
 * grasp is kept by move.
 *
 * One stScripted per thread; it allocates only at creation (the inverse kinematics allocates
 * one buffer per solve). Deterministic: the same world and inputs give the same commands. */
#ifndef SELFTALK_SCRIPTED_H
#define SELFTALK_SCRIPTED_H

#include "selftalk/caretaker.h"
#include "selftalk/integrated.h"
#include "selftalk/trial.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stScripted stScripted;

/* A controller for the protocol's robot and scene (p must outlive it). */
ST_API stStatus st_scripted_create(const stProtocol *p, stScripted **out, char *err, size_t errsz);
ST_API void st_scripted_destroy(stScripted *s); /* nullable */

/* The controller as an stController (reset clears its state; ninputs 25). */
ST_API stController st_scripted_controller(stScripted *s);

/* What the controller is doing (after its last act): "none", "reach", "open",
 * "grasp:approach|close|hold", "move:secure|lift|carry". For traces. */
ST_API const char *st_scripted_phase(const stScripted *s);

/* Main-prim trial `index` (0..15: primitive index / 4, posture index % 4) of generation 0,
 * scored by the library (the primitive scorer of the episode loop). Nullable: trace. */
ST_API stStatus st_scripted_main_trial(const stProtocol *p, stWorkspace *ws, stScripted *s, int index,
                                stTrialResult *r, stTraceFn trace, void *ctx, char *err,
                                size_t errsz);

/* The same trial with generation `generation`'s trial table (its object and target offsets,
 * drawn starts when postures.vary_* draw them) and the solver key of that generation's
 * individual 0, as evolution runs it: what a run's population was asked to solve in that
 * generation (apps/scripted --generations). Generation 0 is st_scripted_main_trial. */
stStatus st_scripted_main_trial_at(const stProtocol *p, stWorkspace *ws, stScripted *s,
                                   int generation, int index, stTrialResult *r, stTraceFn trace,
                                   void *ctx, char *err, size_t errsz);

/* The integrated sequence (thesis §2.9.3, §2.10.1) as an integrated trial of the episode loop
 * (selftalk/integrated.h): reach posture k, object at scene position k and target t (0 or 1),
 * both without offsets; the caretaker names the primitive each step (silent at step 0; the
 * secondary input "move-object-to-target" is given throughout) and the controller performs
 * it; the object-table collision stays on; integrated.steps long (240: 12 s). Scored by the
 * integrated scorer: the trial ends early once the object was within the fitness's target
 * radius while lifted more than integrated.hold_steps (20) steps ago and is still lifted;
 * success is main-prim move's condition (within the radius at some step, still lifted at the
 * end). The solver's generator is keyed by (run seed, generation 0, individual 0, trial
 * 2k + t). Nullable: trace. */
ST_API stStatus st_scripted_integrated(const stProtocol *p, stWorkspace *ws, stScripted *s, int k,
                                int t, stIntTrialResult *r, stTraceFn trace, void *ctx,
                                char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
