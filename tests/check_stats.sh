#!/usr/bin/env bash
# ./apps/stats end to end. mwu against an independent implementation written here (exact p by
# enumerating every split of the ranks, the normal approximation by its formula: Python's
# standard library only) on fixed and random samples; the thesis's Table 3.1 rebuilt from its
# Table A.1 (tests/fixtures/posteval/summary.csv); Table 3.2's layout; median and quartiles
# worked out by hand; the self talk vs caretaker comparison and Table 3.3's times on the
# hand-made trials.csv (its patterns: tests/fixtures/posteval/make_fixtures.py); bad input
# refused naming FILE:LINE, exit 2.
set -uo pipefail
CHECK=check_stats
source "$(dirname "$0")/check_lib.sh"
ST="$APPDIR/stats"
FX=tests/fixtures/posteval

# ---- mwu against the reference below, on fixed and seeded random samples
cat > "$tmp/ref.py" <<'PY'
import itertools, math, random, sys
from fractions import Fraction

def u_of(a, b):
    return sum((x > y) + Fraction(1, 2) * (x == y) for x in a for y in b)

def p_ref(a, b):
    """exact without ties when both have <= 20 values (enumeration: kept to small sizes here),
    else the normal approximation with the tie and 0.5 continuity corrections"""
    n1, n2, ua = len(a), len(b), u_of(a, b)
    k = min(ua, n1 * n2 - ua)
    if len(set(a + b)) == n1 + n2 and max(n1, n2) <= 20:
        splits = list(itertools.combinations(range(n1 + n2), n1))
        le = sum(sum(r) - n1 * (n1 - 1) // 2 <= k for r in splits)
        return min(1.0, 2 * le / len(splits)), float(k), "exact"
    n, pooled = n1 + n2, sorted(a + b)
    ties = sum(t ** 3 - t for t in (pooled.count(v) for v in set(pooled)))
    var = n1 * n2 / 12 * ((n + 1) - ties / (n * (n - 1)))
    if var <= 0:
        return 1.0, float(k), "normal"
    d = max(0.0, abs(float(ua) - n1 * n2 / 2) - 0.5)
    return math.erfc(d / math.sqrt(var) / math.sqrt(2)), float(k), "normal"

rng = random.Random(15)
cases = [([0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46], [1.15, 0.88, 0.90, 0.74, 1.21]),
         ([1, 2, 2, 5], [2, 4, 4, 6, 7]), ([3, 3, 3], [3, 3]), ([1], [2])]
for i in range(24):  # no ties (exact) and with ties (small integers), sizes 1..8
    n1, n2 = rng.randint(1, 8), rng.randint(1, 8)
    if i % 2:
        cases.append(([rng.randint(0, 6) for _ in range(n1)], [rng.randint(0, 6) for _ in range(n2)]))
    else:
        v = rng.sample(range(1000), n1 + n2)
        cases.append(([x / 7 for x in v[:n1]], [x / 7 for x in v[n1:]]))
for i in range(3):  # more than 20 values: normal approximation
    cases.append(([rng.random() for _ in range(25 + i)], [rng.random() + 0.1 for _ in range(21)]))
d = sys.argv[1]
with open(d + "/cases", "w") as out:
    for i, (a, b) in enumerate(cases):
        for s, xs in (("a", a), ("b", b)):
            with open(f"{d}/c{i}{s}", "w") as f:
                f.write("".join(repr(float(x)) + "\n" for x in xs))
        p, u, how = p_ref(a, b)
        out.write(f"{i} {u!r} {p!r} {how}\n")
PY
python3 "$tmp/ref.py" "$tmp"
while read -r i u p how; do
  echo "$i $u $p $how $("$ST" mwu "$tmp/c${i}a" "$tmp/c${i}b" 2>&1)"
done < "$tmp/cases" > "$tmp/got"
res=$(python3 - "$tmp/got" <<'PY'
import re, sys
n = bad = nexact = 0
for line in open(sys.argv[1]):
    i, u, p, how, out = line.rstrip("\n").split(" ", 4)
    m = re.fullmatch(r"U=(\S+) p=(\S+)", out)
    n += 1
    nexact += how == "exact"
    if not (m and float(m[1]) == float(u) and abs(float(m[2]) - float(p)) <= 1e-12 * float(p)):
        bad += 1
        print(f"case {i} ({how}): got '{out}', want U={u} p={p};", end=" ")
print(f"{n} {nexact} {bad}")
PY
)
read -r n nexact bad <<<"${res##*; }"
[ "$bad" = 0 ] && [ "$n" -ge 30 ] && [ "$nexact" -ge 10 ] &&
  ok "mwu agrees with the reference on $n samples ($nexact exact)" || ko "mwu reference" "$res"
# the Hollander & Wolfe example: p = 2 * 382 / 3003 printed with 17 digits
[ "$("$ST" mwu "$tmp/c0a" "$tmp/c0b")" = "U=15 p=$(python3 -c 'print("%.17g" % (764 / 3003))')" ] &&
  ok "mwu prints U=%.17g p=%.17g (Hollander & Wolfe: U 15, p 764/3003)" || ko "mwu format" "$("$ST" mwu "$tmp/c0a" "$tmp/c0b")"
out=$("$ST" mwu "$tmp/c0a" "$tmp/c0b" --verbose --exact-max 0)
grep -q "^U_A=35 U_B=15 z=1.16350762782200.* method=normal n_A=10 n_B=5 tied_values=0$" <<<"$out" &&
  ok "mwu --verbose --exact-max 0: the normal approximation's z = 9.5 / sqrt(200/3)" || ko "mwu verbose" "$out"

# ---- quartiles: R's quantile(c(0.80, ..., 1.46)) = 0.73, 0.8825, 1.415, 1.595, 1.91
python3 - "$("$ST" quartiles "$tmp/c0a")" <<'PY' && ok "quartiles: R's type-7 values" || ko "quartiles" "$("$ST" quartiles "$tmp/c0a")"
import re, sys
got = dict(re.findall(r"(\w+)=(\S+)", sys.argv[1]))
want = {"n": 10, "min": 0.73, "q1": 0.8825, "median": 1.415, "q3": 1.595, "max": 1.91}
sys.exit(any(abs(float(got[k]) - v) > 1e-12 for k, v in want.items()))
PY

# ---- Table 3.1 from Table A.1, exactly as the thesis prints it (U, * p <= 0.05, ** p <= 0.01)
"$ST" table "$FX/summary.csv" --test robustness > "$tmp/t31" 2>&1
cat > "$tmp/t31.want" <<'T'
| U | ST-CT | ST | CT | NI |
|---|---|---|---|---|
| ST-CT | - | 24 | 9.5** | 8.5** |
| ST | 76 | - | 20* | 16.5* |
| CT | 90.5** | 80* | - | 51 |
| NI | 91.5** | 83.5* | 49 | - |
T
grep -A5 '^| U |' "$tmp/t31" | diff - "$tmp/t31.want" > /dev/null &&
  ok "table: Table 3.1 rebuilt from Table A.1 (U and stars)" || ko "table 3.1" "$(cat "$tmp/t31")"
grep -q '^| ST-CT | - | 0.0526 | 0.00197 | 0.00166 |$' "$tmp/t31" &&
  ok "table: the p matrix (3 digits)" || ko "table p" "$(cat "$tmp/t31")"
# --csv: the 12 ordered pairs, p with 17 digits against the reference formula
"$ST" table "$FX/summary.csv" --test robustness --csv > "$tmp/t31.csv"
python3 - "$tmp/t31.csv" "$tmp/ref.py" <<'PY' && ok "table --csv: 12 ordered pairs, U and p as the reference" || ko "table --csv" "$(cat "$tmp/t31.csv")"
import csv, sys
sys.argv, path = [sys.argv[2], "/dev/null"], sys.argv[1]
src = open(sys.argv[0]).read().split("rng = random")[0]
exec(src)
A1 = {"ST-CT": [95, 95, 87.5, 100, 67.5, 90, 92.5, 97.5, 0, 97.5], "ST": [67.5, 0, 95, 90, 0, 90, 75, 80, 87.5, 82.5],
      "CT": [0, 0, 0, 62.5, 62.5, 0, 0, 0, 50, 90], "NI": [0, 0, 32.5, 0, 0, 32.5, 62.5, 60, 75, 0]}
rows = list(csv.DictReader(open(path)))
ok = len(rows) == 12
for r in rows:
    a, b = A1[r["row"]], A1[r["column"]]
    p, _, _ = p_ref(a, b)
    ok = ok and float(r["U"]) == float(u_of(b, a)) and abs(float(r["p"]) - p) <= 1e-12 * p
    ok = ok and r["stars"] == ("**" if p <= 0.01 else "*" if p <= 0.05 else "") and r["test"] == "robustness"
sys.exit(not ok)
PY
# Table 3.2's layout: a caretaker variant (NAME0) is compared with NAME only. The thesis's
# ST-CT0 and ST0 rows come out as printed (65, 36.5); pairs with NI differ by 0.5-3 from the
# thesis's because its Table A.2 does not give exactly the values behind Table 3.2 (docs/PROTOCOL.md).
"$ST" table "$FX/summary.csv" --test generalisation > "$tmp/t32"
grep -qx '| ST-CT0 | 65 | - | - | - | - | - |' "$tmp/t32" && grep -qx '| ST0 | - | 36.5 | - | - | - | - |' "$tmp/t32" &&
  grep -qx '| ST-CT | - | 22\* | 11\*\* | 7\*\* | 35 | - |' "$tmp/t32" &&
  ok "table: Table 3.2's pairs (NAME0 against NAME only)" || ko "table 3.2" "$(cat "$tmp/t32")"

# ---- describe: incremental successes 25 30 20 28 35 10 of 40 -> 62.5 75 50 70 87.5 25 %:
# sorted 25 50 62.5 70 75 87.5, median 66.25, quartiles (h = 1.25, 3.75) 53.125, 73.75;
# open jumped 30 20 21 35 35 40 -> 20 21 30 35 35 40: 32.5, 23.25, 35
out=$("$ST" describe "$FX/summary.csv" --test integration)
grep -qx '| incremental | success % | 6 | 66.25 | 53.125 | 73.75 | 25 | 87.5 |' <<<"$out" &&
  grep -qx '| incremental | open jumped | 6 | 32.5 | 23.25 | 35 | 20 | 40 |' <<<"$out" &&
  ok "describe: median and type-7 quartiles by hand" || ko "describe" "$out"

# ---- selftalk (Fig. 3.11): ST-CT run 0 succeeds in 26 cells of 49 in repetitions 0, 1, 2, 4
# and 25 in 3; ST-CT0 in 13 in all five. U = 0; ties 5 (t^3 - t = 120) and 4 (60): sigma^2 =
# 25/12 (11 - 180/90) = 18.75, z = (12.5 - 0.5) / sigma, p = erfc(z / sqrt 2) = 0.005584 <= 0.01.
# ST run 1 is excluded (no rows): five 0 % against ST0's five 5/49: ties 120 + 120, sigma^2 =
# 25/12 (11 - 240/90), p = erfc(12 / sigma / sqrt 2) = 0.003977, better with the caretaker.
# Times: (150 + 1) x 0.05 = 7.55 s, (170 + 1) x 0.05 = 8.55 s, (200 + 1) x 0.05 = 10.05 s.
"$ST" selftalk "$FX/trials.csv" > "$tmp/st.csv" 2>&1
python3 - "$tmp/st.csv" <<'PY' && ok "selftalk: per-individual U, p, excluded, mean times by hand" || ko "selftalk" "$(cat "$tmp/st.csv")"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
p1 = math.erfc(12 / math.sqrt(18.75) / math.sqrt(2))
p2 = math.erfc(12 / math.sqrt(25 / 12 * (11 - 240 / 90)) / math.sqrt(2))
a, b = rows
ok = len(rows) == 2 and (a["condition"], a["caretaker_condition"], a["run"], a["excluded"]) == ("ST-CT", "ST-CT0", "0", "0")
ok = ok and abs(float(a["selftalk_pct"]) - 100 * 129 / 245) < 1e-12 and abs(float(a["caretaker_pct"]) - 100 * 13 / 49) < 1e-12
ok = ok and float(a["U"]) == 0 and abs(float(a["p"]) - p1) < 1e-12 * p1 and a["better"] == "selftalk"
ok = ok and abs(float(a["selftalk_seconds"]) - 7.55) < 1e-12 and abs(float(a["caretaker_seconds"]) - 8.55) < 1e-12
ok = ok and (b["condition"], b["run"], b["excluded"], b["better"], b["selftalk_seconds"]) == ("ST", "1", "1", "caretaker", "")
ok = ok and abs(float(b["p"]) - p2) < 1e-12 * p2 and abs(float(b["caretaker_seconds"]) - 10.05) < 1e-12
sys.exit(not ok)
PY
# ---- times (Table 3.3): the individuals better with self talk; robot.control_dt scales them
out=$("$ST" times "$FX/trials.csv")
grep -qx '| | ST-CT run 0 |' <<<"$out" && grep -qx '| Self talk | 7.55 |' <<<"$out" && grep -qx '| Caretaker | 8.55 |' <<<"$out" &&
  ok "times: Table 3.3 for ST-CT run 0" || ko "times" "$out"
out=$("$ST" times "$FX/trials.csv" --set robot.control_dt=0.1)
grep -qx '| Self talk | 15.10 |' <<<"$out" && ok "times: robot.control_dt from --set" || ko "times dt" "$out"
out=$("$ST" times "$FX/trials.csv" --alpha 0.005)
grep -q "no individual is significantly better with self talk" <<<"$out" && ok "times: --alpha 0.005 leaves none" || ko "times alpha" "$out"

# ---- bad input: FILE:LINE and what was expected, exit 2
fails() { # NAME NEEDLE CMD...: exit 2 and NEEDLE on stderr
  local name=$1 needle=$2; shift 2
  "$@" > "$tmp/o" 2> "$tmp/e"; local rc=$?
  if [ "$rc" = 2 ] && grep -qF -- "$needle" "$tmp/e"; then ok "$name"; else ko "$name" "rc=$rc $(cat "$tmp/e")"; fi
}
printf '1\n\n# c\nabc\n' > "$tmp/n1"; fails "mwu: a bad line" "$tmp/n1:4: 'abc' is not a number (expected one number per line)" "$ST" mwu "$tmp/n1" "$tmp/c0a"
printf '1 2\n' > "$tmp/n2"; fails "mwu: two numbers on a line" "$tmp/n2:1: '1 2' is not a number" "$ST" mwu "$tmp/c0a" "$tmp/n2"
printf '# only\n\n' > "$tmp/n3"; fails "mwu: no numbers" "$tmp/n3: no numbers (expected one number per line" "$ST" mwu "$tmp/c0a" "$tmp/n3"
: > "$tmp/n4"; fails "mwu: empty file" "$tmp/n4: no numbers" "$ST" mwu "$tmp/n4" "$tmp/c0a"
printf '1\n2\0003\n' > "$tmp/n5"; fails "mwu: NUL byte" "$tmp/n5:2: NUL byte at column 2 (expected a text file)" "$ST" mwu "$tmp/c0a" "$tmp/n5"
printf '1\nnan\n' > "$tmp/n6"; fails "mwu: nan" "$tmp/n6:2: 'nan' is not finite (expected a finite number)" "$ST" mwu "$tmp/c0a" "$tmp/n6"
printf '1\n-inf\n' > "$tmp/n7"; fails "mwu: -inf" "$tmp/n7:2: '-inf' is not finite" "$ST" mwu "$tmp/c0a" "$tmp/n7"
printf '1e400\n' > "$tmp/n8"; fails "mwu: overflow" "$tmp/n8:1: '1e400' is not finite" "$ST" mwu "$tmp/c0a" "$tmp/n8"
fails "mwu: missing file" "$tmp/none: cannot open" "$ST" mwu "$tmp/c0a" "$tmp/none"
fails "mwu: a file that never ends" "/dev/zero: larger than 64 MiB" timeout 600 "$ST" mwu "$tmp/c0a" /dev/zero
fails "table: a directory" "$tmp: cannot read: Is a directory" "$ST" table "$tmp"
fails "mwu: one file" "mwu needs 2 files" "$ST" mwu "$tmp/c0a"
fails "unknown command" "'frob': unknown command" "$ST" frob "$tmp/c0a"
fails "--exact-max out of range" "--exact-max 51: expected 0..50" "$ST" mwu "$tmp/c0a" "$tmp/c0b" --exact-max 51
head -3 "$FX/summary.csv" > "$tmp/s1"; echo "robustness,ST,1,0,41,40,0,0" >> "$tmp/s1"
fails "summary: successes > trials" "$tmp/s1:4: successes 41, open_jumped 0, excluded 0 (expected successes and open_jumped <= trials (40)" "$ST" table "$tmp/s1"
head -3 "$FX/summary.csv" > "$tmp/s2"; echo "robustness,ST,x,0,5,40,0,0" >> "$tmp/s2"
fails "summary: a bad integer" "$tmp/s2:4: run 'x' (expected an integer >= 0)" "$ST" table "$tmp/s2"
head -3 "$FX/summary.csv" > "$tmp/s3"; echo "robustness,ST,1,0,5" >> "$tmp/s3"
fails "summary: short row" "$tmp/s3:4: 5 fields (expected at least 8: test,condition,run,individual,successes,trials,excluded,open_jumped)" "$ST" table "$tmp/s3"
printf 'test,condition,run\n' > "$tmp/s4"
fails "summary: wrong header" "$tmp/s4:1: not the header (expected the header test,condition,run,individual,successes,trials,excluded,open_jumped" "$ST" table "$tmp/s4"
head -1 "$FX/summary.csv" > "$tmp/s5"; fails "summary: no rows" "$tmp/s5: no rows after the header" "$ST" table "$tmp/s5"
fails "summary: several tests" "several tests: choose one with --test (tests in the file: integration, robustness, generalisation)" "$ST" table "$FX/summary.csv"
fails "summary: unknown --test" "no rows of this --test" "$ST" table "$FX/summary.csv" --test robustnes
head -2 "$FX/summary.csv" > "$tmp/s6"; printf 'robustness,"ST",1,0,5,40,0,0\n' >> "$tmp/s6"
fails "summary: quoted field" "$tmp/s6:3: a quoted field (expected plain comma-separated values)" "$ST" table "$tmp/s6"
head -2 "$FX/summary.csv" > "$tmp/s7"; printf 'robustness,ST,1,0,0,40,0,0\0\n' >> "$tmp/s7"
fails "summary: NUL byte" "$tmp/s7:3: NUL byte" "$ST" table "$tmp/s7"
# 33 conditions (ST_POST_MAX_NAMES 32): the file and the line of the first one too many
{ head -1 "$FX/summary.csv"; for c in $(seq 1 33); do echo "robustness,C$c,0,0,5,40,0,0"; done; } > "$tmp/s8"
fails "summary: 33 conditions, the 33rd's line named" "$tmp/s8:34: condition 'C33': more than 32 conditions in the test (expected at most 32)" "$ST" table "$tmp/s8"
sed 's/^robustness,/generalisation,/' "$tmp/s8" > "$tmp/s9"
fails "summary: 33 conditions of the generalisation test" "$tmp/s9:34: condition 'C33': more than 32 conditions in the test (expected at most 32)" "$ST" table "$tmp/s9"
head -2 "$FX/trials.csv" > "$tmp/t1"; echo 'generalisation,ST0,1,0,0,-1,0,0,0,talk,0,-1,0' >> "$tmp/t1"
fails "trials: unknown words" "$tmp/t1:3: words 'talk' (expected none, caretaker or selftalk)" "$ST" selftalk "$tmp/t1"
head -2 "$FX/trials.csv" > "$tmp/t2"; echo 'generalisation,ST0,1,0,0,-1,0,0,0,none,1,-1,0' >> "$tmp/t2"
fails "trials: a success that never reached" "$tmp/t2:3: success 1 with reached_step -1" "$ST" selftalk "$tmp/t2"
head -2 "$FX/trials.csv" > "$tmp/t3"; echo 'generalisation,ST0,1,0,0,-1,49,0,0,none,0,-1,0' >> "$tmp/t3"
fails "trials: cell out of the grid" "$tmp/t3:3: trial 0 with type -1, cell 49, posture 0, repetition 0 (expected type -1, cell 0, posture 0, repetition 0" "$ST" selftalk "$tmp/t3"
head -2 "$FX/trials.csv" > "$tmp/t3b"; echo 'generalisation,ST0,1,0,0,-1,0,0,0,none,2,-1,0' >> "$tmp/t3b"
fails "trials: success 2" "$tmp/t3b:3: success 2, open_jumped 0 (expected 0 or 1)" "$ST" selftalk "$tmp/t3b"
grep -v ',ST-CT0,\|,ST0,' "$FX/trials.csv" > "$tmp/t4"
fails "trials: no caretaker variant" "$tmp/t4: no condition NAME0 in test generalisation" "$ST" times "$tmp/t4"
# the same individual or trial twice, a test posteval has not, a failed trial with a step, a
# trial outside its test's table (posteval.* keys: the thesis's unless --config / --set)
head -2 "$FX/summary.csv" > "$tmp/s8"; sed -n 2p "$FX/summary.csv" >> "$tmp/s8"
fails "summary: an individual twice" "$tmp/s8:3: test integration condition incremental run 0 individual 0 twice (first at line 2; expected each once)" "$ST" describe "$tmp/s8"
head -1 "$FX/summary.csv" > "$tmp/s9"; echo "robustnes,ST,1,0,5,40,0,0" >> "$tmp/s9"
fails "summary: an unknown test" "$tmp/s9:2: test 'robustnes' (expected integration, robustness or generalisation)" "$ST" table "$tmp/s9"
head -1 "$FX/trials.csv" > "$tmp/t5"; echo 'generalisaton,ST0,1,0,0,-1,0,0,0,none,0,-1,0' >> "$tmp/t5"
fails "trials: an unknown test" "$tmp/t5:2: test 'generalisaton' (expected integration, robustness or generalisation)" "$ST" selftalk "$tmp/t5"
head -3 "$FX/trials.csv" > "$tmp/t6"; sed -n 2p "$FX/trials.csv" >> "$tmp/t6"
fails "trials: a trial twice" "$tmp/t6:4: test generalisation condition ST-CT run 0 individual 0 trial 0 twice (first at line 2; expected each once)" "$ST" selftalk "$tmp/t6"
head -2 "$FX/trials.csv" > "$tmp/t7"; echo 'generalisation,ST0,1,0,0,-1,0,0,0,caretaker,0,17,0' >> "$tmp/t7"
fails "trials: a failed trial with a reached step" "$tmp/t7:3: success 0 with reached_step 17 (expected -1" "$ST" selftalk "$tmp/t7"
head -2 "$FX/trials.csv" > "$tmp/t8"; echo 'generalisation,ST0,1,0,1960,-1,0,0,0,caretaker,0,-1,0' >> "$tmp/t8"
fails "trials: a trial beyond the generalisation test" "$tmp/t8:3: trial 1960 (expected 0..1959: the generalisation test has 1960 trials" "$ST" selftalk "$tmp/t8"
head -2 "$FX/trials.csv" > "$tmp/t9"; echo 'robustness,ST0,1,0,40,0,-1,0,10,caretaker,0,-1,0' >> "$tmp/t9"
fails "trials: a trial beyond the robustness test" "$tmp/t9:3: trial 40 (expected 0..39: the robustness test has 40 trials" "$ST" selftalk "$tmp/t9" --test robustness
fails "trials: --set posteval.robustness_trials=41 takes trial 40" "$tmp/t9: no condition NAME0 in test generalisation" "$ST" selftalk "$tmp/t9" --set posteval.robustness_trials=41 --test generalisation
head -2 "$FX/trials.csv" > "$tmp/t10"; echo 'generalisation,ST0,1,0,41,-1,0,0,1,caretaker,0,-1,0' >> "$tmp/t10"
fails "trials: a row that is not its trial's" "$tmp/t10:3: trial 41 with type -1, cell 0, posture 0, repetition 1 (expected type -1, cell 1, posture 0, repetition 1: the generalisation test's trial table; posteval.* keys from --config" "$ST" selftalk "$tmp/t10"

# ---- many individuals (the comparison is O(n log n): sorted once, each individual found by
# binary search): 600 individuals' 48,000 trials in a shuffled order give the rows of the file
# in order, and each individual alone gives its own row
python3 - "$tmp/many.csv" "$tmp/many_shuf.csv" "$tmp/one.csv" <<'PY'
import random, sys
sys.path.insert(0, "tools")
import csvschema
rng = random.Random(24)
head = ",".join(list(csvschema.TRIALS)[:csvschema.TRIALS_READ])
rows = []
for run in range(60):
    for ind in range(10):
        for cond, words, p in (("ST", "selftalk", rng.random()), ("ST0", "caretaker", rng.random())):
            for t in range(40):
                ok = int(rng.random() < p)
                rows.append(f"robustness,{cond},{run},{ind},{t},{t % 4},-1,{t % 4},{t // 4},{words},{ok},{rng.randrange(240) if ok else -1},0")
open(sys.argv[1], "w").write(head + "\n" + "\n".join(rows) + "\n")
one = [r for r in rows if r.startswith("robustness,ST,37,4,") or r.startswith("robustness,ST0,37,4,")]
open(sys.argv[3], "w").write(head + "\n" + "\n".join(one) + "\n")
rng.shuffle(rows)
open(sys.argv[2], "w").write(head + "\n" + "\n".join(rows) + "\n")
PY
"$ST" selftalk "$tmp/many.csv" > "$tmp/m1" 2>&1; r1=$?
"$ST" selftalk "$tmp/many_shuf.csv" > "$tmp/m2" 2>&1; r2=$?
"$ST" selftalk "$tmp/one.csv" > "$tmp/m3" 2>&1; r3=$?
if [ $r1 = 0 ] && [ $r2 = 0 ] && [ $r3 = 0 ] && [ "$(wc -l < "$tmp/m1")" = 601 ] &&
   [ "$(sort "$tmp/m1")" = "$(sort "$tmp/m2")" ] && grep -qxF "$(sed -n 2p "$tmp/m3")" "$tmp/m1" &&
   [ "$(sed -n 2p "$tmp/m1" | cut -d, -f1-4)" = "ST,ST0,0,0" ]; then
  ok "selftalk: 600 individuals, in file order, the same shuffled, each as alone"
else ko "selftalk: many individuals" "$r1 $r2 $r3 $(head -3 "$tmp/m1") / $(head -3 "$tmp/m3")"; fi

fails "trials: a summary file is not a trials file" "summary.csv:1: not the header (expected the header test,condition,run,individual,trial,type" "$ST" selftalk "$FX/summary.csv"

echo "$CHECK: $pass passed, $fail failed"
[ "$fail" = 0 ]
