# SPDX-License-Identifier: MIT
"""Malformed CSVs against every Python tool that reads one (issue 48), in one process.

    tools_sweep.py OUTDIR [--only NAME] [--full] [-v]

Each case is a valid input of a tool (tests/fixtures/, data/evolved/) with one mutation: an
empty file, a header alone, a NUL byte, bytes that are not UTF-8, a byte-order mark, lines cut
short or made longer, a column renamed or dropped or named twice, an unterminated quote, a
field larger than the csv module takes, a row given twice, and in each column in turn (of the
first 20) three of x, nan, inf, -inf, 1e999, empty, -1, 0, 1.5, 1_0, " 1", a huge integer (all
twelve with --full); a directory or a missing file for the file. A case's input may sit in a
copy of a committed directory (a screen, a replication: symlinks but for the file changed). The tool runs as its command line would (runpy, sys.argv; matplotlib
once for all), and the case passes when it exits 0 or 2, exit 2 with "FILE:LINE: " on stderr
(or "FILE: " when the file cannot be opened), and never a traceback. A mutation the file's
schema says is wrong (tools/csvschema.py: a number where a number is expected, a NUL byte, a
duplicated key) must be refused. Prints one line per failing case, then "tools_sweep: N
cases, M failed".
"""
import contextlib
import io
import os
import re
import runpy
import shutil
import sys
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
TOOLS = os.path.join(ROOT, "tools")
sys.path.insert(0, TOOLS)
import csvschema  # noqa: E402
import figlib  # noqa: E402

FX = os.path.join(ROOT, "tests", "fixtures")
FIG = os.path.join(FX, "figures")

# a schema's kind of a column ("%d" names match any trial), None when not in it
def kind_of(schema, col):
    if schema is None:
        return None
    if col in schema:
        return schema[col]
    for name, kind in schema.items():
        if "%d" in name and re.fullmatch(re.escape(name).replace("%d", r"\d+"), col):
            return kind
    return None


BEST_RUN = ("test,condition,run,individual,successes,trials,excluded,open_jumped,run_label,"
            "success_rate,mean_steps_to_target,unstable,generation\n"
            "robustness,ST-CT,2,0,37,40,0,0,int-stct-s3,0.925,90,0,99\n"
            "robustness,ST-CT,0,0,30,40,0,0,int-stct-s1,0.75,90,0,99\n"
            "robustness,ST-CT,1,0,37,40,0,0,int-stct-s2,0.925,90,0,98\n")
EVAL_COST = ("individual,cpu_s,wall_s,fitness,successes\n0,0.52,0.53,10.5,3\n1,0.61,0.62,12,4\n"
             "2,0.47,0.47,9,2\n3,0.9,0.91,20,6\n")

