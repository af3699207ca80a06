#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Fig. 3.10: the generalisation test's 7 x 7 success maps, one per condition: the
percentage of successful trials with the object in each cell (over its postures and
repetitions), the training positions of the object marked by white dots.

    /usr/bin/python3 tools/fig_success_maps.py TRIALS.csv [--test generalisation] [--pick COND:RUN]...
        [--centre 0.30,0.10] [--cell 0.05] [--spacing 0.10] [-o fig3_10.png]...

TRIALS.csv is the post-evaluation's per-trial file (docs/PROTOCOL.md, "Post-evaluation files"):
test,condition,run,individual,trial,type,cell,posture,repetition,words,success,...; cell =
7 row + column, row along the robot's x (0 nearest the robot), column along y (0 the most
negative y, the robot's right). Each condition shows its best individual (the most successes;
ties: the lower run, then individual), or the run --pick names; a caretaker variant NAME0 shows
the individual NAME shows (the thesis: "the results of the best individual when using the
caretaker instructions"). Cell centres: centre + (index - 3) cell (scene.object_center_x/y, the
grid of SPEC §11); training positions: centre +- spacing on x and on y (scene.object_spacing).
Default outputs fig3_10.png and fig3_10.svg.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "fig_success_maps"
COLUMNS = csvschema.pick(csvschema.TRIALS, "test", "condition", "run", "individual", "trial", "cell",
                         "success")
N = 7


def load(path, test):
    rows = figlib.read_csv(path, COLUMNS, "a post-evaluation trials file", schema=csvschema.TRIALS,
                           key=("test", "condition", "run", "individual", "trial"))
    for r in rows:
        if r["test"] == test and not (0 <= r["cell"] < N * N and r["success"] in (0, 1)):
            figlib.die(f"{path}:{r['_line']}: cell {r['cell']}, success {r['success']} (expected a "
                       f"cell 0..{N * N - 1} and success 0 or 1 in the {test} test)")
    rows = [r for r in rows if r["test"] == test]
    if not rows:
        figlib.die(f"{path}: no rows of test '{test}'")
    return rows


def choose(rows, cond, picks, chosen):
    """(run, individual) shown for cond"""
    if cond in picks:
        inds = sorted({r["individual"] for r in rows if r["condition"] == cond and r["run"] == picks[cond]})
        if not inds:
            figlib.die(f"--pick {cond}:{picks[cond]}: no trials of that run")
        return picks[cond], inds[0]
    base = cond[:-1] if cond.endswith("0") else None
    if base in chosen:
        return chosen[base]
    succ = {}
    for r in rows:
        if r["condition"] == cond:
            key = (r["run"], r["individual"])
            succ[key] = succ.get(key, 0) + r["success"]
    return min(succ, key=lambda k: (-succ[k], k))


def grid(rows, cond, who):
    """success percentage per cell (None without trials) and the individual's totals"""
    n, s = [0] * (N * N), [0] * (N * N)
    for r in rows:
        if r["condition"] == cond and (r["run"], r["individual"]) == who:
            n[r["cell"]] += 1
            s[r["cell"]] += r["success"]
    pct = [[100.0 * s[N * i + j] / n[N * i + j] if n[N * i + j] else None for j in range(N)]
           for i in range(N)]
    return pct, sum(n), sum(s)


def pair(text, opt):
    try:
        x, y = (float(v) for v in text.split(","))
        return x, y
    except ValueError:
        figlib.die(f"{opt} '{text}': expected X,Y in metres")


def draw(ax, pct, title, a, cmap):
    import numpy as np
    cx, cy = pair(a.centre, "--centre")
    half = N * a.cell / 2
    data = np.array([[np.nan if v is None else v for v in row] for row in pct])
    # column j at y = cy + (j - 3) cell, row i at x = cx + (i - 3) cell; looking down on the
    # table with the robot below: x up, y growing to the left
    im = ax.imshow(data, origin="lower", cmap=cmap, vmin=0, vmax=100,
                   extent=(cy - half, cy + half, cx - half, cx + half))
    ax.invert_xaxis()
    for dx, dy in ((a.spacing, 0), (-a.spacing, 0), (0, a.spacing), (0, -a.spacing)):
        ax.plot(cy + dy, cx + dx, "o", color="white", ms=6, mec="black", mew=0.5)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("y (m)", fontsize=8)
    ax.set_ylabel("x (m)", fontsize=8)
    ax.tick_params(labelsize=7)
    return im


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("trials")
    ap.add_argument("--test", default="generalisation")
    ap.add_argument("--pick", action="append", default=[], help="COND:RUN, the run a panel shows")
    ap.add_argument("--centre", default="0.30,0.10")
    ap.add_argument("--cell", type=float, default=0.05)
    ap.add_argument("--spacing", type=float, default=0.10)
    figlib.add_out_argument(ap, "fig3_10")
    a = ap.parse_args()
    outs = figlib.outputs(a, "fig3_10")
    picks = {}
    for p in a.pick:
        cond, _, run = p.rpartition(":")
        if not cond or not run.isdigit():
            figlib.die(f"--pick '{p}': expected CONDITION:RUN, e.g. ST-CT:7")
        picks[cond] = int(run)
    rows = load(a.trials, a.test)
    chosen, panels = {}, []
    for cond in figlib.ordered(r["condition"] for r in rows):
        chosen[cond] = choose(rows, cond, picks, chosen)
        pct, n, s = grid(rows, cond, chosen[cond])
        if not n:
            figlib.die(f"{a.trials}: {cond} has no trials of run {chosen[cond][0]} individual "
                       f"{chosen[cond][1]} (the individual its condition shows)")
        panels.append((cond, pct))
        print(f"{figlib.PROG}: {cond} run {chosen[cond][0]} individual {chosen[cond][1]}: "
              f"{s} of {n} trials ({100.0 * s / n:.4g} %), cells with trials "
              f"{sum(v is not None for row in pct for v in row)}")
    plt = figlib.pyplot()
    cols = min(3, len(panels))
    rws = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rws, cols, figsize=(3.2 * cols + 1.2, 3.2 * rws),
                             squeeze=False, layout="constrained")
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("#dddddd")
    for k, (cond, pct) in enumerate(panels):
        im = draw(axes[k // cols][k % cols], pct, f"{cond} (run {chosen[cond][0]})", a, cmap)
    for k in range(len(panels), rws * cols):
        axes[k // cols][k % cols].axis("off")
    fig.colorbar(im, ax=[ax for row in axes for ax in row], label="successful trials (%)", shrink=0.8)
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
