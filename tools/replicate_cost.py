#!/usr/bin/env python3
"""replicate_cost.py: what `make replicate` will cost, step by step, before it starts
(tools/replicate.mk's target `cost`, which passes the replication's variables; `make replicate`
prints it first).

    replicate_cost.py --preset P --protocol thesis|chain --runs N --threads T --out OUT
        [--prim-args A] [--chain-args A] [--int-args A] [--integ-args A] [--rob-args A]
        [--gen-args A] [--prim-pop F] [--chain-pop F] [--int-pop F] [--sample N]
        [--remeasure] [--eval-cost build/eval_cost] [--assume KIND=SECONDS]... [--given-runs N]

Each kind of evaluation - an individual of simple-prim, main-prim, the chain stage, the
integrated stage of each condition; a trial of each post-evaluation test and variant - is timed
by build/eval_cost on this machine: one thread, CPU seconds, a few genotypes of committed runs
(--prim-pop, --chain-pop, --int-pop with % for the condition; --sample N individuals, 2N
trials, 25N simple-prim individuals), with the step's --set options. The means are cached in
OUT/cost/costs.csv, keyed by host, build (eval_cost's bytes: the library is linked in) and the
measurement's arguments, so a second call measures nothing; --remeasure measures again.
--assume KIND=SECONDS (KIND a pattern: 'integrated-*') takes a cost as given instead: the
arithmetic's test (tests/check_replicate.sh). --given-runs N: the replication takes N primitive
runs as given (PRIM_RUNS), so the prims and chain steps cost nothing and the integration test
runs on N runs. What each job runs (population, generations,
trials) is eval_cost's `# plan:` line for the step's config and --set options.

The model: a step's core-hours = its evaluations x CPU seconds each / 3600; evaluations = jobs x
generations x population (evolution) or individuals x trials (a test). Generations, expected:
prims, the thesis's medians (data/thesis/results.json: simple-prim complete at 484, all trials
at 581); the chain stage and the integrated stage, their cap; at most: the cap (--generations
in the step's arguments, else ga.max_generations / ga.integrated_generations), prims all priced
as main-prim. Wall hours: the steps one after the other, a step's jobs one after the other
(make without -j), each on --threads threads (0: every core): core-hours / threads, a
generation of P individuals taking ceil(P / threads) rounds."""
import argparse
import csv
import datetime
import fnmatch
import hashlib
import json
import math
import os
import shlex
import socket
import subprocess
import sys
import textwrap

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import csvschema  # noqa: E402
import figlib  # noqa: E402

figlib.PROG = "replicate cost"
# fitness.csv's columns --status reads, by the library's names (tools/csvschema.py)
GENERATION, STAGE = csvschema.pick(csvschema.FITNESS, "generation", "stage")
THESIS = os.path.join(HERE, "..", "data", "thesis", "results.json")
CONDS = [("stct", "ST-CT"), ("st", "ST"), ("ct", "CT"), ("ni", "NI")]
CONDS0 = ("stct", "st")  # the generalisation test's caretaker variants (ST-CT0, ST0)
CACHE_FIELDS = ["host", "build", "kind", "args", "n", "mean_cpu_s", "min_cpu_s", "max_cpu_s",
                "measured"]
# the cache's columns as read back: what was measured, each number finite (a nan there priced the
# replication at "nan core-hours")
CACHE_KINDS = {"host": "str", "build": "str", "kind": "str", "args": "str", "n": "count",
               "mean_cpu_s": "positive", "min_cpu_s": "positive", "max_cpu_s": "positive",
               "measured": "text"}
CACHE_WHAT = ("the measured costs replicate cost keeps (tools/replicate_cost.py; REMEASURE=1 "
              "measures again and writes it anew)")
die = figlib.die


def step_args(var, text):
    """(--generations or None, [KEY=VALUE, ...]) of a step's arguments (make variable var)"""
    words = shlex.split(text or "")
    gens, sets = None, []
    for i in range(0, len(words), 2):
        opt, v = words[i], words[i + 1] if i + 1 < len(words) else None
        if opt == "--set" and v and "=" in v:
            sets.append(v)
        elif opt == "--generations" and v and v.isdigit() and int(v) >= 1:
            gens = int(v)
        else:
            die("%s: '%s' cannot be priced (expected --generations N and --set KEY=VALUE)"
                % (var, " ".join(words[i:i + 2])))
    return gens, sets


