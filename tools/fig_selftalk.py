#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Fig. 3.11: self talk (ST-CT, ST) against the caretaker's words (ST-CT0, ST0) for the
final best individual of every run in the generalisation test: the success percentage with self
talk (dots) and with the caretaker (+), big where the difference is significant.

    ./apps/stats selftalk TRIALS.csv > selftalk.csv
    /usr/bin/python3 tools/fig_selftalk.py selftalk.csv [-o fig3_11.png]...

selftalk.csv is ./apps/stats selftalk's output (one row per individual: condition,
caretaker_condition, run, individual, excluded, selftalk_pct, caretaker_pct, U, p, method,
better, ...); "better" (selftalk, caretaker or none) carries the significance (p <= --alpha of
./apps/stats, 0.01). One panel per self-talk condition. Default outputs fig3_11.png and .svg.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figlib  # noqa: E402

figlib.PROG = "fig_selftalk"
COLUMNS = {"condition": "str", "caretaker_condition": "str", "run": "int", "individual": "int",
           "selftalk_pct": "float", "caretaker_pct": "float", "p": "float", "better": "str"}


def load(path):
    rows = figlib.read_csv(path, COLUMNS, "the output of ./apps/stats selftalk",
                           key=("condition", "run", "individual"))
    for r in rows:
        if r["better"] not in ("selftalk", "caretaker", "none"):
            figlib.die(f"{path}:{r['_line']}: better '{r['better']}' (expected selftalk, caretaker or none)")
        if not all(0 <= r[k] <= 100 for k in ("selftalk_pct", "caretaker_pct")):
            figlib.die(f"{path}:{r['_line']}: a percentage outside 0..100")
    return rows


def panel(ax, rows, cond):
    mine = sorted((r for r in rows if r["condition"] == cond), key=lambda r: (r["run"], r["individual"]))
    for r in mine:
        big = r["better"] != "none"
        ax.plot(r["run"], r["selftalk_pct"], "o", color="#1f77b4", ms=9 if big else 4)
        ax.plot(r["run"], r["caretaker_pct"], "+", color="#d62728", ms=14 if big else 7,
                mew=2.2 if big else 1.0)
    ax.plot([], [], "o", color="#1f77b4", label=f"self talk ({cond})")
    ax.plot([], [], "+", color="#d62728", label=f"caretaker ({mine[0]['caretaker_condition']})")
    ax.set_title(f"{cond}: big markers p <= alpha", fontsize=9)
    ax.set_xlabel("run")
    ax.set_xticks(sorted({r["run"] for r in mine}))
    ax.set_ylim(-5, 105)
    ax.grid(True, color="#eee")
    ax.legend(fontsize=8, frameon=False, loc="lower left")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("selftalk")
    figlib.add_out_argument(ap, "fig3_11")
    a = ap.parse_args()
    outs = figlib.outputs(a, "fig3_11")
    rows = load(a.selftalk)
    conds = figlib.ordered(r["condition"] for r in rows)
    for c in conds:
        mine = [r for r in rows if r["condition"] == c]
        print(f"{figlib.PROG}: {c}: {len(mine)} individuals, better with self talk "
              f"{sum(r['better'] == 'selftalk' for r in mine)}, with the caretaker "
              f"{sum(r['better'] == 'caretaker' for r in mine)}")
    plt = figlib.pyplot()
    fig, axes = plt.subplots(1, len(conds), figsize=(4.5 * len(conds) + 0.5, 4), squeeze=False)
    for ax, c in zip(axes[0], conds):
        panel(ax, rows, c)
    axes[0][0].set_ylabel("successful trials (%)")
    fig.tight_layout()
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
