#!/usr/bin/env python3
"""Verify data/icub_left_arm.urdf against the iKin v1.0 kinematics it was built from.

Plain python3, standard library only. Usage:

    python3 tools/urdf_fk_check.py [path/to/icub_left_arm.urdf] [--n N] [--seed S]

What it does
  1. Parses the URDF with xml.etree and checks its structure: the link and joint names the C
     code looks up, joint types, limits (deg), efforts > 0, velocity 40 deg/s, mimic declarations,
     massless frame links, positive-definite inertias.
  2. Implements URDF forward kinematics (parent * origin(xyz, rpy) * R(axis, q); mimic joints
     q = multiplier * q_master + offset).
  3. Implements the iKin chains independently from their DH tables (standard DH,
     A = Rz(theta + offset) Tz(d) Tx(a) Rx(alpha)):
       arm:     T_world_EE = Rz(pi) * H0 * A_0 ... A_9            (torso roll link blocked at 0)
       fingers: T_world_tip = T_world_EE * H0_finger * A_0 ... A_n
     with chain angles thumb [oppose, 0 (blocked), prox, prox, prox], index/ring/little
     [0 (abduction, j7 = 60 deg), f, f, f], middle [f, f, f] (every coupled hinge = its master).
  4. Compares, for q = 0 and N random configurations within the URDF limits, the l_ee frame and
     the five *_tip frames (position tolerance 1e-6 m, rotation-matrix tolerance 1e-6).
     Fingers are compared twice:
       strict  - against the iKin chains whose H0 rotation is the proper mirror of iKin's
                 right-hand matrix, projected on SO(3) (what the URDF encodes; see data/README.md)
       raw     - against iKin's left-hand H0 exactly as iKin stores it (not quite orthonormal;
                 for the thumb iKin's left/right mirror misses one sign). Informative; must stay
                 below 1 mm.
  5. Prints the q = 0 end-effector position and, for a typical reaching posture, the world
     positions of the palm centre, its normal and the fingertips.
Exit status 0 if everything passes, 1 otherwise.
"""
import math
import os
import random
import sys
import xml.etree.ElementTree as ET

PI = math.pi
D2R = PI / 180.0
POS_TOL = 1e-6
ROT_TOL = 1e-6
RAW_TOL = 1e-3

# ------------------------------------------------------------------ small 4x4 algebra
def eye():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def mul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def rotz(t):
    c, s = math.cos(t), math.sin(t)
    return [[c, -s, 0.0, 0.0], [s, c, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]


def rotx(t):
    c, s = math.cos(t), math.sin(t)
    return [[1.0, 0.0, 0.0, 0.0], [0.0, c, -s, 0.0], [0.0, s, c, 0.0], [0.0, 0.0, 0.0, 1.0]]


def transl(x, y, z):
    T = eye()
    T[0][3], T[1][3], T[2][3] = x, y, z
    return T


def rot_axis(axis, q):
    """Rodrigues rotation about a unit axis (4x4)."""
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s, v = math.cos(q), math.sin(q), 1.0 - math.cos(q)
    return [[c + x * x * v, x * y * v - z * s, x * z * v + y * s, 0.0],
            [y * x * v + z * s, c + y * y * v, y * z * v - x * s, 0.0],
            [z * x * v - y * s, z * y * v + x * s, c + z * z * v, 0.0],
            [0.0, 0.0, 0.0, 1.0]]


def from_xyz_rpy(xyz, rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, xyz[0]],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, xyz[1]],
            [-sp, cp * sr, cp * cr, xyz[2]],
            [0.0, 0.0, 0.0, 1.0]]


def from_rows(rows, p):
    return [list(map(float, rows[0])) + [p[0]], list(map(float, rows[1])) + [p[1]],
            list(map(float, rows[2])) + [p[2]], [0.0, 0.0, 0.0, 1.0]]