# (name, tool, the valid input's text or path, the file's name in its directory, the input's
# schema (its key: the column whose values identify a row), argv with {f} the file, {d} its
# directory, {o} an output directory)
CASES = [
    ("plot_fitness", "plot_fitness.py", f"{FIG}/prims_run/fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{f}", "-o", "{o}/p.svg"]),
    ("plot_fitness_int", "plot_fitness.py", f"{FIG}/integrated_fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{f}", "-o", "{o}/p.svg"]),
    ("run_report", "run_report.py", f"{FIG}/prims_run/fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{d}", "--no-plot"]),
    ("runs_summary", "runs_summary.py", f"{FIG}/prims_run/fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{d}"]),
    ("fig_prim_fitness", "fig_prim_fitness.py", f"{FIG}/prims_run/fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{d}", "-o", "{o}/f.svg"]),
    ("fig_chain", "fig_chain.py", f"{FIG}/chain_run.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{f}", "-o", "{o}/f.svg"]),
    ("fig_int_fitness", "fig_int_fitness.py", f"{FIG}/integrated_fitness.csv", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{f}", "-o", "{o}/f.svg"]),
    ("fig_integration", "fig_integration.py", f"{FIG}/integration_summary.csv", "summary.csv",
     (csvschema.SUMMARY, None), ["{f}", "-o", "{o}/f.svg"]),
    ("fig_boxplot", "fig_boxplot.py", f"{FX}/posteval/summary.csv", "summary.csv",
     (csvschema.SUMMARY, None), ["{f}", "--test", "robustness", "-o", "{o}/f.svg"]),
    ("best_run", "best_run.py", BEST_RUN, "summary.csv", (csvschema.SUMMARY, None),
     ["{f}", "--condition", "ST-CT"]),
    ("fig_success_maps", "fig_success_maps.py", f"{FX}/posteval/trials.csv", "trials.csv",
     (csvschema.TRIALS, None), ["{f}", "-o", "{o}/f.svg"]),
    ("fig_selftalk", "fig_selftalk.py", f"{FIG}/selftalk.csv", "selftalk.csv", (None, None),
     ["{f}", "-o", "{o}/f.svg"]),
    ("fig_words", "fig_words.py", f"{FIG}/trace_caretaker.csv", "trace.csv", (None, "step"),
     ["{f}", "-o", "{o}/f.svg"]),
    # the collision shapes of one step (./apps/replay --shapes, the grasp trial 8 of prims_s2)
    ("draw_trial", "draw_trial.py", f"{FIG}/shapes.csv", "shapes.csv",
     ({**{c: "float" for c in ("sx", "sy", "sz", "px", "py", "pz")},
       **{f"r{i}{j}": "float" for i in range(3) for j in range(3)}, "step": "int"}, None),
     ["{f}", "-o", "{o}/f.svg"]),
    ("mpi_model", "mpi_model.py", EVAL_COST, "cost.csv", (None, "individual"),
     ["{f}", "--slots", "1,2", "--samples", "3"]),
    ("mpi_model_costs", "mpi_model.py", f"{ROOT}/data/evolved/study/cost/costs.csv", "costs.csv",
     (None, None), ["{f}", "--slots", "1,2", "--samples", "3"]),
    # replicate.mk's cost: its cache of measured costs in OUT/cost/ (every kind assumed, and a
    # stand-in for build/eval_cost that prints a plan at once: pricing takes no time)
    ("replicate_cost", "replicate_cost.py", f"{ROOT}/data/evolved/study/cost/costs.csv",
     "cost/costs.csv", ({"n": "int", "mean_cpu_s": "float", "min_cpu_s": "float",
                         "max_cpu_s": "float"}, "args"),
     ["--preset", "tiny", "--protocol", "chain", "--runs", "1", "--out", "{d}", "--eval-cost", "{fake}",
      "--assume", "*=1"]),
    # --status on a replication while it runs: a run's fitness.csv being written
    ("replicate_status", "replicate_cost.py", f"{FIG}/prims_run/fitness.csv", "prims-s1/fitness.csv",
     (csvschema.FITNESS, "generation"),
     ["--preset", "tiny", "--protocol", "thesis", "--runs", "1", "--out", "{d}", "--eval-cost", "{fake}",
      "--assume", "*=1", "--status"]),
]
# what a case may accept of the mutations that are refused elsewhere: the cache of costs may not
# exist yet; a run's fitness.csv being written may not (or hold its header alone)
MAY_ACCEPT = {"replicate_cost": {"missing"},
              "replicate_status": {"missing", "empty", "blank lines", "header alone", "comments alone"},
              # files a report shows when they are there (a test not run yet)
              "screen_report_summary": {"missing"}, "replicate_report": {"missing"},
              "replicate_report_fitness": {"missing"}, "replicate_report_selftalk": {"missing"}}
# the cases whose file sits in a copy of a directory: (name, tool, directory, the file changed in
# it, schema, argv with {d} the copy)
EV = f"{ROOT}/data/evolved"
GIVEN = ["--prim-runs", f"{EV}/prims_s1 {EV}/prims_s2 {EV}/prims_s4",
         "--chain-runs", f"{EV}/chain_s1 {EV}/chain_s2 {EV}/chain_s4"]
TREES = [
    ("screen_report", "screen_report.py", f"{EV}/chain_candidates/hcg_p2_s1", "fitness.csv",
     (csvschema.FITNESS, "generation"), ["{d}"]),
    ("screen_report_summary", "screen_report.py", f"{EV}/chain_candidates/hcg_p2_s1",
     "integration/summary.csv", (csvschema.SUMMARY, None), ["{d}"]),
    ("screen_report_trials", "screen_report.py", f"{EV}/chain_candidates/hcg_p2_s1",
     "integration/trials.csv", (csvschema.TRIALS, None), ["{d}"]),
    ("replicate_report", "replicate_report.py", f"{EV}/study_palm_down", "summary/robustness.csv",
     (csvschema.SUMMARY, None), ["{d}", "--runs", "5"] + GIVEN + ["-o", "{o}/report.md"]),
    ("replicate_report_fitness", "replicate_report.py", f"{EV}/study_palm_down",
     "int-stct-s1/fitness.csv", (csvschema.FITNESS, "generation"),
     ["{d}", "--runs", "5"] + GIVEN + ["-o", "{o}/report.md"]),
    ("replicate_report_selftalk", "replicate_report.py", f"{EV}/study_palm_down",
     "stats/selftalk.csv", (None, None), ["{d}", "--runs", "5"] + GIVEN + ["-o", "{o}/report.md"]),
]
FAKE_EVAL_COST = """#!/bin/sh
echo individual,cpu_s
echo '# plan: population=10 generations=10 replace_generations=0 trials=4 individuals=2'
"""


