# SPDX-License-Identifier: MIT
"""Shared by the tools that read the results files (tools/fig_*.py, plot_fitness.py,
run_report.py, runs_summary.py, best_run.py, mpi_model.py, replicate_cost.py,
replicate_report.py, screen_report.py, draw_trial.py, trial_video.py): the one strict reader of
their CSV files (read_csv, read_fitness, read_trace), naming FILE:LINE and what was expected;
type-7 quartiles, the conditions' order, and writing PNG and SVG through matplotlib (Debian's
python3-matplotlib; run the scripts with /usr/bin/python3).

Every script reads and checks all of its input before it imports matplotlib, so a malformed
file is refused quickly and without drawing anything. Errors go to stderr as "PROG: message",
exit status 2 (issue 48: never a traceback; tests/tools_sweep.py holds every tool to it).
"""
import csv
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402

PROG = "fig"
# the thesis's order of the conditions (Table 2.1, Tables 3.1-3.2); others follow as they come
CONDITIONS = ["ST-CT", "ST", "CT", "NI", "ST-CT0", "ST0"]
WORDS = ["reach", "open", "grasp", "move"]


def die(msg):
    print(f"{PROG}: {msg}", file=sys.stderr)
    sys.exit(2)


# the values a column holds: Python's int() and float() also take " 1", "1_0", "nan", "inf" and
# other digits than 0-9, which no writer of ours produces
_INT = re.compile(r"-?[0-9]+")
_FLOAT = re.compile(r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?")


def _int(v, lo=-2**31):
    """the C writers' int: 32 bits (a 30-digit run number breaks a plot's axis)"""
    if not _INT.fullmatch(v):
        raise ValueError
    x = int(v)
    if not lo <= x < 2**31:
        raise ValueError(f"from {lo} to {2**31 - 1}")
    return x


def _float(v, positive=False):
    if not _FLOAT.fullmatch(v):
        raise ValueError
    x = float(v)
    if not math.isfinite(x) or (positive and not x > 0):
        raise ValueError
    return x


def _float_or_nan(v):
    return math.nan if v == "nan" else _float(v)


def _bit(v):
    if v not in ("0", "1"):
        raise ValueError
    return int(v)


def _name(v):
    if not v:
        raise ValueError
    return v


# kind: (conversion, what is expected); "text" may be empty (replay's event column), "str" may not
KINDS = {"int": (_int, "an integer"), "count": (lambda v: _int(v, 0), "an integer >= 0"),
         "bit": (_bit, "0 or 1"), "float": (_float, "a finite number"),
         "positive": (lambda v: _float(v, True), "a finite number > 0"),
         "float|nan": (_float_or_nan, "a finite number, or nan for none"),
         "str": (_name, "a name"), "text": (str, "text")}

# fitness.csv's columns, csvschema's kinds made stricter where the meaning says so: a trial's
# column is 0 or 1, generations and counts are >= 0
_PER_TRIAL = {name for name, _, _, per_trial in csvschema.FITNESS_COLUMNS if per_trial}
FITNESS = {n: ("bit" if n in _PER_TRIAL else
               "count" if k == "int" else k) for n, k in csvschema.FITNESS.items()}
FITNESS_WHAT = "the fitness.csv of ./apps/evolve"
# the real columns whose writer puts nan for "none": a post-evaluation's mean steps to the target
# of an individual that never reached it (lib/posteval/posteval.c); any other nan is refused
WRITTEN_NAN = {"mean_steps_to_target"}


# a line ends at \r\n, \r or \n (str.splitlines would also end one at \f, \x1c, \u2028...)
_EOL = re.compile(r"\r\n|\r|\n")


def line_of(data, offset):
    """the line number of a byte offset"""
    return len(re.findall(rb"\r\n|\r|\n", data[:offset])) + 1


def lines_of(text):
    """the text's lines, without their ends"""
    lines = _EOL.split(text)
    return lines[:-1] if lines and lines[-1] == "" else lines


def _text(path, what):
    """the whole file as text: any file a tool reads goes through here (cannot open, NUL byte,
    not UTF-8: FILE:LINE and what was expected)"""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        die(f"{path}: {e.strerror}")
    nul = data.find(b"\0")
    if nul >= 0:
        die(f"{path}:{line_of(data, nul)}: NUL byte (expected {what}, text)")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        die(f"{path}:{line_of(data, e.start)}: not UTF-8 text (expected {what})")


def _kinds(header, columns, schema):
    """{column of the header: kind}: the columns asked for, and those of the schema (a name with
    %d standing for one column per trial) the header has"""
    out = {}
    for name, kind in (schema or {}).items():
        if "%d" in name:
            pat = re.compile(re.escape(name).replace("%d", r"(0|[1-9][0-9]*)"))
            out.update({c: kind for c in header if pat.fullmatch(c)})
        elif name in header:
            out[name] = kind
    out.update({c: k for c, k in columns.items() if c in header})
    return {c: "float|nan" if k == "float" and c in WRITTEN_NAN else k for c, k in out.items()}


def read_csv(path, columns, what, key=None, increasing=False, schema=None, live=False):
    """rows of path as dicts with "_line", the line they came from, and "_raw", the row's text
    values (as written: a number printed again reads as the file has it). columns: {name: kind} the
    file must have (KINDS); schema: {name: kind} of the columns it may have (FITNESS,
    csvschema's), checked where present; other columns kept as text. key: a column, or a tuple
    of them, that no two rows share; increasing: the key (one column) grows row by row. what:
    the file's kind, for the messages. Blank lines and lines starting with # are skipped. live:
    the file may be being written (a run's fitness.csv while it runs): a last line without its
    newline is left out, and a header alone is no rows. Any fault: die() with FILE:LINE and what
    was expected."""
    text = _text(path, what)
    if live and not text.endswith(("\n", "\r")):
        text = text[:max(text.rfind("\n"), text.rfind("\r")) + 1]
    lines = [(n, s) for n, s in enumerate(lines_of(text), start=1)
             if s.strip() and not s.startswith("#")]
    if live and len(lines) < 2:
        return []
    if not lines:
        die(f"{path}:1: empty (expected {what} with the columns {','.join(columns)})")

    def fields(n, s):
        try:
            return next(csv.reader([s], strict=True))
        except csv.Error as e:
            die(f"{path}:{n}: not a CSV line ({e}; expected {what})")
    head_n, header = lines[0][0], fields(*lines[0])
    twice = sorted({c for c in header if header.count(c) > 1})
    if twice:
        die(f"{path}:{head_n}: column {','.join(twice)} twice in the header (expected {what})")
    missing = [c for c in columns if c not in header]
    if missing:
        die(f"{path}:{head_n}: header without {','.join(missing)} (expected {what} with the "
            f"columns {','.join(columns)})")
    kinds = _kinds(header, columns, schema)
    keys = (key,) if isinstance(key, str) else tuple(key or ())
    seen, prev, rows = {}, None, []
    for n, s in lines[1:]:
        row = fields(n, s)
        if len(row) != len(header):
            die(f"{path}:{n}: {len(row)} fields (expected {len(header)}, as the header)")
        row = dict(zip(header, row))
        raw = dict(row)
        for c, kind in kinds.items():
            conv, expect = KINDS[kind]
            try:
                row[c] = conv(row[c])
            except ValueError as e:
                die(f"{path}:{n}: {c} {row[c][:40]!r} (expected {expect}{', ' + str(e) if str(e) else ''})")
        row["_line"], row["_raw"] = n, raw
        if keys:
            k = tuple(row[c] for c in keys)
            if k in seen:
                die(f"{path}:{n}: {', '.join(f'{c} {v}' for c, v in zip(keys, k))} again (first at "
                    f"line {seen[k]}; expected one row each)")
            seen[k] = n
            if increasing and prev is not None and not k[0] > prev:
                die(f"{path}:{n}: {keys[0]} {k[0]} after {prev} (expected them increasing)")
            prev = k[0]
        rows.append(row)
    if not rows:
        die(f"{path}:{head_n}: no rows after the header (expected {what})")
    return rows


# the key of a fitness.csv: one row per generation, in increasing order
GENERATION = next(iter(csvschema.pick(csvschema.FITNESS, "generation")))


def read_text(path, what):
    """the lines of a text file (without their ends), refused with FILE:LINE when it holds a NUL
    byte or is not UTF-8"""
    return lines_of(_text(path, what))


def read_fitness(path, columns=(GENERATION, "best"), what=FITNESS_WHAT, live=False):
    """the rows of a run's fitness.csv (./apps/evolve), one per generation in increasing order,
    every column of the library's table it has checked (FITNESS); columns: those it must have
    (best_t0 and the like: the per-trial columns' names)"""
    kinds = _kinds(list(columns), {}, FITNESS)
    if len(kinds) != len(set(columns)):  # a name the library's table lacks: the tool's error
        raise KeyError(f"not columns of fitness.csv: {set(columns) - set(kinds)}")
    return read_csv(path, kinds, what, key=GENERATION, increasing=True, schema=FITNESS, live=live)


def trial_columns(row, name="best_t%d"):
    """how many of the per-trial columns name (best_t%d) a row has, from 0 without a gap"""
    n = 0
    while name % n in row:
        n += 1
    return n


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
