#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Summarise build/trial_sweep's output (docs/PROTOCOL.md, "Why main-prim runs stall at 15 of 16").

    tools/sweep_summary.py SWEEP.txt [--genotype I]

Prints, for the generations and genotypes of the file:
  trial T: solved in P% of genotype x generation; by N genotypes at the last generation (per
           generation min/median/max); genotypes solving it in >= 1 generation, in >= half, in all
  all listed trials: genotypes solving every listed trial, per generation (min/median/max, and
           how many generations had >= 5: the stop rule's count when the 16 are listed)
  F (when all 16 trials are listed): each generation's F of eq. 2.2-2.3 recomputed from the rows
           (F_p = 10 x successes + 100 / N_p x sum(S - P), N_p the primitive's steps, harmonic
           mean), its best genotype and what it fails
  reach geometry of genotype I (default 0): palm x and y at the last step against the object's,
           a least-squares line (a gain of 1 follows the object), and per reach trial the mean
           palm - reach point offset and the range of the least d_r.
"""
import argparse
import collections
import statistics
import sys

STEPS = [400, 240, 320, 280]  # N_p: 4 trials of 100, 60, 80, 70 steps (stage.main_*_steps)
REACH_HEIGHT = 0.095  # fitness.reach_height


def read(path):
    rows = []
    with open(path) as f:
        for ln, line in enumerate(f, 1):
            a = line.split()
            try:
                d = dict(x.split("=", 1) for x in a[3:])
                rows.append({
                    "g": int(a[0]), "i": int(a[1]), "t": int(a[2]), "ok": int(d["success"]),
                    "S": float(d["sum_S"]), "P": float(d["sum_P"]), "min": float(d["min_d_r"]),
                    "palm": [float(v) for v in d["palm"].split(",")] if "palm" in d else None,
                    "obj": [float(v) for v in d["obj"].split(",")] if "obj" in d else None,
                })
            except (IndexError, KeyError, ValueError):
                sys.exit(f"{path}:{ln}: expected a line of build/trial_sweep")
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def line_fit(xs, ys):
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        return float("nan"), my
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return b, my - b * mx


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep")
    ap.add_argument("--genotype", type=int, default=0)
    a = ap.parse_args()
    rows = read(a.sweep)
    gens = sorted({r["g"] for r in rows})
    inds = sorted({r["i"] for r in rows})
    trials = sorted({r["t"] for r in rows})
    last = gens[-1]
    print(f"{a.sweep}: generations {gens[0]}..{last}, {len(inds)} genotypes, trials {','.join(map(str, trials))}")
    for t in trials:
        rt = [r for r in rows if r["t"] == t]
        byg, byi = collections.Counter(), collections.Counter()
        for r in rt:
            byg[r["g"]] += r["ok"]
            byi[r["i"]] += r["ok"]
        per = [byg[g] for g in gens]
        print(f"  trial {t}: solved in {100 * sum(r['ok'] for r in rt) / len(rt):.1f}% of genotype x generation; "
              f"by {byg[last]} genotypes at {last} (per generation {min(per)}/{statistics.median(per):g}/{max(per)}); "
              f"genotypes solving it in >= 1 generation {sum(1 for i in inds if byi[i] > 0)}, "
              f"in >= half {sum(1 for i in inds if byi[i] >= len(gens) / 2)}, in all {sum(1 for i in inds if byi[i] == len(gens))}; "
              f"least d_r median {statistics.median(r['min'] for r in rt):.4f} m")
    solved = collections.Counter()
    for r in rows:
        solved[(r["g"], r["i"])] += r["ok"]
    per = [sum(1 for i in inds if solved[(g, i)] == len(trials)) for g in gens]
    print(f"  all listed trials: genotypes per generation {min(per)}/{statistics.median(per):g}/{max(per)} "
          f"(min/median/max); generations with >= 5: {sum(1 for x in per if x >= 5)} of {len(gens)}")
    if trials == list(range(16)):
        fp = collections.defaultdict(lambda: [0.0] * 4)
        fails = collections.defaultdict(list)
        for r in rows:
            p = r["t"] // 4
            fp[(r["g"], r["i"])][p] += 10 * r["ok"] + 100 / STEPS[p] * (r["S"] - r["P"])
            if not r["ok"]:
                fails[(r["g"], r["i"])].append(r["t"])
        F = {k: 4 / sum(1 / max(x, 1e-3) for x in v) for k, v in fp.items()}
        for g in gens:
            best = max(inds, key=lambda i: (F[(g, i)], -i))
            print(f"  F generation {g}: best genotype {best} F {F[(g, best)]:.3f} "
                  f"(F_p {' '.join(f'{x:.1f}' for x in fp[(g, best)])}), fails {fails[(g, best)] or 'none'}")
    mine = [r for r in rows if r["i"] == a.genotype and r["t"] < 4 and r["palm"]]
    if mine:
        bx, cx = line_fit([r["obj"][0] for r in mine], [r["palm"][0] for r in mine])
        by, cy = line_fit([r["obj"][1] for r in mine], [r["palm"][1] for r in mine])
        print(f"  genotype {a.genotype}, reach trials, last step: palm x = {bx:.2f} obj x {cx:+.3f}, "
              f"palm y = {by:.2f} obj y {cy:+.3f}")
        for t in sorted({r["t"] for r in mine}):
            rt = [r for r in mine if r["t"] == t]
            off = [statistics.fmean(r["palm"][j] - r["obj"][j] - (REACH_HEIGHT if j == 2 else 0) for r in rt)
                   for j in range(3)]
            print(f"    reach k={t}: solved {sum(r['ok'] for r in rt)} of {len(rt)}; palm - reach point "
                  f"dx {off[0]:+.3f} dy {off[1]:+.3f} dz {off[2]:+.3f} m; least d_r "
                  f"{min(r['min'] for r in rt):.3f}..{max(r['min'] for r in rt):.3f} m")


if __name__ == "__main__":
    main()