def inv3(A):
    a, b, c = A[0]
    d, e, f = A[1]
    g, h, i = A[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def nearest_rotation(T):
    """Polar decomposition by Newton iteration R <- (R + R^-T) / 2; translation kept."""
    R = [[T[i][j] for j in range(3)] for i in range(3)]
    for _ in range(50):
        Ri = inv3(R)
        R = [[0.5 * (R[i][j] + Ri[j][i]) for j in range(3)] for i in range(3)]
    return [R[0] + [T[0][3]], R[1] + [T[1][3]], R[2] + [T[2][3]], [0.0, 0.0, 0.0, 1.0]]


def pos_err(A, B):
    return math.sqrt(sum((A[i][3] - B[i][3]) ** 2 for i in range(3)))


def rot_err(A, B):
    return max(abs(A[i][j] - B[i][j]) for i in range(3) for j in range(3))


def fmt(v, n=4):
    return "(" + ", ".join("%+.*f" % (n, x) for x in v) + ")"


def pos(T):
    return [T[0][3], T[1][3], T[2][3]]


def col(T, j):
    return [T[0][j], T[1][j], T[2][j]]


# ------------------------------------------------------------------ reference kinematics (iKin)
def dh(a, d, alpha, offset, q):
    """Standard DH: Rz(q + offset) Tz(d) Tx(a) Rx(alpha)."""
    T = rotz(q + offset)
    T = mul(T, transl(a, 0.0, d))
    return mul(T, rotx(alpha))


# iKin iCubArm("left"), version 1.0: (a, d, alpha, offset) -- icub-main iKinFwd.cpp
IKIN_ARM = [
    (0.032, 0.0, PI / 2, 0.0),
    (0.0, -0.0055, PI / 2, -PI / 2),
    (0.0233647, -0.1433, -PI / 2, 105.0 * D2R),
    (0.0, 0.10774, -PI / 2, PI / 2),
    (0.0, 0.0, PI / 2, -PI / 2),
    (0.015, 0.15228, -PI / 2, 75.0 * D2R),
    (-0.015, 0.0, PI / 2, 0.0),
    (0.0, 0.1373, PI / 2, -PI / 2),
    (0.0, 0.0, PI / 2, PI / 2),
    (0.0625, -0.016, 0.0, 0.0),
]
IKIN_H0 = from_rows([[0, -1, 0], [0, 0, -1], [1, 0, 0]], [0.0, 0.0, 0.0])
ROOT_TO_WORLD = rotz(PI)   # iKin root: x backward, y right -> world: x forward, y left

# iKin iCubFinger RIGHT-hand H0 as stored in iKinFwd.cpp (rows, translation)
H0_RIGHT = {
    "thumb": ([[0.478469, 0.063689, -0.875792], [-0.878095, 0.039246, -0.476873], [0.004, 0.997198, 0.074703]],
              [-0.024029759, -0.01193433, -0.00168926]),
    "index": ([[0.898138, 0.439714, 0.0], [-0.43804, 0.89472, 0.087156], [0.038324, -0.078278, 0.996195]],
              [0.00245549, -0.025320433, -0.010973325]),
    "middle": ([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]], [0.0178, -0.00830233, -0.0118]),
    "ring": ([[0.9998, 0.0192, 0.0], [0.0191, -0.9960, 0.0872], [0.0017, -0.0871, -0.9962]],
             [0.001569230, 0.007158757, -0.011458935]),
    "little": ([[0.9998, 0.0192, 0.0], [0.0191, -0.9960, 0.0872], [0.0017, -0.0871, -0.9962]],
               [-0.00042147, 0.0232755, -0.00956329]),
}
# the elements iKin negates for the LEFT hand (iKinFwd.cpp, iCubFinger::allocate)
IKIN_LEFT_FLIPS = {
    "thumb": [(2, 1), (0, 2), (1, 2), (2, 3)],
    "index": [(2, 0), (2, 1), (1, 2), (2, 3)],
    "middle": [(2, 1), (1, 2), (2, 3)],
    "ring": [(2, 0), (2, 1), (1, 2), (2, 3)],
    "little": [(2, 0), (2, 1), (1, 2), (2, 3)],
}
# left-hand finger DH links (a, d, alpha, offset)
IKIN_FINGER = {
    "thumb": [(0.0, 0.0, PI / 2, 0.0), (0.021, -0.0056, 0.0, 0.0), (0.026, 0.0, 0.0, 0.0),
              (0.022, 0.0, 0.0, 0.0), (0.0168, 0.0, -PI / 2, 0.0)],
    "index": [(0.0148, 0.0, -PI / 2, 0.0), (0.0259, 0.0, 0.0, 0.0), (0.022, 0.0, 0.0, 0.0),
              (0.0168, 0.0, -PI / 2, 0.0)],
    "middle": [(0.0285, 0.0, 0.0, 0.0), (0.024, 0.0, 0.0, 0.0), (0.0168, 0.0, -PI / 2, 0.0)],
    "ring": [(0.0148, 0.0, PI / 2, -20.0 * D2R), (0.0259, 0.0, 0.0, 0.0), (0.022, 0.0, 0.0, 0.0),
             (0.0168, 0.0, -PI / 2, 0.0)],
    "little": [(0.0148, 0.0, PI / 2, -20.0 * D2R), (0.0219, 0.0, 0.0, 0.0), (0.019, 0.0, 0.0, 0.0),
               (0.0168, 0.0, -PI / 2, 0.0)],
}
FINGERS = ["thumb", "index", "middle", "ring", "little"]


