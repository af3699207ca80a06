/* SPDX-License-Identifier: MIT
 * libselftalk: ODE's LCP solved with the joints' unbounded rows eliminated first
 * (dynamics.lcp = schur; lib/world/ode_lcp.c); not installed.
 *
 * dWorldStep hands its LCP to dxSolveLCP (ODE 0.16's lcp.cpp) through the PLT. The library
 * defines that symbol: on a thread inside st__lcp_begin / st__lcp_end the problem is solved by
 * the Schur complement (below); everywhere else, and whenever the reduction does not apply,
 * the call goes to ODE's own function unchanged, so a world without the key steps bit for bit
 * as before. */
#ifndef SELFTALK_ODE_LCP_H
#define SELFTALK_ODE_LCP_H

/* Per-world scratch of the reduction (one world steps on one thread at a time). */
typedef struct stLcp stLcp;

typedef struct stLcpStats {
  long calls;       /* LCPs of the world's steps since creation or st__lcp_stats_reset */
  long reduced;     /* of which solved by the reduction (the others went to ODE whole) */
  long rows;        /* rows of the reduced ones */
  long unbounded;   /* of which eliminated by the sparse factorisation */
  long orderings;   /* fill-reducing orderings computed (the others were reused) */
} stLcpStats;

stLcp *st__lcp_create(void);
void st__lcp_destroy(stLcp *s);
void st__lcp_stats(const stLcp *s, stLcpStats *out);
void st__lcp_stats_reset(stLcp *s);

/* The LCPs of ODE steps taken by the calling thread between these go through s. */
void st__lcp_begin(stLcp *s);
void st__lcp_end(void);

/* NULL when ODE's calls of dxSolveLCP reach the library's definition and lay the problem out as
 * ODE 0.16.2 does (checked once per process with a probe step of two powered hinges); else why
 * not, and dynamics.lcp = schur cannot act and is refused: a program linked with the shared
 * library (which exports only the st_ API), an ODE that binds the call internally or another
 * version's layout. */
const char *st__lcp_unavailable(void);

/* Check mode (tests), on the calling thread: every LCP that st__lcp_begin routes is solved
 * by ODE's own function as well, on a copy, and the step goes on with ODE's solution;
 * st__lcp_check_count counts the reduced ones compared since st__lcp_check, and
 * st__lcp_check_max_diff is their largest max|x - x_ode| / max(1, max|x_ode|). ODE's
 * step arena is sized for one solve of the whole problem; the reduced one is smaller and fits
 * in the reserve a world with dynamics.lcp = schur keeps beyond it (1 MB at least;
 * dWorldSetStepMemoryReservationPolicy). */
void st__lcp_check(int on);
/* ... and the reduced ones on which ODE's Dantzig warned (not compared: the world would redo
 * the sub-step softer) */
long st__lcp_check_warned(void);
long st__lcp_check_count(void);
double st__lcp_check_max_diff(void);

#endif
