#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Fig. 3.3: the integration test (§2.10.1, §3.1.1) - how many individuals succeeded in
how many of its caretaker-guided trials, one bar colour per condition (the thesis: the
incremental runs, simple-prim then main-prim, against the non-incremental ones, main-prim only).

    /usr/bin/python3 tools/fig_integration.py SUMMARY.csv... [--bin 5] [--label NAME...]
                                              [-o fig3_3.png]...

Each SUMMARY.csv is a post-evaluation summary (docs/PROTOCOL.md, "Post-evaluation files"): one row
per individual, test,condition,run,individual,successes,trials,excluded,open_jumped; the rows of
test "integration" are drawn (the others are skipped), their conditions free names (e.g.
incremental, nonincremental). --label names each file's rows instead, one name per file in
order (each file then holds one condition), so that two protocols' tests, each run with
posteval's default condition, are drawn side by side (--label thesis chain); files given the
same label pool into one condition, each run's test told apart by its run_label (posteval's name
of the population: --label study study for two runs' tests). Every individual of the test has
the same number of trials (40) and appears once; none is excluded. The bars
count the individuals whose successes fall in each bin of --bin trials (the last bin closed:
35-40 of 40 with the default 5). Prints, per condition, n, median,
quartiles (definition 7, as ./apps/stats), extremes and the counts per bin, then the same
statistics of open_jumped over all individuals (the thesis: median 30 of 40, quartiles 20.25
and 35) and per condition. Default outputs fig3_3.png and fig3_3.svg.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "fig_integration"
COLUMNS = csvschema.pick(csvschema.SUMMARY, "test", "condition", "run", "individual", "successes",
                         "trials", "excluded", "open_jumped")
TEST = "integration"
COLOURS = ["#4c72b0", "#dd8452", "#55a868", "#c44e52", "#8172b3", "#937860"]


def check_row(path, r):
    """one integration row: counts in range, none excluded"""
    n = f"{path}:{r['_line']}"
    if r["trials"] < 1 or not 0 <= r["successes"] <= r["trials"]:
        figlib.die(f"{n}: successes {r['successes']} of {r['trials']} trials (expected 0 <= "
                   "successes <= trials, trials >= 1)")
    if not 0 <= r["open_jumped"] <= r["trials"]:
        figlib.die(f"{n}: open_jumped {r['open_jumped']} of {r['trials']} trials (expected 0..trials)")
    if r["excluded"] != 0:
        figlib.die(f"{n}: excluded {r['excluded']} (expected 0: the integration test excludes no one)")


def load(path, only=False):
    """one file's integration rows, each checked on its own; only: a row of another test is
    refused (a file that should hold the integration test alone), else skipped"""
    rows = figlib.read_csv(path, COLUMNS, "a post-evaluation summary")
    other = next((r for r in rows if r["test"] != TEST), None)
    if only and other:
        figlib.die(f"{path}:{other['_line']}: test '{other['test']}' (expected an integration "
                   "test's summary.csv (./apps/posteval integration))")
    rows = [r for r in rows if r["test"] == TEST]
    if not rows:
        figlib.die(f"{path}: no rows of test '{TEST}' (expected the integration test's summary rows)")
    for r in rows:
        check_row(path, r)
        r["_path"] = path
    return rows


def where(r, other):
    """row other as row r's error message names it: its line in the same file, else file:line"""
    return f"line {other['_line']}" if other["_file"] == r["_file"] else f"{other['_path']}:{other['_line']}"


def load_all(paths, labels, only=False):
    """the rows of every file, each file's condition replaced by its label if given; every
    individual with the first row's trials, and once only (in one file or across files);
    only: as load's"""
    if labels and len(labels) != len(paths):
        figlib.die(f"--label: {len(labels)} names for {len(paths)} summaries (expected one per file)")
    rows, seen = [], {}
    for i, path in enumerate(paths):
        part = load(path, only)
        for r in part:
            r["_file"] = i  # the same path given twice is two files
        if labels:
            conds = figlib.ordered(r["condition"] for r in part)
            if len(conds) > 1:
                figlib.die(f"{path}: conditions {', '.join(conds)} (expected one with --label)")
            for r in part:
                r["condition"] = labels[i]
        rows += part
    first = rows[0]
    for r in rows:
        n = f"{r['_path']}:{r['_line']}"
        if r["trials"] != first["trials"]:
            figlib.die(f"{n}: {r['trials']} trials (expected {first['trials']}, as {where(r, first)}: "
                       "every individual of the test has the same trials)")
        # run_label (posteval's name of the population, when it has one) tells apart two runs'
        # tests given the same --label, each of them run 0: one condition pooled from several runs
        label = r.get("run_label", "")
        key = (r["condition"], label, r["run"], r["individual"])
        if key in seen:
            o = seen[key]
            run = f"run {key[2]}" + (f" ({label})" if label else "")
            if o["_file"] == r["_file"]:
                figlib.die(f"{n}: {key[0]} {run} individual {key[3]} again (expected one row "
                           f"per individual; first at {where(r, o)})")
            figlib.die(f"{n}: {key[0]} {run} individual {key[3]} is also at {where(r, o)} "
                       "(expected each individual once; --label names each file)")
        seen[key] = r
    return rows