def lines_of(text):
    return text.split("\n")


VALUES = ("x", "nan", "inf", "-inf", "1e999", "", "-1", "0", "1.5", "1_0", " 1", "9" * 30)


def mutations(text, schema, key, full=False):
    """(name, bytes or None for a directory or "missing", must be refused)"""
    schema_cols, _ = schema, key
    lines = lines_of(text)
    head_i = next(i for i, s in enumerate(lines) if s.strip() and not s.startswith("#"))
    header = lines[head_i].split(",")
    rows = [i for i in range(head_i + 1, len(lines)) if lines[i].strip() and not lines[i].startswith("#")]
    r1 = rows[0]

    def join(ls):
        return "\n".join(ls).encode()

    def with_row(i, fields):
        ls = list(lines)
        ls[i] = ",".join(fields)
        return join(ls)

    yield "empty", b"", True
    yield "blank lines", b"\n\n\n", True
    yield "header alone", join(lines[:head_i + 1] + [""]), True
    yield "comments alone", b"# nothing\n", True
    yield "NUL byte", join(lines).replace(lines[r1].encode(), lines[r1].encode() + b"\0", 1), True
    yield "not UTF-8", join(lines).replace(lines[r1].encode(), lines[r1].encode()[:-1] + b"\xe9", 1), True
    yield "byte-order mark", b"\xef\xbb\xbf" + join(lines), False
    yield "CR line ends", join(lines).replace(b"\n", b"\r"), False
    yield "CRLF line ends", join(lines).replace(b"\n", b"\r\n"), False
    yield "no final newline", join(lines).rstrip(b"\n"), False
    f1 = lines[r1].split(",")
    yield "a row cut short", with_row(r1, f1[:-1]), True
    yield "a row one field longer", with_row(r1, f1 + ["7"]), True
    yield "a row of one field", with_row(r1, f1[:1]), True
    yield "unterminated quote", with_row(r1, ['"' + f1[0]] + f1[1:]), True
    yield "a field over the csv module's limit", with_row(r1, [f1[0] + "9" * 200000] + f1[1:]), True
    yield "quoted newline", with_row(r1, ['"' + f1[0] + '\n"'] + f1[1:]), True
    yield "header: a column twice", with_row(head_i, header[:-1] + [header[0]]), True
    yield "header: first column renamed", with_row(head_i, ["zz"] + header[1:]), False
    yield "header: a column dropped", join(
        [",".join(s.split(",")[1:]) if i >= head_i and s.strip() and not s.startswith("#") else s
         for i, s in enumerate(lines)]), False
    yield "header alone, twice", join(lines[:head_i + 1] + [lines[head_i]] + [lines[r]for r in rows]), True
    if key:
        yield f"a row given twice (key {key})", join(lines[:r1 + 1] + [lines[r1]] + lines[r1 + 1:]), True
        if len(rows) > 1:
            yield "rows swapped", join([lines[rows[1]] if i == r1 else lines[r1] if i == rows[1] else s
                                        for i, s in enumerate(lines)]), key in ("generation", "step")
    else:
        yield "a row given twice", join(lines[:r1 + 1] + [lines[r1]] + lines[r1 + 1:]), False
    for c, col in enumerate(header[:20]):
        kind = kind_of(schema_cols, col)
        numeric = kind in ("int", "float")
        # quick: three values a column, in turn, so that every value meets several columns
        for v in VALUES if full else [VALUES[(3 * c + k) % len(VALUES)] for k in range(3)]:
            f = list(f1)
            if c >= len(f):
                continue
            f[c] = v
            bad = numeric and (v in ("x", "inf", "-inf", "1e999", "", "1_0", " 1")
                               or (v == "nan" and col not in figlib.WRITTEN_NAN)
                               or (kind == "int" and v in ("1.5",)))
            yield f"{col} = '{v}'", with_row(r1, f), bad
    yield "a directory", None, True
    yield "missing", "missing", True


