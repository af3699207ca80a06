# SPDX-License-Identifier: MIT
"""Shared by the thesis-figure scripts (tools/fig_*.py) and the robot's pictures and videos
(draw_trial.py, trial_video.py): CSV reading that names FILE:LINE and what was expected, replay
traces, type-7 quartiles, the conditions' order, and writing PNG and SVG through matplotlib
(Debian's python3-matplotlib; run the scripts with /usr/bin/python3).

Every script reads and checks all of its input before it imports matplotlib, so a malformed
file is refused quickly and without drawing anything. Errors go to stderr as "PROG: message",
exit status 1.
"""
import csv
import math
import os
import sys

PROG = "fig"
# the thesis's order of the conditions (Table 2.1, Tables 3.1-3.2); others follow as they come
CONDITIONS = ["ST-CT", "ST", "CT", "NI", "ST-CT0", "ST0"]
WORDS = ["reach", "open", "grasp", "move"]


def die(msg):
    print(f"{PROG}: {msg}", file=sys.stderr)
    sys.exit(1)


def _int(v):
    return int(v)


def _float(v):
    x = float(v)
    if not math.isfinite(x):
        raise ValueError
    return x


# "text" may be empty (replay's event column), "str" may not
KINDS = {"int": (_int, "an integer"), "float": (_float, "a finite number"), "str": (str, "a name"),
         "text": (str, "text")}


def line_of(data, offset):
    """the line number of a byte offset"""
    return data[:offset].count(b"\n") + 1


def read_csv(path, columns, what):
    """rows of path as dicts, the columns named in `columns` ({name: "int"|"float"|"str"})
    converted; other columns kept as text. what: the file's kind for the messages."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        die(f"{path}: {e.strerror}")
    nul = data.find(b"\0")
    if nul >= 0:
        die(f"{path}:{line_of(data, nul)}: NUL byte (expected {what}, text)")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        die(f"{path}:{line_of(data, e.start)}: not UTF-8 text (expected {what})")
    lines = [(n, s) for n, s in enumerate(text.splitlines(), start=1)
             if s.strip() and not s.startswith("#")]
    if not lines:
        die(f"{path}: empty (expected {what} with the columns {','.join(columns)})")
    header = next(csv.reader([lines[0][1]]))
    missing = [c for c in columns if c not in header]
    if missing:
        die(f"{path}:{lines[0][0]}: header without {','.join(missing)} (expected {what} with the "
            f"columns {','.join(columns)})")
    rows = []
    for n, s in lines[1:]:
        fields = next(csv.reader([s]))
        if len(fields) != len(header):
            die(f"{path}:{n}: {len(fields)} fields (expected {len(header)}, as the header)")
        row = dict(zip(header, fields))
        for c, kind in columns.items():
            conv, expect = KINDS[kind]
            try:
                row[c] = conv(row[c])
            except ValueError:
                die(f"{path}:{n}: {c} '{row[c]}' (expected {expect})")
            if kind == "str" and not row[c]:
                die(f"{path}:{n}: {c} is empty (expected {expect})")
        row["_line"] = n
        rows.append(row)
    if not rows:
        die(f"{path}: no rows after the header (expected {what})")
    return rows


def read_trace(path, columns, what="an ./apps/replay trace (--out)"):
    """the rows of one trial's replay trace, one per step, each step the one before's + 1;
    caretaker_word and selftalk_label (when in `columns`) -1 (none) or a word 0-3"""
    rows = read_csv(path, columns, what)
    for prev, r in zip([None] + rows, rows):
        if prev is not None and r["step"] != prev["step"] + 1:
            die(f"{path}:{r['_line']}: step {r['step']} (expected {prev['step'] + 1}: one row per "
                "step)")
        for c in ("caretaker_word", "selftalk_label"):
            if c in columns and not -1 <= r[c] <= 3:
                die(f"{path}:{r['_line']}: {c} {r[c]} (expected -1 for none or 0-3: "
                    f"{', '.join(WORDS)})")
    return rows


def quartiles(xs):
    """(q1, median, q3) of definition 7 (R's default; numpy's and matplotlib's boxplot)"""
    s = sorted(xs)

    def q(p):
        h = (len(s) - 1) * p
        j = math.floor(h)
        return s[j] if j + 1 >= len(s) else s[j] + (h - j) * (s[j + 1] - s[j])
    return q(0.25), q(0.5), q(0.75)


def ordered(names):
    """the distinct names, the thesis's conditions first"""
    seen = list(dict.fromkeys(names))
    return [c for c in CONDITIONS if c in seen] + [c for c in seen if c not in CONDITIONS]


def add_out_argument(ap, default):
    ap.add_argument("-o", "--out", action="append", default=None,
                    help=f"output .png or .svg (repeatable); default {default}.png and {default}.svg")


def outputs(a, default):
    outs = a.out or [default + ".png", default + ".svg"]
    for o in outs:
        if os.path.splitext(o)[1].lower() not in (".png", ".svg"):
            die(f"{o}: unknown output format (expected a name ending in .png or .svg)")
    return outs


def pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        die(f"drawing needs matplotlib, which {sys.executable} does not have (Debian: apt-get "
            "install python3-matplotlib, then run /usr/bin/python3)")
    matplotlib.rcParams["svg.hashsalt"] = "selftalk"  # the same SVG for the same data
    matplotlib.rcParams["svg.fonttype"] = "none"      # text stays text
    return plt


def save(plt, fig, outs):
    """writes each output atomically; PNG at 100 dpi, SVG without a date"""
    for o in outs:
        fmt = os.path.splitext(o)[1].lower()[1:]
        tmp = o + ".tmp"
        meta = {"Date": None} if fmt == "svg" else {}
        fig.savefig(tmp, format=fmt, dpi=100, metadata=meta)
        os.replace(tmp, o)
        print(f"{PROG}: wrote {o}")
    plt.close(fig)


def panel_per_run(doc, default, load, describe, panel, width, height):
    """the main of a figure with one panel per run: RUN... [--label NAME]... [-o FILE]...;
    load(arg) reads a run (refusing what it cannot draw), describe(run) is the line printed
    for it, panel(ax, run, title) draws it; height: inches per panel"""
    import argparse
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--label", action="append", default=[], help="panel title, one per run")
    add_out_argument(ap, default)
    a = ap.parse_args()
    outs = outputs(a, default)
    if a.label and len(a.label) != len(a.runs):
        die(f"{len(a.label)} --label for {len(a.runs)} runs (expected one per run)")
    runs = [load(r) for r in a.runs]
    for run in runs:
        print(describe(run))
    plt = pyplot()
    fig, axes = plt.subplots(len(runs), 1, figsize=(width, height * len(runs) + 0.4), squeeze=False)
    for i, run in enumerate(runs):
        panel(axes[i][0], run, a.label[i] if a.label else run["path"])
    axes[-1][0].set_xlabel("generation")
    fig.tight_layout()
    save(plt, fig, outs)
