#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plot a run's fitness.csv: a self-contained SVG (standard library only) or a PNG (matplotlib).

    python3 tools/plot_fitness.py RUN_DIR/fitness.csv [-o plot.svg|plot.png] [--from G] [--to G]

Three panels over generations: best and mean fitness (stage changes marked), the best
individual's per-primitive fitness F_p (the harmonic mean's parts: the lowest is the one holding
the run back), and which of the 16 trials the best solves (one row per trial, filled when
solved). This is the evidence to look at when a run stalls. The columns are those apps/evolve
writes (see docs/PROTOCOL.md, "Evolution runs"); only generation and best are required.
The output's extension picks the format (default: the CSV's name with .svg). PNG needs
matplotlib (Debian: python3-matplotlib, for /usr/bin/python3).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

PRIMS = ["reach", "open", "grasp", "move"]
# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
COLUMNS = csvschema.pick(csvschema.FITNESS, "generation", "best", "mean", "stage", "best_t%d",
                         *("best_F_" + p for p in PRIMS))
COLOURS = {"best": "#1f77b4", "mean": "#ff7f0e", "reach": "#2ca02c", "open": "#9467bd",
           "grasp": "#d62728", "move": "#8c564b"}

figlib.PROG = "plot_fitness"  # the name errors carry (tools/run_report.py sets its own)
die = figlib.die


def read(path, lo, hi, columns=("generation", "best")):
    """the rows of fitness.csv (figlib.read_fitness: every column checked) in [lo, hi]"""
    rows = figlib.read_fitness(path, columns)
    out = [r for r in rows if (lo is None or r["generation"] >= lo) and (hi is None or r["generation"] <= hi)]
    if not out:
        die(f"{path}: no generation in the requested range")
    return out


def num(r, k):
    try:
        return float(r[k])
    except (KeyError, TypeError, ValueError):
        return None


class Panel:
    """One plot area: maps (generation, value) to SVG coordinates."""

    def __init__(self, svg, top, height, g0, g1, v0, v1, title):
        self.svg, self.top, self.h = svg, top, height
        self.left, self.w = 70, 820
        self.g0, self.g1 = g0, g1 if g1 > g0 else g0 + 1
        self.v0, self.v1 = v0, v1 if v1 > v0 else v0 + 1
        svg.append(f'<rect x="{self.left}" y="{top}" width="{self.w}" height="{height}" '
                   'fill="none" stroke="#888"/>')
        svg.append(f'<text x="{self.left}" y="{top - 6}" font-size="13">{title}</text>')

    def x(self, g):
        return self.left + self.w * (g - self.g0) / (self.g1 - self.g0)

    def y(self, v):
        return self.top + self.h * (1 - (v - self.v0) / (self.v1 - self.v0))

    def yticks(self, n=4):
        for i in range(n + 1):
            v = self.v0 + (self.v1 - self.v0) * i / n
            y = self.y(v)
            self.svg.append(f'<text x="{self.left - 6}" y="{y + 4:.1f}" font-size="11" '
                            f'text-anchor="end">{v:.4g}</text>')
            self.svg.append(f'<line x1="{self.left}" x2="{self.left + self.w}" y1="{y:.1f}" '
                            f'y2="{y:.1f}" stroke="#eee"/>')

    def xticks(self, n=8):
        for i in range(n + 1):
            g = round(self.g0 + (self.g1 - self.g0) * i / n)
            x = self.x(g)
            self.svg.append(f'<text x="{x:.1f}" y="{self.top + self.h + 14}" font-size="11" '
                            f'text-anchor="middle">{g}</text>')

    def line(self, gs, vs, colour, label, slot):
        pts = " ".join(f"{self.x(g):.1f},{self.y(v):.1f}" for g, v in zip(gs, vs) if v is not None)
        if not pts:
            return
        self.svg.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" '
                        'stroke-width="1.2"/>')
        lx = self.left + self.w + 10
        ly = self.top + 14 + 16 * slot
        self.svg.append(f'<line x1="{lx}" x2="{lx + 18}" y1="{ly - 4}" y2="{ly - 4}" '
                        f'stroke="{colour}" stroke-width="2"/>')
        self.svg.append(f'<text x="{lx + 22}" y="{ly}" font-size="11">{label}</text>')