def run(tool, argv):
    """(exit status, stderr, traceback or None) of the tool's command line, in this process"""
    err, out = io.StringIO(), io.StringIO()
    old = sys.argv
    sys.argv = [tool] + argv
    code, tb = 0, None
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            runpy.run_path(os.path.join(TOOLS, tool), run_name="__main__")
    except SystemExit as e:
        code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
        if not isinstance(e.code, int) and e.code is not None:
            err.write(str(e.code) + "\n")
    except BaseException:  # what the command line would print as a traceback
        tb = traceback.format_exc()
        code = 1
    finally:
        sys.argv = old
    return code, err.getvalue(), tb


def overlay(tree, dst, rel):
    """dst as a copy of the directory tree made of symlinks, but for the directories on the way
    to rel, which are real (rel itself is left to the caller)"""
    os.makedirs(dst, exist_ok=True)
    parts = rel.split("/")
    src = tree
    for i, part in enumerate(parts):
        for e in os.listdir(src):
            if e != part:
                os.symlink(os.path.join(src, e), os.path.join(dst, e))
        if i < len(parts) - 1:
            src, dst = os.path.join(src, part), os.path.join(dst, part)
            os.makedirs(dst)


def main():
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--only", help="one case (a name of CASES or TREES)")
    ap.add_argument("--full", action="store_true", help="every value in every column")
    ap.add_argument("-v", dest="verbose", action="store_true")
    a = ap.parse_args()
    only, full, verbose = a.only, a.full, a.verbose
    base = os.path.abspath(a.outdir)
    os.makedirs(base, exist_ok=True)
    os.chdir(ROOT)  # the tools' defaults name files of the repository
    fake = os.path.join(base, "eval_cost")
    with open(fake, "w") as fh:
        fh.write(FAKE_EVAL_COST)
    os.chmod(fake, 0o755)
    try:  # drawing once first: matplotlib imported before the cases (as the CLI would)
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot  # noqa: F401
    except ImportError:
        pass
    total = failed = 0
    cases = [c[:2] + (None,) + c[2:] for c in CASES] + [(t[0], t[1], t[2], os.path.join(t[2], t[3])) + t[3:]
                                                         for t in TREES]
    for name, tool, tree, src, fname, (schema, key), argv in cases:
        if only and only != name:
            continue
        text = open(src, encoding="utf-8").read() if os.path.exists(src) else src
        for n, (mname, data, must) in enumerate(mutations(text, schema, key, full)):
            d = os.path.join(base, f"{name}-{n}")
            shutil.rmtree(d, ignore_errors=True)
            if tree:
                overlay(tree, d, fname)
            os.makedirs(os.path.join(d, "out"), exist_ok=True)
            f = os.path.join(d, fname)
            os.makedirs(os.path.dirname(f), exist_ok=True)
            if data is None:
                os.makedirs(f)
            elif data != "missing":
                with open(f, "wb") as fh:
                    fh.write(data)
            if not tree and os.path.exists(os.path.join(os.path.dirname(src), "config.ini")):
                shutil.copy(os.path.join(os.path.dirname(src), "config.ini"), d)
            a = [x.format(f=f, d=d, o=os.path.join(d, "out"), fake=fake) for x in argv]
            code, err, tb = run(tool, a)
            total += 1
            why = None
            if tb:
                why = "traceback:\n" + tb
            elif code not in (0, 2):
                why = f"exit {code}"
            elif code == 2 and not re.search(re.escape(f) + (r"[^:\n]*: " if mname in ("a directory", "missing")
                                                             else r":\d+: "), err):
                why = f"exit 2 without '{f}:LINE: '"
            elif must and code == 0 and mname not in MAY_ACCEPT.get(name, ()):
                why = "accepted (expected a refusal)"
            if why:
                failed += 1
                print(f"tools_sweep: {name}: {mname}: {why}\n  {err.strip()[:300]}")
            elif verbose:
                print(f"tools_sweep: {name}: {mname}: exit {code} {err.strip()[:120]}")
            if not why:
                shutil.rmtree(d, ignore_errors=True)
    print(f"tools_sweep: {total} cases, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
