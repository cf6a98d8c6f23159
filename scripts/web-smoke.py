#!/usr/bin/env python3
"""Smoke test of the page in headless Chromium, over WebDriver (chromedriver), with nothing but
Python's standard library.

Serves the folder scripts/build-web.sh made (default target/web), opens it, and checks:
  1. the page loads and the window starts (the loading message goes);
  2. the canvas shows a rendered Earth: the viewport's centre holds ocean blue and land colours
     (not a blank or one-colour canvas), and, once the render has settled, its block means match
     web/smoke-earth.png within a tolerance;
  3. clicking a lesson's experiment changes the image;
  4. the browser's console has no errors.
Prints the time to the first image and writes the screenshots to --out.

Usage: scripts/web-smoke.py [--site target/web] [--out target/web-smoke] [--update-reference]
"""

import argparse
import base64
import functools
import http.server
import json
import os
import socket
import struct
import subprocess
import sys
import threading
import time
import urllib.request
import zlib

WIDTH, HEIGHT = 1600, 1000
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(ROOT, "web", "smoke-earth.png")
# Block means of the settled Earth, compared channel by channel (0-255): the largest difference
# of any block, and the mean difference over all blocks.
BLOCK = 16
MAX_BLOCK_DIFF = 40.0
MAX_MEAN_DIFF = 6.0
# Where to click in the page's viewport (1600 x 857 at WIDTH x HEIGHT: the window's size less
# headless Chromium's frame), as the docked layout lays the window out: View, its Lessons
# toggle, then the first lesson's "Open the lesson's scene"; then that lesson's first
# experiment, "A constant blue, seen from the side", just below where the button was.
OPEN_LESSON = [(146, 12), (177, 62), (1170, 380)]
EXPERIMENT = (1203, 398)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# --- PNG, decoded with zlib (8-bit RGB or RGBA, not interlaced: what Chromium writes) ---------

def png_decode(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, (depth, colour, interlace)
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, channels, rows


def png_encode_rgb(width, height, pixels):
    raw = b"".join(b"\x00" + bytes(pixels[y * width * 3:(y + 1) * width * 3]) for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Image:
    def __init__(self, png):
        self.width, self.height, self.channels, self.rows = png_decode(png)

    def pixel(self, x, y):
        i = x * self.channels
        return tuple(self.rows[y][i:i + 3])

    def block_means(self, box, block=BLOCK):
        x0, y0, x1, y1 = box
        out = []
        for by in range(y0, y1 - block + 1, block):
            for bx in range(x0, x1 - block + 1, block):
                s = [0, 0, 0]
                for y in range(by, by + block):
                    for x in range(bx, bx + block):
                        p = self.pixel(x, y)
                        s[0] += p[0]
                        s[1] += p[1]
                        s[2] += p[2]
                out.append(tuple(v / (block * block) for v in s))
        return out


# --- WebDriver ---------------------------------------------------------------------------------

class Driver:
    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.session = None

    def call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=120) as r:
                return json.loads(r.read() or b"{}").get("value")
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"{method} {path}: {e.read().decode(errors='replace')}") from e

    def start(self, chromium):
        caps = {
            "browserName": "chrome",
            "goog:loggingPrefs": {"browser": "ALL"},
            "goog:chromeOptions": {
                "binary": chromium,
                "args": [
                    "--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                    f"--window-size={WIDTH},{HEIGHT}", "--hide-scrollbars",
                    # No GPU here: WebGL2 on SwiftShader, Chromium's CPU implementation.
                    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                    "--ignore-gpu-blocklist", "--force-device-scale-factor=1",
                    # No network beyond localhost here: Chromium's own background connections
                    # would only be refused, many at a time.
                    "--no-first-run", "--disable-background-networking", "--disable-quic",
                    "--disable-component-update", "--disable-sync",
                ],
            },
        }
        value = self.call("POST", "/session", {"capabilities": {"alwaysMatch": caps}})
        self.session = value["sessionId"]

    def s(self, path):
        return f"/session/{self.session}{path}"

    def go(self, url):
        self.call("POST", self.s("/url"), {"url": url})

    def js(self, script, *args):
        return self.call("POST", self.s("/execute/sync"), {"script": script, "args": list(args)})

    def screenshot(self):
        return base64.b64decode(self.call("GET", self.s("/screenshot")))

    def click(self, x, y):
        pointer = {"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
                   "actions": [
                       {"type": "pointerMove", "duration": 0, "x": int(x), "y": int(y), "origin": "viewport"},
                       {"type": "pointerDown", "button": 0},
                       {"type": "pause", "duration": 80},
                       {"type": "pointerUp", "button": 0},
                   ]}
        self.call("POST", self.s("/actions"), {"actions": [pointer]})
        self.call("DELETE", self.s("/actions"))

    def console(self):
        return self.call("POST", self.s("/se/log"), {"type": "browser"}) or []

    def quit(self):
        if self.session:
            try:
                self.call("DELETE", self.s(""))
            except Exception:  # noqa: BLE001 - the browser may be gone already
                pass


# --- The checks --------------------------------------------------------------------------------

def viewport_box(img):
    """The middle of the window, where the viewport's Earth is whatever the panels' widths."""
    w, h = img.width, img.height
    return (int(w * 0.30), int(h * 0.22), int(w * 0.70), int(h * 0.78))


def earth_colours(img):
    """(ocean-blue pixels, land pixels, distinct colours) in the viewport box, sampled."""
    x0, y0, x1, y1 = viewport_box(img)
    blue = land = 0
    colours = set()
    for y in range(y0, y1, 4):
        for x in range(x0, x1, 4):
            r, g, b = img.pixel(x, y)
            colours.add((r >> 3, g >> 3, b >> 3))
            if b > r + 20 and b > 40:
                blue += 1
            elif r > b + 15 and g > b + 5:
                # Deserts, forests and plains (the grey panels have r = g = b).
                land += 1
    return blue, land, len(colours)


