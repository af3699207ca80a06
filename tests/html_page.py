# SPDX-License-Identifier: MIT
"""Checks of a trial page (./apps/replay --html) for tests/check_html.sh; standard library only.

    html_page.py static PAGE THREE_DIR       self-contained: nothing it loads, three.js inlined unchanged
                                             under a comment that ends where it should; the page's
                                             script parses no markup
    html_page.py report DOM TRACE [STEP]     what the page's script read (--dump-dom) equals the trace,
                                             the ball drawn at the trace's object at the step shown
    html_page.py pixels PNG DOM MIN_BALL     the screenshot shows the robot and the ball where the camera puts them
    html_page.py netlog NETLOG               the page requested nothing (Chromium's --log-net-log)

Each prints one line and exits 1 with the reason when the check fails."""
import csv
import html.parser
import json
import re
import struct
import sys
import zlib

# the three.js files the page inlines (Debian's libjs-three layout), and the only http(s) text
# in them: not addresses the page loads but an XML namespace name (createElementNS's argument),
# a comment inside a shader's source and the authors' names in OrbitControls' comment
LIBS = ("three.min.js", "examples/js/controls/OrbitControls.js")
LIB_URLS = {"http://www.w3.org/1999/xhtml", "https://graphics.stanford.edu/papers/envmap/envmap.pdf",
            "https://github.com/qiao", "http://mrdoob.com", "http://alteredqualia.com/",
            "http://github.com/WestLangley", "http://erichaines.com", "http://github.com/sciecode"}
# attributes that make a browser load something
LOADING = {"src", "href", "srcset", "action", "formaction", "data", "poster", "background",
           "manifest", "codebase", "cite", "longdesc", "ping", "xlink:href"}
# the DOM's markup parsers and code from strings: the page's own script uses none (it builds
# elements and text nodes), so no name in the data can become an element or a handler
MARKUP = re.compile(r"\.innerHTML|\.outerHTML|insertAdjacentHTML|document\.write|DOMParser|"
                    r"createContextualFragment|srcdoc|\beval\(|new Function|setTimeout\(\s*['\"]")
# text that loads something from a script or a style sheet
LOADING_TEXT = re.compile(r"https?:|\bsrc\s*=|\bhref\s*=|url\(|@import|fetch\(|XMLHttpRequest|"
                          r"import\(|\bimport\s|new Worker|sendBeacon|EventSource|WebSocket|"
                          r"\bfile:|//[a-z0-9.-]+\.[a-z]{2,}/", re.I)


def die(msg):
    print(f"html_page: {msg}")
    sys.exit(1)


class Elements(html.parser.HTMLParser):
    """every start tag with its attributes, and the text of each <script> and <style>"""
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.blocks, self._in = [], [], None

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag in ("script", "style"):
            self._in = [tag, dict(attrs), ""]

    def handle_data(self, data):
        if self._in is not None:
            self._in[2] += data

    def handle_endtag(self, tag):
        if self._in is not None and tag == self._in[0]:
            self.blocks.append(tuple(self._in))
            self._in = None


def static(page, three_dir):
    text = open(page, encoding="ascii").read()  # the writer keeps the page ASCII
    p = Elements()
    p.feed(text)
    for tag, attrs in p.tags:
        if tag in ("link", "iframe", "img", "object", "embed", "base", "frame", "audio", "video",
                   "source", "track", "image"):
            die(f"<{tag}> element: pages have none (it would load a file)")
        for a, v in attrs.items():
            if a in LOADING and not (v or "").startswith("#"):
                die(f"<{tag} {a}=\"{v}\">: the page must load nothing")
        if tag == "meta" and attrs.get("http-equiv", "").lower() == "refresh":
            die("<meta http-equiv=refresh>")
    libs = [open(f"{three_dir}/{f}", encoding="utf-8").read() for f in LIBS]
    found = [False] * len(libs)
    for tag, attrs, body in p.blocks:
        rest = body
        for i, lib in enumerate(libs):
            if lib in body:  # inlined unchanged; its http(s) text is the known names only
                found[i] = True
                rest = rest.replace(lib, "")
                # the comment heading it (its licence and where it was read from) ends just
                # before it: a directory named "x*/code;/*" must not end it early
                if not re.fullmatch(r"\s*/\*(?:(?!\*/)[^<])*\*/\s*", rest, re.S):
                    die(f"{LIBS[i]}: its heading comment ends early or holds '<': {rest[:300]!r}")
                extra = set(re.findall(r"https?://[^\s\"'`)\\]+", lib)) - LIB_URLS
                if extra:
                    die(f"{LIBS[i]} holds other addresses than the known names: {sorted(extra)}")
        m = LOADING_TEXT.search(rest)
        if m:
            die(f"<{tag}>: '{rest[max(0, m.start() - 40):m.end() + 40]}' (the page's own script, "
                "style and data must name no address)")
        if tag == "script" and "src" in attrs:
            die("<script src>")
        if tag == "script" and attrs.get("type") != "application/json" and not any(lib in body for lib in libs):
            m = MARKUP.search(body)
            if m:
                die(f"the page's script parses markup or code from a string: "
                    f"'{body[max(0, m.start() - 60):m.end() + 40]}'")
    if not all(found):
        die(f"three.js not inlined unchanged: {[f for f, ok in zip(LIBS, found) if not ok]}")
    outside = re.sub(r"<(script|style)\b.*?</\1>", "", text, flags=re.S | re.I)
    m = LOADING_TEXT.search(outside)
    if m:
        die(f"markup names an address: '{outside[max(0, m.start() - 40):m.end() + 40]}'")
    if "Permission is hereby granted" not in text or "three.js authors" not in text:
        die("no licence notice of three.js")
    print(f"html_page: {page}: loads nothing; {', '.join(LIBS)} inlined unchanged with the licence")


