#!/usr/bin/env python3
"""Generates data/icub_left_arm.urdf from the iCub v1 facts: python3 tools/gen_icub_urdf.py [OUT]; then check it with python3 tools/urdf_fk_check.py."""
import math
import os

# Hand structure (data/README.md §3b): which phalanges are separate bodies. Environment
# overrides exist for the measurements recorded there; the defaults generate the shipped URDF.
FINGER_HINGES = int(os.environ.get("ST_FINGER_HINGES", "3"))      # 3 = iKin (MCP, PIP, DIP); 2 = DIP welded straight
THUMB_HINGES = int(os.environ.get("ST_THUMB_HINGES", "2"))        # flexing thumb hinges: 3 = iKin; 2 = distal welded
MERGE_RING_LITTLE = os.environ.get("ST_MERGE_RING_LITTLE", "1") == "1"  # iCub_SIM: one body per phalanx level
MERGE_INDEX_MIDDLE = os.environ.get("ST_MERGE_INDEX_MIDDLE", "1") == "1"  # likewise index and middle
# thumb base moved from iKin's, in the palm frame (+x along the fingers, +y towards the thumb), m
THUMB_SHIFT = [float(v) for v in os.environ.get("ST_THUMB_SHIFT", "-0.035,0").split(",")]

PI = math.pi
D = PI / 180.0

# ---------------------------------------------------------------- linear algebra
def matmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]

def chain(*Ts):
    R = eye()
    for T in Ts:
        R = matmul(R, T)
    return R

def eye():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]

def rotz(t):
    c, s = math.cos(t), math.sin(t)
    return [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]

def rotx(t):
    c, s = math.cos(t), math.sin(t)
    return [[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]]

def trans(x, y, z):
    T = eye(); T[0][3] = x; T[1][3] = y; T[2][3] = z
    return T

def inv(T):
    R = [[T[j][i] for j in range(3)] for i in range(3)]
    p = [-sum(R[i][k] * T[k][3] for k in range(3)) for i in range(3)]
    return [R[0] + [p[0]], R[1] + [p[1]], R[2] + [p[2]], [0, 0, 0, 1]]

def from_rows(rows, p):
    return [list(rows[0]) + [p[0]], list(rows[1]) + [p[1]], list(rows[2]) + [p[2]], [0, 0, 0, 1]]