def looks_like_earth(img):
    blue, land, colours = earth_colours(img)
    return blue > 200 and land > 50 and colours > 40


def compare_blocks(a, b):
    box = viewport_box(a)
    ma, mb = a.block_means(box), b.block_means(box)
    diffs = [max(abs(p[i] - q[i]) for i in range(3)) for p, q in zip(ma, mb)]
    return max(diffs), sum(diffs) / len(diffs)


def settle(driver, out, first, timeout=90):
    """Screenshots until two in a row a few seconds apart differ little (the render is done)."""
    prev = first
    deadline = time.time() + timeout
    while time.time() < deadline:
        time.sleep(3)
        shot = driver.screenshot()
        img = Image(shot)
        worst, mean = compare_blocks(prev, img)
        prev = img
        if worst < 3 and mean < 0.5:
            return shot, img
    return shot, prev


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--site", default=os.path.join(ROOT, "target", "web"))
    ap.add_argument("--out", default=os.path.join(ROOT, "target", "web-smoke"))
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    ap.add_argument("--update-reference", action="store_true",
                    help="write the settled screenshot's viewport as web/smoke-earth.png")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    failures = []

    # The page, served as any static server would (with the wasm MIME type).
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=a.site)
    handler.func.extensions_map[".wasm"] = "application/wasm"
    handler.func.log_message = lambda *args: None
    server = http.server.ThreadingHTTPServer(("127.0.0.1", free_port()), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/index.html"

    port = free_port()
    chromedriver = subprocess.Popen([a.chromedriver, f"--port={port}"],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    driver = Driver(port)
    try:
        for _ in range(100):
            try:
                driver.call("GET", "/status")
                break
            except Exception:  # noqa: BLE001 - not listening yet
                time.sleep(0.1)
        driver.start(a.chromium)
        t0 = time.time()
        driver.go(url)

        # 1. The window starts: the loading message is removed.
        started = None
        while time.time() - t0 < 120:
            gone = driver.js("return document.getElementById('status') === null")
            if gone:
                started = time.time() - t0
                break
            time.sleep(0.2)
        if started is None:
            text = driver.js("var s = document.getElementById('status'); return s && s.textContent")
            failures.append(f"the window did not start in 120 s: {text!r}")
        else:
            print(f"window started after {started:.1f} s")

        # 2. The first image of the Earth.
        first = None
        while started is not None and time.time() - t0 < 180:
            shot = driver.screenshot()
            img = Image(shot)
            if looks_like_earth(img):
                first = time.time() - t0
                with open(os.path.join(a.out, "first.png"), "wb") as f:
                    f.write(shot)
                break
            time.sleep(0.25)
        if first is None:
            failures.append("no Earth on the canvas within 180 s (blue, land, colours: %s)"
                            % (earth_colours(img),) if started is not None else "no window")
        else:
            print(f"first image of the Earth after {first:.1f} s")
            shot, img = settle(driver, a.out, img)
            with open(os.path.join(a.out, "earth.png"), "wb") as f:
                f.write(shot)
            print(f"settled after {time.time() - t0:.1f} s")
            if a.update_reference:
                with open(REFERENCE, "wb") as f:
                    f.write(shot)
                print(f"wrote {REFERENCE}")
            elif os.path.exists(REFERENCE):
                with open(REFERENCE, "rb") as f:
                    ref = Image(f.read())
                worst, mean = compare_blocks(ref, img)
                print(f"against {os.path.relpath(REFERENCE, ROOT)}: largest block difference {worst:.1f}, mean {mean:.2f}")
                if worst > MAX_BLOCK_DIFF or mean > MAX_MEAN_DIFF:
                    failures.append(f"the Earth differs from the reference: block {worst:.1f} > {MAX_BLOCK_DIFF} or mean {mean:.2f} > {MAX_MEAN_DIFF}")
            else:
                failures.append(f"{REFERENCE} is missing (make it with --update-reference)")

            # 3. A lesson's experiment changes the image.
            for x, y in OPEN_LESSON:
                driver.click(x, y)
                time.sleep(1.5)
            lesson_shot, lesson = settle(driver, a.out, Image(driver.screenshot()))
            with open(os.path.join(a.out, "lesson.png"), "wb") as f:
                f.write(lesson_shot)
            if not looks_like_earth(lesson):
                failures.append("the first lesson's scene is not the Earth (see lesson.png)")
            driver.click(*EXPERIMENT)
            time.sleep(1.5)
            after_shot, after = settle(driver, a.out, Image(driver.screenshot()))
            with open(os.path.join(a.out, "experiment.png"), "wb") as f:
                f.write(after_shot)
            worst, mean = compare_blocks(lesson, after)
            blue, land, _ = earth_colours(after)
            print(f"after the experiment: largest block difference {worst:.1f}, mean {mean:.2f}; blue {blue}, land {land}")
            if worst < 20 or land > 20:
                failures.append("clicking the experiment \"A constant blue\" did not turn the Earth blue")

        # 4. No errors in the console.
        errors = [e for e in driver.console() if e.get("level") == "SEVERE"]
        for e in errors:
            failures.append(f"console: {e.get('message')}")
    finally:
        driver.quit()
        chromedriver.terminate()
        server.shutdown()

    for f in failures:
        print(f"FAIL: {f}", file=sys.stderr)
    print("web smoke test: " + ("FAILED" if failures else "passed"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