def left_h0_raw(f):
    rows, p = H0_RIGHT[f]
    T = from_rows(rows, p)
    for (i, j) in IKIN_LEFT_FLIPS[f]:
        T[i][j] = -T[i][j]
    return T


def left_h0_mirror(f):
    """Proper mirror M H0_right M, M = diag(1, 1, -1), projected on SO(3)."""
    rows, p = H0_RIGHT[f]
    T = from_rows(rows, p)
    for (i, j) in [(2, 0), (2, 1), (0, 2), (1, 2), (2, 3)]:
        T[i][j] = -T[i][j]
    return nearest_rotation(T)


def ikin_arm(qd):
    """qd: dict of URDF joint values (rad). Torso chain order pitch, roll (=0), yaw."""
    q = [qd["torso_pitch"], 0.0, qd["torso_yaw"], qd["l_shoulder_pitch"], qd["l_shoulder_roll"],
         qd["l_shoulder_yaw"], qd["l_elbow"], qd["l_wrist_prosup"], qd["l_wrist_pitch"], qd["l_wrist_yaw"]]
    T = mul(ROOT_TO_WORLD, IKIN_H0)
    for (a, d, al, off), qi in zip(IKIN_ARM, q):
        T = mul(T, dh(a, d, al, off, qi))
    return T


def finger_chain_angles(f, qd):
    if f == "thumb":
        p = qd["l_thumb_proximal"]
        return [qd["l_thumb_oppose"], 0.0, p, p, p]
    fl = qd["l_index_proximal"]
    if f == "middle":
        return [fl, fl, fl]
    return [0.0, fl, fl, fl]


def ikin_finger(f, qd, T_ee, raw=False):
    T = mul(T_ee, left_h0_raw(f) if raw else left_h0_mirror(f))
    for (a, d, al, off), qi in zip(IKIN_FINGER[f], finger_chain_angles(f, qd)):
        T = mul(T, dh(a, d, al, off, qi))
    return T


