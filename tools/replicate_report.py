#!/usr/bin/env python3
"""replicate_report.py: report.md of a replication (tools/replicate.mk), each of the thesis's
numbers (data/thesis/results.json) beside ours, and how its runs depart from the thesis's
protocol (their config.ini's keys away from their defaults: tools/keytable.py).

    replicate_report.py OUT [--preset NAME] [--runs N] [--protocol chain|thesis]
                        [--prim-runs 'DIR ...' [--chain-runs 'DIR ...']] [-o report.md]
    replicate_report.py DIR --types     the robustness test by trial type of DIR/robustness-*/

Reads OUT/prims-s*/fitness.csv (and OUT/chain-s*/fitness.csv with --protocol chain), or the
fitness.csv of the given runs' directories instead,
OUT/int-<cond>-s*/fitness.csv, OUT/summary/*.csv,
OUT/stats/*.txt (./apps/stats's tables) and links OUT/figures/*.png. Written atomically."""
import argparse
import glob
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import csvschema  # noqa: E402
import figlib  # noqa: E402
import keytable  # noqa: E402
import runconfig  # noqa: E402

figlib.PROG = "replicate_report"

# the columns read, by the library's names (tools/csvschema.py): a renamed one fails here
FITNESS = csvschema.pick(csvschema.FITNESS, "generation", "stage", "all_success", "best",
                         "best_bonus", "best_bonus_auto", "best_successes", "best_t%d", "best_c%d")
TRIALS = csvschema.pick(csvschema.TRIALS, "condition", "run_label", "type", "success")
SUMMARY = csvschema.pick(csvschema.SUMMARY, "condition", "run", "individual", "successes", "trials",
                         "open_jumped")
THESIS = os.path.join(HERE, "..", "data", "thesis", "results.json")
CONDS = [("stct", "ST-CT"), ("st", "ST"), ("ct", "CT"), ("ni", "NI")]
NFIXED = csvschema.TRIAL_KINDS["fixed"]  # main-prim's fixed trials (the thesis's 16)
# what the primitive runs are (tools/replicate.mk's PROTOCOL), said at the top of the report
PROTOCOLS = {
    "chain": "Primitives: protocol `chain` (the default): each primitive run of the thesis's "
             "protocol (`configs/prims.cfg`) continued by the chain stage (`configs/chain_prim.cfg`: "
             "hand-over, varied and chained trials beside the 16 fixed ones; SPEC §12, "
             "`docs/PROTOCOL.md`), whose final populations the integration test and the integrated "
             "stage take. Not the thesis's protocol: `PROTOCOL=thesis` replicates that one alone.",
    "thesis": "Primitives: protocol `thesis`: the thesis's primitive stages alone "
              "(`configs/prims.cfg`), whose final populations the integration test and the "
              "integrated stage take (on the committed runs their integration test gives 0 of "
              "1200: `docs/PROTOCOL.md`).",
}


die = figlib.die


def quantile(sorted_x, p):
    """Hyndman & Fan definition 7, as ./apps/stats (docs/PROTOCOL.md, Quartiles)"""
    h = (len(sorted_x) - 1) * p
    j = int(h)
    if j + 1 >= len(sorted_x):
        return sorted_x[-1]
    return sorted_x[j] + (h - j) * (sorted_x[j + 1] - sorted_x[j])


def five(xs):
    """(median, lower quartile, upper quartile) or None"""
    if not xs:
        return None
    s = sorted(xs)
    return quantile(s, 0.5), quantile(s, 0.25), quantile(s, 0.75)


def fmt(x):
    return "-" if x is None else ("%g" % x)


def fmt5(q):
    return "-" if q is None else "%g (%g, %g)" % q


def as_text(rows):
    """figlib's checked rows with their values as written (the sections convert what they use)"""
    return [dict(r["_raw"], _line=r["_line"]) for r in rows]


