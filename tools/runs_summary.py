#!/usr/bin/env python3
"""Summarises evolution runs: for each run directory (an `evolve --out DIR`), the generation at
which each stage was completed (ga.success_genotypes of its config.ini, 5 by default, genotypes
solving all 16 trials), the generations run, and the final best individual's successes per
trial. Prints CSV (one row per run), then the median and quartiles of the completion
generations, the thesis's summary statistics (§3.1).

    python3 tools/runs_summary.py runs/simple_prim-s1 runs/simple_prim-s2 ...
"""
import csv
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402
import runconfig  # noqa: E402

figlib.PROG = "runs_summary"

# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
COLUMNS = csvschema.pick(csvschema.FITNESS, "generation", "stage", "all_success", "best",
                         "best_successes", "best_t%d")


def success_genotypes(run_dir):
    """ga.success_genotypes of the run's config.ini (a stage is complete when that many genotypes
    solve all trials); 5, the thesis's, when the directory has no config.ini"""
    try:
        return runconfig.value(run_dir, "ga", "success_genotypes", 5, int)
    except ValueError as e:
        figlib.die(str(e))


def summarise(run_dir):
    path = run_dir + "/fitness.csv"
    rows = figlib.read_fitness(path, ("generation", "stage", "all_success", "best",
                                      "best_successes", "best_t0"),
                               "the fitness.csv of a primitive run of ./apps/evolve")
    done, need = {}, success_genotypes(run_dir)
    for r in rows:
        if r["all_success"] >= need and r["stage"] not in done:
            done[r["stage"]] = r["generation"]
    last = rows[-1]
    trials = "".join(str(last["best_t%d" % t]) for t in range(figlib.trial_columns(last)))
    return {
        "run": run_dir,
        "generations": last["generation"] + 1,
        "simple_prim_done": done.get("simple-prim", ""),
        "main_prim_done": done.get("main-prim", ""),
        "final_stage": last["stage"],
        "final_best": last["_raw"]["best"],
        "final_best_successes": last["best_successes"],
        "final_best_trials": trials,
    }


def quartiles(xs):
    if len(xs) < 2:
        return xs[0], xs[0], xs[0]
    q = statistics.quantiles(xs, n=4, method="inclusive")
    return q[0], statistics.median(xs), q[2]


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out = [summarise(d) for d in argv[1:]]
    w = csv.DictWriter(sys.stdout, fieldnames=list(out[0].keys()), lineterminator="\n")
    w.writeheader()
    w.writerows(out)
    for stage in ("simple_prim_done", "main_prim_done"):
        xs = [r[stage] for r in out if r[stage] != ""]
        if xs:
            lo, med, hi = quartiles(xs)
            print("# %s: %d of %d runs, median %g (quartiles %g, %g)" % (stage, len(xs), len(out), med, lo, hi))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
