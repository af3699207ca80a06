#!/usr/bin/env python3
"""Independent reference implementation of the libselftalk network (SPEC §4).

Plain Python 3, standard library only. Written from SPEC §4 ("Network" and
"Genotype layout") alone, without looking at the C implementation, so that
tests/check_neteval.sh can compare the two.

Usage:
    python3 tests/ref/netref.py GENOME_FILE --arch base|A|B  < rows

GENOME_FILE is in the SPEC §4 genome text format; the FIRST genotype in it is
used. stdin holds one input row per line (25 numbers for base, 26 for A and
B, the secondary linguistic input last). Blank lines are ignored. Network
state persists from line to line: line 1 is step t = 0, with u(-1) = 0 and
emitted(-1) = 0. For each row one output row is printed, values formatted
with '%.17g' and separated by single spaces:
    base: the 13 outputs
    A:    the 13 outputs, then the 4 linguistic outputs (gamma = 1 times u)
    B:    the 13 outputs, then the 4 hidden-linguistic values (gamma = 10 times u)
"""

import math
import sys

# --- Sizes (SPEC §4 "Inputs" / "Outputs") ----------------------------------
N_IN = 25        # inputs 0-24 feed the hidden layer
N_HID = 15       # hidden neurons
N_OUT = 13       # outputs 0-11 desired q-hat, 12 focus
N_FOCUS = 3      # inputs 18-20: focus vector
FOCUS_IN0 = 18
N_DIRECT_OUT = 9  # direct focus links go to outputs 0-8 (torso + arm)
N_LING = 4       # linguistic cluster: reach, open, grasp, move

# --- Genotype layout (SPEC §4 table; indices are target-major) -------------
IN_HID0 = 0      # input -> hidden:              0   + h*25 + i
HID_OUT0 = 375   # hidden -> output:             375 + k*15 + h
FOCUS_OUT0 = 570  # focus input f -> output k:   570 + k*3 + f   (k 0-8, f 0-2)
BIAS0 = 597      # hidden bias:                  597 + h
HID_LING0 = 612  # hidden -> linguistic:         612 + m*15 + h
LING_REC0 = 672  # linguistic recurrent n -> m:  672 + m*4 + n
DECAY0 = 688     # decay delta of unit m:        688 + m
SEC_LING0 = 692  # secondary input -> ling. m:   692 + m
LING_HID0 = 696  # (type B) hidden-ling. m -> hidden h: 696 + h*4 + m

# SPEC §4: "Base: 612 genes. Type A: 696. Type B: 756."
N_GENES = {"base": 612, "A": 696, "B": 756}
# SPEC §4: emitted value = gamma*u, gamma = 1 (type A), 10 (type B).
GAMMA = {"A": 1.0, "B": 10.0}
# Row width: 25 inputs (base), 26 with the secondary linguistic input (A/B).
N_ROW = {"base": 25, "A": 26, "B": 26}


def decode(u):
    """SPEC §4: a 16-bit gene u in [0, 65535] decodes to v = -1 + 2u/65535."""
    return -1.0 + 2.0 * u / 65535.0


def sigma(x):
    """SPEC §4: sigma(x) = 1 / (1 + e^(-1.5x)).

    Evaluated in the overflow-free form for negative x (same function,
    e/(1+e) with e = e^(1.5x)), since math.exp raises OverflowError on huge
    arguments, where C's exp() would return inf and still give 0.
    """
    z = 1.5 * x
    if z >= 0.0:
        return 1.0 / (1.0 + math.exp(-z))
    e = math.exp(z)
    return e / (1.0 + e)


def read_first_genotype(path):
    """SPEC §4 genome text format: '#' lines are comments/metadata; every
    other non-empty line is one genotype, 4 hex digits per gene, in layout
    order, no separators. Returns the genes (ints) of the first genotype."""
    with open(path, "r") as fh:
        for lineno, line in enumerate(fh, 1):
            s = line.strip()
            if not s or s.startswith("#"):
                continue
            if len(s) % 4 != 0:
                raise ValueError("%s:%d: genotype length %d is not a multiple of 4"
                                 % (path, lineno, len(s)))
            genes = []
            for j in range(0, len(s), 4):
                chunk = s[j:j + 4]
                if any(c not in "0123456789abcdefABCDEF" for c in chunk):
                    raise ValueError("%s:%d: bad hex gene %r" % (path, lineno, chunk))
                genes.append(int(chunk, 16))
            return genes
    raise ValueError("%s: no genotype line" % path)


