#!/usr/bin/env bash
# Compare the C network evaluator (./apps/neteval) against the independent
# Python reference (tests/ref/netref.py) on random genomes and random input
# sequences, for each architecture of SPEC §4 (base, A, B).
#
# Run from the repo root:  bash tests/check_neteval.sh
set -euo pipefail

NETEVAL=${NETEVAL:-./apps/neteval}   # override only to test this script
NETREF=tests/ref/netref.py
TOL=1e-9

if [ ! -f "$NETREF" ]; then
    echo "check_neteval: $NETREF not found (run from the repo root)" >&2
    exit 2
fi
if [ ! -x "$NETEVAL" ]; then
    echo "check_neteval: $NETEVAL not found or not executable (build it first)" >&2
    exit 2
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

passed=0
failed=0
for arch in base A B; do
    genome="$tmp/genome_$arch.txt"
    rows="$tmp/rows_$arch.txt"

    # Random genome + ~200 random input rows, fixed seed per arch.
    python3 - "$arch" "$genome" "$rows" <<'PY'
import random, sys
arch, genome_path, rows_path = sys.argv[1:4]
n_genes = {"base": 612, "A": 696, "B": 756}[arch]
seed = {"base": 4101, "A": 4102, "B": 4103}[arch]
rng = random.Random(seed)

# Genes: mostly uniform 16-bit, a few at the extremes / the "near zero" 0x8000.
genes = []
for _ in range(n_genes):
    r = rng.random()
    if r < 0.03:
        genes.append(0x0000)
    elif r < 0.06:
        genes.append(0xffff)
    elif r < 0.08:
        genes.append(0x8000)
    else:
        genes.append(rng.randrange(65536))
with open(genome_path, "w") as fh:
    fh.write("# genes %d\n" % n_genes)
    fh.write("# fitness 1.5\n")
    fh.write("".join("%04x" % g for g in genes) + "\n")

def normal_row():
    row = [rng.random() for _ in range(12)]                  # 0-11 proprioception
    row += [float(rng.random() < 0.3) for _ in range(6)]     # 12-17 touch
    row += [rng.uniform(-6.0, 6.0) for _ in range(3)]        # 18-20 focus
    word = rng.randrange(5)                                  # 21-24 words
    row += [10.0 if word == j else 0.0 for j in range(4)]    # (word 4: none)
    if arch != "base":
        row.append(10.0 if rng.random() < 0.5 else 0.0)      # 25 secondary
    return row

def extreme_row():
    n = 25 if arch == "base" else 26
    return [rng.choice([-50.0, 50.0, -1e3, 1e3, 0.0]) * rng.random() ** 0.1
            for _ in range(n)]

rows = []
for t in range(200):
    rows.append(extreme_row() if (t % 37 == 17 or t in (1, 2)) else normal_row())
with open(rows_path, "w") as fh:
    for row in rows:
        fh.write(" ".join(repr(x) for x in row) + "\n")
PY

    ok=1
    if ! "$NETEVAL" "$genome" --arch "$arch" < "$rows" > "$tmp/c_$arch.txt" 2> "$tmp/c_$arch.err"; then
        echo "neteval vs reference: arch=$arch FAILED: $NETEVAL exited non-zero:"
        sed 's/^/  /' "$tmp/c_$arch.err"
        ok=0
    fi
    if ! python3 "$NETREF" "$genome" --arch "$arch" < "$rows" > "$tmp/py_$arch.txt" 2> "$tmp/py_$arch.err"; then
        echo "neteval vs reference: arch=$arch FAILED: $NETREF exited non-zero:"
        sed 's/^/  /' "$tmp/py_$arch.err"
        ok=0
    fi

    if [ "$ok" = 1 ] && python3 - "$arch" "$rows" "$tmp/c_$arch.txt" "$tmp/py_$arch.txt" "$TOL" <<'PY'
import math, sys
arch, rows_path, c_path, py_path, tol = sys.argv[1:6]
tol = float(tol)
want_cols = {"base": 13, "A": 17, "B": 17}[arch]

def load(path):
    with open(path) as fh:
        return [line.split() for line in fh if line.strip()]

n_in = len(load(rows_path))
c, py = load(c_path), load(py_path)
errors = []
if len(c) != n_in or len(py) != n_in:
    errors.append("row counts: input %d, neteval %d, reference %d" % (n_in, len(c), len(py)))
max_diff = 0.0
worst = None
for r, (a, b) in enumerate(zip(c, py)):
    if len(a) != want_cols or len(b) != want_cols:
        errors.append("row %d: columns neteval %d, reference %d, expected %d"
                      % (r + 1, len(a), len(b), want_cols))
        break
    for col, (x, y) in enumerate(zip(a, b)):
        try:
            xf, yf = float(x), float(y)
        except ValueError:
            errors.append("row %d col %d: unparsable %r / %r" % (r + 1, col, x, y))
            break
        d = abs(xf - yf)
        if not math.isfinite(d):
            errors.append("row %d col %d: non-finite %r / %r" % (r + 1, col, x, y))
            break
        if d > max_diff:
            max_diff, worst = d, (r + 1, col, x, y)
if max_diff > tol:
    errors.append("max_abs_diff %.3g > %g at row %d col %d (neteval %s, reference %s)"
                  % ((max_diff, tol) + worst))
status = "ok" if not errors else "FAILED"
print("neteval vs reference: arch=%s rows=%d cols=%d max_abs_diff=%.2g %s"
      % (arch, len(c), len(c[0]) if c else 0, max_diff, status))
for e in errors:
    print("  " + e)
sys.exit(0 if not errors else 1)
PY
    then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
    fi
done

echo "check_neteval: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
