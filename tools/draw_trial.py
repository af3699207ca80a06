#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Pictures of the robot: a replayed trial's collision shapes (arm, hand, ball, table, target) at
chosen steps, one 3D panel per step, so one can see what an individual does.

    ./apps/replay GENOME CONFIG --trial K --out trace.csv --shapes shapes.csv --at 0,20,40,last
    /usr/bin/python3 tools/draw_trial.py shapes.csv [--trace trace.csv] [--steps 0,40,last]
        [--view ELEV,AZIM] [--cols N] [--title TEXT] [--dt 0.05] [-o trial.png]...

shapes.csv is ./apps/replay's --shapes output (docs/PROTOCOL.md, "Robot pictures"): one row
per shape and step, step,kind,owner,type,sx,sy,sz,px,py,pz,r00..r22. Boxes are drawn as
faces, cylinders as their sides and caps, spheres as the ball, the target as a translucent
sphere of the success radius and the table by its top face (clipped to the picture). A mesh
(never in the default model) is drawn as its bounding box. Every panel has the same limits and
equal scaling on the three axes; the view is from the robot's front left, above (--view: the
elevation and azimuth in degrees, matplotlib's; azimuth 0 looks from +x, the robot's front,
90 from +y, its left).

--steps picks steps of the file (numbers, "first", "last"; default: up to five spread over
the file, the first and last included). With --trace (the same replay's --out), each panel's
title has the step's time ((step + 1) x --dt s), d_r, d_g, touching and lifted; the trace must
be of the same trial (its object centre is the ball's, checked). Prints one line per panel:
the step, the number of shapes, the ball's and the target's centres and their distance.
Default outputs trial.png and trial.svg.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figlib  # noqa: E402

figlib.PROG = "draw_trial"
ROT = [f"r{i}{j}" for i in range(3) for j in range(3)]
COLUMNS = {"step": "int", "kind": "str", "owner": "str", "type": "str",
           **{c: "float" for c in ("sx", "sy", "sz", "px", "py", "pz")}, **{c: "float" for c in ROT}}
TRACE_COLUMNS = {"step": "int", "obj_x": "float", "obj_y": "float", "obj_z": "float",
                 "d_r": "float", "d_g": "float", "touching": "int", "lifted": "int"}
KINDS = ("robot", "ball", "table", "target")
TYPES = ("sphere", "box", "cylinder", "mesh")
# face colours (RGBA) by kind; the ball's base a shade darker than its sphere
COLOUR = {"robot": (0.55, 0.63, 0.75, 1.0), "ball": (0.95, 0.55, 0.15, 1.0),
          "base": (0.80, 0.42, 0.08, 1.0), "table": (0.80, 0.70, 0.52, 0.55),
          "target": (0.20, 0.70, 0.30, 0.13)}
ORTHO_TOL = 1e-6  # the shapes file's 9 significant digits are far better
FAR = 1e3  # m: the arm spans 1 m; a shape further or larger is a diverged simulation, not drawn


# ---- reading ------------------------------------------------------------------------------

def check_shape(path, r):
    n = f"{path}:{r['_line']}"
    if r["kind"] not in KINDS:
        figlib.die(f"{n}: kind '{r['kind']}' (expected {', '.join(KINDS)})")
    if r["type"] not in TYPES:
        figlib.die(f"{n}: type '{r['type']}' (expected {', '.join(TYPES)})")
    if r["step"] < 0:
        figlib.die(f"{n}: step {r['step']} (expected a step number >= 0)")
    size = [r["sx"], r["sy"], r["sz"]]
    if min(size) < 0 or max(size) > FAR:
        figlib.die(f"{n}: size {size[0]:g} {size[1]:g} {size[2]:g} (expected extents >= 0 and at "
                   f"most {FAR:g} m)")
    if max(abs(r[c]) for c in ("px", "py", "pz")) > FAR:
        figlib.die(f"{n}: position {r['px']:g} {r['py']:g} {r['pz']:g} (expected within {FAR:g} m "
                   "of the robot: a diverged simulation cannot be drawn)")
    R = [r[c] for c in ROT]
    for i in range(3):
        for j in range(3):
            d = sum(R[3 * i + k] * R[3 * j + k] for k in range(3))
            if abs(d - (i == j)) > ORTHO_TOL:
                figlib.die(f"{n}: r00..r22 is not a rotation (rows {i} and {j}: dot {d:.6g}; "
                           "expected an orthonormal matrix, world <- shape)")
    return {"step": r["step"], "kind": r["kind"], "owner": r["owner"], "type": r["type"],
            "size": size, "pos": [r["px"], r["py"], r["pz"]], "R": R, "line": r["_line"]}


def read_shapes(path):
    """{step: [shape, ...]} in file order"""
    steps = {}
    for r in figlib.read_csv(path, COLUMNS, "./apps/replay --shapes output"):
        s = check_shape(path, r)
        steps.setdefault(s["step"], []).append(s)
    return steps


def read_trace(path, more=None):
    """{step: row} of a replay trace; more: columns beyond TRACE_COLUMNS (figlib.read_csv's)"""
    rows = {}
    for r in figlib.read_trace(path, {**TRACE_COLUMNS, **(more or {})}):
        for c in ("touching", "lifted"):
            if r[c] not in (0, 1):
                figlib.die(f"{path}:{r['_line']}: {c} {r[c]} (expected 0 or 1)")
        rows[r["step"]] = r
    return rows


def pick_steps(spec, have, path):
    """the steps to draw: --steps or up to five spread over the file"""
    steps = sorted(have)
    if spec is None:
        if len(steps) <= 5:
            return steps
        return sorted({steps[round(i * (len(steps) - 1) / 4)] for i in range(5)})
    out = []
    for tok in spec.split(","):
        if tok in ("first", "last"):
            out.append(steps[0] if tok == "first" else steps[-1])
            continue
        try:
            s = int(tok)
        except ValueError:
            figlib.die(f"--steps '{spec}': '{tok}' (expected step numbers, 'first' or 'last', "
                       "comma-separated)")
        if s not in have:
            near = ", ".join(str(x) for x in steps[:12]) + (" ..." if len(steps) > 12 else "")
            figlib.die(f"--steps: {path} has no shapes of step {s} (it has steps {near}; "
                       "./apps/replay --at chooses them)")
        out.append(s)
    return list(dict.fromkeys(out))


def ball_of(shapes):
    return next((s for s in shapes if s["kind"] == "ball" and s["type"] == "sphere"), None)


def target_of(shapes):
    return next((s for s in shapes if s["kind"] == "target"), None)


def check_same_trial(shapes_path, trace_path, steps, shapes, trace):
    """each drawn step is in the trace, whose object centre is the ball's"""
    for st in steps:
        if st not in trace:
            figlib.die(f"{trace_path}: no row of step {st} (expected the trace of the replay that "
                       f"wrote {shapes_path})")
        b = ball_of(shapes[st])
        if b is None:
            continue
        obj = [trace[st]["obj_x"], trace[st]["obj_y"], trace[st]["obj_z"]]
        if max(abs(a - o) for a, o in zip(b["pos"], obj)) > 1e-6:
            figlib.die(f"{trace_path}:{trace[st]['_line']}: object at {fmt3(obj)}, but "
                       f"{shapes_path}:{b['line']} has the ball at {fmt3(b['pos'])} (expected the "
                       "trace of the same replay)")


def fmt3(v):
    return "(" + ", ".join(f"{x:.4f}" for x in v) + ")"


# ---- geometry: every shape as polygons (world frame) ---------------------------------------

def world(s, local):
    """a point of the shape's frame in the world"""
    R, p = s["R"], s["pos"]
    return tuple(p[i] + R[3 * i] * local[0] + R[3 * i + 1] * local[1] + R[3 * i + 2] * local[2]
                 for i in range(3))


def box_faces(s):
    hx, hy, hz = (0.5 * x for x in s["size"])
    c = [world(s, (sx * hx, sy * hy, sz * hz)) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return [[c[i] for i in q] for q in quads]


def cylinder_faces(s, n=16):
    rx, ry, hz = 0.5 * s["size"][0], 0.5 * s["size"][1], 0.5 * s["size"][2]
    ring = [(rx * math.cos(2 * math.pi * k / n), ry * math.sin(2 * math.pi * k / n)) for k in range(n)]
    lo = [world(s, (x, y, -hz)) for x, y in ring]
    hi = [world(s, (x, y, hz)) for x, y in ring]
    sides = [[lo[k], lo[(k + 1) % n], hi[(k + 1) % n], hi[k]] for k in range(n)]
    return sides + [lo[::-1], hi]


def sphere_faces(s, n_lon=16, n_lat=9):
    r = [0.5 * x for x in s["size"]]

    def pt(i, j):
        th, ph = math.pi * i / n_lat, 2 * math.pi * j / n_lon
        return world(s, (r[0] * math.sin(th) * math.cos(ph), r[1] * math.sin(th) * math.sin(ph),
                         r[2] * math.cos(th)))
    return [[pt(i, j), pt(i, j + 1), pt(i + 1, j + 1), pt(i + 1, j)]
            for i in range(n_lat) for j in range(n_lon)]


def table_top(s, lim):
    """the table's top face, clipped to the picture's x/y limits when the table is level"""
    faces = box_faces(s)
    top = max(faces, key=lambda f: sum(p[2] for p in f))
    level = abs(s["R"][8]) > 1 - 1e-9
    if not level:
        return [top]
    xs, ys, z = [p[0] for p in top], [p[1] for p in top], top[0][2]
    x0, x1 = max(min(xs), lim[0][0]), min(max(xs), lim[0][1])
    y0, y1 = max(min(ys), lim[1][0]), min(max(ys), lim[1][1])
    if x0 >= x1 or y0 >= y1:
        return []
    return [[(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]]


def faces_of(s, lim):
    if s["kind"] == "table":
        return table_top(s, lim)
    if s["type"] == "sphere":
        return sphere_faces(s, 20, 12) if s["kind"] == "target" else sphere_faces(s)
    if s["type"] == "cylinder":
        return cylinder_faces(s)
    return box_faces(s)  # box, and a mesh as its bounding box


def colour_of(s):
    if s["kind"] == "ball" and s["type"] != "sphere":
        return COLOUR["base"]
    return COLOUR[s["kind"]]


def limits(shapes_by_step, steps):
    """one cube holding every shape but the table in every drawn step, with a margin"""
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for st in steps:
        for s in shapes_by_step[st]:
            if s["kind"] == "table":
                continue
            ext = 0.5 * max(s["size"]) * math.sqrt(3)
            for i in range(3):
                lo[i] = min(lo[i], s["pos"][i] - ext)
                hi[i] = max(hi[i], s["pos"][i] + ext)
    if not math.isfinite(lo[0]):
        lo, hi = [-0.5] * 3, [0.5] * 3
    half = 0.5 * max(h - l for l, h in zip(lo, hi)) * 1.05
    mid = [0.5 * (l + h) for l, h in zip(lo, hi)]
    return [(m - half, m + half) for m in mid]


# ---- drawing --------------------------------------------------------------------------------

def panel_title(st, trace, dt):
    t = f"step {st}"
    if trace is None:
        return t
    r = trace[st]
    return (f"{t} (t = {(st + 1) * dt:.2f} s)\nd_r = {r['d_r']:.3f} m  d_g = {r['d_g']:.3f} m\n"
            f"touching {r['touching']}  lifted {r['lifted']}")


def add_shapes(ax, Poly3DCollection, shapes, lim):
    """the shapes as one collection of polygons (returned: an animation replaces it)"""
    polys, colours = [], []
    for s in shapes:
        f = faces_of(s, lim)
        polys += f
        colours += [colour_of(s)] * len(f)
    edge = [(0.2, 0.2, 0.25, 0.35 if c[3] > 0.5 else 0.0) for c in colours]
    return ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors=edge,
                                                linewidths=0.3))


def draw_panel(ax, Poly3DCollection, ticker, shapes, lim, title, view):
    add_shapes(ax, Poly3DCollection, shapes, lim)
    set_axes(ax, ticker, lim, view)
    ax.set_title(title, fontsize=8)


def set_axes(ax, ticker, lim, view):
    """limits, equal scaling, the camera and the axes' labels of a panel"""
    ax.set_xlim(*lim[0])
    ax.set_ylim(*lim[1])
    ax.set_zlim(*lim[2])
    ax.set_box_aspect((1, 1, 1), zoom=1.12)
    ax.view_init(elev=view[0], azim=view[1])
    for axis, name in ((ax.xaxis, "x"), (ax.yaxis, "y"), (ax.zaxis, "z")):
        axis.set_label_text(f"{name} (m)", fontsize=7)
        axis.labelpad = -7
        axis.set_major_locator(ticker.MultipleLocator(0.2))
    ax.tick_params(labelsize=6, pad=-3)


def parse_view(v):
    try:
        e, a = (float(x) for x in v.split(","))
        if math.isfinite(e) and math.isfinite(a):
            return e, a
    except ValueError:
        pass
    figlib.die(f"--view '{v}': expected ELEV,AZIM in degrees (e.g. 25,40)")


def report(st, shapes):
    b, t = ball_of(shapes), target_of(shapes)
    line = f"{figlib.PROG}: step {st}: {len(shapes)} shapes"
    if b:
        line += f", ball {fmt3(b['pos'])}"
    if t:
        line += f", target {fmt3(t['pos'])} radius {0.5 * t['size'][0]:g}"
    if b and t:
        line += f", ball-target {math.dist(b['pos'], t['pos']):.4f} m"
    print(line)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("shapes", help="./apps/replay --shapes output")
    ap.add_argument("--trace", help="the same replay's trace (--out): d_r, d_g, touching, lifted")
    ap.add_argument("--steps", help="steps to draw: numbers, first, last (comma-separated)")
    ap.add_argument("--view", default="25,40", help="ELEV,AZIM in degrees (default 25,40)")
    ap.add_argument("--cols", type=int, default=0, help="panels per row (default: all in one row)")
    ap.add_argument("--title", help="the figure's title (default: the shapes file's name)")
    ap.add_argument("--dt", type=float, default=0.05, help="seconds per step (robot.control_dt)")
    figlib.add_out_argument(ap, "trial")
    a = ap.parse_args()
    outs = figlib.outputs(a, "trial")
    view = parse_view(a.view)
    if a.cols < 0 or not (a.dt > 0 and math.isfinite(a.dt)):
        figlib.die(f"--cols {a.cols}, --dt {a.dt:g}: expected --cols >= 0 and --dt > 0")
    shapes = read_shapes(a.shapes)
    steps = pick_steps(a.steps, shapes, a.shapes)
    trace = read_trace(a.trace) if a.trace else None
    if trace is not None:
        check_same_trial(a.shapes, a.trace, steps, shapes, trace)
    for st in steps:
        report(st, shapes[st])
    lim = limits(shapes, steps)
    plt = figlib.pyplot()
    from matplotlib import ticker
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    cols = a.cols or len(steps)
    rows = (len(steps) + cols - 1) // cols
    fig = plt.figure(figsize=(3.3 * cols, 3.6 * rows + 0.4))
    for i, st in enumerate(steps):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d")
        draw_panel(ax, Poly3DCollection, ticker, shapes[st], lim, panel_title(st, trace, a.dt), view)
    fig.suptitle(a.title if a.title is not None else os.path.basename(a.shapes), fontsize=10)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.02, top=0.83 if trace else 0.88, wspace=0.05)
    figlib.save(plt, fig, outs)


if __name__ == "__main__":
    main()
