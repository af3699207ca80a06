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
  long direct;      /* warm: reduced LCPs solved directly (the guess checked) ... */
  long fallbacks;   /* ... and those left to ODE's Dantzig */
  long rounds;      /* ... the direct ones' rounds of guess and check, both phases */
} stLcpStats;

/* The scratch of dynamics.lcp = schur; st__lcp_set_mode makes it another variant (ST_DYN_LCP_*
 * but dense). st__lcp_reset: the statistics and the warm start's memory (a world's reset). */
stLcp *st__lcp_create(void);
void st__lcp_set_mode(stLcp *s, int mode);
void st__lcp_reset(stLcp *s);
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
 * by the world's variant on a copy and by the reference (ODE's own function, or with
 * ST_LCP_CHECK_SCHUR schur's reduction), and the step goes on with the reference's solution;
 * st__lcp_check_count counts the reduced ones compared since st__lcp_check, and
 * st__lcp_check_max_diff is their largest max|x - x_ref| / max(1, max|x_ref|). ODE's
 * step arena is sized for one solve of the whole problem; the reduced one is smaller and fits
 * in the reserve a world with dynamics.lcp = schur keeps beyond it (1 MB at least;
 * dWorldSetStepMemoryReservationPolicy). */
enum { ST_LCP_CHECK_DENSE = 1, ST_LCP_CHECK_SCHUR = 2 }; /* st__lcp_check's reference */
void st__lcp_check(int on);
/* ... and the reduced ones on which ODE's Dantzig warned (not compared: the world would redo
 * the sub-step softer) */
long st__lcp_check_warned(void);
long st__lcp_check_count(void);
double st__lcp_check_max_diff(void);

/* Tests: on the calling thread, dynamics.lcp = warm leaves every reduced LCP to ODE's Dantzig
 * (its fallback), as block does. */
void st__lcp_force_fallback(int on);

#endif
