#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The chain stage at a glance (SPEC 12, configs/chain_prim.cfg): per generation, the share
of each kind of trial the best individual solved - the thesis's 16 fixed trials, the open,
grasp and move hand-over trials, the varied starts and the chained trials - with the chain
term F_chain on the right axis; one panel per run.

    /usr/bin/python3 tools/fig_chain.py RUN [RUN...] [--label NAME]... [-o fig_chain.png]...

RUN is an `evolve --out` directory of a run with main-prim's hand-over and chained trials (or
its fitness.csv): columns generation, best_t0..15, best_h0..11, best_c0.., best_F_chain, and
best_v0..7 when the run has varied trials (docs/PROTOCOL.md, "Hand-over trials and chained
trials"). Where the directory holds integration tests of its checkpoints, RUN/integration_gG/
summary.csv (`./apps/posteval integration ... --out RUN/integration_gG` on the checkpoint
after G generations), each is a point at G: the share of its trials that succeeded, beside the
thesis's median of 25 of 40. Prints a line per run: generations, those whose best solved the
16 fixed trials, those with a grasp hand-over and with a chained trial solved, and each
integration test (successes of trials, the median per genotype). Default outputs
fig_chain.png and fig_chain.svg.
"""
import glob
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import fig_integration  # noqa: E402  (its reader of integration summaries)
import figlib  # noqa: E402

figlib.PROG = "fig_chain"
T, H, C, V = csvschema.pick(csvschema.FITNESS, "best_t%d", "best_h%d", "best_c%d", "best_v%d")
NFIXED = csvschema.TRIAL_KINDS["fixed"]
NHAND = csvschema.TRIAL_KINDS["handover"]
NPOST = NHAND // 3  # hand-over trials per primitive: open, grasp, move in that order
WHAT = "a chain-stage run's fitness.csv (main-prim with stage.handover and stage.chain_trials)"
THESIS_MEDIAN = 25 / 40  # Fig. 3.3: the median genotype succeeded in 25 of its 40 trials


def integration_tests(run_dir):
    """[(G, successes, trials, median successes per genotype, trials per genotype)] of the
    run's integration_gG/summary.csv, by G"""
    out = []
    for path in glob.glob(os.path.join(run_dir, "integration_g*", "summary.csv")):
        m = re.fullmatch(r"integration_g(\d+)", os.path.basename(os.path.dirname(path)))
        if not m:
            continue  # another test of the run (integration_all_g77: the whole population)
        rows = fig_integration.load_all([path], None, only=True)
        per = [r["successes"] for r in rows]
        out.append((int(m.group(1)), sum(per), sum(r["trials"] for r in rows),
                    statistics.median(per), rows[0]["trials"]))
    return sorted(out)


def header_of(path):
    """(line, column names) of the header, so the run's chained and varied columns can be asked
    for (figlib.read_fitness checks the whole file after)"""
    for n, line in enumerate(figlib.read_text(path, WHAT), start=1):
        if line.strip() and not line.startswith("#"):
            return n, line.strip().split(",")
    return 1, []


def load(arg):
    path = arg if arg.endswith(".csv") and not os.path.isdir(arg) else os.path.join(arg, "fitness.csv")
    line, header = header_of(path)
    nchain = sum(1 for c in header if c.startswith("best_c") and c[6:].isdigit())
    nvaried = sum(1 for c in header if c.startswith("best_v") and c[6:].isdigit())
    if header and nchain == 0:
        figlib.die(f"{path}:{line}: header without best_c0 (expected {WHAT})")
    cols = csvschema.pick(csvschema.FITNESS, "generation", "best_F_chain")
    cols.update({T % i: "int" for i in range(NFIXED)})
    cols.update({H % i: "int" for i in range(NHAND)})
    cols.update({C % i: "int" for i in range(nchain)})
    cols.update({V % i: "int" for i in range(nvaried)})
    rows = figlib.read_fitness(path, cols, WHAT)

    def count(r, name, n, first=0):
        return sum(r[name % i] for i in range(first, first + n))

    series = {"generation": [r["generation"] for r in rows],
              "F_chain": [r["best_F_chain"] for r in rows],
              "fixed": [count(r, T, NFIXED) for r in rows],
              "chained": [count(r, C, nchain) for r in rows]}
    for p, name in enumerate(("open", "grasp", "move")):
        series[name] = [count(r, H, NPOST, p * NPOST) for r in rows]
    if nvaried:
        series["varied"] = [count(r, V, nvaried) for r in rows]
    tests = integration_tests(arg) if os.path.isdir(arg) else []
    return {"path": path, "nchain": nchain, "nvaried": nvaried, "s": series, "tests": tests}


# (series, trials it counts of, colour, line width, legend)
def lines(run):
    out = [("fixed", NFIXED, "#000000", 1.4, f"fixed ({NFIXED})"),
           ("open", NPOST, "#2ca02c", 0.9, f"open hand-over ({NPOST})"),
           ("grasp", NPOST, "#ff7f0e", 1.1, f"grasp hand-over ({NPOST})"),
           ("move", NPOST, "#9467bd", 0.9, f"move hand-over ({NPOST})")]
    if run["nvaried"]:
        out.append(("varied", run["nvaried"], "#8c8c8c", 0.9, f"varied starts ({run['nvaried']})"))
    out.append(("chained", run["nchain"], "#d62728", 1.8, f"chained ({run['nchain']})"))
    return out


def panel(ax, run, label):
    s = run["s"]
    gs = s["generation"]
    for name, n, colour, lw, legend in lines(run):
        ax.step(gs, [v / n for v in s[name]], where="mid", color=colour, lw=lw, label=legend)
    if run["tests"]:
        ax.plot([t[0] for t in run["tests"]], [t[1] / t[2] for t in run["tests"]], "D",
                color="#7f0000", ms=5, label="integration test, top 10 (share of trials)")
        ax.axhline(THESIS_MEDIAN, color="#7f0000", ls=":", lw=1.0,
                   label="thesis: median 25 of 40")
    ax.set_ylim(-0.03, 1.03)
    ax.set_ylabel("share solved by the best")
    ax.set_title(label, fontsize=10)
    ax.set_xlim(gs[0], max([gs[-1], gs[0] + 1] + [t[0] + 1 for t in run["tests"]]))
    ax.grid(True, color="#eee")
    right = ax.twinx()
    right.plot(gs, s["F_chain"], color="#1f77b4", ls="--", lw=0.9, label="F_chain (right)")
    right.set_ylabel("F_chain")
    right.set_ylim(bottom=0)
    handles = ax.get_legend_handles_labels()
    more = right.get_legend_handles_labels()
    ax.legend(handles[0] + more[0], handles[1] + more[1], loc="upper left",
              bbox_to_anchor=(1.08, 1.0), fontsize=8, frameon=False)


def summary(run):
    s = run["s"]
    gs = s["generation"]
    fixed = sum(1 for v in s["fixed"] if v == NFIXED)
    grasp = [g for g, v in zip(gs, s["grasp"]) if v]
    chained = [g for g, v in zip(gs, s["chained"]) if v]
    return (f"{figlib.PROG}: {run['path']}: {len(gs)} generations, the best solved the {NFIXED} fixed "
            f"trials in {fixed}, a grasp hand-over in {len(grasp)} (first {grasp[0] if grasp else 'none'})"
            f", a chained trial in {len(chained)} (first {chained[0] if chained else 'none'}, most "
            f"{max(s['chained'])} of {run['nchain']})"
            + "".join(f"; integration test at {g}: {k} of {n}, median {m:g} of {per}"
                      for g, k, n, m, per in run["tests"]))


def main():
    figlib.panel_per_run(__doc__, "fig_chain", load, summary, panel, 10.5, 2.9)


if __name__ == "__main__":
    main()