def read_fitness(path, *columns):
    """a run's fitness.csv, every column checked (figlib.read_fitness), the named ones required"""
    return as_text(figlib.read_fitness(path, ("generation",) + columns))


def read_post(path, table, what, *columns):
    """a post-evaluation file (summary.csv, trials.csv) or ./apps/stats selftalk's, checked by its
    table (csvschema's, or None), the named columns required"""
    key = {"summary": ("test", "condition", "run", "individual"),
           "trials": ("test", "condition", "run", "individual", "trial"),
           "selftalk": ("condition", "run", "individual")}[table]
    schema = {"summary": csvschema.SUMMARY, "trials": csvschema.TRIALS,
              "selftalk": {"condition": "str", "run": "int", "individual": "int", "better": "str"}}[table]
    kinds = {c: schema[c] for c in key + columns}
    return as_text(figlib.read_csv(path, kinds, what, key=key, schema=schema))


def run_seed(path):
    # OUT/prims-s3/fitness.csv, or a given run's directory such as data/evolved/chain_s3
    m = re.search(r"[-_]s(\d+)$", os.path.basename(os.path.dirname(path)))
    return int(m.group(1)) if m else -1


def run_value(run_dir, section, key, default, conv):
    """section.key of the run's config.ini (runconfig.value), a bad value refused with FILE:LINE"""
    try:
        return runconfig.value(run_dir, section, key, default, conv)
    except ValueError as e:
        die(str(e))


def success_genotypes(run_dir):
    """ga.success_genotypes of the run's config.ini (5 when absent)"""
    return run_value(run_dir, "ga", "success_genotypes", 5, int)


def prim_run(path):
    """one primitive run: generations to complete simple-prim and main-prim (None: not)"""
    rows = read_fitness(path, "stage", "all_success", "best_successes")
    need = success_genotypes(os.path.dirname(path))
    simple = [int(r["generation"]) for r in rows if r["stage"] == "simple-prim"]
    main = [r for r in rows if r["stage"] == "main-prim"]
    done_simple = simple[-1] if simple and main else None
    last = rows[-1]
    done_main = (int(last["generation"]) if main and int(last["all_success"]) >= need else None)
    return {"seed": run_seed(path), "simple": done_simple, "total": done_main,
            "generations": int(last["generation"]) + 1,
            "best_successes": int(last["best_successes"])}


def run_files(out, pattern, given):
    """the fitness.csv of each run: the given directories (PRIM_RUNS, CHAIN_RUNS) in their
    order, else OUT's runs of the pattern"""
    if given:
        return [os.path.join(d, "fitness.csv") for d in given]
    return sorted(glob.glob(os.path.join(out, pattern, "fitness.csv")))


def section_departures(out, given):
    """how the runs depart from the thesis's protocol: the keys of each run's config.ini away
    from their defaults (keytable.departures; the "run" tier, a run's own seed, stage,
    populations and condition, left out), runs with the same departures on one line"""
    dirs = given + sorted(d for d in glob.glob(os.path.join(out, "*")) if os.path.isdir(d))
    dirs += sorted(glob.glob(os.path.join(out, "posteval", "*")))
    groups = {}
    for d in dirs:
        path = os.path.join(d, "config.ini")
        if os.path.isfile(path):
            found = tuple(keytable.departures(path))
            groups.setdefault(found, []).append(os.path.relpath(d, out) if d.startswith(out) else d)
    lines = ["## How the runs depart from the thesis's protocol", "",
             "Each run's `config.ini` keys away from their defaults, by tier (`--help-config`; "
             "`speed` keys give the same results). Seeds, stages, starting populations and the "
             "condition (tier `run`) are each run's own and not listed.", "",
             "| runs | tier | key | value | default |", "|---|---|---|---|---|"]
    for found, runs in sorted(groups.items(), key=lambda g: g[1][0]):
        label = ", ".join("`%s`" % r for r in runs)
        if not found:
            lines.append("| %s | | (none) | | |" % label)
        for i, (tier, key, value, default) in enumerate(found):
            lines.append("| %s | %s | `%s` | %s | %s |" % (label if i == 0 else "", tier, key,
                                                           value, default))
    return lines + [""]