class Network:
    def __init__(self, genes, arch):
        if arch not in N_GENES:
            raise ValueError("unknown arch %r" % arch)
        if len(genes) != N_GENES[arch]:
            raise ValueError("arch %s needs %d genes, genome has %d"
                             % (arch, N_GENES[arch], len(genes)))
        self.arch = arch
        v = [decode(u) for u in genes]

        # input -> hidden: w_ih[h][i] = v[0 + h*25 + i]
        self.w_ih = [[v[IN_HID0 + h * N_IN + i] for i in range(N_IN)]
                     for h in range(N_HID)]
        # hidden -> output: w_ho[k][h] = v[375 + k*15 + h]
        self.w_ho = [[v[HID_OUT0 + k * N_HID + h] for h in range(N_HID)]
                     for k in range(N_OUT)]
        # direct focus input f (input 18+f) -> output k (k = 0-8):
        # w_fo[k][f] = v[570 + k*3 + f]
        self.w_fo = [[v[FOCUS_OUT0 + k * N_FOCUS + f] for f in range(N_FOCUS)]
                     for k in range(N_DIRECT_OUT)]
        # hidden biases beta_h = v[597 + h]
        self.bias = [v[BIAS0 + h] for h in range(N_HID)]

        self.has_ling = arch in ("A", "B")
        if self.has_ling:
            # hidden -> linguistic unit m: w_hl[m][h] = v[612 + m*15 + h]
            self.w_hl = [[v[HID_LING0 + m * N_HID + h] for h in range(N_HID)]
                         for m in range(N_LING)]
            # recurrent, from unit n to unit m: w_ll[m][n] = v[672 + m*4 + n]
            self.w_ll = [[v[LING_REC0 + m * N_LING + n] for n in range(N_LING)]
                         for m in range(N_LING)]
            # decay delta_m = (v + 1) / 2 with v = v[688 + m]
            self.delta = [(v[DECAY0 + m] + 1.0) / 2.0 for m in range(N_LING)]
            # secondary input (input 25) -> unit m: v[692 + m]
            self.w_sl = [v[SEC_LING0 + m] for m in range(N_LING)]
            self.gamma = GAMMA[arch]
        if arch == "B":
            # hidden-linguistic unit m -> hidden h: w_lh[h][m] = v[696 + h*4 + m]
            self.w_lh = [[v[LING_HID0 + h * N_LING + m] for m in range(N_LING)]
                         for h in range(N_HID)]

        # Leaky-unit state (SPEC §4, eq. 2.13): u(-1) = 0, emitted(-1) = 0.
        self.u = [0.0] * N_LING
        self.emitted = [0.0] * N_LING

    def step(self, row):
        """One time step. row = inputs 0-24 (+ input 25 for A/B).
        Returns (outputs[13], emitted linguistic values[4] or [])."""
        x = row[:N_IN]

        # 1. Hidden: O_h = sigma(-beta_h + sum_i w*I_i), from inputs at t and,
        #    in type B only, the hidden-linguistic emitted values at t-1.
        #    (Type A's linguistic cluster does NOT feed the hidden layer.)
        hidden = []
        for h in range(N_HID):
            s = -self.bias[h]
            for i in range(N_IN):
                s += self.w_ih[h][i] * x[i]
            if self.arch == "B":
                for m in range(N_LING):
                    s += self.w_lh[h][m] * self.emitted[m]
            hidden.append(sigma(s))

        # 2. Outputs (no bias): from hidden at t, plus the direct links from
        #    the focus inputs 18-20 to outputs 0-8.
        outputs = []
        for k in range(N_OUT):
            s = 0.0
            for h in range(N_HID):
                s += self.w_ho[k][h] * hidden[h]
            if k < N_DIRECT_OUT:
                for f in range(N_FOCUS):
                    s += self.w_fo[k][f] * x[FOCUS_IN0 + f]
            outputs.append(sigma(s))

        if not self.has_ling:
            return outputs, []

        # 3. Linguistic cluster (no bias): from hidden at t, its own EMITTED
        #    values at t-1 via the recurrent links, and the secondary input
        #    (input 25) at t. Then the leaky integration
        #    u_m(t) = delta_m*O_m(t) + (1-delta_m)*u_m(t-1), emitted = gamma*u_m(t).
        secondary = row[N_IN]
        prev_emitted = list(self.emitted)
        new_u = []
        for m in range(N_LING):
            s = 0.0
            for h in range(N_HID):
                s += self.w_hl[m][h] * hidden[h]
            for n in range(N_LING):
                s += self.w_ll[m][n] * prev_emitted[n]
            s += self.w_sl[m] * secondary
            o = sigma(s)
            new_u.append(self.delta[m] * o + (1.0 - self.delta[m]) * self.u[m])
        self.u = new_u
        self.emitted = [self.gamma * um for um in new_u]
        return outputs, list(self.emitted)


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(description="SPEC §4 reference network evaluator")
    ap.add_argument("genome")
    ap.add_argument("--arch", required=True, choices=["base", "A", "B"])
    args = ap.parse_args(argv)

    try:
        net = Network(read_first_genotype(args.genome), args.arch)
    except (OSError, ValueError) as e:
        sys.stderr.write("netref: %s\n" % e)
        return 2

    width = N_ROW[args.arch]
    out = sys.stdout
    for lineno, line in enumerate(sys.stdin, 1):
        fields = line.split()
        if not fields:
            continue
        if len(fields) != width:
            sys.stderr.write("netref: stdin line %d: %d values, arch %s needs %d\n"
                             % (lineno, len(fields), args.arch, width))
            return 2
        try:
            row = [float(f) for f in fields]
        except ValueError as e:
            sys.stderr.write("netref: stdin line %d: %s\n" % (lineno, e))
            return 2
        outputs, ling = net.step(row)
        out.write(" ".join("%.17g" % val for val in outputs + ling) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
