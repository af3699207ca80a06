#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Fig. 3.1: main (the best individual's), bonus and average fitness of primitive runs
over the simple-prim and main-prim generations, one panel per run, the maximum possible bonus
dotted, the stage change marked.

    /usr/bin/python3 tools/fig_prim_fitness.py RUN [RUN...] [--label NAME]... [-o fig3_1.png]...

RUN is an `evolve --out` directory of configs/prims.cfg (or its fitness.csv): columns
generation, best, mean, best_bonus, stage and best_t0.. (docs/PROTOCOL.md, "Evolution runs").
The maximum bonus is fitness.bonus (config.ini beside fitness.csv; 10 without one) times the
number of best_tI columns (16: 160). Default outputs fig3_1.png and fig3_1.svg.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402
import runconfig  # noqa: E402

figlib.PROG = "fig_prim_fitness"
COLUMNS = csvschema.pick(csvschema.FITNESS, "generation", "best", "mean", "best_bonus", "stage")
TRIAL = next(iter(csvschema.pick(csvschema.FITNESS, "best_t%d")))  # one column per trial


def config_bonus(run_dir):
    """fitness.bonus of the run's config.ini, 10 (the thesis's) without one"""
    try:
        return runconfig.value(run_dir, "fitness", "bonus", 10.0, float)
    except ValueError as e:
        figlib.die(str(e))


def load(arg):
    path = arg if arg.endswith(".csv") and not os.path.isdir(arg) else os.path.join(arg, "fitness.csv")
    rows = figlib.read_fitness(path, COLUMNS, "a primitive run's fitness.csv")
    ntrials = sum(1 for t in range(len(rows[0])) if TRIAL % t in rows[0])
    return {"path": path, "rows": rows, "max_bonus": config_bonus(os.path.dirname(path)) * ntrials,
            "changes": [r["generation"] for a, r in zip(rows, rows[1:]) if r["stage"] != a["stage"]]}


def panel(ax, run, label):
    gs = [r["generation"] for r in run["rows"]]
    ax.plot(gs, [r["best"] for r in run["rows"]], color="#1f77b4", lw=1.2, label="main (best)")
    ax.plot(gs, [r["best_bonus"] for r in run["rows"]], color="#d62728", lw=1.0, label="bonus")
    ax.plot(gs, [r["mean"] for r in run["rows"]], color="#7f7f7f", lw=1.0, label="average")
    ax.axhline(run["max_bonus"], color="#d62728", ls=":", lw=1.0, label="maximum bonus")
    for g in run["changes"]:
        ax.axvline(g - 0.5, color="#555", ls="--", lw=0.8)
        ax.text(g, run["max_bonus"], " main-prim", fontsize=8, va="bottom")
    ax.set_title(label, fontsize=10)
    ax.set_ylabel("fitness")
    ax.set_xlim(gs[0], max(gs[-1], gs[0] + 1))
    ax.grid(True, color="#eee")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)


def describe(run):
    last = run["rows"][-1]
    return (f"{figlib.PROG}: {run['path']}: {len(run['rows'])} generations, stage changes at "
            f"{run['changes'] or 'none'}, last best {last['best']:.6g} bonus {last['best_bonus']:g}"
            f" of {run['max_bonus']:g}")


def main():
    figlib.panel_per_run(__doc__, "fig3_1", load, describe, panel, 9.5, 2.8)


if __name__ == "__main__":
    main()
