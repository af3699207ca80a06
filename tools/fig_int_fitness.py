#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Figs. 3.5-3.8: the fitness of the best individual in every generation of integrated
runs of one condition, one colour per run: total fitness solid, total bonus dotted, the bonus of
the trials without the caretaker (self talk or no words) dashed.

    /usr/bin/python3 tools/fig_int_fitness.py RUN [RUN...] [--label NAME]... [--panel NAME]... [--title T] [--start G] [-o fig3_5.png]...

With --panel (one per run), runs of the same panel name share a subplot titled by it, panels in
order of first appearance, two to a row, one y axis: Figs. 3.5-3.8 side by side, one panel per
condition, one line per seed.

RUN is an `evolve --out` directory of configs/integrated_*.cfg (or its fitness.csv): columns
generation, best, best_bonus, best_bonus_auto (docs/PROTOCOL.md, "Runs"). Default outputs
fig3_5.png and fig3_5.svg. --start 1 leaves out generation 0, whose first-generation fitness
(thesis 2.9, docs/PROTOCOL.md "Integrated stage") is on another scale and flattens the rest.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "fig_int_fitness"
COLUMNS = csvschema.pick(csvschema.FITNESS, "generation", "best", "best_bonus", "best_bonus_auto")
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]


def load(arg):
    path = arg if arg.endswith(".csv") and not os.path.isdir(arg) else os.path.join(arg, "fitness.csv")
    return path, figlib.read_fitness(path, COLUMNS, "an integrated run's fitness.csv")


def plotted(path, rows, start):
    """The rows from generation START on; a run with none is refused."""
    kept = [r for r in rows if r["generation"] >= start]
    if not kept:
        figlib.die(f"{path}: no generation from {start} on (its last is {rows[-1]['generation']:g})")
    print(f"{figlib.PROG}: {path}: generations {kept[0]['generation']:g}-{kept[-1]['generation']:g} plotted "
          f"(--start {start}), best {max(r['best'] for r in kept):.6g}")
    return kept


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--label", action="append", default=[], help="legend name, one per run")
    ap.add_argument("--panel", action="append", default=[], help="subplot name, one per run")
    ap.add_argument("--title", default="integrated stage: the best individual of every generation")
    ap.add_argument("--start", type=int, default=0, metavar="G", help="plot generations G and later (default 0)")
    figlib.add_out_argument(ap, "fig3_5")
    a = ap.parse_args()
    outs = figlib.outputs(a, "fig3_5")
    if a.label and len(a.label) != len(a.runs):
        figlib.die(f"{len(a.label)} --label for {len(a.runs)} runs (expected one per run)")
    if a.panel and len(a.panel) != len(a.runs):
        figlib.die(f"{len(a.panel)} --panel for {len(a.runs)} runs (expected one per run)")
    runs = [load(r) for r in a.runs]
    for path, rows in runs:
        print(f"{figlib.PROG}: {path}: {len(rows)} generations, best {max(r['best'] for r in rows):.6g}, "
              f"last bonus {rows[-1]['best_bonus']:g} (without the caretaker {rows[-1]['best_bonus_auto']:g})")
    if a.start:
        runs = [(path, plotted(path, rows, a.start)) for path, rows in runs]
    panels = list(dict.fromkeys(a.panel)) if a.panel else [None]
    if a.panel:
        print(f"{figlib.PROG}: {len(panels)} panels: " + ", ".join(
            f"{p} ({a.panel.count(p)} run{'s' if a.panel.count(p) > 1 else ''})" for p in panels))
    plt = figlib.pyplot()
    cols = 1 if len(panels) == 1 else 2
    rows_n = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows_n, cols, figsize=(9 if cols == 1 else 12, 4.5 if rows_n == 1 else 3.2 * rows_n),
                             sharey=True, squeeze=False)
    flat = [ax for row in axes for ax in row]
    for i, (path, rows) in enumerate(runs):
        pi = panels.index(a.panel[i]) if a.panel else 0
        ax = flat[pi]
        ci = a.panel[:i].count(a.panel[i]) if a.panel else i
        c, name = COLOURS[ci % len(COLOURS)], a.label[i] if a.label else path
        gs = [r["generation"] for r in rows]
        ax.plot(gs, [r["best"] for r in rows], color=c, lw=1.3, label=f"{name}: fitness")
        ax.plot(gs, [r["best_bonus"] for r in rows], color=c, lw=1.0, ls=":", label=f"{name}: bonus")
        ax.plot(gs, [r["best_bonus_auto"] for r in rows], color=c, lw=1.0, ls="--",
                label=f"{name}: bonus without the caretaker")
    for pi, ax in enumerate(flat):
        if pi >= len(panels):
            ax.set_visible(False)
            continue
        ax.set_xlabel("generation")
        ax.set_ylabel("fitness")
        ax.grid(True, color="#eee")
        if a.panel:
            ax.set_title(panels[pi], fontsize=10)
            ax.legend(loc="best", fontsize=7, frameon=False)
        else:
            ax.set_title(a.title, fontsize=10)
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    if a.panel:
        fig.suptitle(a.title, fontsize=11)
    fig.tight_layout()
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