def need_file(path, var):
    if not os.path.isfile(path):
        die("%s (%s): no such file" % (path, var))
    return path


class Cost:
    """a kind's CPU seconds per evaluation, how many were measured, and the job's plan"""

    def __init__(self, seconds, n, plan):
        self.seconds, self.n, self.plan = seconds, n, plan


class Meter:
    """eval_cost's measurements, cached in OUT/cost/costs.csv"""

    def __init__(self, a):
        self.exe = a.eval_cost
        if not (os.path.isfile(self.exe) and os.access(self.exe, os.X_OK)):
            die("%s not found: build it first (make; make replicate does)" % self.exe)
        with open(self.exe, "rb") as f:
            self.build = hashlib.sha256(f.read()).hexdigest()[:12]
        self.host = socket.gethostname()
        self.path = os.path.join(a.out, "cost", "costs.csv")
        self.rows = []
        if os.path.exists(self.path) and not a.remeasure:
            self.rows = [{k: r["_raw"][k] for k in CACHE_FIELDS}
                         for r in figlib.read_csv(self.path, CACHE_KINDS, CACHE_WHAT,
                                                  key=("host", "build", "args"))]
        self.assumed = []
        for s in a.assume or []:
            kind, _, v = s.partition("=")
            try:
                self.assumed.append((kind, figlib.KINDS["positive"][0](v.strip())))
            except ValueError:
                die("--assume %s: expected KIND=SECONDS, a finite number > 0" % s)
        self.used = {"measured now": 0, "measured earlier": 0, "assumed": 0}

    def run(self, args, count):
        """eval_cost's per-evaluation CPU seconds and its plan"""
        cmd = [self.exe] + args + ["--count", str(count)]
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True)
        if p.returncode:
            die("%s: %s" % (" ".join(cmd), p.stderr.strip() or "failed"))
        lines = p.stdout.splitlines()
        col = lines[0].split(",").index("cpu_s")
        cpu = [float(x.split(",")[col]) for x in lines[1:] if x and not x.startswith("#")]
        plan = [x for x in lines if x.startswith("# plan:")]
        if not plan:
            die("%s: no plan line in its output" % " ".join(cmd))
        return cpu, {k: int(v) for k, v in (kv.split("=") for kv in plan[0][7:].split())}

    def cost(self, kind, args, count):
        key = " ".join(args + ["--count", str(count)])
        _, plan = self.run(args, 0)  # the plan alone: nothing simulated
        for pattern, seconds in self.assumed:
            if fnmatch.fnmatchcase(kind, pattern):
                self.used["assumed"] += 1
                return Cost(seconds, 0, plan)
        mine = (self.host, self.build, key)
        for r in self.rows:
            if (r["host"], r["build"], r["args"]) == mine:
                self.used["measured earlier"] += 1
                return Cost(float(r["mean_cpu_s"]), int(r["n"]), plan)
        if not self.used["measured now"]:
            print("replicate cost: measuring what one evaluation costs on this machine (a few "
                  "genotypes of each kind, under a minute; cached in %s)" % self.path,
                  file=sys.stderr, flush=True)
        self.used["measured now"] += 1
        cpu, _ = self.run(args, count)
        if not cpu:
            die("%s: nothing measured" % key)
        mean = sum(cpu) / len(cpu)
        self.rows = [r for r in self.rows if (r["host"], r["build"], r["args"]) != mine]
        now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
        self.rows.append(dict(zip(CACHE_FIELDS, [self.host, self.build, kind, key, len(cpu),
                                                 "%.6f" % mean, "%.6f" % min(cpu),
                                                 "%.6f" % max(cpu), now])))
        return Cost(mean, len(cpu), plan)

    def save(self):
        if not self.used["measured now"]:
            return
        tmp = self.path + ".tmp"
        try:
            os.makedirs(os.path.dirname(self.path), exist_ok=True)
            with open(tmp, "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=CACHE_FIELDS)
                w.writeheader()
                w.writerows(self.rows)
            os.replace(tmp, self.path)
        except OSError as e:
            die("%s: cannot write: %s" % (self.path, e.strerror))

    def source(self):
        return " and ".join(k for k, v in self.used.items() if v)


class Step:
    """a row of the table: jobs, CPU seconds per evaluation, generations per job (None: a test)
    and evaluations, expected and at most; pop, the individuals of a generation"""

    def __init__(self, name, jobs, cost, gens, evals, pop=None, max_gens=None, max_evals=None):
        self.name, self.jobs, self.cost, self.gens, self.evals = name, jobs, cost, gens, evals
        self.pop = pop
        self.max_gens = gens if max_gens is None else max_gens
        self.max_evals = evals if max_evals is None else max_evals
        # where its jobs write (--status): an evolution step's run directories and the
        # generations of theirs it covers ([first, last), or the fitness.csv rows of one stage);
        # a test's (directory, trials, CPU s per trial) per job
        self.runs, self.first, self.stage, self.tests = [], 0, None, []

    def core_hours(self, upper=False):
        return (self.max_evals if upper else self.evals) * self.cost / 3600.0

    def threads_used(self, threads):
        if self.pop:  # a generation's individuals in ceil(pop / threads) rounds
            return self.pop / math.ceil(self.pop / threads)
        return max(1.0, min(threads, self.evals / self.jobs))  # a test's trials

    def wall_hours(self, threads, upper=False):
        return self.core_hours(upper) / self.threads_used(threads)


def evolution(name, runs, c, gens_arg):
    """a step of runs evolution jobs at their cap"""
    cap = gens_arg or c.plan["generations"]
    return Step(name, runs, c.seconds, cap, runs * c.plan["population"] * cap, c.plan["population"])


def run_dirs(a, prefix):
    """the run directories of a step's jobs, as tools/replicate.mk names them"""
    return [os.path.join(a.out, "%s-s%d" % (prefix, seed)) for seed in range(1, a.runs + 1)]


def plan_primitive_steps(a, meter, pop, primitives, steps, costs, notes):
    """the steps that evolve the primitive runs (prims and, with PROTOCOL=chain, chain)"""
    n = a.sample
    thesis = json.load(open(THESIS))["primitive_runs"]
    simple_med = thesis["simple_prim"]["median"]
    main_med = thesis["total"]["median"] - simple_med
    prim_gens, prim_sets = step_args("PRIM_ARGS", a.prim_args)
    base = ["configs/prims.cfg", "--population", pop]
    simple = meter.cost("simple-prim", base + ["--stage", "simple-prim"] + prim_sets, 25 * n)
    main = meter.cost("main-prim", base + ["--stage", "main-prim", "--spread"] + prim_sets, n)
    costs += [("simple-prim individual", simple, pop), ("main-prim individual", main, pop)]
    cap, P = prim_gens or main.plan["generations"], main.plan["population"]
    gs, gm = min(cap, simple_med), min(max(cap - simple_med, 0), main_med)
    steps.append(Step("prims: simple-prim", a.runs, simple.seconds, gs, a.runs * P * gs, P, 0, 0))
    steps.append(Step("prims: main-prim", a.runs, main.seconds, gm, a.runs * P * gm, P, cap,
                      a.runs * P * cap))
    for s, stage in zip(steps[-2:], ("simple-prim", "main-prim")):
        s.runs, s.stage = run_dirs(a, "prims"), stage
    notes.append("prims: expected, the thesis's medians (%s, 3.1): simple-prim complete at "
                 "generation %d, all 16 trials at %d, so %d in main-prim%s; at most %d "
                 "generations (%s), all priced as main-prim." % (
                     os.path.relpath(THESIS), simple_med, simple_med + main_med, main_med,
                     "; the cap of %d leaves %d and %d" % (cap, gs, gm)
                     if cap < simple_med + main_med else "", cap,
                     "PRIM_ARGS' --generations" if prim_gens else "ga.max_generations"))

    if a.protocol == "chain":
        chain_gens, chain_sets = step_args("CHAIN_ARGS", a.chain_args)
        # two phases: generations below postures.vary_replace_generations (the drawn starts in
        # place of open's and grasp's) priced at generation 0, the rest (the varied trials
        # too, the dearer phase) at the run's last generation
        chain_args = ["configs/chain_prim.cfg", "--population", primitives, "--spread"]
        plan = meter.run(chain_args + chain_sets, 0)[1]
        cap = chain_gens or plan["generations"]
        replace = min(plan.get("replace_generations", 0), cap)
        if replace:
            early = meter.cost("chain-replace", chain_args + ["--generation", "0"] + chain_sets, n)
            costs.append(("chain replace individual", early, primitives))
            steps.append(evolution("chain: replace", a.runs, early, replace))
            steps[-1].runs = run_dirs(a, "chain")
        if cap > replace:
            chain = meter.cost("chain", chain_args + ["--generation", str(cap - 1)] + chain_sets, n)
            costs.append(("chain extra individual" if replace else "chain-stage individual",
                          chain, primitives))
            steps.append(evolution("chain: extra" if replace else "chain", a.runs, chain,
                                   cap - replace))
            steps[-1].runs, steps[-1].first = run_dirs(a, "chain"), replace
        notes.append("chain: %sexpected and at most its cap, %d generations (%s): a chain run "
                     "ends earlier only when ga.success_genotypes genotypes of one generation "
                     "solve the 16 fixed and all chained trials (stage.chain_complete), an "
                     "early exit that 1 of the 3 completed runs took (seed 2, at 123; "
                     "docs/PROTOCOL.md, 'The chain stage's budget')." % (
                         "the first %d (postures.vary_replace_generations) priced at generation "
                         "0's trials, the rest at the last generation's; " % replace
                         if replace and cap > replace else "", cap,
                         "CHAIN_ARGS' --generations" if chain_gens else "ga.max_generations"))


def plan_steps(a, meter):
    """the steps, the costs measured (name, seconds or None, what), notes on the generations"""
    n = a.sample
    steps, costs, notes = [], [], []

    pop = need_file(a.prim_pop, "COST_PRIM_POP")
    primitives = pop if a.protocol == "thesis" else need_file(a.chain_pop, "COST_CHAIN_POP")
    if a.given_runs:
        notes.append("prims%s: given (PRIM_RUNS%s, %s), nothing to run." % (
            ", chain" if a.protocol == "chain" else "",
            ", CHAIN_RUNS" if a.protocol == "chain" else "", plural(a.given_runs, "run")))
    else:
        plan_primitive_steps(a, meter, pop, primitives, steps, costs, notes)
    primitive_runs = a.given_runs or a.runs

    _, integ_sets = step_args("INTEG_ARGS", a.integ_args)
    integ = meter.cost("integration", ["configs/prims.cfg", "--population", primitives,
                                       "--posteval", "integration"] + integ_sets, 2 * n)
    costs.append(("integration-test trial", integ, primitives))
    steps.append(Step("integration test", 1, integ.seconds, None,
                      primitive_runs * integ.plan["individuals"] * integ.plan["trials"]))
    steps[-1].tests = [(os.path.join(a.out, "posteval", "integration"), steps[-1].evals,
                        integ.seconds)]

    int_gens, int_sets = step_args("INT_ARGS", a.int_args)
    _, rob_sets = step_args("ROB_ARGS", a.rob_args)
    _, gen_sets = step_args("GEN_ARGS", a.gen_args)
    tests = {"robustness": [], "generalisation": []}  # (label, cost, directory) of each job
    for c, label in CONDS:
        cfg = "configs/integrated_%s.cfg" % c
        ipop = need_file(a.int_pop.replace("%", c), "COST_INT_POP")
        run = meter.cost("integrated-" + c, [cfg, "--population", ipop, "--spread",
                                             "--generation", "1"] + int_sets, n)
        steps.append(evolution("integrated " + label, a.runs, run, int_gens))
        steps[-1].runs = run_dirs(a, "int-" + c)
        int_cap = steps[-1].gens
        costs.append(("integrated %s individual" % label, run, ipop))
        test = [cfg, "--population", ipop, "--posteval"]
        tests["robustness"].append((label, meter.cost("robustness-" + c, test + ["robustness"]
                                                      + rob_sets, 2 * n), "robustness-" + c))
        for v in [""] + (["0"] if c in CONDS0 else []):
            tests["generalisation"].append((label + v, meter.cost(
                "generalisation-" + c + v, test + ["generalisation"] +
                (["--caretaker"] if v else []) + gen_sets, 2 * n), "generalisation-" + c + v))
    for name, jobs in tests.items():
        evals = [a.runs * c.plan["individuals"] * c.plan["trials"] for _, c, _ in jobs]
        cpu = sum(e * c.seconds for e, (_, c, _) in zip(evals, jobs))
        steps.append(Step(name, len(jobs), cpu / sum(evals), None, sum(evals)))
        steps[-1].tests = [(os.path.join(a.out, "posteval", d), e, c.seconds)
                           for e, (_, c, d) in zip(evals, jobs)]
        costs.append(("%s trial" % name, None, ", ".join("%s %.3g" % (label, c.seconds)
                                                         for label, c, _ in jobs)
                      + (" s  (%s each, by genotypes of the integrated runs' files above)"
                         % plural(jobs[0][1].n, "trial") if jobs[0][1].n else " s  (assumed)")))
    notes.append("integrated: %d generations (%s), always run in full. Tests: every trial of "
                 "every individual (the generalisation test's exclusion rule can only lower "
                 "it)." % (int_cap, "INT_ARGS' --generations" if int_gens
                           else "ga.integrated_generations"))
    return steps, costs, notes


def plural(n, unit):
    return "%d %s%s" % (n, unit, "" if n == 1 else "s")


def hours(x):
    if x == 0:
        return "0"
    if x < 0.001:
        return "<0.001"
    return "%.0f" % x if x >= 99.5 else "%.1f" % x if x >= 0.995 else "%.2g" % x


def table(a, meter, steps, costs, notes, threads):
    ts = "%d thread%s" % (threads, "" if threads == 1 else "s")
    out = ["make replicate PRESET=%s PROTOCOL=%s RUNS=%d on %s: what it will cost, step by step "
           "(an estimate)" % (a.preset, a.protocol, a.runs, ts),
           "CPU seconds per evaluation, one thread, %s on host %s (build %s; cached in %s, "
           "REMEASURE=1 measures again): the mean over a few genotypes of committed runs"
           % (meter.source(), meter.host, meter.build, meter.path)]
    for name, c, what in costs:  # what: the genotypes' file, or the line of a test's kinds
        unit = name.split()[-1]
        out.append("  %-28s %s" % (name, what if c is None else "%.3g s  (assumed)" % c.seconds
                                   if not c.n else "%.3g s  (%s of %s)" % (
                                       c.seconds, plural(c.n, unit), what) if unit == "individual"
                                   else "%.3g s  (%s by genotypes of %s)" % (
                                       c.seconds, plural(c.n, unit), what)))
    head = [["", "", "", "expected", "", "", "", "", "at most", "", ""],
            ["step", "jobs", "CPU s", "gens", "evaluations", "core-h", "wall h", "|", "gens",
             "core-h", "wall h"]]
    rows = []
    for s in steps:
        gens = "-" if s.gens is None else str(s.gens)
        upper = [gens if s.gens is None else str(s.max_gens),
                 hours(s.core_hours(True)), hours(s.wall_hours(threads, True))]
        rows.append([s.name, str(s.jobs), "%.3g" % s.cost, gens, "{:,}".format(s.evals),
                     hours(s.core_hours()), hours(s.wall_hours(threads)), "|"]
                    + (upper if s.max_evals else ["-", "-", "-"]))
    rows.append(["stats, figures, report", "1", "-", "-", "-", "~0", "~0", "|", "-", "~0", "~0"])
    tot = [sum(s.core_hours() for s in steps), sum(s.wall_hours(threads) for s in steps),
           sum(s.core_hours(True) for s in steps), sum(s.wall_hours(threads, True) for s in steps)]
    rows.append(["total", "", "", "", "", hours(tot[0]), hours(tot[1]), "|", "", hours(tot[2]),
                 hours(tot[3])])
    wid = [max(len(r[i]) for r in rows + head) for i in range(len(rows[0]))]
    out.append("")
    out += ["  ".join(x.ljust(wid[0]) if i == 0 else x.rjust(wid[i])
                      for i, x in enumerate(r)).rstrip() for r in head + rows]
    notes = ["evaluations: individuals evaluated (trials run, for a test) by all the step's "
             "jobs; gens: generations per job; core-h: evaluations x CPU s / 3600."] + notes
    out += ["", "Expected: %s core-hours, %s hours on %s; at most %s core-hours, %s hours."
            % (hours(tot[0]), hours(tot[1]), ts, hours(tot[2]), hours(tot[3]))]
    notes.append("wall h: the steps in sequence, a step's jobs one after the other (make without "
               "-j), each on %s: core-h / threads, a generation of P individuals taking "
               "ceil(P / threads) rounds (100 on 64 threads: 2 rounds, 78%% busy). Not counted: "
               "each generation's wait for its slowest individual, the GA and files between "
               "generations (~0.1 s each), other load on the machine. A few genotypes were "
               "measured: costs vary 2-3x between individuals and more between trials." % ts)
    out += [textwrap.fill(x, 100, subsequent_indent="  ") for x in notes]
    out.append("total %s core-hours (expected; at most %s), %s hours on %s"
               % (hours(tot[0]), hours(tot[2]), hours(tot[1]), ts))  # last: for scripts
    return "\n".join(out)


def generations_run(run, stage):
    """the generations a run directory's fitness.csv holds (of one stage, if given)"""
    path = os.path.join(run, "fitness.csv")
    if not os.path.exists(path):
        return 0
    rows = figlib.read_fitness(path, (GENERATION, STAGE) if stage else (GENERATION,), live=True)
    return sum(1 for r in rows if not stage or r[STAGE] == stage)


def job_progress(step, run):
    """(generations of the step run, finished, running) for one job of an evolution step"""
    done = os.path.exists(os.path.join(run, "population.genome"))
    if step.stage:  # prims: simple-prim is finished once main-prim has begun
        g = generations_run(run, step.stage)
        later = step.stage == "simple-prim" and generations_run(run, "main-prim") > 0
    else:
        g, later = min(max(generations_run(run, None) - step.first, 0), step.max_gens), False
    finished = done or later or g >= step.max_gens
    return g, finished, not finished and (g > 0 or os.path.exists(os.path.join(run, "checkpoint")))


def status_table(a, meter, steps, threads):
    """what is done and what is left of the replication in OUT, from its files"""
    ts = "%d thread%s" % (threads, "" if threads == 1 else "s")
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    head = [["", "", "", "", "", "left, expected", "", "", "left, at most", ""],
            ["step", "jobs", "done", "running", "gens run", "core-h", "wall h", "|", "core-h",
             "wall h"]]
    rows, running, left = [], [], [0.0, 0.0, 0.0, 0.0]
    for s in steps:
        if s.tests:  # a test's job is done when its summary is written
            done = [os.path.exists(os.path.join(d, "summary.csv")) for d, _, _ in s.tests]
            exp = sum(e * c for (_, e, c), ok in zip(s.tests, done) if not ok) / 3600.0
            top, gens, n_run = exp, "-", 0
        else:
            jobs = [(r,) + job_progress(s, r) for r in s.runs]
            done = [fin for _, _, fin, _ in jobs]
            per_gen = s.pop * s.cost / 3600.0
            exp = sum(max(s.gens - g, 0) for _, g, fin, _ in jobs if not fin) * per_gen
            top = sum(max(s.max_gens - g, 0) for _, g, fin, _ in jobs if not fin) * per_gen
            gens = "%d of %d" % (sum(g for _, g, _, _ in jobs), s.jobs * s.max_gens)
            running += ["%s (%s, generation %d of %d)" % (os.path.basename(r), s.name, g,
                                                          s.max_gens)
                        for r, g, _, run in jobs if run]
            n_run = sum(run for _, _, _, run in jobs)
        use = s.threads_used(threads)
        left = [left[0] + exp, left[1] + exp / use, left[2] + top, left[3] + top / use]
        rows.append([s.name, str(s.jobs), str(sum(done)), str(n_run), gens, hours(exp),
                     hours(exp / use), "|", hours(top), hours(top / use)])
    rows.append(["total", "", "", "", "", hours(left[0]), hours(left[1]), "|", hours(left[2]),
                 hours(left[3])])
    wid = [max(len(r[i]) for r in rows + head) for i in range(len(rows[0]))]
    out = ["make replicate PRESET=%s PROTOCOL=%s RUNS=%d in %s, %s: what is done and what is "
           "left on %s (an estimate)" % (a.preset, a.protocol, a.runs, a.out, now, ts), ""]
    out += ["  ".join(x.ljust(wid[0]) if i == 0 else x.rjust(wid[i])
                      for i, x in enumerate(r)).rstrip() for r in head + rows]
    out += ["", "Left: %s core-hours, %s hours on %s; at most %s core-hours, %s hours."
            % (hours(left[0]), hours(left[1]), ts, hours(left[2]), hours(left[3]))]
    out += ["Running: " + (", ".join(running) if running else "nothing") + "."]
    notes = ["done: jobs whose result is written (a run's population.genome, a test's "
             "summary.csv; a primitive stage also once the next one has begun); running: "
             "jobs with generations or a checkpoint but no result; gens run: the generations "
             "the jobs' fitness.csv hold, of their cap. left: the generations still to run "
             "(expected: to the expected generations of `cost`; at most: to the cap) and the "
             "tests not done, at the CPU seconds per evaluation of `cost` (%s), each job "
             "one after the other as there. A job past its expected generations but not done "
             "is counted as needing none more (expected)." % meter.source()]
    out += [textwrap.fill(x, 100, subsequent_indent="  ") for x in notes]
    return "\n".join(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--preset", required=True)
    ap.add_argument("--protocol", required=True, choices=["thesis", "chain"])
    ap.add_argument("--runs", required=True)
    ap.add_argument("--threads", default="0")
    ap.add_argument("--given-runs", default="0",
                    help="primitive runs given (PRIM_RUNS): the prims and chain steps run nothing")
    ap.add_argument("--out", required=True)
    for k in ("prim", "chain", "int", "integ", "rob", "gen"):
        ap.add_argument("--%s-args" % k, default="")
    ap.add_argument("--prim-pop", default="data/evolved/prims_s2/population.genome")
    ap.add_argument("--chain-pop", default="data/evolved/chain_candidates/hcg_p2_from50/checkpoint")
    ap.add_argument("--int-pop", default="data/evolved/unchained/int_%_s1/population.genome")
    ap.add_argument("--sample", default="4")
    ap.add_argument("--remeasure", action="store_true")
    ap.add_argument("--eval-cost", default="build/eval_cost")
    ap.add_argument("--assume", action="append", metavar="KIND=SECONDS")
    ap.add_argument("--status", action="store_true",
                    help="what is done and left in OUT, from its files, instead of the plan")
    a = ap.parse_args(argv)
    for name, var, least in (("runs", "RUNS", 1), ("threads", "THREADS", 0),
                             ("given_runs", "PRIM_RUNS' count", 0),
                             ("sample", "COST_SAMPLE", 1)):
        v = getattr(a, name)
        if not v.isdigit() or int(v) < least:
            die("%s=%s: expected an integer >= %d" % (var, v, least))
        setattr(a, name, int(v))
    if "%" not in a.int_pop:
        die("COST_INT_POP=%s: expected a %% where the condition goes (stct, st, ct, ni)"
            % a.int_pop)
    threads = a.threads or len(os.sched_getaffinity(0))
    meter = Meter(a)
    steps, costs, notes = plan_steps(a, meter)
    meter.save()
    try:
        print(status_table(a, meter, steps, threads) if a.status
              else table(a, meter, steps, costs, notes, threads), flush=True)
    except BrokenPipeError:  # `... cost | head`: what was read is enough
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


if __name__ == "__main__":
    main(sys.argv[1:])
