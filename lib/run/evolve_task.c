/* SPDX-License-Identifier: MIT
 * One individual's evaluation as a task (selftalk/evolve.h): the code every evaluation of an
 * evolution run goes through, on st_evolve_run's threads or in another process. */
#include <math.h>
#include <string.h>

#include "core/internal.h"
#include "selftalk/evolve.h"

/* the primitive stages evolve the base network; the integrated stage network.arch's */
void st_evolve_task_run(const stProtocol *p, const stIntegratedDef *idef, stWorkspace *ws,
                        const stEvolveTask *t, stEvolveResult *r) {
  ST_ASSERT(p && idef && ws && t && r);
  memset(r, 0, sizeof *r);
  r->individual = t->individual;
  stNetParams np, rollin;
  const stNetArch arch = t->integrated ? idef->arch : ST_ARCH_BASE;
  char *e = r->err;
  const size_t n = sizeof r->err;
  stStatus st = st_net_decode(&p->net, arch, &t->genome, &np, e, n);
  if (!st && t->has_rollin) st = st_net_decode(&p->net, ST_ARCH_BASE, &t->rollin, &rollin, e, n);
  if (!st && t->integrated)
    st = st_int_evaluate(p, idef, ws, t->generation, t->individual, &np, &r->ieval, e, n);
  else if (!st)
    st = st_stage_evaluate(p, ws, t->stage, t->generation, t->individual, &np,
                           t->has_rollin ? &rollin : NULL, &r->eval, e, n);
  r->status = st;
  r->fitness = st ? NAN : t->integrated ? r->ieval.fitness : r->eval.fitness;
}
