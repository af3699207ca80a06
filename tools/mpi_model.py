#!/usr/bin/env python3
"""The scaling model of evolve under MPI (docs/PROTOCOL.md, "Evaluation across processes").

    python3 tools/mpi_model.py COSTS.csv [COSTS.csv...] [--slots 1,2,16,32,64] [--serial S]
        [--latency L] [--bandwidth B] [--nap N] [--population P] [--samples K]

COSTS.csv: per-individual CPU seconds (`cpu_s` column), as build/eval_cost prints them; or a
replication's cost/costs.csv (tools/replicate_cost.py: the mean CPU seconds of each kind of
evaluation, `mean_cpu_s`), modelled kind by kind with every individual at its kind's mean. A
generation of P individuals on W evaluation slots (one per core: W ranks of 1 thread, or fewer
ranks with more threads) takes

    T(W) = serial + makespan(W)

serial: rank 0's time between a generation's last result and the next's first task (GA, files,
fsync, checkpoint: `rank 0 between generations` in evolve's closing MPI line). makespan: rank 0
hands the individuals in GA order to whichever slot asks first (dynamic, one at a time);
simulated here with the measured costs in random order (K samples, resampled with
replacement: an individual's cost does not depend on its index). Each task costs its CPU time
plus the exchange: a task message down and a result up (sizes below), each one latency plus
size / bandwidth, plus rank 0's and the slot's polling naps (on average half the longest nap
each); rank 0 serves the messages one at a time (dispatch of a generation's first W tasks is
sequential). Efficiency = T(1 slot) / (W T(W)), per evaluation core; with rank 0 on a core of
its own it is W / (W + 1) of that.

Prints one row per W: the mean generation time, its 10-90% range over the samples, speed-up
and efficiency, for every costs file.
"""
import argparse
import heapq
import os
import random
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figlib  # noqa: E402

figlib.PROG = "mpi_model"

DOWN_BYTES = 1536  # sizeof(downMsg): kind + stEvolveTask (a 756-gene genome; 612 used)
UP_BYTES = 712     # sizeof(upMsg): slot, flags, timings + stEvolveResult


EVAL_COST = "build/eval_cost's per-individual costs (individual,cpu_s,...)"
REPLICATION = "a replication's cost/costs.csv (kind,n,mean_cpu_s,...)"


def read_costs(path):
    """[(label, CPU seconds of each individual)]: one set from eval_cost's output, or one per
    kind of a replication's costs.csv (every individual at the kind's mean)"""
    header = figlib.read_csv(path, {}, f"{EVAL_COST} or {REPLICATION}")[0]
    if "cpu_s" in header or "mean_cpu_s" not in header:
        key = ("individual", "trial") if "trial" in header else ("individual",)
        rows = figlib.read_csv(path, {**{k: "count" for k in key}, "cpu_s": "positive"}, EVAL_COST,
                               key=key)
        return [(None, [r["cpu_s"] for r in rows])]
    rows = figlib.read_csv(path, {"host": "str", "build": "str", "kind": "str", "args": "str",
                                  "n": "count", "mean_cpu_s": "positive"}, REPLICATION,
                           key=("host", "build", "args"))
    return [(f"{r['kind']} (host {r['host']}, {r['n']} measured)", [r["mean_cpu_s"]]) for r in rows]


def generation_time(costs, slots, a):
    """One generation: greedy dynamic assignment in the given order."""
    exchange = 2 * a.latency + (DOWN_BYTES + UP_BYTES) / a.bandwidth + a.nap  # per task
    service = a.latency + DOWN_BYTES / a.bandwidth  # rank 0's share of one dispatch
    free = [(k * service, k) for k in range(min(slots, len(costs)))]  # sequential first sends
    heapq.heapify(free)
    end = 0.0
    rank0 = 0.0  # rank 0 is busy until then (one message at a time)
    for c in costs:
        t, k = heapq.heappop(free)
        start = max(t, rank0)
        rank0 = start + service
        done = start + c + exchange
        end = max(end, done)
        heapq.heappush(free, (done, k))
    return a.serial + end


def model(costs, a):
    rng = random.Random(1)
    base = None
    rows = []
    for w in a.slots:
        times = []
        for _ in range(a.samples):
            gen = [rng.choice(costs) for _ in range(a.population)]
            times.append(generation_time(gen, w, a))
        times.sort()
        mean = statistics.fmean(times)
        if base is None:
            base = mean * a.slots[0]  # T(1) from the first row (W = 1 unless told otherwise)
        rows.append((w, mean, times[len(times) // 10], times[9 * len(times) // 10], base / mean,
                     base / (w * mean)))
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("costs", nargs="+")
    p.add_argument("--slots", default="1,2,4,8,16,32,48,64,100",
                   type=lambda s: [int(x) for x in s.split(",")])
    p.add_argument("--serial", type=float, default=0.05, help="rank 0 per generation, s")
    p.add_argument("--latency", type=float, default=50e-6, help="one message, s (TCP: 50e-6)")
    p.add_argument("--bandwidth", type=float, default=1e9, help="bytes/s")
    p.add_argument("--nap", type=float, default=2e-4, help="both sides' polling, s per task")
    p.add_argument("--population", type=int, default=100)
    p.add_argument("--samples", type=int, default=400)
    a = p.parse_args()
    for name, v, ok in (("--slots", min(a.slots), min(a.slots) >= 1),
                        ("--serial", a.serial, a.serial >= 0), ("--latency", a.latency, a.latency >= 0),
                        ("--bandwidth", a.bandwidth, a.bandwidth > 0), ("--nap", a.nap, a.nap >= 0),
                        ("--population", a.population, a.population >= 1),
                        ("--samples", a.samples, a.samples >= 1)):
        if not ok or v != v or v in (float("inf"), float("-inf")):
            figlib.die(f"{name} {v}: expected a finite number, at least 1 for counts and slots, "
                       "more than 0 for the bandwidth, at least 0 for times")
    if a.slots[0] != 1:
        a.slots.insert(0, 1)
    print(f"# serial {a.serial} s, latency {a.latency * 1e6:.0f} us, bandwidth {a.bandwidth / 1e9:g} "
          f"GB/s, nap {a.nap * 1e3:g} ms, messages {DOWN_BYTES} + {UP_BYTES} B per individual, "
          f"population {a.population}")
    sets = [(path, label, costs) for path in a.costs for label, costs in read_costs(path)]
    for path, label, costs in sets:
        s = sorted(costs)
        if label:
            print(f"# {path}: {label}: {s[0]:.3f} s an evaluation, every individual at it")
        else:
            print(f"# {path}: {len(costs)} individuals, CPU min {s[0]:.3f} s, median "
                  f"{s[len(s) // 2]:.3f}, max {s[-1]:.3f}, mean {statistics.fmean(s):.3f}, "
                  f"max/min {s[-1] / s[0]:.1f}")
        print("slots,T_gen_s,T_p10_s,T_p90_s,speedup,efficiency")
        for w, mean, lo, hi, sp, eff in model(costs, a):
            print(f"{w},{mean:.3f},{lo:.3f},{hi:.3f},{sp:.1f},{eff:.2f}")


if __name__ == "__main__":
    sys.exit(main())
