#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What a run gave, for the end of `make run`: when each stage was completed, what the final best
solves, how the run departs from the thesis's protocol (its config.ini's keys away from their
defaults, tier by tier: tools/keytable.py), the files and what each holds, and a PNG plot of the
run's fitness written next to them (with the command that redraws it).

    /usr/bin/python3 tools/run_report.py RUN_DIR [--no-plot]

Stage completion is read from fitness.csv (the first generation in which ga.success_genotypes
genotypes solve every trial, as apps/evolve decides it); the plot is tools/plot_fitness.py's.
"""
import argparse
import os
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import figlib  # noqa: E402
import keytable  # noqa: E402
from plot_fitness import PRIMS  # noqa: E402
from runs_summary import success_genotypes  # noqa: E402

figlib.PROG = "run_report"
# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
COLUMNS = csvschema.pick(csvschema.FITNESS, "generation", "best", "stage", "all_success", "best_t%d")

FILES = [  # (name, what it holds)
    ("config.ini", "the resolved configuration, every key (./apps/evolve DIR/config.ini --out NEW reruns it)"),
    ("fitness.csv", "one row per generation: best, mean, worst, the best's F_p and the trials it solves"),
    ("best.genome", "the best genotype of every generation"),
    ("population.genome", "the final population, best first, with fitness"),
    ("checkpoint", "where --resume continues from"),
]


def read_rows(path):
    """a primitive run's fitness.csv: its stages, their completions and the trials the best solves"""
    return figlib.read_fitness(path, ("generation", "best", "stage", "all_success", "best_t0"),
                               "the fitness.csv of a primitive run of ./apps/evolve")


def stage_lines(rows, need):
    """one line per stage the run reached: complete at generation G, or not (yet)"""
    lines, seen = [], []
    for r in rows:
        if r["stage"] not in seen:
            seen.append(r["stage"])
    for stage in seen:
        mine = [r for r in rows if r["stage"] == stage]
        done = next((i for i, r in enumerate(mine) if r["all_success"] >= need), None)
        if done is not None:
            r = mine[done]
            lines.append(f"{stage}: complete at generation {r['generation']} ({r['all_success']} "
                         f"genotypes solve every trial; {need} needed), after {done + 1} "
                         f"generations of this stage")
        else:
            most = max(r["all_success"] for r in mine)
            lines.append(f"{stage}: not complete after {len(mine)} generations (at most {most} of "
                         f"the {need} genotypes needed solved every trial in one generation)")
    return lines


def best_line(row):
    n = figlib.trial_columns(row)
    solved = [row[f"best_t{k}"] == 1 for k in range(n)]
    per = ", ".join(f"{p} {sum(solved[4 * i:4 * i + 4])}/{len(solved[4 * i:4 * i + 4])}"
                    for i, p in enumerate(PRIMS) if solved[4 * i:4 * i + 4])
    return (f"the best of the last generation ({row['generation']}, {row['stage']}): fitness "
            f"{row['best']:.2f}, solves {sum(solved)}/{n} trials ({per})")


def protocol_line(run_dir):
    """which reach starts and contact solver the run used (SPEC 13), from its config.ini; a key
    the file lacks (made before the key existed) is at its default, as evolve reads it"""
    path = os.path.join(run_dir, "config.ini")
    if not os.path.exists(path):
        return f"reach starts and contact solver: not recorded (no {path})"
    values = keytable.read_ini(path)
    value = lambda key: values.get(key, keytable.KEYS[key][2])
    starts = "palm down" if value("postures.reach_palm_down").lower() in ("true", "yes", "on", "1") else \
        "position only, palm as the arm leaves it"
    contact = "none (simple-prim is kinematic)" if value("stage.stages") == "simple_prim" else \
        f"ODE, dynamics.lcp = {value('dynamics.lcp')}"
    return f"reach starts {starts} (postures.reach_palm_down); contact {contact}"


def shortest(value):
    """a real as config.ini writes it (%.17g: 0.90000000000000002) in the fewest digits that read
    back to it (0.9); any other value as it is"""
    try:
        x = float(value)
    except ValueError:
        return value
    return repr(x) if "." in value or "e" in value.lower() else value


def departure_lines(run_dir):
    """how the run departs from the thesis's protocol, one line per tier (keytable.departures of
    its config.ini); nothing without a config.ini"""
    path = os.path.join(run_dir, "config.ini")
    if not os.path.exists(path):
        return []
    found = keytable.departures(path)
    if not found:
        return ["the thesis's protocol: no key away from it (config.ini)"]
    lines = ["how it departs from the thesis's protocol (config.ini, each key's default after it):"]
    for tier in keytable.TIERS:
        keys = [f"{k} = {shortest(v)} ({d})" for t, k, v, d in found if t == tier]
        if keys:
            what = " (the same results)" if tier == "speed" else ""
            lines.append(f"  {tier}{what}: " + ", ".join(keys))
    return lines


def plot(csv_path, png):
    """draws the PNG with this interpreter; returns the command, and an error or None"""
    cmd = [sys.executable, "tools/plot_fitness.py", csv_path, "-o", png]
    r = subprocess.run(cmd, capture_output=True, text=True)
    return " ".join(shlex.quote(c) for c in cmd), (r.stderr.strip() or "failed") if r.returncode else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--no-plot", action="store_true", help="report only, draw nothing")
    a = ap.parse_args()
    d = a.run_dir.rstrip("/")
    csv_path = f"{d}/fitness.csv"
    rows = read_rows(csv_path)
    need = success_genotypes(d)
    print(f"\n== what the run gave ({d})")
    print(f"  {protocol_line(d)}")
    for line in stage_lines(rows, need):
        print(f"  {line}")
    print(f"  {best_line(rows[-1])}")
    for line in departure_lines(d):
        print(f"  {line}")
    print(f"  files in {d}/:")
    for name, what in FILES:
        if os.path.exists(f"{d}/{name}"):
            print(f"    {name:<18} {what.replace('DIR', d)}")
    if not a.no_plot:
        png = f"{d}/fitness.png"
        cmd, err = plot(csv_path, png)
        if err:
            print(f"  no plot: {err}")
        else:
            print(f"    {'fitness.png':<18} the plot of fitness.csv: fitness, the best's F_p, the trials it solves")
        print(f"  redraw the plot: {cmd}")
    print(f"  replay a trial (K = 0..15) of the last generation's best, step by step:\n"
          f"    ./apps/replay {d}/best.genome {d}/config.ini --trial K --out trace.csv")
    print("  for comparison: the thesis's simple-prim took a median of 484 generations over 10 runs "
          "(§3.1);\n  this repository's runs are in data/evolved/README.md")


if __name__ == "__main__":
    main()