def report_of(dom):
    m = re.search(r'<div id="st-report"([^>]*)>', open(dom, encoding="utf-8").read())
    if not m:
        die(f"{dom}: no st-report element (the page's script did not run)")
    return dict(re.findall(r'(data-[a-z]+)="([^"]*)"', m.group(1)))


def report(dom, trace, step=None):
    r = report_of(dom)
    if r.get("data-status") != "ok":
        die(f"status {r.get('data-status')}: {r.get('data-error', '')}")
    rows = list(csv.DictReader(open(trace)))
    want = {"data-steps": str(len(rows)),
            "data-words": " ".join(x["caretaker_word"] for x in rows),
            "data-labels": " ".join(x["selftalk_label"] for x in rows)}
    for k, v in want.items():
        if r.get(k) != v:
            die(f"{k}: the page read '{r.get(k, '')[:80]}', the trace has '{v[:80]}'")
    if step is not None:
        if r.get("data-step") != step:
            die(f"shows step {r.get('data-step')} (expected {step})")
        # the ball drawn where the trace has the object (the data's 0.1 mm)
        ball = [float(v) for v in r.get("data-ballxyz", "nan,nan,nan").split(",")]
        obj = [float(rows[int(step)][c]) for c in ("obj_x", "obj_y", "obj_z")]
        if not max(abs(a - b) for a, b in zip(ball, obj)) <= 1.5e-4:
            die(f"the ball drawn at {ball}, the trace's object at step {step}: {obj}")
    print(f"html_page: the page read {len(rows)} steps, their words and labels, as the trace"
          + (f"; the ball drawn at the trace's object of step {step}" if step is not None else ""))


def png(path):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA PNG"""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        die(f"{path}: not a PNG")
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                die(f"{path}: depth {depth} colour type {ctype} interlace {interlace}")
            ch = 3 if ctype == 2 else 4
        idat += body if kind == b"IDAT" else b""
        pos += 12 + n
    raw, stride, prev, rows = zlib.decompress(idat), w * ch, bytearray(w * ch), []
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # the PNG filters: none, sub, up, average, Paeth
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * ch:x * ch + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def robot_like(r, g, b):  # the blue-grey of the arm (0x8ca1bf) under any light of the scene
    return b - r >= 25 and b >= 1.15 * r and b >= 1.04 * g


def ball_like(r, g, b):  # the orange ball (0xf28c26)
    return r >= 150 and r - b >= 110 and 0.35 * r <= g <= 0.8 * r


def pixels(png_path, dom, min_ball):
    r = report_of(dom)
    if r.get("data-status") != "ok":
        die(f"status {r.get('data-status')}: {r.get('data-error', '')}")
    w, h, rows = png(png_path)
    cx, cy, cw, ch = (int(v) for v in r["data-canvas"].split(","))
    bx, by, br = (int(v) for v in r["data-ball"].split(","))
    x0, y0, x1, y1 = (int(v) for v in r["data-robot"].split(","))
    if not (0 <= cx and 0 <= cy and cx + cw <= w and cy + ch <= h and cw > 200 and ch > 200):
        die(f"canvas {cx},{cy} {cw}x{ch} in a {w}x{h} screenshot")
    colours, robot, robot_in, ball, disc = set(), 0, 0, 0, 0
    m = 60  # the shapes reach past their centres, which the robot box spans
    for y in range(cy, cy + ch):
        for x in range(cx, cx + cw):
            p = rows[y][x]
            colours.add(p)
            if robot_like(*p):
                robot += 1
                robot_in += x0 - m <= x <= x1 + m and y0 - m <= y <= y1 + m
            if (x - bx) ** 2 + (y - by) ** 2 <= (br + 2) ** 2:
                disc += 1
                ball += ball_like(*p)
    if len(colours) < 200:
        die(f"the canvas has {len(colours)} colours: blank")
    if robot < 3000 or robot_in < 0.97 * robot:
        die(f"{robot} robot-coloured pixels, {robot_in} of them in the robot's box "
            f"{x0},{y0}..{x1},{y1} (expected >= 3000, 97% in the box)")
    if disc == 0 or ball < min_ball * disc:
        die(f"{ball} of the {disc} pixels where the ball projects ({bx},{by} r {br}) are orange "
            f"(expected >= {min_ball:.0%})")
    print(f"html_page: {len(colours)} colours; {robot} robot pixels, {robot_in / robot:.1%} in its "
          f"box; the ball at {bx},{by}: {ball / disc:.0%} orange")


def netlog(path):
    d = json.load(open(path))
    types = {v: k for k, v in d["constants"]["logEventTypes"].items()}
    # requests of the page carry its origin (file://: "null"); the browser's own background
    # requests (updates, accounts) are "not an origin"
    mine = [e["params"]["url"] for e in d["events"] if types.get(e["type"]) == "URL_REQUEST_START_JOB"
            and e.get("params", {}).get("initiator", "not an origin") != "not an origin"]
    if mine:
        die(f"the page requested {mine}")
    print("html_page: the page requested nothing")


if __name__ == "__main__":
    cmds = {"static": (static, 2), "report": (report, 2), "pixels": (pixels, 3), "netlog": (netlog, 1)}
    if len(sys.argv) < 2 or sys.argv[1] not in cmds or len(sys.argv) - 2 < cmds[sys.argv[1]][1]:
        die(__doc__)
    fn, n = cmds[sys.argv[1]]
    args = sys.argv[2:]
    if fn is pixels:
        args[2] = float(args[2])
    fn(*args)
