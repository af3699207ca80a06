/* SPDX-License-Identifier: MIT
 * The per-step trace CSV (selftalk/trace.h). */
#include "selftalk/trace.h"

#include "core/internal.h"

void st_trace_csv_header(const stTraceCsv *c) {
  ST_ASSERT(c && c->f);
  FILE *f = c->f;
  fprintf(f, "step");
  for (int d = 0; d < ST_NDOF; d++) fprintf(f, ",q%d", d);
  fprintf(f, ",palm_x,palm_y,palm_z,obj_x,obj_y,obj_z,target_x,target_y,target_z");
  for (int i = 0; i < ST_NTOUCH; i++) fprintf(f, ",touch%d", i);
  fprintf(f, ",focus_out,focus_target,ling_reach,ling_open,ling_grasp,ling_move,S,P,success_now,"
             "event,d_r,d_g,d_m,d_mhat,h,p,touching,lifted,caretaker_word,selftalk_label,lo_reach,"
             "lo_open,lo_grasp,lo_move,hl_0,hl_1,hl_2,hl_3");
  fprintf(f, c->phase ? ",phase\n" : "\n");
}

/* the words and the linguistic cluster: type A's outputs, type B's hidden-linguistic values */
static void language(FILE *f, stNetArch arch, const stTraceStep *s) {
  const int given = st_word_source_given(s->source);
  fprintf(f, ",%d,%d", given ? s->word : -1, s->label);
  for (int k = 0; k < 2; k++) {
    const int show = s->nout >= ST_NET_MAX_OUT && arch == (k ? ST_ARCH_B : ST_ARCH_A);
    for (int m = 0; m < ST_NET_NLING; m++)
      if (show) fprintf(f, ",%.17g", s->out[ST_NET_NOUT + m]); /* exact: score can re-read it */
      else fputc(',', f);
  }
}

static void real(const stTraceCsv *c, double x) { fprintf(c->f, ",%.*g", c->digits, x); }

void st_trace_csv_row(const stTraceCsv *c, const stTraceStep *s) {
  ST_ASSERT(c && c->f && s);
  FILE *f = c->f;
  const stWorld *w = s->world;
  const stQuantities *q = s->q;
  static const char *const events[] = {"", "end_success", "end_failure", "end_quiet"};
  fprintf(f, "%d", s->step);
  for (int d = 0; d < ST_NDOF; d++) real(c, w->qhat[d]);
  const double *points[3] = {q->palm, w->obj, w->target};
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) real(c, points[i][k]);
  for (int i = 0; i < ST_NTOUCH; i++) fprintf(f, ",%d", w->contacts.touch[i]);
  real(c, s->out[ST_NET_OUT_FOCUS]);
  fprintf(f, ",%d", s->focus_target);
  for (int m = 0; m < ST_NET_NLING; m++) fprintf(f, ",%g", s->in[ST_NET_IN_LING + m]);
  real(c, s->S);
  real(c, s->P);
  fprintf(f, ",%d,%s", s->success_now,
          s->event >= ST_END_SUCCESS && s->event <= ST_END_QUIET ? events[s->event] : "");
  const double dist[6] = {q->d_r, q->d_g, q->d_m, q->d_mhat, q->h, q->p};
  for (int i = 0; i < 6; i++) real(c, dist[i]);
  fprintf(f, ",%d,%d", q->touching, q->lifted);
  language(f, c->arch, s);
  if (c->phase) fprintf(f, ",%s", c->phase(c->phase_self));
  fputc('\n', f);
}

void st_trace_csv_fn(void *ctx, const stTraceStep *s) {
  ST_ASSERT(ctx && s);
  st_trace_csv_row(ctx, s);
}
