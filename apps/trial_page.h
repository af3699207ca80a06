/* SPDX-License-Identifier: MIT
 * replay --html: one self-contained HTML page of a traced trial (docs/PROTOCOL.md, "Trial
 * pages"). The page template (tools/trial_page.html) is compiled into the app; three.js (Debian's
 * libjs-three) is read at run time and inlined, so the page needs nothing but a browser.
 * Only replay uses it: an app module, not part of the library. */
#ifndef SELFTALK_TRIAL_PAGE_H
#define SELFTALK_TRIAL_PAGE_H

#include "selftalk/episode.h"
#include "selftalk/net.h"

/* Where three.js is looked for: --three DIR, else $SELFTALK_THREE_DIR, else this. The directory
 * holds three.min.js and examples/js/controls/OrbitControls.js (Debian's layout). */
#define TRIAL_PAGE_THREE_DIR "/usr/share/javascript/three"
#define TRIAL_PAGE_THREE_ENV "SELFTALK_THREE_DIR"

typedef struct trialPage trialPage;

/* Reads three.js from three_dir (NULL: the environment, then the default) and prepares a page
 * for path with the shapes of the protocol's worlds; dies (exit 2, "PROG: ...") when three.js is
 * missing or path cannot be written, before the trial runs. */
trialPage *trial_page_open(const char *prog, const char *path, const char *three_dir,
                           const stProtocol *p);

/* Records one traced step (called in order from step 0; s->world must be the step's state). */
void trial_page_step(trialPage *pg, const stTraceStep *s, stNetArch arch);

typedef struct trialPageSummary {
  const char *title; /* what was replayed: genotype and trial */
  const char *line;  /* replay's summary line, as printed */
  int success;
  const char *end;   /* how the trial ended: full, success, failure, quiet */
  int has_bonus;     /* 0: the trial has no bonus (post-evaluation trials) */
  double bonus;
  long steps_run, steps;
} trialPageSummary;

/* Writes the page (atomically) and frees pg; dies on a write error. */
void trial_page_finish(trialPage *pg, const trialPageSummary *sum);

#endif
