#!/usr/bin/env python3
"""The report page in a real browser: `hba optimize` writes report.html for a
small simulated drive; Debian's chromium (headless, software WebGL) opens it,
takes screenshots, and this script checks that the map and the trajectories
are drawn (not a blank canvas), that the input/optimized toggle changes the
picture, and that the page reported no error. Exit 77 (skipped) without
chromium.

usage: report_page_browser.py HBA [--keep DIR]   (DIR keeps the page and shots)
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

BROWSERS = ["chromium", "chromium-browser", "google-chrome", "google-chrome-stable"]
BACKGROUND = (17, 20, 24)  # the canvas's clear colour (0.067, 0.078, 0.094)
WIDTH, HEIGHT = 1200, 800


def find_browser():
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


def read_png(path):
    """Pixels of an 8-bit RGB or RGBA PNG (what Chromium writes) as rows of (r, g, b)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    at, idat, header = 8, b"", None
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, color, _, _, interlace = header
    assert depth == 8 and color in (2, 6) and interlace == 0, "unexpected PNG kind %s" % (header,)
    channels = 3 if color == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up = previous[x]
            corner = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[x] = (line[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[i:i + 3]) for i in range(0, stride, channels)])
        previous = line
    return rows


def canvas_pixels(rows):
    """The map's area: left of the 420-px side panel."""
    return [row[:len(row) - 440] for row in rows]


def chromium(browser, page, fragment, args):
    command = [browser, "--headless", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
               "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--window-size=%d,%d" % (WIDTH, HEIGHT),
               "--virtual-time-budget=8000", "--enable-logging=stderr", "--v=0"] + args
    command.append("file://" + os.path.abspath(page) + "#" + fragment)
    done = subprocess.run(command, capture_output=True, text=True, timeout=240)
    return done


def screenshot(browser, page, fragment, png):
    done = chromium(browser, page, fragment, ["--screenshot=" + png])
    if not os.path.exists(png):
        sys.exit("chromium wrote no screenshot for #%s:\n%s" % (fragment, done.stderr[-3000:]))
    return canvas_pixels(read_png(png)), done.stderr


def differing(a, b):
    return sum(1 for ra, rb in zip(a, b) for pa, pb in zip(ra, rb) if max(abs(x - y) for x, y in zip(pa, pb)) > 24)


def drawn(pixels):
    return sum(1 for row in pixels for p in row if max(abs(x - y) for x, y in zip(p, BACKGROUND)) > 24)


def near_color(pixels, color, tolerance=40):
    return sum(1 for row in pixels for p in row if max(abs(x - y) for x, y in zip(p, color)) <= tolerance)


def console_errors(stderr):
    """What the page wrote to its console, as Chromium logs it ("INFO:CONSOLE:12] ..."): the page
    writes nothing when all is well, so any line is a failure, but the driver's performance notes."""
    return [line for line in stderr.splitlines()
            if re.search(r"CONSOLE[:(]\d+", line) and "GL Driver Message" not in line]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    hba = sys.argv[1]
    keep = sys.argv[sys.argv.index("--keep") + 1] if "--keep" in sys.argv else None
    browser = find_browser()
    if not browser:
        print("SKIP: no chromium (apt-get install chromium)")
        return 77
    work = keep or tempfile.mkdtemp(prefix="hba-page-")
    os.makedirs(work, exist_ok=True)
    try:
        data, out = os.path.join(work, "sim"), os.path.join(work, "out")
        subprocess.run([hba, "-q", "simulate", "-o", data, "--frames", "120", "--sensor", "vlp16", "--force"],
                       check=True)
        subprocess.run([hba, "-q", "optimize", data, "-o", out, "--force"], check=True)
        page = os.path.join(out, "report.html")
        assert os.path.exists(page), "hba optimize wrote no report.html"

        shots = {}
        logs = ""
        for name, fragment in [("optimized", "map=optimized&layers=map,trajectory"),
                               ("input", "map=input&layers=map,trajectory"),
                               ("trajectories", "map=optimized&layers=trajectory&view=top"),
                               ("both", "map=both&view=free&color=crisper&layers=map,trajectory,links,regions")]:
            shots[name], stderr = screenshot(browser, page, fragment, os.path.join(work, name + ".png"))
            logs += stderr
        area = len(shots["optimized"]) * len(shots["optimized"][0])
        checks = {
            "map drawn (share of the canvas)": (drawn(shots["optimized"]) / area, 0.03),
            "input map drawn": (drawn(shots["input"]) / area, 0.03),
            "toggle changes the picture (share)": (differing(shots["input"], shots["optimized"]) / area, 0.002),
            # Without the map, whatever is drawn is a trajectory; the optimized one is white.
            "trajectory pixels, alone": (drawn(shots["trajectories"]), 300),
            "white (optimized) trajectory pixels": (near_color(shots["trajectories"], (245, 245, 245)), 100),
            "side by side drawn": (drawn(shots["both"]) / area, 0.03),
        }
        # The trajectories alone leave most of the canvas empty: the map is not drawn there.
        checks["canvas empty without the map (share)"] = (1.0 - drawn(shots["trajectories"]) / area, 0.9)

        # A click at the canvas's centre names the scan of the point drawn there.
        dom = chromium(browser, page, "map=input&pick=%d,%d" % ((WIDTH - 440) // 2, HEIGHT // 2), ["--dump-dom"])
        picked = re.search(r'<div id="picked">scan (\d+) \(of (\d+)\)</div>', dom.stdout)
        status_text = re.search(r'<pre id="hba-status"[^>]*>(.*?)</pre>', dom.stdout, re.S)
        assert status_text, "the page wrote no status:\n" + dom.stderr[-3000:]
        status = json.loads(status_text.group(1).replace("&quot;", '"').replace("&amp;", "&"))
        errors = status["errors"] + console_errors(logs + dom.stderr)

        failed = False
        for name, (value, least) in checks.items():
            ok = value >= least
            failed |= not ok
            print("%-45s %10.4f  (at least %g)  %s" % (name, value, least, "ok" if ok else "FAILED"))
        print("page status:", status)
        if not status["drawn"] or status["map"] != "input" or status["points"] < 1000:
            print("FAILED: the page did not draw the input map")
            failed = True
        if not picked or int(picked.group(1)) >= int(picked.group(2)):
            print("FAILED: a click on the map named no scan")
            failed = True
        else:
            print("a click at the centre: scan %s of %s" % picked.groups())
        if errors:
            print("FAILED: errors in the page's console:\n  " + "\n  ".join(errors))
            failed = True
        print("page: %.1f MB; screenshots in %s" % (os.path.getsize(page) / 1e6, work if keep else "(removed)"))
        return 1 if failed else 0
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
