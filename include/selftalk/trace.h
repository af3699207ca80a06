/* SPDX-License-Identifier: MIT
 * libselftalk: an episode's per-step trace as CSV, the one format of every app that writes one
 * (replay --out, scripted --trace) and of the tools that read it (tools/draw_trial.py,
 * tools/trial_video.py, tools/figlib.py): a header, then one row per step of the episode loop
 * (stTraceStep, selftalk/episode.h). The columns, in order:
 *   step; q0..q11 (the measured posture); palm_x..palm_z, obj_x..obj_z, target_x..target_z;
 *   touch0..touch5; focus_out, focus_target; ling_reach..ling_move (the linguistic inputs);
 *   S, P, success_now, event ("", end_success, end_failure, end_quiet); d_r, d_g, d_m, d_mhat,
 *   h, p, touching, lifted; caretaker_word (the word given, -1: none or self talk),
 *   selftalk_label (-1: a controller that does not talk); lo_reach..lo_move (type A's
 *   linguistic outputs) and hl_0..hl_3 (type B's hidden-linguistic values), each empty for the
 *   other architectures and exact to 17 digits; then, with a phase function, phase. */
#ifndef SELFTALK_TRACE_H
#define SELFTALK_TRACE_H

#include <stdio.h>

#include "selftalk/episode.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stTraceCsv {
  FILE *f;
  int digits;     /* significant digits of the reals: 9, or 17 to read them back bit for bit */
  stNetArch arch; /* whose linguistic cluster fills lo_* (type A) or hl_* (type B) */
  const char *(*phase)(const void *self); /* nullable: a last column, "phase": what the
                                             controller is doing (e.g. st_scripted_phase) */
  const void *phase_self;
} stTraceCsv;

/* The header line. */
ST_API void st_trace_csv_header(const stTraceCsv *c);

/* One step's row. */
ST_API void st_trace_csv_row(const stTraceCsv *c, const stTraceStep *s);

/* st_trace_csv_row as an stTraceFn: ctx is the stTraceCsv. */
ST_API void st_trace_csv_fn(void *ctx, const stTraceStep *s);

#ifdef __cplusplus
}
#endif

#endif