# ------------------------------------------------------------------ URDF model
class Urdf:
    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.links = {}
        for l in root.findall("link"):
            self.links[l.get("name")] = l
        self.joints = {}
        self.child_joints = {}
        self.parent_of = {}
        for j in root.findall("joint"):
            name = j.get("name")
            o = j.find("origin")
            xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
            rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
            ax = j.find("axis")
            axis = [float(v) for v in (ax.get("xyz") if ax is not None else "1 0 0").split()]
            lim = j.find("limit")
            mim = j.find("mimic")
            jd = {
                "name": name, "type": j.get("type"),
                "parent": j.find("parent").get("link"), "child": j.find("child").get("link"),
                "origin": from_xyz_rpy(xyz, rpy), "axis": axis,
                "lower": float(lim.get("lower", 0)) if lim is not None else None,
                "upper": float(lim.get("upper", 0)) if lim is not None else None,
                "effort": float(lim.get("effort", 0)) if lim is not None else None,
                "velocity": float(lim.get("velocity", 0)) if lim is not None else None,
                "mimic": None if mim is None else (mim.get("joint"), float(mim.get("multiplier", 1)),
                                                   float(mim.get("offset", 0))),
            }
            self.joints[name] = jd
            self.child_joints.setdefault(jd["parent"], []).append(jd)
            self.parent_of[jd["child"]] = jd
        roots = [l for l in self.links if l not in self.parent_of]
        if len(roots) != 1:
            raise ValueError("expected exactly one root link, got %r" % roots)
        self.root = roots[0]

    def actuated(self):
        return [j for j in self.joints.values() if j["type"] in ("revolute", "continuous", "prismatic")
                and j["mimic"] is None]

    def joint_value(self, j, q):
        if j["type"] == "fixed":
            return 0.0
        if j["mimic"] is not None:
            master, mult, off = j["mimic"]
            return mult * self.joint_value(self.joints[master], q) + off
        return q.get(j["name"], 0.0)

    def fk(self, q):
        """World transform of every link for the actuated joint values q (dict, rad)."""
        out = {self.root: eye()}
        stack = [self.root]
        while stack:
            l = stack.pop()
            for j in self.child_joints.get(l, []):
                T = mul(out[l], j["origin"])
                if j["type"] in ("revolute", "continuous"):
                    T = mul(T, rot_axis(j["axis"], self.joint_value(j, q)))
                elif j["type"] == "prismatic":
                    v = self.joint_value(j, q)
                    T = mul(T, transl(j["axis"][0] * v, j["axis"][1] * v, j["axis"][2] * v))
                out[j["child"]] = T
                stack.append(j["child"])
        return out


# ------------------------------------------------------------------ expectations
EXPECTED_LIMITS_DEG = {
    "torso_pitch": (-22, 70), "torso_yaw": (-50, 50),
    "l_shoulder_pitch": (-95.5, 10), "l_shoulder_roll": (0, 160.8), "l_shoulder_yaw": (-37, 80),
    "l_elbow": (15, 106), "l_wrist_prosup": (-90, 90), "l_wrist_pitch": (-90, 0), "l_wrist_yaw": (-20, 40),
    "l_thumb_oppose": (0, 90), "l_thumb_proximal": (0, 90), "l_thumb_distal1": (0, 90),
    "l_thumb_distal2": (0, 90),
}
for _f in ["index", "middle", "ring", "little"]:
    for _s in ["proximal", "distal1", "distal2"]:
        EXPECTED_LIMITS_DEG["l_%s_%s" % (_f, _s)] = (0, 90)
EXPECTED_MIMIC = {"l_thumb_distal1": "l_thumb_proximal", "l_thumb_distal2": "l_thumb_proximal"}
for _f in ["index", "middle", "ring", "little"]:
    for _s in ["proximal", "distal1", "distal2"]:
        if (_f, _s) != ("index", "proximal"):
            EXPECTED_MIMIC["l_%s_%s" % (_f, _s)] = "l_index_proximal"
ACTUATED = ["torso_pitch", "torso_yaw", "l_shoulder_pitch", "l_shoulder_roll", "l_shoulder_yaw", "l_elbow",
            "l_wrist_prosup", "l_wrist_pitch", "l_wrist_yaw", "l_thumb_oppose", "l_thumb_proximal",
            "l_index_proximal"]
BODY_LINKS = ["root_link", "torso_1", "torso_2", "chest", "l_shoulder_1", "l_shoulder_2", "l_shoulder_3",
              "l_upper_arm", "l_forearm", "l_wrist_1", "l_hand", "l_thumb_0", "l_thumb_1", "l_thumb_2",
              "l_thumb_3"] + ["l_%s_%d" % (f, i) for f in ["index", "middle", "ring", "little"] for i in (1, 2, 3)]
