#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The individual of a post-evaluation's summary.csv that succeeded most: prints its run_label,
individual and generation (`int-stct-s3 0 99`; generation -1 for a genome file's individual),
for the figures that show one individual per condition (thesis Fig. 3.12, "the best individual
of the ST-CT condition run 7", as `make replicate` draws it).

    /usr/bin/python3 tools/best_run.py SUMMARY.csv [--condition NAME]

Ties go to the lower run, then the lower individual (the order ./apps/stats and Fig. 3.10 use).
--condition keeps the rows of one condition (ST-CT, ST, CT, NI); a file with several conditions
needs it.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "best_run"
COLUMNS = csvschema.pick(csvschema.SUMMARY, "condition", "run", "individual", "successes", "run_label",
                         "generation")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("summary")
    ap.add_argument("--condition", help="the condition's rows only")
    a = ap.parse_args()
    rows = figlib.read_csv(a.summary, COLUMNS, "a post-evaluation's summary.csv",
                           schema=csvschema.SUMMARY, key=("condition", "run", "individual"))
    if a.condition:
        rows = [r for r in rows if r["condition"] == a.condition]
    conds = sorted({r["condition"] for r in rows})
    if not rows:
        figlib.die(f"{a.summary}: no rows" + (f" of condition {a.condition}" if a.condition else ""))
    if len(conds) > 1:
        figlib.die(f"{a.summary}: conditions {', '.join(conds)} (expected one: give --condition)")
    best = min(rows, key=lambda r: (-r["successes"], r["run"], r["individual"]))
    if not best["run_label"]:
        figlib.die(f"{a.summary}: run {best['run']} has no run_label (expected the run's directory name)")
    print(best["run_label"], best["individual"], best["generation"])


if __name__ == "__main__":
    main()
