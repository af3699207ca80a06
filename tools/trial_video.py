#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Videos of the robot: a replayed trial as an animation (GIF, or MP4 with ffmpeg), the arm, the
ball, the table and the target drawn as tools/draw_trial.py draws them, with the step, the time,
the word heard, the word said, lifted, touching and success on every frame (the thesis's
Appendix A.2 videos).

    ./apps/replay GENOME CONFIG --trial K --out trace.csv --shapes shapes.csv --shapes-every 1 \\
        > replay.txt
    /usr/bin/python3 tools/trial_video.py shapes.csv trace.csv [--summary replay.txt] \\
        [--stride N] [--fps F] [--size WxH] [--dpi D] [--view ELEV,AZIM] [--colors N] \\
        [--hold S] [--title TEXT] [--dt 0.05] [--list] -o trial.gif|trial.mp4

tools/trial_video.sh does both in one command. Frame i shows step first + i x --stride of the
trace, and the trace's last step closes the video whatever the stride: ceil(n / stride) frames,
one more when the stride does not land on the last of n steps. Each frame's step must be in
shapes.csv (--shapes-every 1 writes every step); the trace and the shapes must be of one replay
(the ball where the trace has the object). The word heard is the trace's given word
(caretaker_word: the caretaker's, a primitive trial's fixed word, a hand-over's), else the word
of its linguistic inputs (ling_*: self talk, the label said the step before); the word said is
the self-talk label (selftalk_label, - for a network without linguistic outputs). --summary,
replay's standard output, names where the given words come from and puts the trial's line and
its outcome (success, end) in the picture; it must have as many steps as the trace.

GIF (Pillow: Debian's python3-pil): every frame quantised to one palette of --colors colours
(default 32: 26 by maximum coverage of the first, middle and last frames, and 6 greys), no
dithering; frames after the first store only the rectangle that changed. Its delays are whole
hundredths of a second (--fps 15: 0.07 s); the last frame stays --hold seconds (default 1.5).
MP4 (ffmpeg's libx264, yuv420p, even --size): one video frame per frame, at --fps. Default
--fps: real time, 1 / (dt x stride). --list prints each frame's step, words and state.
Written atomically; malformed input is refused with FILE:LINE and exit 1, nothing written.
"""
import argparse
import importlib.util
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figlib  # noqa: E402
import draw_trial  # noqa: E402

figlib.PROG = "trial_video"  # draw_trial's import set its own
LING = [f"ling_{w}" for w in figlib.WORDS]
MORE = {**{c: "float" for c in LING}, "caretaker_word": "int", "selftalk_label": "int",
        "success_now": "int", "event": "text"}
EVENTS = {"": None, "end_success": "success",
          "end_failure": "failure (the object fell, or the simulation gave up)",
          "end_quiet": "the object fell after the table went (quiet)"}
# the GIF palette's greys (the text, the grid, the edges), besides the colours of the frames
GREYS = (0, 80, 140, 180, 210, 235)
# the summary's fields shown under the title (replay's line has the fitness terms too)
CAPTION_KEYS = ("k", "type", "cell", "posture", "words", "success", "steps", "end", "reached_step")


# ---- reading ------------------------------------------------------------------------------

def read_trace(path):
    """the trace's rows in step order, each with heard (the word heard, -1 none) and given
    (1 when someone else gave it)"""
    rows = draw_trial.read_trace(path, MORE)
    for r in rows.values():
        n = f"{path}:{r['_line']}"
        ling = [r[c] for c in LING]
        on = [k for k, v in enumerate(ling) if v != 0]
        if min(ling) < 0 or len(on) > 1:
            figlib.die(f"{n}: ling_reach..ling_move {', '.join(f'{v:g}' for v in ling)} (expected "
                       "at most one word heard: one value above 0, the others 0)")
        given = r["caretaker_word"]
        if given >= 0 and on and on[0] != given:
            figlib.die(f"{n}: caretaker_word {given} but the linguistic inputs give word {on[0]} "
                       "(expected the word given to be the word heard)")
        r["heard"], r["given"] = (given, 1) if given >= 0 else (on[0] if on else -1, 0)
        if r["success_now"] not in (0, 1):
            figlib.die(f"{n}: success_now {r['success_now']} (expected 0 or 1)")
        if r["event"] not in EVENTS:
            figlib.die(f"{n}: event '{r['event']}' (expected empty, "
                       f"{', '.join(e for e in EVENTS if e)})")
    return [rows[s] for s in sorted(rows)]


def read_summary(path, nsteps):
    """(caption, {key: value}) of replay's standard output: its line 'trial K ...'"""
    lines = figlib.read_text(path, "./apps/replay's standard output")
    found = [(n, s) for n, s in enumerate(lines, start=1) if s.startswith("trial ")]
    if len(found) != 1:
        at = found[1][0] if found else max(1, len(lines))
        figlib.die(f"{path}:{at}: {len(found)} lines 'trial K ...' (expected one: ./apps/replay's "
                   "standard output)")
    n, line = found[0]
    words = [t for t in line.split() if "=" not in t]
    fields = dict(t.split("=", 1) for t in line.split() if "=" in t)
    run = fields.get("steps", "").split("/")[0]
    if not run.isdigit() or "success" not in fields:
        figlib.die(f"{path}:{n}: no steps=RUN/OF or success= (expected ./apps/replay's summary "
                   "line)")
    if int(run) != nsteps:
        figlib.die(f"{path}:{n}: steps={fields['steps']} but the trace has {nsteps} steps "
                   "(expected the output of the replay that wrote the trace)")
    # a primitive trial's word is its fixed word; the other trials say where theirs come from
    fields.setdefault("words", "fixed")
    caption = " ".join(words + [f"{k}={fields[k]}" for k in CAPTION_KEYS if k in fields])
    return caption, fields


def frame_steps(trace, stride):
    """every stride-th step of the trace from its first, and its last"""
    steps = [r["step"] for r in trace][::stride]
    if steps[-1] != trace[-1]["step"]:
        steps.append(trace[-1]["step"])
    return steps


def check_shapes(shapes_path, trace_path, shapes, trace, steps):
    last = trace[-1]["step"]
    beyond = [s for s in shapes if s > last or s < trace[0]["step"]]
    if beyond:
        figlib.die(f"{shapes_path}: shapes of step {beyond[0]}, but {trace_path} has steps "
                   f"{trace[0]['step']}..{last} (expected the files of one replay)")
    for s in steps:
        if s not in shapes:
            figlib.die(f"{shapes_path}: no shapes of step {s} (expected every frame's step: "
                       "./apps/replay --shapes FILE --shapes-every 1)")
    draw_trial.check_same_trial(shapes_path, trace_path, steps, shapes,
                                {r["step"]: r for r in trace})


# ---- options ------------------------------------------------------------------------------

def parse_size(v):
    try:
        w, h = (int(x) for x in v.lower().split("x"))
        if 64 <= w <= 4096 and 64 <= h <= 4096:
            return w, h
    except ValueError:
        pass
    figlib.die(f"--size '{v}': expected WxH in pixels, 64..4096 each (e.g. 480x420)")


def check_options(a):
    fmt = os.path.splitext(a.out)[1].lower()
    if fmt not in (".gif", ".mp4"):
        figlib.die(f"{a.out}: unknown video format (expected a name ending in .gif or .mp4)")
    bad = [(f"--stride {a.stride}", a.stride >= 1), (f"--dpi {a.dpi:g}", 20 <= a.dpi <= 600),
           (f"--colors {a.colors}", 8 <= a.colors <= 256),
           (f"--hold {a.hold:g}", 0 <= a.hold <= 60),
           (f"--dt {a.dt:g}", a.dt > 0 and math.isfinite(a.dt)),
           (f"--fps {a.fps}", a.fps is None or 0.1 <= a.fps <= 100)]
    for what, good in bad:
        if not good:
            figlib.die(f"{what}: out of range (expected --stride >= 1, --dpi 20..600, --colors "
                       "8..256, --hold 0..60 s, --dt > 0, --fps 0.1..100)")
    size = parse_size(a.size)
    if fmt == ".mp4":
        if shutil.which("ffmpeg") is None:
            figlib.die(f"{a.out}: MP4 needs ffmpeg, which is not in PATH (Debian: apt-get install "
                       "ffmpeg), or write a .gif")
        if size[0] % 2 or size[1] % 2:
            figlib.die(f"--size {a.size}: MP4 (yuv420p) needs an even width and height")
    elif importlib.util.find_spec("PIL") is None:
        figlib.die(f"GIF needs Pillow, which {sys.executable} does not have (Debian: apt-get "
                   "install python3-pil, then run /usr/bin/python3)")
    return fmt[1:], size


# ---- frames -------------------------------------------------------------------------------

def word(w):
    return figlib.WORDS[w] if w >= 0 else "-"


def yes(v):
    return "yes" if v else "no"


def heard_text(r, source):
    """the word heard and who gave it"""
    if r["heard"] < 0:
        return "-"
    return f"{word(r['heard'])} ({source if r['given'] else 'self talk: its own word'})"


def state_text(r):
    return (f"lifted {yes(r['lifted'])}   touching {yes(r['touching'])}   "
            f"success now {yes(r['success_now'] or r['event'] == 'end_success')}")


def frame_text(r, last, dt, source, outcome):
    """the lines under the robot: where the trial is, the words, the state"""
    st = r["step"]
    lines = [f"step {st:3d} of {last}   t = {(st + 1) * dt:5.2f} s",
             f"heard: {heard_text(r, source)}",
             f"said:  {word(r['selftalk_label'])}",
             state_text(r)]
    if st == last:
        lines.append(outcome)
    return "\n".join(lines)


def outcome_of(trace, fields):
    """the trial's result, shown on the last frame"""
    end = EVENTS[trace[-1]["event"]]
    if fields is not None:
        res = "success" if fields["success"] == "1" else "no success"
        return f"trial: {res} (end={fields.get('end', '?')})"
    return f"trial: {end}" if end else "trial: ran its full length"


class Renderer:
    """one figure, redrawn per frame: the shapes' collection and the text replaced"""

    def __init__(self, size, dpi, lim, view, title, caption):
        self.plt = figlib.pyplot()
        from matplotlib import ticker
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
        self.Poly3DCollection = Poly3DCollection
        self.size = size
        self.fig = self.plt.figure(figsize=(size[0] / dpi, size[1] / dpi), dpi=dpi)
        self.fig.patch.set_facecolor("white")
        self.ax = self.fig.add_axes([0.0, 0.19, 1.0, 0.72], projection="3d")
        draw_trial.set_axes(self.ax, ticker, lim, view)
        self.ax.set_box_aspect((1, 1, 1), zoom=1.25)  # the pictures' margin is for a title above
        for axis in (self.ax.xaxis, self.ax.yaxis, self.ax.zaxis):
            axis.set_pane_color((1, 1, 1, 0))  # white panes: fewer colours, a smaller GIF
        self.lim = lim
        self.fig.text(0.5, 0.985, title, ha="center", va="top", fontsize=8.5)
        self.fig.text(0.5, 0.935, caption, ha="center", va="top", fontsize=6.5, color="0.3")
        self.info = self.fig.text(0.02, 0.015, "", ha="left", va="bottom", fontsize=7,
                                  family="DejaVu Sans Mono", linespacing=1.25)
        self.coll = None

    def frame(self, shapes, text):
        """the frame as an RGB PIL image of exactly size pixels"""
        from PIL import Image
        if self.coll is not None:
            self.coll.remove()
        self.coll = draw_trial.add_shapes(self.ax, self.Poly3DCollection, shapes, self.lim)
        self.info.set_text(text)
        self.fig.canvas.draw()
        w, h = self.fig.canvas.get_width_height()
        im = Image.frombuffer("RGBA", (w, h), self.fig.canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
        im = im.convert("RGB")
        if im.size != self.size:  # W / dpi inches may round to a pixel less
            canvas = Image.new("RGB", self.size, "white")
            canvas.paste(im, (0, 0))
            im = canvas
        return im

    def close(self):
        self.plt.close(self.fig)


def write_gif(tmp, frames, render, fps, hold, colors):
    from PIL import Image
    # one palette for all frames (from the first, middle and last: every colour the trial
    # shows, most of them), so frames differ only where the picture does and compress well
    picks = sorted({0, len(frames) // 2, len(frames) - 1})
    samples = [render(frames[i]) for i in picks]
    strip = Image.new("RGB", (samples[0].width, samples[0].height * len(samples)))
    for k, im in enumerate(samples):
        strip.paste(im, (0, k * im.height))
    # maximum coverage keeps the small ball's orange, which median cut merges into the table's;
    # it leaves out the thin grey lines (the grid, the edges), so greys are added
    cover = strip.quantize(colors=colors - len(GREYS), method=Image.Quantize.MAXCOVERAGE,
                           dither=Image.Dither.NONE)
    pal = Image.new("P", (1, 1))
    greys = [g for g in GREYS for _ in "rgb"]
    pal.putpalette(cover.getpalette()[:3 * (colors - len(GREYS))] + greys)
    out = [render(f).quantize(palette=pal, dither=Image.Dither.NONE) for f in frames]
    ms = max(10, round(100 / fps) * 10)  # GIF delays are hundredths of a second
    durations = [ms] * len(out)
    durations[-1] = max(ms, round(hold * 100) * 10)
    out[0].save(tmp, format="GIF", save_all=True, append_images=out[1:], duration=durations,
                loop=0, optimize=False)


def write_mp4(tmp, frames, render, fps, size):
    cmd = ["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
           f"{size[0]}x{size[1]}", "-framerate", f"{fps:g}", "-i", "-", "-an", "-c:v", "libx264",
           "-pix_fmt", "yuv420p", "-crf", "28", "-movflags", "+faststart", "-f", "mp4", tmp]
    p = subprocess.Popen(cmd, stdin=subprocess.PIPE)
    try:
        for f in frames:
            p.stdin.write(render(f).tobytes())
        p.stdin.close()
    except BrokenPipeError:
        pass
    if p.wait() != 0:
        figlib.die(f"ffmpeg failed (exit {p.returncode}) writing {tmp}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("shapes", help="./apps/replay --shapes output (--shapes-every 1)")
    ap.add_argument("trace", help="the same replay's trace (--out)")
    ap.add_argument("-o", "--out", default="trial.gif", help="the video: .gif or .mp4 (trial.gif)")
    ap.add_argument("--summary", help="the replay's standard output (its summary line)")
    ap.add_argument("--stride", type=int, default=1, help="a frame every N steps (default 1)")
    ap.add_argument("--fps", type=float, help="frames per second (default real time)")
    ap.add_argument("--size", default="480x420", help="WxH in pixels (default 480x420)")
    ap.add_argument("--dpi", type=float, default=80, help="pixels per inch: the text's scale (80)")
    ap.add_argument("--view", default="25,40", help="ELEV,AZIM in degrees (default 25,40)")
    ap.add_argument("--colors", type=int, default=32, help="GIF palette size (default 32)")
    ap.add_argument("--hold", type=float, default=1.5, help="GIF: seconds on the last frame (1.5)")
    ap.add_argument("--title", help="the title (default: the shapes file's name)")
    ap.add_argument("--dt", type=float, default=0.05, help="seconds per step (robot.control_dt)")
    ap.add_argument("--list", action="store_true", help="print each frame's step, words and state")
    a = ap.parse_args()
    fmt, size = check_options(a)
    view = draw_trial.parse_view(a.view)
    shapes = draw_trial.read_shapes(a.shapes)
    trace = read_trace(a.trace)
    steps = frame_steps(trace, a.stride)
    check_shapes(a.shapes, a.trace, shapes, trace, steps)
    caption, fields = read_summary(a.summary, len(trace)) if a.summary else ("", None)
    source = fields["words"] if fields else "given"
    fps = a.fps if a.fps is not None else 1 / (a.dt * a.stride)
    by_step = {r["step"]: r for r in trace}
    last = trace[-1]["step"]
    outcome = outcome_of(trace, fields)
    title = a.title if a.title is not None else os.path.basename(a.shapes)
    if a.list:  # what each frame says, as text (tests/check_video.sh reads it)
        for i, st in enumerate(steps):
            r = by_step[st]
            print(f"{figlib.PROG}: frame {i}: step {st}: heard {heard_text(r, source)}; said "
                  f"{word(r['selftalk_label'])}; {state_text(r)}")
    rend = Renderer(size, a.dpi, draw_trial.limits(shapes, steps), view, title, caption)

    def render(st):
        return rend.frame(shapes[st], frame_text(by_step[st], last, a.dt, source, outcome))

    tmp = a.out + ".tmp"
    try:
        if fmt == "gif":
            write_gif(tmp, steps, render, fps, a.hold, a.colors)
        else:
            write_mp4(tmp, steps, render, fps, size)
        os.replace(tmp, a.out)
    finally:
        rend.close()
        if os.path.exists(tmp):
            os.remove(tmp)
    print(f"{figlib.PROG}: wrote {a.out}: {len(steps)} frames (steps {steps[0]}..{last}, every "
          f"{a.stride} and the last), {size[0]}x{size[1]} pixels, {fps:g} fps, "
          f"{os.path.getsize(a.out)} bytes")


if __name__ == "__main__":
    main()