def inv3(A):
    a, b, c = A[0]; d, e, f_ = A[1]; g, h, i = A[2]
    det = a * (e * i - f_ * h) - b * (d * i - f_ * g) + c * (d * h - e * g)
    return [[(e * i - f_ * h) / det, (c * h - b * i) / det, (b * f_ - c * e) / det],
            [(f_ * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f_) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]

def orthonormalise(T):
    """Nearest rotation (polar decomposition, Newton iteration R <- (R + R^-T)/2); the iKin H0 are
    printed with 4-6 digits, so they are orthonormal only to ~1e-4..1e-6."""
    R = [[T[i][j] for j in range(3)] for i in range(3)]
    for _ in range(50):
        Ri = inv3(R)
        R = [[0.5 * (R[i][j] + Ri[j][i]) for j in range(3)] for i in range(3)]
    return [R[0] + [T[0][3]], R[1] + [T[1][3]], R[2] + [T[2][3]], [0, 0, 0, 1]]

def rpy_of(T):
    """URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r20 = max(-1.0, min(1.0, T[2][0]))
    pitch = -math.asin(r20)
    if abs(r20) < 1 - 1e-12:
        roll = math.atan2(T[2][1], T[2][2])
        yaw = math.atan2(T[1][0], T[0][0])
    else:  # gimbal lock: set yaw = 0
        yaw = 0.0
        roll = math.atan2(-T[1][2], T[1][1]) if r20 < 0 else math.atan2(-T[1][2], T[1][1])
    return roll, pitch, yaw

def rot_from_rpy(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]

def check_rpy(T):
    R = rot_from_rpy(*rpy_of(T))
    err = max(abs(R[i][j] - T[i][j]) for i in range(3) for j in range(3))
    assert err < 1e-12, err

def dh_const(a, d, alpha, offset):
    """Constant part of a standard DH link: Rz(offset) Tz(d) Tx(a) Rx(alpha)."""
    return chain(rotz(offset), trans(0, 0, d), trans(a, 0, 0), rotx(alpha))

def apply(T, p):
    return [sum(T[i][k] * p[k] for k in range(3)) + T[i][3] for i in range(3)]

# ---------------------------------------------------------------- formatting
def f(v):
    if abs(v) < 5e-15:
        v = 0.0
    s = "%.12g" % v
    return "0" if s in ("-0", "0") else s

def origin(T):
    check_rpy(T)
    r, p, y = rpy_of(T)
    return '<origin xyz="%s %s %s" rpy="%s %s %s"/>' % (f(T[0][3]), f(T[1][3]), f(T[2][3]), f(r), f(p), f(y))

# ---------------------------------------------------------------- inertia
def cyl_inertia(m, r, L):   # about COM, axis z
    ixx = m * (3 * r * r + L * L) / 12.0
    return [[ixx, 0, 0], [0, ixx, 0], [0, 0, m * r * r / 2.0]]

def box_inertia(m, x, y, z):
    return [[m * (y * y + z * z) / 12.0, 0, 0], [0, m * (x * x + z * z) / 12.0, 0], [0, 0, m * (x * x + y * y) / 12.0]]

def sph_inertia(m, r):
    i = 2.0 / 5.0 * m * r * r
    return [[i, 0, 0], [0, i, 0], [0, 0, i]]

def rot3(T):
    return [[T[i][j] for j in range(3)] for i in range(3)]

def rotate_inertia(R, I):
    # R I R^T
    RI = [[sum(R[i][k] * I[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return [[sum(RI[i][k] * R[j][k] for k in range(3)) for j in range(3)] for i in range(3)]

class Prim:
    """A primitive in a link frame: kind, dims, pose T (4x4 in link frame), mass, collide."""
    def __init__(self, kind, dims, T, mass, collide=True, tag=""):
        self.kind, self.dims, self.T, self.mass, self.collide, self.tag = kind, dims, T, mass, collide, tag

    def inertia_link_axes(self):
        if self.kind == "cylinder":
            I = cyl_inertia(self.mass, self.dims[0], self.dims[1])
        elif self.kind == "box":
            I = box_inertia(self.mass, *self.dims)
        else:
            I = sph_inertia(self.mass, self.dims[0])
        return rotate_inertia(rot3(self.T), I)

def combine(prims):
    ms = [p for p in prims if p.mass > 0]
    M = sum(p.mass for p in ms)
    c = [sum(p.mass * p.T[i][3] for p in ms) / M for i in range(3)]
    I = [[0.0] * 3 for _ in range(3)]
    for p in ms:
        Ip = p.inertia_link_axes()
        r = [p.T[i][3] - c[i] for i in range(3)]
        rr = sum(v * v for v in r)
        for i in range(3):
            for j in range(3):
                I[i][j] += Ip[i][j] + p.mass * ((rr if i == j else 0.0) - r[i] * r[j])
    return M, c, I

def posdef(I):
    a, b, c_ = I[0][0], I[0][1], I[0][2]
    d, e, g = I[1][1], I[1][2], I[2][2]
    m1 = a; m2 = a * d - b * b
    m3 = a * (d * g - e * e) - b * (b * g - e * c_) + c_ * (b * e - d * c_)
    return m1 > 0 and m2 > 0 and m3 > 0

def seg_pose(p0, p1):
    """Pose of a primitive whose local z runs from p0 to p1 (centre at midpoint)."""
    v = [p1[i] - p0[i] for i in range(3)]
    L = math.sqrt(sum(x * x for x in v))
    z = [x / L for x in v]
    # pick x perpendicular to z
    h = [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0]
    dd = sum(a * b for a, b in zip(h, z))
    x = [a - dd * b for a, b in zip(h, z)]
    n = math.sqrt(sum(t * t for t in x)); x = [t / n for t in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    mid = [(p0[i] + p1[i]) / 2 for i in range(3)]
    T = [[x[0], y[0], z[0], mid[0]], [x[1], y[1], z[1], mid[1]], [x[2], y[2], z[2], mid[2]], [0, 0, 0, 1]]
    return T, L

def cyl_seg(r, p0, p1, mass, collide=True, tag=""):
    T, L = seg_pose(p0, p1)
    return Prim("cylinder", (r, L), T, mass, collide, tag)

def dh_end(a, d, offset):
    return [a * math.cos(offset), a * math.sin(offset), d]

# ---------------------------------------------------------------- model data
# iKin iCubArm("left") v1.0: (a, d, alpha, offset_deg)
ARM_DH = [
    (0.032, 0.0, PI / 2, 0.0),            # 0 torso pitch
    (0.0, -0.0055, PI / 2, -90.0),        # 1 torso roll (fixed at 0)
    (0.0233647, -0.1433, -PI / 2, 105.0), # 2 torso yaw
    (0.0, 0.10774, -PI / 2, 90.0),        # 3 shoulder pitch
    (0.0, 0.0, PI / 2, -90.0),            # 4 shoulder roll
    (0.015, 0.15228, -PI / 2, 75.0),      # 5 shoulder yaw
    (-0.015, 0.0, PI / 2, 0.0),           # 6 elbow
    (0.0, 0.1373, PI / 2, -90.0),         # 7 wrist prosup
    (0.0, 0.0, PI / 2, 90.0),             # 8 wrist pitch
    (0.0625, -0.016, 0.0, 0.0),           # 9 wrist yaw
]
H0_ARM = from_rows([[0, -1, 0], [0, 0, -1], [1, 0, 0]], [0, 0, 0])
ROOT_TO_WORLD = rotz(PI)
C = [dh_const(a, d, al, off * D) for (a, d, al, off) in ARM_DH]

# iKin iCubFinger, LEFT hand H0 = M * H0_right * M with M = diag(1, 1, -1) (mirror through the EE x-y plane).
# Values: icub-main iKinFwd.cpp (right-hand matrices, full-precision translations). iKin's own left-hand code
# flips H0(2,1), H0(0,2), H0(1,2), H0(2,3) for the thumb but forgets H0(2,0); we apply the full mirror
# (thumb row 3 starts with -0.004 instead of +0.004) so that the matrix is a rotation (see README).
FINGER_H0 = {
    "thumb": ([[0.478469, 0.063689, 0.875792], [-0.878095, 0.039246, 0.476873], [-0.004, -0.997198, 0.074703]],
              [-0.024029759, -0.01193433, 0.00168926]),
    "index": ([[0.898138, 0.439714, 0.0], [-0.43804, 0.89472, -0.087156], [-0.038324, 0.078278, 0.996195]],
              [0.00245549, -0.025320433, 0.010973325]),
    "middle": ([[1, 0, 0], [0, 0, 1], [0, -1, 0]], [0.0178, -0.00830233, 0.0118]),
    "ring": ([[0.9998, 0.0192, 0.0], [0.0191, -0.9960, -0.0872], [-0.0017, 0.0871, -0.9962]],
             [0.001569230, 0.007158757, 0.011458935]),
    "little": ([[0.9998, 0.0192, 0.0], [0.0191, -0.9960, -0.0872], [-0.0017, 0.0871, -0.9962]],
               [-0.00042147, 0.0232755, 0.00956329]),
}
FINGER_DH = {
    "thumb": [(0.0, 0.0, PI / 2, 0.0), (0.021, -0.0056, 0.0, 0.0), (0.026, 0.0, 0.0, 0.0),
              (0.022, 0.0, 0.0, 0.0), (0.0168, 0.0, -PI / 2, 0.0)],
    "index": [(0.0148, 0.0, -PI / 2, 0.0), (0.0259, 0.0, 0.0, 0.0), (0.022, 0.0, 0.0, 0.0),
              (0.0168, 0.0, -PI / 2, 0.0)],
    "middle": [(0.0285, 0.0, 0.0, 0.0), (0.024, 0.0, 0.0, 0.0), (0.0168, 0.0, -PI / 2, 0.0)],
    "ring": [(0.0148, 0.0, PI / 2, -20.0), (0.0259, 0.0, 0.0, 0.0), (0.022, 0.0, 0.0, 0.0),
             (0.0168, 0.0, -PI / 2, 0.0)],
    "little": [(0.0148, 0.0, PI / 2, -20.0), (0.0219, 0.0, 0.0, 0.0), (0.019, 0.0, 0.0, 0.0),
               (0.0168, 0.0, -PI / 2, 0.0)],
}

VEL = 40 * D
EFF = {"torso_pitch": 36, "torso_yaw": 80, "l_shoulder_pitch": 84, "l_shoulder_roll": 84,
       "l_shoulder_yaw": 34, "l_elbow": 20, "l_wrist_prosup": 0.45, "l_wrist_pitch": 0.65,
       "l_wrist_yaw": 0.65}
FINGER_EFFORT = 0.5
LIM = {"torso_pitch": (-22, 70), "torso_yaw": (-50, 50),
       "l_shoulder_pitch": (-95.5, 10), "l_shoulder_roll": (0, 160.8), "l_shoulder_yaw": (-37, 80),
       "l_elbow": (15, 106), "l_wrist_prosup": (-90, 90), "l_wrist_pitch": (-90, 0),
       "l_wrist_yaw": (-20, 40)}
R_FINGER = 0.0065
M_PHALANX = 0.010     # per flexing finger segment (see README)
M_KNUCKLE = 0.005     # fixed abduction/knuckle segments of index, ring, little

# ---------------------------------------------------------------- model assembly
links = {}     # name -> dict(prims=[...], comment)
link_order = []
joints = []    # dicts

def add_link(name, prims=None, comment="", massless=False):
    links[name] = {"prims": prims or [], "comment": comment, "massless": massless}
    link_order.append(name)

def add_joint(name, jtype, parent, child, T, lim=None, effort=None, mimic=None, comment=""):
    joints.append(dict(name=name, type=jtype, parent=parent, child=child, T=T, lim=lim,
                       effort=effort, mimic=mimic, comment=comment))

# --- world-frame pose of every arm link at q = 0 (for placing torso geometry)
F_base = matmul(ROOT_TO_WORLD, H0_ARM)             # DH frame "-1": z = torso pitch axis
F = [None] * 10
prev = F_base
for k in range(10):
    F[k] = matmul(prev, C[k])                        # q = 0
    prev = F[k]
# link frame L_k = F_{k-1} Rz(q_k); at q=0: L_0 = F_base, L_k = F_{k-1}
def Lzero(k):
    return F_base if k == 0 else F[k - 1]

def world_prims_to_link(k, prims):
    Tinv = inv(Lzero(k))
    for p in prims:
        p.T = matmul(Tinv, p.T)
    return prims

# root_link: pelvis box (iCub_SIM torso[0]), world frame
pelvis = Prim("box", (0.064, 0.047, 0.1199), trans(0, 0, -0.031 - 0.1199 / 2), 0.20297, tag="pelvis")
add_link("root_link", [pelvis], "world frame: origin on the torso-pitch axis (iKin root), x forward, y left, z up")

# torso_1: torso pitch cylinder on the pitch axis (link z = pitch axis)
add_link("torso_1", [Prim("cylinder", (0.031, 0.1362), eye(), 0.91179, tag="torso pitch cylinder")],
         "child of torso_pitch (iKin link 0)")
# torso_2: roll cylinder on the roll axis (link z = roll axis)
add_link("torso_2", [Prim("cylinder", (0.031, 0.097), eye(), 0.91179, tag="torso roll cylinder")],
         "behind the fixed torso_roll joint (iKin link 1 blocked at 0); z = roll axis")
# chest: yaw cylinder + two chest boxes, defined in world at q = 0
yaw_pt = apply(F[1], [0, 0, 0])   # a point of the yaw axis (world)
z_yaw_c = 0.032 + 0.031 + 0.0274 / 2
z_box_lo = 0.032 + 0.031 + 0.0274
z_box_hi = 0.2253 - 0.015
hbox = z_box_hi - z_box_lo
wbox = 0.1101 - 0.011 - 0.059 / 2
chest_prims = [
    Prim("cylinder", (0.040, 0.0274), trans(yaw_pt[0], 0, z_yaw_c), 0.45165, tag="torso yaw cylinder"),
    Prim("box", (0.109, wbox, hbox), trans(yaw_pt[0], +wbox / 2, (z_box_lo + z_box_hi) / 2), 1.8388, tag="chest, left half"),
    Prim("box", (0.109, wbox, hbox), trans(yaw_pt[0], -wbox / 2, (z_box_lo + z_box_hi) / 2), 1.8388, tag="chest, right half"),
]
add_link("chest", world_prims_to_link(2, chest_prims), "child of torso_yaw (iKin link 2)")

def segment_link_prims(k, r, mass, collide=True, tag=""):
    a, d, al, off = ARM_DH[k]
    return cyl_seg(r, [0, 0, 0], dh_end(a, d, off * D), mass, collide, tag)

# shoulder cap ("clavicle"): on the pitch axis (link z), centre 0.035 m medial of the shoulder centre
d3 = ARM_DH[3][1]
add_link("l_shoulder_1", [Prim("cylinder", (0.031, 0.011), trans(0, 0, d3 - 0.035), 0.48278, tag="shoulder cap")],
         "child of l_shoulder_pitch (iKin link 3); z = shoulder pitch axis, shoulder centre at z = 0.10774")
add_link("l_shoulder_2", [Prim("cylinder", (0.030, 0.059), eye(), 0.20779, tag="shoulder")],
         "child of l_shoulder_roll (iKin link 4); origin = shoulder centre, z = roll axis")
M_SH3 = 0.156
add_link("l_shoulder_3", [Prim("cylinder", (0.026, 0.03), trans(0, 0, 0.015), M_SH3, collide=False, tag="upper-arm top (inertial only)")],
         "child of l_shoulder_yaw (iKin link 5); z = upper-arm (yaw) axis")
L_UA = ARM_DH[5][1]
add_link("l_upper_arm", [Prim("cylinder", (0.026, L_UA), trans(0, 0, L_UA / 2), 1.1584 - M_SH3, tag="upper arm")],
         "rigidly attached to l_shoulder_3 (same frame)")
add_link("l_elbow_1", [Prim("sphere", (0.010,), trans(ARM_DH[6][0], 0, 0), 0.050798, tag="elbow")],
         "child of l_elbow (iKin link 6); z = elbow axis")
M_WR1 = 0.020
L_FA = ARM_DH[7][1]
add_link("l_forearm", [Prim("cylinder", (0.020, L_FA), trans(0, 0, L_FA / 2), 0.48774 - M_WR1, tag="forearm")],
         "child of l_wrist_prosup (iKin link 7); z = forearm (prosup) axis")
add_link("l_wrist_1", [Prim("sphere", (0.010,), eye(), M_WR1, collide=False, tag="wrist cross (inertial only)")],
         "child of l_wrist_pitch (iKin link 8); origin = wrist centre")
T_hand_ee = C[9]
# palm box centre in the EE frame: 0.03125 m from the wrist along the hand (iCub_SIM), i.e. x = -0.03125;
# y = 0 (SIM centres it on the EE); z = +0.011 so that the inner face is the z = 0 palm-skin plane.
palm_box_ee = trans(-(0.0625 - 0.03125), 0.0, 0.022 / 2)
add_link("l_hand", [Prim("box", (0.069, 0.065, 0.022), matmul(T_hand_ee, palm_box_ee), 0.19099, tag="palm")],
         "child of l_wrist_yaw (iKin link 9) = the palm; l_ee is (0.0625, 0, -0.016) from its origin")

# ---------------------------------------------------------------- arm joints
add_joint("torso_pitch", "revolute", "root_link", "torso_1", F_base, LIM["torso_pitch"], EFF["torso_pitch"],
          comment="iKin link 0 axis; origin = Rz(pi)*H0")
add_joint("torso_roll", "fixed", "torso_1", "torso_2", C[0],
          comment="iKin link 1, blocked at 0 (SPEC 3); child frame z = roll axis")
add_joint("torso_yaw", "revolute", "torso_2", "chest", C[1], LIM["torso_yaw"], EFF["torso_yaw"],
          comment="origin = iKin link-1 DH transform at q=0 (incl. -90 deg offset)")
arm_names = ["l_shoulder_pitch", "l_shoulder_roll", "l_shoulder_yaw", "l_elbow", "l_wrist_prosup",
             "l_wrist_pitch", "l_wrist_yaw"]
parents = ["chest", "l_shoulder_1", "l_shoulder_2", "l_upper_arm", "l_elbow_1", "l_forearm", "l_wrist_1"]
children = ["l_shoulder_1", "l_shoulder_2", "l_shoulder_3", "l_elbow_1", "l_forearm", "l_wrist_1", "l_hand"]
for i, nm in enumerate(arm_names):
    k = 3 + i
    if nm == "l_elbow":
        add_joint("l_upper_arm_fixed", "fixed", "l_shoulder_3", "l_upper_arm", eye(),
                  comment="l_upper_arm rigidly attached to l_shoulder_3")
    add_joint(nm, "revolute", parents[i], children[i], C[k - 1], LIM[nm], EFF[nm],
              comment="iKin link %d" % k)

# frames on the palm
add_link("l_ee", massless=True, comment="iKin v1.0 arm end-effector (DH frame 10, HN = I)")
add_joint("l_ee_fixed", "fixed", "l_hand", "l_ee", T_hand_ee, comment="iKin link 9 constant part")
PALM_C = (-0.0134, 0.0052)
add_link("l_palm_center", massless=True,
         comment="palm-skin taxel centroid, +z = outward palm normal (= -z of l_ee)")
add_joint("l_palm_center_fixed", "fixed", "l_hand", "l_palm_center",
          chain(T_hand_ee, trans(PALM_C[0], PALM_C[1], 0.0), rotx(PI)))

# ---------------------------------------------------------------- fingers
def finger_H0(f_):
    rows, p = FINGER_H0[f_]
    return orthonormalise(from_rows(rows, p))

FC = {f_: [dh_const(a, d, al, off * D) for (a, d, al, off) in FINGER_DH[f_]] for f_ in FINGER_DH}

def phalanx(f_, k, mass, tag):
    a, d, al, off = FINGER_DH[f_][k]
    return cyl_seg(R_FINGER, [0, 0, 0], dh_end(a, d, off * D), mass, True, tag)

fl = (0, 90)

def flex_joint(hinged, name, parent, child, T, mimic, comment):
    """A flexion joint of a finger or the thumb: a mimicking hinge, or welded straight (fixed)."""
    if hinged:
        add_joint(name, "revolute", parent, child, T, fl, FINGER_EFFORT, mimic=mimic, comment=comment)
    else:
        add_joint(name, "fixed", parent, child, T, comment=comment + ", welded straight to the phalanx before it")

# thumb
H = chain(T_hand_ee, trans(THUMB_SHIFT[0], -THUMB_SHIFT[1], 0.0), finger_H0("thumb"))  # palm y = -EE y
# l_thumb_0: child of oppose (link 0, zero length) + the blocked metacarpal link 1 (fixed at 0)
Cm = FC["thumb"][0]                              # link-0 constant part (Rx(pi/2))
a1, d1 = FINGER_DH["thumb"][1][0], FINGER_DH["thumb"][1][1]
p_meta_end = apply(matmul(Cm, FC["thumb"][1]), [0, 0, 0])
add_link("l_thumb_0", [cyl_seg(R_FINGER, [0, 0, 0], p_meta_end, M_PHALANX, True, "thumb metacarpal (iKin thumb links 0+1)")],
         "child of l_thumb_oppose (iKin thumb link 0); carries the blocked link 1")
add_link("l_thumb_1", [phalanx("thumb", 2, M_PHALANX, "thumb proximal")], "iKin thumb link 2")
add_link("l_thumb_2", [phalanx("thumb", 3, M_PHALANX, "thumb middle")], "iKin thumb link 3")
add_link("l_thumb_3", [phalanx("thumb", 4, M_PHALANX, "thumb distal (fingertip sensor)")], "iKin thumb link 4 (distal, fingertip)")
add_link("l_thumb_tip", massless=True, comment="end of the iKin thumb chain")
add_joint("l_thumb_oppose", "revolute", "l_hand", "l_thumb_0", H, (0, 90), FINGER_EFFORT,
          comment="iKin thumb link 0 (j8); origin = EE * H0_thumb")
add_joint("l_thumb_proximal", "revolute", "l_thumb_0", "l_thumb_1", matmul(FC["thumb"][0], FC["thumb"][1]), fl, FINGER_EFFORT,
          comment="iKin thumb link 2 (j9); origin folds links 0 and 1 (link 1 blocked at 0)")
flex_joint(THUMB_HINGES >= 2, "l_thumb_distal1", "l_thumb_1", "l_thumb_2", FC["thumb"][2],
           "l_thumb_proximal", "iKin thumb link 3")
flex_joint(THUMB_HINGES >= 3, "l_thumb_distal2", "l_thumb_2", "l_thumb_3", FC["thumb"][3],
           "l_thumb_proximal", "iKin thumb link 4")
add_joint("l_thumb_tip_fixed", "fixed", "l_thumb_3", "l_thumb_tip", FC["thumb"][4])

for f_ in ["index", "middle", "ring", "little"]:
    H = matmul(T_hand_ee, finger_H0(f_))
    has_abd = f_ != "middle"
    k0 = 1 if has_abd else 0
    if has_abd:
        add_link("l_%s_0" % f_, [phalanx(f_, 0, M_KNUCKLE, "%s knuckle (abduction link)" % f_)],
                 "iKin %s link 0 (abduction) fixed at chain angle 0 (j7 = 60 deg)" % f_)
        add_joint("l_%s_abduction" % f_, "fixed", "l_hand", "l_%s_0" % f_, H,
                  comment="iKin %s link 0, fixed at 0; origin = EE * H0_%s" % (f_, f_))
    for s in range(3):
        add_link("l_%s_%d" % (f_, s + 1), [phalanx(f_, k0 + s, M_PHALANX, "%s phalanx %d%s" % (f_, s + 1, " (fingertip sensor)" if s == 2 else ""))],
                 "iKin %s link %d" % (f_, k0 + s))
    add_link("l_%s_tip" % f_, massless=True, comment="end of the iKin %s chain" % f_)
    jn = ["l_%s_proximal" % f_, "l_%s_distal1" % f_, "l_%s_distal2" % f_]
    par = ["l_%s_0" % f_ if has_abd else "l_hand", "l_%s_1" % f_, "l_%s_2" % f_]
    for s in range(3):
        T = FC[f_][k0 + s - 1] if (s > 0 or has_abd) else H
        mim = None if (f_ == "index" and s == 0) else "l_index_proximal"
        flex_joint(s < FINGER_HINGES, jn[s], par[s], "l_%s_%d" % (f_, s + 1), T, mim,
                   "iKin %s link %d" % (f_, k0 + s))
    add_joint("l_%s_tip_fixed" % f_, "fixed", "l_%s_3" % f_, "l_%s_tip" % f_, FC[f_][k0 + 2])

def zero_pose(link):
    """Pose of a link in the root frame with every joint at 0 (joint origins chained)."""
    for j in joints:
        if j["child"] == link:
            return matmul(zero_pose(j["parent"]), j["T"])
    return eye()

def merge_finger(host, guest, why):
    """Each guest phalanx becomes a fixed child of the host phalanx at its level: one rigid body
    per level, driven by the host's hinges."""
    for s in range(1, 4):
        for j in joints:
            if j["child"] == "l_%s_%d" % (guest, s):
                j.update(type="fixed", parent="l_%s_%d" % (host, s), lim=None, effort=None, mimic=None,
                         T=matmul(inv(zero_pose("l_%s_%d" % (host, s))), zero_pose("l_%s_%d" % (guest, s))),
                         comment="%s phalanx %d: rigid with the %s phalanx of its level (%s)" % (guest, s, host, why))

if MERGE_RING_LITTLE:
    merge_finger("ring", "little", "iCub_SIM")
if MERGE_INDEX_MIDDLE:
    merge_finger("index", "middle", "one finger DOF: they always move together")

# ---------------------------------------------------------------- emit
out = []
w = out.append
w('<?xml version="1.0"?>')
w('<!-- iCub v1 torso + left arm + left hand for libselftalk. Generated; see data/README.md for every')
w('     number and its source. Kinematics: iKin iCubArm("left") v1.0 + iCubFinger (left), standard DH;')
w('     base frame root_link = iKin root rotated by Rz(pi): x forward, y left, z up. Joint angles equal')
w('     the robot/iKin joint angles (same sign, same zero). Units: m, kg, rad. -->')
w('<robot name="icub_v1_left_arm">')
w('  <material name="grey"><color rgba="0.7 0.7 0.7 1"/></material>')

def geom_xml(p):
    if p.kind == "cylinder":
        return '<cylinder radius="%s" length="%s"/>' % (f(p.dims[0]), f(p.dims[1]))
    if p.kind == "box":
        return '<box size="%s %s %s"/>' % tuple(f(v) for v in p.dims)
    return '<sphere radius="%s"/>' % f(p.dims[0])

summary = []
for name in link_order:
    L = links[name]
    w('')
    w('  <!-- %s -->' % L["comment"])
    if L["massless"]:
        w('  <link name="%s"/>' % name)
        continue
    w('  <link name="%s">' % name)
    M, c, I = combine(L["prims"])
    assert posdef(I), name
    summary.append((name, M, c, I))
    w('    <inertial>')
    w('      <origin xyz="%s %s %s" rpy="0 0 0"/>' % (f(c[0]), f(c[1]), f(c[2])))
    w('      <mass value="%s"/>' % f(M))
    w('      <inertia ixx="%s" ixy="%s" ixz="%s" iyy="%s" iyz="%s" izz="%s"/>' %
      (f(I[0][0]), f(I[0][1]), f(I[0][2]), f(I[1][1]), f(I[1][2]), f(I[2][2])))
    w('    </inertial>')
    for p in L["prims"]:
        if not p.collide:
            continue
        w('    <visual>  <!-- %s -->' % p.tag)
        w('      ' + origin(p.T))
        w('      <geometry>' + geom_xml(p) + '</geometry>')
        w('      <material name="grey"/>')
        w('    </visual>')
        w('    <collision name="%s">' % p.tag.split(" (")[0].replace(",", "").replace(" ", "_"))
        w('      ' + origin(p.T))
        w('      <geometry>' + geom_xml(p) + '</geometry>')
        w('    </collision>')
    w('  </link>')

w('')
for j in joints:
    if j["comment"]:
        w('  <!-- %s -->' % j["comment"])
    w('  <joint name="%s" type="%s">' % (j["name"], j["type"]))
    w('    <parent link="%s"/>' % j["parent"])
    w('    <child link="%s"/>' % j["child"])
    w('    ' + origin(j["T"]))
    if j["type"] == "revolute":
        w('    <axis xyz="0 0 1"/>')
        lo, hi = j["lim"]
        w('    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>' % (f(lo * D), f(hi * D), f(j["effort"]), f(VEL)))
        if j["mimic"]:
            w('    <mimic joint="%s" multiplier="1" offset="0"/>' % j["mimic"])
    w('  </joint>')
w('</robot>')
import os, sys
out_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "icub_left_arm.urdf")
open(out_path, "w").write("\n".join(out) + "\n")

tot = 0
for (n, M, c, I) in summary:
    tot += M
    print("%-14s m=%.5f com=(%.4f %.4f %.4f) I=(%.3e %.3e %.3e | %.2e %.2e %.2e)" % (n, M, c[0], c[1], c[2], I[0][0], I[1][1], I[2][2], I[0][1], I[0][2], I[1][2]))
print("total mass", tot)
