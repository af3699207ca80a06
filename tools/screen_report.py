#!/usr/bin/env python3
"""One table row per screened candidate (tools/screen.mk; docs/PROTOCOL.md, "Screening chaining
candidates"): generations run and their cost, the best's trials in the last generation, and the
integration test of its top 10 (successes of 400, the median per genotype of 40, genotypes that
succeed at least once, the words heard, open jumped) beside the same trials with no words.

    python3 tools/screen_report.py DIR...

DIR is a screen's directory (fitness.csv, progress.log, integration/, integration-nowords/)."""
import collections
import csv
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csvschema  # noqa: E402
import runconfig  # noqa: E402

# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
SUMMARY = csvschema.pick(csvschema.SUMMARY, "successes")
TRIALS = csvschema.pick(csvschema.TRIALS, "heard", "open_jumped")
FITNESS = csvschema.pick(csvschema.FITNESS, "best_t%d", "best_h%d", "best_F_chain", "best_c%d", "best_v%d")


def die(msg):
    sys.exit("screen_report: " + msg)


def read_csv(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        die("%s: %s" % (path, e.strerror))


def integration(d):
    """successes, median and genotypes >= 1 of summary.csv; heard split and open jumped"""
    s = read_csv(os.path.join(d, "summary.csv"))
    t = read_csv(os.path.join(d, "trials.csv"))
    per = [int(r["successes"]) for r in s]
    heard = collections.Counter(r["heard"] for r in t)
    jumped = sum(int(r["open_jumped"]) for r in t)
    return sum(per), len(t), statistics.median(per), sum(p > 0 for p in per), len(per), heard, jumped


def cost(d):
    """seconds per generation over the progress log's sessions (each resumed run's elapsed time
    counts from its own start, and its generations from the one it resumed at), or None"""
    path = os.path.join(d, "progress.log")
    if not os.path.exists(path):
        return None
    sessions, first, last, sec = [], None, None, 0
    for line in open(path, errors="replace"):
        if line.startswith("evolve: ") and ", output in " in line:  # a (re)started run
            sessions.append((first, last, sec))
            first, last, sec = None, None, 0
        m = re.match(r"gen\s+(\d+) .*elapsed (\d+):(\d\d):(\d\d)", line)
        if m:
            last = int(m.group(1))
            if first is None:
                first = last if sessions else 0  # a fresh run's first session starts at 0
            sec = int(m.group(2)) * 3600 + int(m.group(3)) * 60 + int(m.group(4))
    sessions.append((first, last, sec))
    gens = sum(l - f + 1 for f, l, _ in sessions if f is not None)
    return sum(s for f, _, s in sessions if f is not None) / gens if gens else None


def replace_generations(d):
    """postures.vary_replace_generations of the run's config.ini (0 without one): before it
    the varied columns are 0 because the drawn starts replace open's and grasp's"""
    try:
        return runconfig.value(d, "postures", "vary_replace_generations", 0, int)
    except ValueError as e:
        die(str(e))


def row(d):
    rows = read_csv(os.path.join(d, "fitness.csv"))
    if not rows:
        die("%s/fitness.csv: no generation" % d)
    last = rows[-1]
    fixed = sum(int(last["best_t%d" % t]) for t in range(16))
    extra = ""
    if "best_h0" in last:
        extra += ", hand-over %d/12" % sum(int(last["best_h%d" % t]) for t in range(12))
    if "best_v0" in last and int(last["generation"]) < replace_generations(d):
        extra += ", varied: replacing (open and grasp from drawn starts)"
    elif "best_v0" in last:
        extra += ", varied %d/%d" % (sum(int(last["best_v%d" % t]) for t in range(csvschema.TRIAL_KINDS["varied"])),
                                     csvschema.TRIAL_KINDS["varied"])
    if "best_F_chain" in last:
        n = len([k for k in last if re.match(r"best_c\d+$", k)])
        extra += ", chained %d/%d" % (sum(int(last["best_c%d" % t]) for t in range(n)), n)
    c = cost(d)
    out = ["`%s`" % os.path.basename(os.path.normpath(d)), str(len(rows)),
           "%.0f s" % c if c else "?", "%d/16%s" % (fixed, extra)]
    it = os.path.join(d, "integration")
    if os.path.exists(os.path.join(it, "summary.csv")):
        succ, n, med, some, geno, heard, jumped = integration(it)
        split = ", ".join("`%s` %d" % (h, k) for h, k in heard.most_common(4))
        out += ["%d of %d" % (succ, n), "%g" % med, "%d of %d" % (some, geno), split, str(jumped)]
    else:
        out += ["not run"] * 5
    nw = os.path.join(d, "integration-nowords")
    out.append("%d of %d" % integration(nw)[:2] if os.path.exists(os.path.join(nw, "summary.csv")) else "not run")
    return "| " + " | ".join(out) + " |"


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) >= 2 else 2
    print("| screen | generations | per generation | best's trials (last) | integration | median of 40 |"
          " genotypes >= 1 | heard (top 4) | open jumped | no words |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for d in argv[1:]:
        print(row(d))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