def section_prims(out, th, given):
    runs = [prim_run(p) for p in run_files(out, "prims-s*", given)]
    t = th["primitive_runs"]
    lines = ["## Primitive stages (thesis §3.1)", "",
             "| run (seed) | simple-prim complete at | main-prim complete at | main-prim generations | "
             "generations run | final best: trials solved |", "|---|---|---|---|---|---|"]
    for r in runs:
        mp = r["total"] - r["simple"] if r["total"] is not None and r["simple"] is not None else None
        lines.append("| %d | %s | %s | %s | %d | %d/16 |" % (
            r["seed"], fmt(r["simple"]), fmt(r["total"]), fmt(mp), r["generations"], r["best_successes"]))
    simple = five([r["simple"] for r in runs if r["simple"] is not None])
    total = five([r["total"] for r in runs if r["total"] is not None])
    done = sum(1 for r in runs if r["total"] is not None)
    ts, tt = t["simple_prim"], t["total"]
    lines += ["", "| | thesis | ours |", "|---|---|---|",
              "| runs completing both stages | %d of %d | %d of %d |" % (t["completed"], t["runs"], done, len(runs)),
              "| simple-prim complete at: median (quartiles) | %g (%g, %g) | %s |" % (
                  ts["median"], ts["lower_quartile"], ts["upper_quartile"], fmt5(simple)),
              "| both stages complete at: median (quartiles) | %g (%g, %g) | %s |" % (
                  tt["median"], tt["lower_quartile"], tt["upper_quartile"], fmt5(total)),
              "", "![Fig. 3.1](figures/fig3_1.png)", ""]
    return lines


def section_chain(out, given):
    """the chain stage (PROTOCOL=chain): per run, its generations and what its final best solves
    of the thesis's 16 fixed trials and of its chained trials"""
    lines = ["### The chain stage (SPEC §12; not the thesis's)", "",
             "| run (seed) | generations run | final best: fixed trials solved | "
             "final best: chained trials solved |", "|---|---|---|---|"]
    paths = run_files(out, "chain-s*", given)
    if not paths:
        die("%s: no chain-s*/fitness.csv (expected the chain runs of --protocol chain)" % out)
    for path in paths:
        last = read_fitness(path, *("best_t%d" % k for k in range(NFIXED)), "best_c0")[-1]
        fixed = sum(int(last["best_t%d" % k]) for k in range(NFIXED))
        chained = [int(v) for k, v in last.items() if re.fullmatch(r"best_c\d+", k)]
        lines.append("| %d | %d | %d/%d | %d/%d |" % (run_seed(path), int(last["generation"]) + 1,
                                                    fixed, NFIXED, sum(chained), len(chained)))
    return lines + [""]


def summary_by(out, test):
    path = os.path.join(out, "summary", test + ".csv")
    if not os.path.exists(path):
        return None
    res = {}
    for r in read_post(path, "summary", "a post-evaluation summary (summary/TEST.csv)", "successes",
                       "trials", "open_jumped"):
        pct = 100.0 * int(r["successes"]) / int(r["trials"]) if int(r["trials"]) else 0.0
        res.setdefault(r["condition"], []).append((int(r["run"]), int(r["individual"]), pct, r))
    return res


def stats_text(out, name):
    path = os.path.join(out, "stats", name)
    if not os.path.exists(path):
        return ["(missing: %s)" % path]
    return [line for line in figlib.read_text(path, "./apps/stats's output") if not line.startswith("#")]