def bins(trials, width):
    """[(lo, hi)] covering 0..trials, width trials each, the last closed (35-40 of 40 by 5)"""
    edges = list(range(0, trials + 1, width))
    if len(edges) > 1 and trials - edges[-1] + 1 < width:
        edges.pop()  # a short remainder joins the last full bin
    return [(lo, (edges[i + 1] - 1) if i + 1 < len(edges) else trials) for i, lo in enumerate(edges)]


def label(b):
    return f"{b[0]}-{b[1]}" if b[1] > b[0] else f"{b[0]}"


def counts(xs, bs):
    return [sum(lo <= x <= hi for x in xs) for lo, hi in bs]


def stats(xs):
    q1, med, q3 = figlib.quartiles(xs)
    return f"n={len(xs)} median={med:g} q1={q1:g} q3={q3:g} min={min(xs)} max={max(xs)}"


def report(rows, conds, bs):
    for c in conds:
        xs = [r["successes"] for r in rows if r["condition"] == c]
        per = " ".join(f"{label(b)}:{k}" for b, k in zip(bs, counts(xs, bs)))
        print(f"{figlib.PROG}: {c}: successes {stats(xs)}")
        print(f"{figlib.PROG}: {c}: individuals per bin {per}")
    print(f"{figlib.PROG}: open jumped, all: {stats([r['open_jumped'] for r in rows])}")
    for c in conds:
        print(f"{figlib.PROG}: open jumped, {c}: "
              f"{stats([r['open_jumped'] for r in rows if r['condition'] == c])}")


def draw(plt, rows, conds, bs, trials):
    fig, ax = plt.subplots(figsize=(max(5.5, 0.3 * len(bs) * len(conds) + 2.5), 3.8))
    width = 0.8 / len(conds)
    for i, c in enumerate(conds):
        xs = [r["successes"] for r in rows if r["condition"] == c]
        med = figlib.quartiles(xs)[1]
        pos = [b + (i - (len(conds) - 1) / 2) * width for b in range(len(bs))]
        ax.bar(pos, counts(xs, bs), width, color=COLOURS[i % len(COLOURS)],
               label=f"{c} (n = {len(xs)}, median {med:g})")
    ax.set_xticks(range(len(bs)))
    ax.set_xticklabels([label(b) for b in bs], fontsize=8, rotation=90 if len(bs) > 12 else 0)
    ax.set_xlabel(f"successful trials (of {trials})")
    ax.set_ylabel("individuals")
    ax.yaxis.get_major_locator().set_params(integer=True)
    ax.set_title("integration test", fontsize=10)
    ax.grid(True, axis="y", color="#eee")
    ax.set_axisbelow(True)
    ax.legend(fontsize=8, frameon=False)
    fig.tight_layout()
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("summary", nargs="+")
    ap.add_argument("--bin", type=int, default=5, help="trials per bar (default 5)")
    ap.add_argument("--label", nargs="+", default=[], metavar="NAME",
                    help="one condition name per summary file, in order")
    figlib.add_out_argument(ap, "fig3_3")
    a = ap.parse_args()
    outs = figlib.outputs(a, "fig3_3")
    rows = load_all(a.summary, a.label)
    trials = rows[0]["trials"]
    if not 1 <= a.bin <= trials:
        figlib.die(f"--bin {a.bin}: expected 1..{trials} (the test's trials)")
    conds = figlib.ordered(r["condition"] for r in rows)
    bs = bins(trials, a.bin)
    report(rows, conds, bs)
    plt = figlib.pyplot()
    figlib.save(plt, draw(plt, rows, conds, bs, trials), outs)


if __name__ == "__main__":
    main()
