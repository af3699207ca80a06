#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Thesis Fig. 3.12: the self-talk and caretaker instructions over a trial, one panel per trial
(e.g. the four trial types of an individual), from ./apps/replay traces.

    ./apps/replay best.genome config.ini --trial K --out selftalk_K.csv          # self talk heard
    ./apps/replay best.genome config.ini --trial K --set integrated.words_odd=caretaker ... --out care_K.csv
    /usr/bin/python3 tools/fig_words.py selftalk_0.csv+care_0.csv selftalk_1.csv+care_1.csv ...
        [--label NAME]... [--title TEXT] [--dt 0.05] [-o fig3_12.png]...

A panel is one trace or several joined by '+'. Each trace gives one line: its caretaker words
(column caretaker_word) when the caretaker spoke in it, otherwise its self-talk labels (column
selftalk_label: the label the network produced at each step, heard at the next); -1 (none) is a
gap. Time is (step + 1) x --dt seconds (robot.control_dt, 0.05). Prints each line's runs of one
word as WORD FIRST-LAST (steps). Default outputs fig3_12.png and fig3_12.svg.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figlib  # noqa: E402

figlib.PROG = "fig_words"
COLUMNS = {"step": "int", "caretaker_word": "int", "selftalk_label": "int"}


def series(path):
    """('caretaker' or 'self talk', steps, words) of one trace"""
    rows = figlib.read_trace(path, COLUMNS, "an ./apps/replay trace")
    care = any(r["caretaker_word"] >= 0 for r in rows)
    col = "caretaker_word" if care else "selftalk_label"
    return ("caretaker" if care else "self talk"), [r["step"] for r in rows], [r[col] for r in rows]


def runs(steps, words):
    """'WORD FIRST-LAST' for each run of one word"""
    out, start = [], 0
    for i in range(1, len(words) + 1):
        if i == len(words) or words[i] != words[start]:
            name = figlib.WORDS[words[start]] if words[start] >= 0 else "none"
            out.append(f"{name} {steps[start]}-{steps[i - 1]}")
            start = i
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("panels", nargs="+", help="TRACE.csv or TRACE.csv+TRACE.csv")
    ap.add_argument("--label", action="append", default=[], help="panel title, one per panel")
    ap.add_argument("--title", help="the figure's title (e.g. the individual)")
    ap.add_argument("--dt", type=float, default=0.05, help="seconds per step (robot.control_dt)")
    figlib.add_out_argument(ap, "fig3_12")
    a = ap.parse_args()
    outs = figlib.outputs(a, "fig3_12")
    if a.label and len(a.label) != len(a.panels):
        figlib.die(f"{len(a.label)} --label for {len(a.panels)} panels (expected one per panel)")
    if a.title:
        print(f"{figlib.PROG}: title: {a.title}")
    panels = []
    for p in a.panels:
        lines = [(path,) + series(path) for path in p.split("+")]
        for path, kind, steps, words in lines:
            print(f"{figlib.PROG}: {path}: {kind}: {', '.join(runs(steps, words))}")
        panels.append(lines)
    plt = figlib.pyplot()
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 1.9 * len(panels) + 0.6), squeeze=False,
                             sharex=True)
    style = {"self talk": ("#1f77b4", "-", 0.08), "caretaker": ("#d62728", "--", -0.08)}
    for k, lines in enumerate(panels):
        ax = axes[k][0]
        for path, kind, steps, words in lines:
            c, ls, off = style[kind]
            ys = [w + off if w >= 0 else float("nan") for w in words]
            ax.step([(s + 1) * a.dt for s in steps], ys, where="post", color=c, ls=ls, lw=1.6, label=kind)
        ax.set_yticks(range(4))
        ax.set_yticklabels(figlib.WORDS, fontsize=8)
        ax.set_ylim(-0.5, 3.5)
        ax.set_title(a.label[k] if a.label else " + ".join(line[0] for line in lines), fontsize=9)
        ax.grid(True, color="#eee")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    axes[-1][0].set_xlabel("time (s)")
    if a.title:
        fig.suptitle(a.title, fontsize=10)
        fig.tight_layout(rect=(0, 0, 1, 1 - 0.35 / fig.get_figheight()))  # the title above the panels
    else:
        fig.tight_layout()
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
