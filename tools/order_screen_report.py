#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The table of the integrated trial-type order screen (tools/order_screen.mk; issue 47 item 2):
one row per run OUT/COND-ORDER-sSEED (fitness.csv; robustness/trials.csv once its test ran):
robustness successes of 40 and by type, the first generation with an autonomous bonus, the
largest autonomous bonus and the first generation with it, then per condition and order the
median robustness.

    python3 tools/order_screen_report.py OUT"""
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "order_screen_report"
# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
TRIALS = csvschema.pick(csvschema.TRIALS, "type", "success")
FITNESS = csvschema.pick(csvschema.FITNESS, "generation", "best_bonus_auto")
RUN = re.compile(r"(stct|st|ct|ni)-(mod4|pairs)-s([0-9]+)")


def run_row(d, name):
    cond, order, seed = RUN.fullmatch(name).groups()
    fit = figlib.read_fitness(os.path.join(d, "fitness.csv"), tuple(FITNESS), live=True)
    auto = [(r["generation"], r["best_bonus_auto"]) for r in fit]
    top = max((a for _, a in auto), default=0)
    first = next((g for g, a in auto if a > 0), None)
    first_top = next((g for g, a in auto if a == top), None) if top > 0 else None
    trials = os.path.join(d, "robustness", "trials.csv")
    rob = by_type = None
    if os.path.exists(os.path.join(d, "robustness", "summary.csv")):
        rows = figlib.read_csv(trials, dict(TRIALS, success="bit"), "posteval's trials.csv")
        rob = sum(r["success"] for r in rows)
        by_type = [sum(r["success"] for r in rows if r["type"] == k) for k in range(4)]
    return {"cond": cond, "order": order, "seed": int(seed), "gens": len(auto), "rob": rob,
            "types": by_type, "first": first, "top": top, "first_top": first_top}


def main():
    if len(sys.argv) != 2:
        figlib.die("usage: order_screen_report.py OUT")
    out = sys.argv[1]
    if not os.path.isdir(out):
        figlib.die(f"{out}: no such directory (expected tools/order_screen.mk's OUT)")
    rows = [run_row(os.path.join(out, n), n) for n in sorted(os.listdir(out))
            if RUN.fullmatch(n) and os.path.exists(os.path.join(out, n, "fitness.csv"))]
    if not rows:
        figlib.die(f"{out}: no run COND-ORDER-sSEED with a fitness.csv yet")
    rows.sort(key=lambda r: (r["cond"], r["order"], r["seed"]))
    print("| run | generations | robustness (of 40) | by type 0-3 | first autonomous bonus | "
          "largest autonomous bonus (first at) |")
    print("|---|---|---|---|---|---|")
    dash = lambda v: "-" if v is None else v
    for r in rows:
        types = "-" if r["types"] is None else ", ".join(map(str, r["types"]))
        print(f"| {r['cond']}-{r['order']}-s{r['seed']} | {r['gens']} | {dash(r['rob'])} | {types} | "
              f"{dash(r['first'])} | {r['top']} ({dash(r['first_top'])}) |")
    print()
    for cond in sorted({r["cond"] for r in rows}):
        for order in ("mod4", "pairs"):
            done = [r["rob"] for r in rows if r["cond"] == cond and r["order"] == order and r["rob"] is not None]
            if done:
                print(f"{cond} {order}: robustness median {statistics.median(done)} of 40 over "
                      f"{len(done)} runs ({', '.join(map(str, done))})")


if __name__ == "__main__":
    main()
