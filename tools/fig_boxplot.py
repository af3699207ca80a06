#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Figs. 3.4 and 3.9: box plots of the individuals' success percentages by condition, in
the robustness test (Fig. 3.4) or the generalisation test (Fig. 3.9, with ST-CT0 and ST0).

    /usr/bin/python3 tools/fig_boxplot.py SUMMARY.csv --test robustness|generalisation|... [-o fig3_4.png]...

SUMMARY.csv is the post-evaluation summary (docs/PROTOCOL.md, "Post-evaluation files"): one row
per individual, test,condition,run,individual,successes,trials,...; the percentage is
100 successes / trials. Boxes span the quartiles (definition 7, as ./apps/stats), the line is
the median, whiskers reach the most extreme values within 1.5 interquartile ranges, values
beyond are marked + (the thesis's "outliers marked as +"). Prints each condition's n, median
and quartiles. Default outputs fig3_4.png and fig3_4.svg (robustness), fig3_9.* (generalisation).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "fig_boxplot"
COLUMNS = csvschema.pick(csvschema.SUMMARY, "test", "condition", "run", "individual", "successes",
                         "trials")
DEFAULT = {"robustness": "fig3_4", "generalisation": "fig3_9"}


def samples(path, test):
    rows = figlib.read_csv(path, COLUMNS, "a post-evaluation summary", schema=csvschema.SUMMARY,
                           key=("test", "condition", "run", "individual"))
    for r in rows:
        if r["trials"] < 1 or not 0 <= r["successes"] <= r["trials"]:
            figlib.die(f"{path}:{r['_line']}: successes {r['successes']} of {r['trials']} trials "
                       "(expected 0 <= successes <= trials, trials >= 1)")
    tests = list(dict.fromkeys(r["test"] for r in rows))
    if test not in tests:
        figlib.die(f"{path}: no rows of test '{test}' (tests in the file: {', '.join(tests)})")
    rows = [r for r in rows if r["test"] == test]
    conds = figlib.ordered(r["condition"] for r in rows)
    return {c: [100.0 * r["successes"] / r["trials"] for r in rows if r["condition"] == c] for c in conds}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("summary")
    ap.add_argument("--test", required=True)
    figlib.add_out_argument(ap, "fig3_4 (robustness) / fig3_9 (generalisation)")
    a = ap.parse_args()
    outs = figlib.outputs(a, DEFAULT.get(a.test, "fig_" + a.test))
    data = samples(a.summary, a.test)
    for c, xs in data.items():
        q1, med, q3 = figlib.quartiles(xs)
        print(f"{figlib.PROG}: {a.test} {c}: n={len(xs)} median={med:g} q1={q1:g} q3={q3:g} "
              f"min={min(xs):g} max={max(xs):g}")
    plt = figlib.pyplot()
    fig, ax = plt.subplots(figsize=(1.3 * len(data) + 2, 4.2))
    ax.boxplot(list(data.values()), labels=list(data), sym="+", whis=1.5)
    ax.set_ylabel("successful trials (%)")
    ax.set_ylim(-5, 105)
    ax.set_title(f"{a.test} test", fontsize=10)
    ax.grid(True, axis="y", color="#eee")
    fig.tight_layout()
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