FRAME_LINKS = ["l_ee", "l_palm_center"] + ["l_%s_tip" % f for f in FINGERS]
PALM_CENTER_EE = (-0.0134, 0.0052, 0.0)    # palm-taxel centroid in the EE frame (data/README.md)
Q0_EE_EXPECTED = (0.0108, 0.0941, -0.1768)  # icub_facts 1.4 with x, y negated (rounded to 0.1 mm)


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "..", "data", "icub_left_arm.urdf")
    n_random, seed = 30, 12345
    args = list(argv[1:])
    while args:
        a = args.pop(0)
        if a == "--n":
            n_random = int(args.pop(0))
        elif a == "--seed":
            seed = int(args.pop(0))
        else:
            path = a
    model = Urdf(path)
    failures = []

    def fail(msg):
        failures.append(msg)
        print("FAIL: " + msg)

    # ---------------- structure
    if model.root != "root_link":
        fail("root link is %s, expected root_link" % model.root)
    for l in BODY_LINKS + FRAME_LINKS:
        if l not in model.links:
            fail("missing link %s" % l)
    for l in FRAME_LINKS:
        if l in model.links:
            e = model.links[l]
            if e.find("inertial") is not None or e.find("collision") is not None or e.find("visual") is not None:
                fail("frame link %s must be massless and geometry-free" % l)
            if l in model.parent_of and model.parent_of[l]["type"] != "fixed":
                fail("frame link %s must hang on a fixed joint" % l)
    if "torso_roll" in model.joints and model.joints["torso_roll"]["type"] != "fixed":
        fail("torso_roll must be fixed")
    for name, (lo, hi) in EXPECTED_LIMITS_DEG.items():
        j = model.joints.get(name)
        if j is None:
            fail("missing joint %s" % name)
            continue
        if j["type"] != "revolute":
            fail("%s is %s, expected revolute" % (name, j["type"]))
            continue
        if abs(j["lower"] - lo * D2R) > 1e-9 or abs(j["upper"] - hi * D2R) > 1e-9:
            fail("%s limits %.4f..%.4f deg, expected %g..%g" % (name, j["lower"] / D2R, j["upper"] / D2R, lo, hi))
        if not j["effort"] > 0:
            fail("%s effort must be > 0" % name)
        if abs(j["velocity"] - 40 * D2R) > 1e-6:
            fail("%s velocity %.6f rad/s, expected 40 deg/s" % (name, j["velocity"]))
        want = EXPECTED_MIMIC.get(name)
        got = j["mimic"]
        if want is None and got is not None:
            fail("%s must not be a mimic joint" % name)
        if want is not None and (got is None or got[0] != want or got[1] != 1.0 or got[2] != 0.0):
            fail("%s must mimic %s with multiplier 1, offset 0 (got %r)" % (name, want, got))
    movable = sorted(j["name"] for j in model.joints.values() if j["type"] != "fixed")
    extra = sorted(set(movable) - set(EXPECTED_LIMITS_DEG))
    if extra:
        fail("unexpected movable joints: %s" % ", ".join(extra))
    act = sorted(j["name"] for j in model.actuated())
    if act != sorted(ACTUATED):
        fail("actuated (non-mimic) joints %s, expected %s" % (act, sorted(ACTUATED)))
    n_inertial = 0
    total_mass = 0.0
    for name, e in model.links.items():
        ine = e.find("inertial")
        if ine is None:
            continue
        n_inertial += 1
        m = float(ine.find("mass").get("value"))
        total_mass += m
        I = ine.find("inertia")
        g = {k: float(I.get(k)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        M = [[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]], [g["ixz"], g["iyz"], g["izz"]]]
        m2 = M[0][0] * M[1][1] - M[0][1] ** 2
        m3 = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] ** 2) - M[0][1] * (M[0][1] * M[2][2] - M[1][2] * M[0][2])
              + M[0][2] * (M[0][1] * M[1][2] - M[1][1] * M[0][2]))
        if not (m > 0 and M[0][0] > 0 and m2 > 0 and m3 > 0):
            fail("link %s: mass/inertia not positive definite" % name)
        # principal moments must satisfy the triangle inequality (physically realisable body):
        # checked on the diagonal, sufficient here since every tensor is near-diagonal.
        a, b, c = M[0][0], M[1][1], M[2][2]
        if a + b < c * (1 - 1e-9) or a + c < b * (1 - 1e-9) or b + c < a * (1 - 1e-9):
            fail("link %s: inertia violates the triangle inequality" % name)
    print("structure: %d links (%d with inertia, total mass %.3f kg), %d joints (%d movable, %d actuated)"
          % (len(model.links), n_inertial, total_mass, len(model.joints), len(movable), len(act)))

    # ---------------- FK comparison
    rng = random.Random(seed)
    limits = {j["name"]: (j["lower"], j["upper"]) for j in model.actuated()}
    configs = [("q=0", {n: 0.0 for n in limits})]
    for k in range(n_random):
        configs.append(("random %d" % k, {n: rng.uniform(lo, hi) for n, (lo, hi) in limits.items()}))
    # also the limit corners of the hand, where the coupling matters most
    configs.append(("hand closed", dict({n: 0.0 for n in limits}, l_thumb_oppose=PI / 2,
                                        l_thumb_proximal=PI / 2, l_index_proximal=PI / 2)))
    max_ee = [0.0, 0.0]
    max_tip = {f: [0.0, 0.0] for f in FINGERS}
    max_raw = {f: 0.0 for f in FINGERS}
    max_palm = [0.0, 0.0]
    for label, q in configs:
        T = model.fk(q)
        ref_ee = ikin_arm(q)
        e_p, e_r = pos_err(T["l_ee"], ref_ee), rot_err(T["l_ee"], ref_ee)
        max_ee = [max(max_ee[0], e_p), max(max_ee[1], e_r)]
        for f in FINGERS:
            ref = ikin_finger(f, q, ref_ee)
            tip = T["l_%s_tip" % f]
            max_tip[f] = [max(max_tip[f][0], pos_err(tip, ref)), max(max_tip[f][1], rot_err(tip, ref))]
            max_raw[f] = max(max_raw[f], pos_err(tip, ikin_finger(f, q, ref_ee, raw=True)))
        ref_palm = mul(mul(ref_ee, transl(*PALM_CENTER_EE)), rotx(PI))
        max_palm = [max(max_palm[0], pos_err(T["l_palm_center"], ref_palm)),
                    max(max_palm[1], rot_err(T["l_palm_center"], ref_palm))]

    print("\nFK comparison over %d configurations (q=0, %d random within limits, hand closed):"
          % (len(configs), n_random))
    ok = max_ee[0] <= POS_TOL and max_ee[1] <= ROT_TOL
    print("  l_ee vs iKin arm v1.0          max |dp| = %.3e m   max |dR| = %.3e   %s"
          % (max_ee[0], max_ee[1], "ok" if ok else "FAIL"))
    if not ok:
        fail("l_ee differs from the iKin chain")
    for f in FINGERS:
        ok = max_tip[f][0] <= POS_TOL and max_tip[f][1] <= ROT_TOL
        print("  l_%-7s_tip vs iKin %-7s   max |dp| = %.3e m   max |dR| = %.3e   %s"
              % (f, f, max_tip[f][0], max_tip[f][1], "ok" if ok else "FAIL"))
        if not ok:
            fail("l_%s_tip differs from the iKin %s chain" % (f, f))
    ok = max_palm[0] <= POS_TOL and max_palm[1] <= ROT_TOL
    print("  l_palm_center vs EE*T(%g,%g,0)*Rx(pi)  max |dp| = %.3e m   max |dR| = %.3e   %s"
          % (PALM_CENTER_EE[0], PALM_CENTER_EE[1], max_palm[0], max_palm[1], "ok" if ok else "FAIL"))
    if not ok:
        fail("l_palm_center misplaced")
    print("  informative: fingertips vs iKin's left H0 exactly as stored (not orthonormal), tolerance %g m:"
          % RAW_TOL)
    for f in FINGERS:
        ok = max_raw[f] <= RAW_TOL
        print("    %-7s max |dp| = %.3e m  %s" % (f, max_raw[f], "ok" if ok else "FAIL"))
        if not ok:
            fail("l_%s_tip is more than %g m from the raw iKin chain" % (f, RAW_TOL))

    # ---------------- human sanity checks
    T0 = model.fk(configs[0][1])
    ee0 = pos(T0["l_ee"])
    d0 = math.sqrt(sum((a - b) ** 2 for a, b in zip(ee0, Q0_EE_EXPECTED)))
    print("\nq = 0: l_ee world position %s m (icub_facts 1.4, x/y negated: %s)  %s"
          % (fmt(ee0), fmt(Q0_EE_EXPECTED), "ok" if d0 < 1e-4 else "FAIL"))
    if d0 >= 1e-4:
        fail("q=0 EE position differs from icub_facts 1.4")
    print("       l_ee axes: x %s, y %s, z %s" % (fmt(col(T0["l_ee"], 0), 3), fmt(col(T0["l_ee"], 1), 3),
                                                   fmt(col(T0["l_ee"], 2), 3)))

    # sign conventions (icub_facts 1.4 and SPEC 3)
    def with_(**kw):
        q = {n: 0.0 for n in limits}
        q["l_elbow"] = 0.0
        for k, v in kw.items():
            q[k] = v * D2R
        return model.fk(q)

    sh0 = pos(T0["l_shoulder_2"])
    checks = []
    T = with_(l_shoulder_pitch=-90)
    checks.append(("shoulder_pitch -90 raises the arm forward",
                   pos(T["l_ee"])[0] - sh0[0] > 0.3 and abs(pos(T["l_ee"])[2] - sh0[2]) < 0.05))
    T = with_(l_shoulder_roll=90)
    checks.append(("shoulder_roll +90 raises the arm sideways to the left",
                   pos(T["l_ee"])[1] - sh0[1] > 0.3 and abs(pos(T["l_ee"])[2] - sh0[2]) < 0.05))
    T = with_(l_elbow=90)
    checks.append(("elbow +90 brings the forearm forward", pos(T["l_ee"])[0] > 0.15))
    T = with_(torso_pitch=30)
    checks.append(("torso_pitch > 0 leans the chest forward", pos(T["l_shoulder_2"])[0] > sh0[0] + 0.05))
    T = with_(torso_yaw=30)
    checks.append(("torso_yaw > 0 brings the left shoulder forward", pos(T["l_shoulder_2"])[0] > sh0[0] + 0.03))
    T = with_(l_index_proximal=60, l_thumb_proximal=60)
    pn = col(T0["l_palm_center"], 2)
    tip_open = pos(T0["l_index_tip"])
    tip_closed = pos(T["l_index_tip"])
    pc = pos(T0["l_palm_center"])
    # flexion moves the fingertip to the palm side, i.e. along the outward palm normal
    checks.append(("finger flexion curls the index toward the palm side",
                   sum((tip_closed[i] - tip_open[i]) * pn[i] for i in range(3)) > 0.02))
    # at q=0 the arm hangs down and the palm faces the body (-y)
    checks.append(("q=0 palm normal points to the body (-y)", pn[1] < -0.99))
    print("\nsign conventions:")
    for text, good in checks:
        print("  %-58s %s" % (text, "ok" if good else "FAIL"))
        if not good:
            fail("sign convention: " + text)

    posture = {"l_shoulder_pitch": -30, "l_shoulder_roll": 30, "l_shoulder_yaw": 0, "l_elbow": 60}
    q = {n: 0.0 for n in limits}
    for k, v in posture.items():
        q[k] = v * D2R
    T = model.fk(q)
    print("\ntypical reach posture (deg: shoulder pitch -30, roll 30, yaw 0, elbow 60, all others 0), world m:")
    print("  l_shoulder_2 (shoulder centre) %s" % fmt(pos(T["l_shoulder_2"])))
    print("  l_ee                           %s" % fmt(pos(T["l_ee"])))
    print("  l_palm_center                  %s   normal %s" % (fmt(pos(T["l_palm_center"])),
                                                               fmt(col(T["l_palm_center"], 2), 3)))
    for f in FINGERS:
        print("  l_%-7s_tip                  %s" % (f, fmt(pos(T["l_%s_tip" % f]))))

    print("\n%s" % ("ALL CHECKS PASSED" if not failures else "%d CHECK(S) FAILED" % len(failures)))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