def stage_changes(rows, gs):
    """(generation, new stage) wherever the stage column changes"""
    return [(gs[i], rows[i]["stage"]) for i in range(1, len(rows))
            if rows[i].get("stage") != rows[i - 1].get("stage")]


def solved_spans(rows, gs, k):
    """(first, last) generations of each run of consecutive rows in which the best solves trial k"""
    spans, start = [], None
    for i, r in enumerate(rows + [None]):
        solved = r is not None and r.get(f"best_t{k}") == 1
        if solved and start is None:
            start = gs[i]
        if not solved and start is not None:
            spans.append((start, gs[i - 1]))
            start = None
    return spans


def segments(rows, gs, key):
    """(generations, values) of column key, one piece per stage: a stage change is a new
    fitness function, not a fall of the same one, so the lines are not joined across it"""
    pieces, cur, stage = [], ([], []), None
    for g, r in zip(gs, rows):
        if r.get("stage") != stage and cur[0]:
            pieces.append(cur)
            cur = ([], [])
        stage = r.get("stage")
        v = num(r, key)
        if v is not None:
            cur[0].append(g)
            cur[1].append(v)
    if cur[0]:
        pieces.append(cur)
    return pieces


def png(a, rows, out):
    """the same three panels as the SVG, drawn by matplotlib"""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        die(f"{out}: PNG needs matplotlib, which {sys.executable} does not have (Debian: apt-get "
            "install python3-matplotlib, then run /usr/bin/python3); an .svg output needs nothing")
    gs = [int(r["generation"]) for r in rows]
    trials = [k for k in range(16) if f"best_t{k}" in rows[0]]
    has_fp = any(num(r, f"best_F_{p}") is not None for r in rows for p in PRIMS)
    ratios = [3] + ([2] if has_fp else []) + ([2] if trials else [])
    fig, axes = plt.subplots(len(ratios), 1, figsize=(10, 2.6 * len(ratios) + 0.6), sharex=True,
                             gridspec_kw={"height_ratios": ratios}, squeeze=False)
    axes = [ax[0] for ax in axes]
    ax = axes[0]
    for key in ("best", "mean"):
        for i, (xs, vs) in enumerate(segments(rows, gs, key)):
            ax.plot(xs, vs, color=COLOURS[key], lw=1.2, label=key if i == 0 else None)
    ax.set_ylabel("fitness F")
    ax.set_ylim(bottom=min(0.0, ax.get_ylim()[0]))
    ax.set_title(f"{a.csv}: {len(rows)} generations ({gs[0]}-{gs[-1]})", fontsize=11)
    panel = 1
    if has_fp:
        ax = axes[panel]
        panel += 1
        for p in PRIMS:
            for i, (xs, vs) in enumerate(segments(rows, gs, f"best_F_{p}")):
                ax.plot(xs, vs, color=COLOURS[p], lw=1.0, label=f"F_{p}" if i == 0 else None)
        ax.set_ylabel("best's F_p")
        ax.set_ylim(bottom=min(0.0, ax.get_ylim()[0]))
    if trials:
        ax = axes[panel]
        width = max(1, gs[-1] - gs[0] + 1) / max(1, len(gs))  # one row's width in generations
        for k in trials:
            spans = [(g0 - width / 2, g1 - g0 + width) for g0, g1 in solved_spans(rows, gs, k)]
            ax.broken_barh(spans, (k - 0.4, 0.8), color=COLOURS[PRIMS[min(k // 4, 3)]], lw=0)
        ax.set_ylim(15.6, -0.6)
        ax.set_yticks(range(0, 16, 4))
        ax.set_yticks(range(16), minor=True)
        ax.set_ylabel("trial the best solves")
        for i, p in enumerate(PRIMS):  # the colours' key, beside each primitive's rows
            ax.text(1.01, 4 * i + 1.5, f"{p} {4 * i}-{4 * i + 3}", color=COLOURS[p], fontsize=8,
                    va="center", transform=ax.get_yaxis_transform())
    for ax in axes:
        for g, stage in stage_changes(rows, gs):
            ax.axvline(g - 0.5, color="#555", ls="--", lw=0.8)
            if ax is axes[0]:
                ax.text(g, ax.get_ylim()[1], f" {stage}", fontsize=8, va="top")
        ax.set_axisbelow(True)  # grid lines behind the spans: no false gaps
        ax.grid(True, color="#eee")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    axes[-1].set_xlabel("generation")
    axes[-1].set_xlim(gs[0] - 0.5, gs[-1] + 0.5)
    fig.tight_layout()
    tmp = out + ".tmp"
    fig.savefig(tmp, format="png", dpi=100)
    plt.close(fig)
    os.replace(tmp, out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("-o", "--out", default=None,
                    help="plot.svg (no dependencies) or plot.png (matplotlib); default: the CSV's "
                         "name with .svg")
    ap.add_argument("--from", dest="lo", type=int, default=None, help="first generation")
    ap.add_argument("--to", dest="hi", type=int, default=None, help="last generation")
    a = ap.parse_args()
    rows = read(a.csv, a.lo, a.hi)
    out = a.out or (a.csv[:-4] if a.csv.endswith(".csv") else a.csv) + ".svg"
    if out.lower().endswith(".png"):
        png(a, rows, out)
        print(f"plot_fitness: {len(rows)} generations ({rows[0]['generation']}-"
              f"{rows[-1]['generation']}) -> {out}")
        return

    gs = [int(r["generation"]) for r in rows]
    g0, g1 = gs[0], gs[-1]
    best = [num(r, "best") for r in rows]
    mean = [num(r, "mean") for r in rows]
    fp = {p: [num(r, f"best_F_{p}") for r in rows] for p in PRIMS}
    trials = [k for k in range(16) if f"best_t{k}" in rows[0]]

    svg = []
    vals = [v for v in best + mean if v is not None]
    top = Panel(svg, 30, 200, g0, g1, min(0.0, min(vals)), max(vals) * 1.05,
                f"{a.csv}: fitness (best, mean)")
    top.yticks()
    top.xticks()
    top.line(gs, best, COLOURS["best"], "best", 0)
    top.line(gs, mean, COLOURS["mean"], "mean", 1)
    # stage boundaries: where the stage column changes
    for g, stage in stage_changes(rows, gs):
        x = top.x(g)
        svg.append(f'<line x1="{x:.1f}" x2="{x:.1f}" y1="30" y2="230" stroke="#555" '
                   'stroke-dasharray="4,3"/>')
        svg.append(f'<text x="{x + 4:.1f}" y="44" font-size="11">{stage}</text>')
    height = 250
    if any(v is not None for p in PRIMS for v in fp[p]):
        vals = [v for p in PRIMS for v in fp[p] if v is not None]
        mid = Panel(svg, 270, 180, g0, g1, min(0.0, min(vals)), max(vals) * 1.05,
                    "best individual's F_p per primitive")
        mid.yticks()
        mid.xticks()
        for i, p in enumerate(PRIMS):
            mid.line(gs, fp[p], COLOURS[p], f"F_{p}", i)
        height = 470
    if trials:
        t = Panel(svg, height + 20, 10 * len(trials), g0, g1, 0, len(trials),
                  "trials the best solves (row k = trial k; reach 0-3, open 4-7, grasp 8-11, "
                  "move 12-15)")
        t.xticks()
        wcell = max(t.w / max(1, g1 - g0 + 1), 0.5)
        for k in trials:
            y = t.top + 10 * k
            svg.append(f'<text x="{t.left - 6}" y="{y + 9}" font-size="9" '
                       f'text-anchor="end">{k}</text>')
            for first, last in solved_spans(rows, gs, k):
                x0 = t.x(first)
                x1 = min(t.x(last) + wcell, t.left + t.w)
                prim = PRIMS[min(k // 4, 3)]
                svg.append(f'<rect x="{x0:.1f}" y="{y + 1}" width="{x1 - x0:.1f}" '
                           f'height="8" fill="{COLOURS[prim]}"/>')
        height = t.top + t.h + 30
    doc = (f'<svg xmlns="http://www.w3.org/2000/svg" width="1000" height="{height}" '
           'font-family="sans-serif">\n<rect width="100%" height="100%" fill="white"/>\n' +
           "\n".join(svg) + "\n</svg>\n")
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        f.write(doc)
    os.replace(tmp, out)
    print(f"plot_fitness: {len(rows)} generations ({g0}-{g1}) -> {out}")


if __name__ == "__main__":
    main()