def thesis_matrix(tab):
    cols = tab["columns"]
    lines = ["| U | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
    for name in cols:
        lines.append("| %s | %s |" % (name, " | ".join(tab["rows"][name])))
    return lines


def section_integration(out, th):
    s = summary_by(out, "integration") or {}
    rows = [x for v in s.values() for x in v]
    succ = five([int(x[3]["successes"]) for x in rows])
    jumped = five([int(x[3]["open_jumped"]) for x in rows])
    t = th["integration_test"]
    tj = t["open_jumped"]
    return ["## Integration test (thesis §3.1.1)", "",
            "| | thesis | ours |", "|---|---|---|",
            "| individuals | 100 (top 10 of 10 runs) | %d |" % len(rows),
            "| successes of 40: median (quartiles) | %g | %s |" % (t["successes_median"], fmt5(succ)),
            "| trials with open jumped: median (quartiles) | %g (%g, %g) | %s |" % (
                tj["median"], tj["lower_quartile"], tj["upper_quartile"], fmt5(jumped)),
            "", "![Fig. 3.3](figures/fig3_3.png)", ""] + stats_text(out, "integration.txt") + [""]


def section_integrated(out):
    lines = ["## Integrated stage (thesis §3.2): the best of each run's last generation", "",
             "| condition | run (seed) | generations | best | bonus | autonomous bonus | trials solved |",
             "|---|---|---|---|---|---|---|"]
    for key, name in CONDS:
        for p in sorted(glob.glob(os.path.join(out, "int-%s-s*" % key, "fitness.csv"))):
            r = read_fitness(p, "best", "best_bonus", "best_bonus_auto", "best_successes")[-1]
            trials = len([c for c in r if re.match(r"best_t\d+$", c)])
            lines.append("| %s | %d | %d | %s | %s | %s | %s/%d |" % (
                name, run_seed(p), int(r["generation"]) + 1, "%.1f" % float(r["best"]),
                r["best_bonus"], r["best_bonus_auto"], r["best_successes"], trials))
    lines.append("")
    lines += ["![%s](figures/fig3_int_%s.png)" % (name, key) for key, name in CONDS]
    return lines + [""]


def int_run_counts(run_dir, robustness):
    """one integrated run as the thesis counts it (§3.2.1-3.2.4): whether its best succeeds in
    the robustness test at all (None: not tested), whether its last generation's best earns the
    whole autonomous bonus (every trial without the caretaker's words a success: eq. 2.14's two
    bonuses each), and the first generation whose best did"""
    bonus = run_value(run_dir, "fitness", "bonus", 10.0, float)
    trials = run_value(run_dir, "integrated", "trials", 8, int)
    words = [run_value(run_dir, "integrated", "words_" + k, "caretaker", str) for k in ("even", "odd")]
    auto_max = 2 * bonus * sum(1 for i in range(trials) if words[i % 2] != "caretaker")
    rows = read_fitness(os.path.join(run_dir, "fitness.csv"), "best_bonus_auto")
    full = [int(r["generation"]) for r in rows
            if auto_max > 0 and float(r["best_bonus_auto"]) >= auto_max - 1e-9]
    rob = robustness.get(os.path.basename(run_dir))
    return {"learned": None if rob is None else rob > 0,
            "all_auto": bool(full) and full[-1] == int(rows[-1]["generation"]),
            "first_all": full[0] if full else None}


def section_integrated_counts(out, th):
    """the thesis's counts of §3.2.1-3.2.4 per condition beside ours"""
    t = th["integrated_runs"]
    s = summary_by(out, "robustness") or {}
    lines = ["### The runs as the thesis counts them (§3.2.1-3.2.4)", "",
             "Learned: the run's best succeeds autonomously in at least one trial (ours: of the "
             "robustness test; the thesis's runs above 0 in Table A.1). All autonomous: its last "
             "generation's best earns the whole bonus of every trial without the caretaker's "
             "words. First generation: the first whose best did.", "",
             "| condition | runs | learned: thesis (of 10) | ours | all autonomous: thesis | ours "
             "| first generation all autonomous: thesis | ours (median, range) |",
             "|---|---|---|---|---|---|---|---|"]
    for k, name in CONDS:
        rob = {x[3]["run_label"]: int(x[3]["successes"]) for x in s.get(name, [])}
        runs = [int_run_counts(os.path.dirname(p), rob)
                for p in sorted(glob.glob(os.path.join(out, "int-%s-s*" % k, "fitness.csv")))]
        learned = [r["learned"] for r in runs if r["learned"] is not None]
        first = [r["first_all"] for r in runs if r["first_all"] is not None]
        g = t["generations_to_all"][name]
        lines.append("| %s | %d | %d | %s | %d | %d | %s | %s |" % (
            name, len(runs), t["learned"][name],
            "%d of %d tested" % (sum(learned), len(learned)) if learned else "-",
            t["all_autonomous"][name], sum(1 for r in runs if r["all_auto"]),
            "%d-%d" % tuple(g) if g else "-",
            "%s (%d-%d), %d runs" % (fmt(five(first)[0]), min(first), max(first), len(first))
            if first else "-"))
    return lines + [""]


def section_types(root, th):
    """the robustness test by trial type (its four types of positions, 10 trials each) from
    ROOT/robustness-<cond>/trials.csv (OUT/posteval, or OUT/interim): which runs succeed in all
    four, the thesis's count for ST-CT (§3.2.1: 'in all the four types of positions') and the
    types where each run fails"""
    t = th["integrated_runs"]["all_autonomous"]
    lines = ["### By trial type", "",
             "Successes of each run's best in the robustness test by trial type (type = trial "
             "mod 4: reach posture, object position and target). The thesis counts the ST-CT "
             "runs whose best succeeds \"in all the four types of positions\" (§3.2.1).", "",
             "| condition | run | type 0 | type 1 | type 2 | type 3 | all four types |",
             "|---|---|---|---|---|---|---|"]
    count = {}
    for k, name in CONDS:
        path = os.path.join(root, "robustness-%s" % k, "trials.csv")
        if not os.path.exists(path):
            continue
        runs = {}
        for r in read_post(path, "trials", "a post-evaluation's trials.csv", "run_label", "type",
                           "success"):
            n = runs.setdefault(r["run_label"], [[0, 0] for _ in range(4)])
            n[int(r["type"]) % 4][0] += int(r["success"])
            n[int(r["type"]) % 4][1] += 1
        for label in sorted(runs, key=lambda x: (run_seed(x + "/"), x)):
            n = runs[label]
            every = all(won > 0 for won, _ in n)
            count[name] = count.get(name, 0) + every
            lines.append("| %s | %s | %s | %s |" % (name, label, " | ".join(
                "%d/%d" % tuple(x) for x in n), "yes" if every else "no"))
    lines += ["", "| condition | runs succeeding in all four types: thesis (of 10) | ours |",
              "|---|---|---|"]
    for _, name in CONDS:
        lines.append("| %s | %s | %s |" % (name, t[name] if name == "ST-CT" else "-",
                                         count.get(name, "-")))
    return lines + [""]


def per_run_table(s, th_tab, conds):
    lines = ["| condition | thesis: runs 0-9 (median) | ours: runs (median) |", "|---|---|---|"]
    for c in conds:
        ours = sorted(s.get(c, []), key=lambda x: (x[0], x[1])) if s else []
        th = th_tab.get(c)
        lines.append("| %s | %s (%s) | %s (%s) |" % (
            c, " ".join("%g" % v for v in th) if th else "-", fmt(five(th)[0]) if th else "-",
            " ".join("%.1f" % x[2] for x in ours) or "-", fmt(five([x[2] for x in ours])[0]) if ours else "-"))
    return lines


def section_test(out, th, test, title, table, fig, th_table, th_a, conds):
    s = summary_by(out, test)
    return (["## %s" % title, "", "Success percentage per individual (Table %s):" % th_a, ""]
            + per_run_table(s, th["table_" + th_a.lower().replace(".", "")], conds)
            + ["", "Thesis, Table %s:" % th_table, ""] + thesis_matrix(th["table_" + th_table.replace(".", "_")])
            + ["", "Ours (`./apps/stats table`):"] + stats_text(out, table) + ["", "Ours, per condition:"]
            + stats_text(out, test + ".txt") + [""] + ["![%s](figures/%s.png)" % (f, f) for f in fig] + [""])


def section_selftalk(out, th):
    path = os.path.join(out, "stats", "selftalk.csv")
    better = {}
    if os.path.exists(path):
        for r in read_post(path, "selftalk", "./apps/stats selftalk's output", "better"):
            if r["better"] == "selftalk":
                better[r["condition"]] = better.get(r["condition"], 0) + 1
    t = th["selftalk_better"]
    t3 = th["table_3_3"]
    lines = ["## Self talk against the caretaker's words (thesis §3.2.5, Fig. 3.11, Table 3.3)", "",
             "| condition | thesis: individuals better with self talk | ours |", "|---|---|---|"]
    for c in ("ST-CT", "ST"):
        lines.append("| %s | %d of 10 | %d |" % (c, t[c], better.get(c, 0)))
    lines += ["", "Thesis, Table 3.3 (seconds to the target):", "",
              "| | " + " | ".join(t3["columns"]) + " |", "|---" * (len(t3["columns"]) + 1) + "|",
              "| Self talk | " + " | ".join("%.2f" % v for v in t3["self_talk"]) + " |",
              "| Caretaker | " + " | ".join("%.2f" % v for v in t3["caretaker"]) + " |",
              "", "Ours (`./apps/stats times`):"] + stats_text(out, "table_3_3.txt")
    return lines + ["", "![Fig. 3.11](figures/fig3_11.png)", ""]


WORD_RUN = re.compile(r"^fig_words: (\S+): (self talk|caretaker): (.*)$")


def words_used(runs):
    """the words of 'reach 0-12, grasp 13-13, ...' in order of first use"""
    seen = []
    for r in runs.split(", "):
        w = r.split(" ")[0]
        if w != "none" and w not in seen:
            seen.append(w)
    return seen


def section_strategies(out):
    """Fig. 3.12 (make replicate's fig3_12_<cond>: the best run's words in the four trial types,
    as fig_words.py printed them)"""
    lines = ["## Strategies (thesis §3.2.6, Fig. 3.12)", "",
             "The thesis (§3.2.6): the self talk of ST-CT run 7 and ST run 5 keeps the "
             "caretaker's sequence with primitives of other lengths; ST-CT run 7's fluctuates "
             "rapidly between two words before the next one settles; every individual \"never "
             "uses the *open* instruction\".", "",
             "| condition | individual | trial type | self talk: words in order of first use | "
             "says *open* | the caretaker's words |", "|---|---|---|---|---|---|"]
    for cond, name in (("stct", "ST-CT"), ("st", "ST")):
        path = os.path.join(out, "figures", "fig3_12_%s.txt" % cond)
        if not os.path.exists(path):
            lines.append("| %s | (no fig3_12_%s.txt) | | | | |" % (name, cond))
            continue
        title = ""
        by_type = {}
        for line in figlib.read_text(path, "tools/fig_words.py's output"):
            if line.startswith("fig_words: title: "):
                title = line[len("fig_words: title: "):].strip().replace("'s best", "")
            m = WORD_RUN.match(line.rstrip("\n"))
            if not m:
                continue
            t = re.search(r"(self|care)-(\d)\.csv$", m.group(1))
            if t:
                by_type.setdefault(int(t.group(2)), {})[m.group(2)] = words_used(m.group(3))
        for k in sorted(by_type):
            st, ct = by_type[k].get("self talk", []), by_type[k].get("caretaker", [])
            lines.append("| %s | %s | %d | %s | %s | %s |" % (
                name, title, k, ", ".join(st), "yes" if "open" in st else "no", ", ".join(ct)))
    lines += ["", "![Fig. 3.12, ST-CT](figures/fig3_12_stct.png)", "",
              "![Fig. 3.12, ST](figures/fig3_12_st.png)", ""]
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--preset", default="full")
    ap.add_argument("--runs", type=int, default=0)
    ap.add_argument("--protocol", choices=sorted(PROTOCOLS), default="chain")
    ap.add_argument("--prim-runs", default="", metavar="'DIR ...'",
                    help="the primitive runs taken as given (replicate.mk's PRIM_RUNS)")
    ap.add_argument("--chain-runs", default="", metavar="'DIR ...'",
                    help="their chain stages (CHAIN_RUNS)")
    ap.add_argument("-o", dest="report", default=None)
    ap.add_argument("--types", action="store_true",
                    help="print only the robustness test by trial type, of OUT/robustness-<cond>/ "
                         "(replicate.mk interim)")
    a = ap.parse_args()
    if not os.path.isdir(a.out):
        die("%s: not a directory" % a.out)
    if a.types:
        with open(THESIS) as f:
            print("\n".join(section_types(a.out, json.load(f))[2:]))
        return
    given_prims, given_chains = a.prim_runs.split(), a.chain_runs.split()
    if given_chains and a.protocol != "chain":
        die("--chain-runs with --protocol %s, which has no chain stage" % a.protocol)
    if given_chains and len(given_chains) != len(given_prims):
        die("--chain-runs: %d directories for %d primitive runs (--prim-runs): expected one each"
            % (len(given_chains), len(given_prims)))
    for d in given_prims + given_chains:
        if not os.path.isfile(os.path.join(d, "fitness.csv")):
            die("%s: no fitness.csv (expected a run's directory)" % d)
    with open(THESIS) as f:
        th = json.load(f)
    lines = ["# Replication of the study", "",
             "Preset `%s`, %d runs per stage and condition, in `%s` (tools/replicate.mk). The "
             "thesis's numbers come from `data/thesis/results.json`." % (a.preset, a.runs, a.out), "",
             PROTOCOLS[a.protocol], ""]
    if given_prims:
        lines += ["The primitive runs were given (`PRIM_RUNS`%s), not run here: %s. `%d runs` "
                  "counts the integrated runs of each condition." % (
                      ", `CHAIN_RUNS`" if given_chains else "",
                      ", ".join("`%s`" % d for d in given_prims + given_chains), a.runs), ""]
    if a.preset != "full":
        lines += ["**A quick look, not a replication:** the `%s` preset caps the generations and "
                  "shrinks the post-evaluations, so its numbers are not comparable with the "
                  "thesis's." % a.preset, ""]
    lines += section_departures(a.out, given_prims + given_chains)
    lines += section_prims(a.out, th, given_prims)
    if a.protocol == "chain":
        lines += section_chain(a.out, given_chains)
    lines += section_integration(a.out, th) + section_integrated(a.out)
    lines += section_integrated_counts(a.out, th)
    lines += section_test(a.out, th, "robustness", "Robustness test (thesis §3.2, Fig. 3.4)",
                          "table_3_1.txt", ["fig3_4"], "3.1", "A.1", th["conditions"])
    lines += section_types(os.path.join(a.out, "posteval"), th)
    lines += section_test(a.out, th, "generalisation", "Generalisation test (thesis §3.2.5)",
                          "table_3_2.txt", ["fig3_9", "fig3_10"], "3.2", "A.2",
                          th["conditions"] + ["ST-CT0", "ST0"])
    lines += section_selftalk(a.out, th)
    lines += section_strategies(a.out)
    report = a.report or os.path.join(a.out, "report.md")
    with open(report + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(report + ".tmp", report)


if __name__ == "__main__":
    main()
