#!/usr/bin/env python3
"""The page's browser test, in headless Chromium and in Firefox ESR (under Xvfb: Firefox has
no WebGL2 fully headless here), over WebDriver (chromedriver, geckodriver), with nothing but
Python's standard library.

Serves the folder scripts/build-web.sh made (default target/web) as `python3 -m http.server`
does (the same handler, counting the bytes it sends), opens the page with two render workers
(`?workers=2`) and its widgets listed for scripts (`?widgets`: each button found by its label,
clicked with the browser's own pointer), and checks, in each browser:
  1. the first image: the window starts; while the Earth's image downloads (held back by the
     server until then) the sphere stands grey, then the Earth shows; what the first visit
     fetched before it (at most 6 MB); the settled Earth against web/smoke-earth.png;
  2. two workers rendered it (each rendered chunks; their memory is printed);
  3. presentation mode (P): the film follows the image drawn (the canvas's height), and the
     preset's resolution comes back after it;
  4. the app's keys lose the browser's default (F5, F1, Ctrl+S, Ctrl+O, Ctrl+Z), a plain
     letter keeps it;
  5. a link opening a lesson's experiment (#texplore1-l-01-constant-vs-image~1, put in the
     address bar of the open page): the Lessons panel on lesson 1, the Earth turned blue;
  6. a lesson experiment pressed ("A different image: the cat") changes the image;
  7. a reload keeps the lesson, its experiment and the panel;
  8. a lesson whose mesh downloads when it opens (lesson 9's two triangles, at "Show (u, v)"):
     no error, the (u, v) in red and green;
  9. an exercise's Check (lesson 6: Show solution, then Check) says "Correct" and puts the
     formulas on the Earth;
  10. a link opening a scene (the Earth's preset in a #texplore1-s- link), then a student's own
     image reaching the sphere, chosen with Browse… (the page's file input) and dropped on
     the page;
  11. no error or warning in the console from the page.
Prints the times, the bytes and the render's rays per second, and writes screenshots to --out
(one folder per browser).

With --bench N,N,... it times the Earth's render instead (README, "In the browser"), or with
--lesson NAME (repeatable) each lesson's own scene, opened by its link.

Usage: scripts/web-smoke.py [--site target/web] [--out target/web-smoke]
                            [--browser chromium|firefox|both] [--update-reference]
                            [--bench 0,1,2,4 [--runs 3] [--lesson NAME ...]]
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
import urllib.error
import urllib.request
import zlib

# The page's viewport in CSS pixels, the same in both browsers (the window is sized to it).
WIDTH, HEIGHT = 1600, 860
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(ROOT, "web", "smoke-earth.png")
# Block means of the settled Earth, compared channel by channel (0-255): the largest difference
# of any block, and the mean difference over all blocks.
BLOCK = 16
MAX_BLOCK_DIFF = 40.0
MAX_MEAN_DIFF = 6.0
# The most a first visit may fetch before the first image (issue 36: 6 MB).
MAX_FIRST_LOAD = 6_000_000
LESSON_1 = "01-constant-vs-image"
LESSON_6 = "06-spherical-mapping"
LESSON_9 = "09-triangle-meshes"
MESH = "assets/two-triangles.ply"
EARTH_IMAGE = "assets/earth_2048x1024.jpg"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# --- PNG, decoded and encoded with zlib (8-bit RGB or RGBA, not interlaced) ---------------------

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


def png_encode_rgb(width, height, pixel):
    """A PNG of `pixel(x, y) -> (r, g, b)`."""
    raw = b"".join(b"\x00" + bytes(v for x in range(width) for v in pixel(x, y)) for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Image:
    def __init__(self, png):
        self.png = png
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
                for y in range(by, by + block, 2):
                    for x in range(bx, bx + block, 2):
                        p = self.pixel(x, y)
                        s[0] += p[0]
                        s[1] += p[1]
                        s[2] += p[2]
                n = (block // 2) ** 2
                out.append(tuple(v / n for v in s))
        return out


# --- The server: python3 -m http.server's handler, counting what it sends ----------------------

class Counting(http.server.SimpleHTTPRequestHandler):
    sent = []  # (time, path, bytes of the body)
    # Files whose body waits until the test lets it go (path: threading.Event): a slow download.
    held = {}

    def copyfile(self, source, outputfile):
        held = Counting.held.get(self.path.split("?")[0])
        if held:
            held.wait(120)
        n = 0
        while True:
            buf = source.read(1 << 16)
            if not buf:
                break
            outputfile.write(buf)
            n += len(buf)
        Counting.sent.append((time.time(), self.path, n))

    def log_message(self, *args):
        pass


# --- WebDriver ---------------------------------------------------------------------------------

class Driver:
    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.session = None

    def call(self, method, path, body=None, timeout=120):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=timeout) as r:
                return json.loads(r.read() or b"{}").get("value")
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"{method} {path}: {e.read().decode(errors='replace')[:500]}") from e

    def wait_ready(self):
        for _ in range(300):
            try:
                self.call("GET", "/status", timeout=2)
                return
            except Exception:  # noqa: BLE001 - not listening yet
                time.sleep(0.1)
        raise RuntimeError("the WebDriver did not start")

    def start(self, caps):
        value = self.call("POST", "/session", {"capabilities": {"alwaysMatch": caps}})
        self.session = value["sessionId"]

    def s(self, path):
        return f"/session/{self.session}{path}"

    def go(self, url):
        self.call("POST", self.s("/url"), {"url": url})

    def refresh(self):
        self.call("POST", self.s("/refresh"), {})

    def js(self, script, *args):
        return self.call("POST", self.s("/execute/sync"), {"script": script, "args": list(args)})

    def screenshot(self):
        return base64.b64decode(self.call("GET", self.s("/screenshot")))

    def size_viewport(self, width, height):
        """Sizes the window so that the page's viewport is width x height CSS pixels."""
        w, h = width, height
        for _ in range(4):
            self.call("POST", self.s("/window/rect"), {"width": w, "height": h})
            time.sleep(0.3)
            iw, ih = self.js("return [innerWidth, innerHeight]")
            if (iw, ih) == (width, height):
                return
            w, h = w + width - iw, h + height - ih
        raise RuntimeError(f"cannot size the viewport to {width}x{height}: {iw}x{ih}")

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

    def key(self, key):
        """Presses and lets go of `key` (a character) where the focus is."""
        keys = {"type": "key", "id": "keyboard",
                "actions": [{"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}
        self.call("POST", self.s("/actions"), {"actions": [keys]})
        self.call("DELETE", self.s("/actions"))

    def find_css(self, selector):
        value = self.call("POST", self.s("/element"), {"using": "css selector", "value": selector})
        return next(iter(value.values()))

    def send_keys(self, element, text):
        self.call("POST", self.s(f"/element/{element}/value"), {"text": text})

    def chromium_console(self):
        """Chromium's console entries (None where the driver keeps none: geckodriver)."""
        try:
            return self.call("POST", self.s("/se/log"), {"type": "browser"}) or []
        except RuntimeError:
            return None

    def quit(self):
        if self.session:
            try:
                self.call("DELETE", self.s(""), timeout=30)
            except Exception:  # noqa: BLE001 - the browser may be gone already
                pass


def chromium_session(port, binary):
    return {
        "browserName": "chrome",
        "goog:loggingPrefs": {"browser": "ALL"},
        "goog:chromeOptions": {
            "binary": binary,
            "args": [
                "--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                f"--window-size={WIDTH},{HEIGHT + 140}", "--hide-scrollbars",
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


def firefox_session(binary):
    return {
        "browserName": "firefox",
        "moz:firefoxOptions": {
            "binary": binary,
            "prefs": {
                # A test profile: no first-run pages, no background connections.
                "browser.shell.checkDefaultBrowser": False,
                "datareporting.policy.dataSubmissionEnabled": False,
                "app.update.disabledForTesting": True,
                "network.captive-portal-service.enabled": False,
                "layout.css.devPixelsPerPx": "1.0",
            },
            "log": {"level": "error"},
        },
    }


# --- The page ----------------------------------------------------------------------------------

def image_box(img):
    """Inside the image pane (the left 68% of the window, below the menu and above the status
    line), around the viewport's centre."""
    w, h = img.width, img.height
    return (int(w * 0.08), int(h * 0.20), int(w * 0.58), int(h * 0.80))


def viewport_box(img):
    """The middle of the window, where the viewport's Earth is whatever the panels' widths."""
    w, h = img.width, img.height
    return (int(w * 0.30), int(h * 0.22), int(w * 0.70), int(h * 0.78))


def colours(img, box=None):
    """(ocean-blue, land, red, green, mid-grey pixels, distinct colours) in `box`, sampled."""
    x0, y0, x1, y1 = box or viewport_box(img)
    blue = land = red = green = grey = 0
    seen = set()
    for y in range(y0, y1, 4):
        for x in range(x0, x1, 4):
            r, g, b = img.pixel(x, y)
            seen.add((r >> 3, g >> 3, b >> 3))
            if b > r + 20 and b > 40:
                blue += 1
            elif r > b + 15 and g > b + 5:
                # Deserts, forests and plains (the grey panels have r = g = b).
                land += 1
            if r > 120 and r > g + 60 and r > b + 60:
                red += 1
            if g > 100 and g > r + 50 and g > b + 50:
                green += 1
            if 40 < r < 220 and max(r, g, b) - min(r, g, b) < 8:
                grey += 1
    return {"blue": blue, "land": land, "red": red, "green": green, "grey": grey, "colours": len(seen)}


def looks_like_earth(img):
    c = colours(img)
    return c["blue"] > 200 and c["land"] > 50 and c["colours"] > 40


def compare_blocks(a, b, box=None):
    box = box or viewport_box(a)
    ma, mb = a.block_means(box), b.block_means(box)
    diffs = [max(abs(p[i] - q[i]) for i in range(3)) for p, q in zip(ma, mb)]
    return max(diffs), sum(diffs) / len(diffs)


class Page:
    def __init__(self, driver, out, failures):
        self.d, self.out, self.failures = driver, out, failures

    def fail(self, what):
        print(f"  FAIL: {what}")
        self.failures.append(what)

    def shot(self, name=None):
        png = self.d.screenshot()
        if name:
            with open(os.path.join(self.out, name), "wb") as f:
                f.write(png)
        return Image(png)

    def wait(self, what, check, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline:
            value = check()
            if value:
                return value
            time.sleep(0.25)
        self.fail(f"{what}: not within {timeout} s")
        return None

    def status(self):
        return self.d.js("return globalThis.texploreStatus || null") or {}

    def started(self, timeout=180):
        return self.wait("the window starts (the loading message goes)",
                         lambda: self.d.js("return document.getElementById('status') === null "
                                           "&& !!globalThis.texploreStatus"), timeout)

    def settled(self, timeout=180):
        """Waits for the render to finish (every pass of the scene's samples), with every file
        in (no stand-in; builds before stand-ins have no count)."""
        return self.wait("the render finishes",
                         lambda: (lambda s: s.get("finished") == 1 and s.get("standIns", 0) == 0)(self.status()),
                         timeout)

    def widgets(self):
        return self.d.js("return globalThis.texploreWidgets || []") or []

    def widget(self, label, prefix=False):
        for w in self.widgets():
            text = w.get("label", "")
            if (text.startswith(label) if prefix else text == label) and w["w"] > 0:
                return w
        return None

    def press(self, label, timeout=30):
        """Scrolls the widget labelled `label` into view and clicks its centre."""
        w = self.wait(f"a widget labelled {label!r}", lambda: self.widget(label), timeout)
        if not w:
            return False
        frames = self.status().get("frames", 0)
        self.d.js("globalThis.texploreScrollTo(arguments[0])", w["id"])
        # The scroll lands a frame or two later: wait for frames, then until the widget stays
        # where it is.
        self.wait("frames after the scroll", lambda: self.status().get("frames", 0) >= frames + 3, 10)
        for _ in range(40):
            time.sleep(0.3)
            now = self.widget(label) or w
            if (now["x"], now["y"]) == (w["x"], w["y"]):
                break
            w = now
        if w.get("disabled"):
            self.fail(f"{label!r} is disabled")
            return False
        x, y = w["x"] + w["w"] / 2, w["y"] + w["h"] / 2
        if not (0 <= x < WIDTH and 0 <= y < HEIGHT):
            self.fail(f"{label!r} is off the page at ({x:.0f}, {y:.0f})")
            return False
        self.d.click(x, y)
        return True

    def follow(self, fragment):
        """Puts a link in the address bar of the open page (its fragment changes: no reload)."""
        self.d.js("location.hash = arguments[0]", fragment)


def scene_link(preset):
    """The #texplore1-s- link of a shipped preset (its asset paths relative to presets/, as
    the page's links are): the preset's text deflated, in base64url (src/link.rs)."""
    with open(os.path.join(ROOT, "presets", preset), encoding="utf-8") as f:
        text = f.read().encode()
    c = zlib.compressobj(9, zlib.DEFLATED, -15)
    data = c.compress(text) + c.flush()
    return "texplore1-s-" + base64.urlsafe_b64encode(data).decode().rstrip("=")


# Key presses sent to the page's body: the page's own listener (on the window, capturing) sees
# them on their way, the window (egui listens on its canvas) does not, so nothing is pressed.
KEYS_SCRIPT = """
const out = {};
for (const [name, init] of arguments[0]) {
  const e = new KeyboardEvent('keydown', Object.assign({bubbles: true, cancelable: true}, init));
  document.body.dispatchEvent(e);
  out[name] = e.defaultPrevented;
}
return out;
"""
# What a page without a GPU logs once: not the page's fault (a laptop's browser has one).
ENVIRONMENT = ["Software rasterizer detected - loss of performance expected"]

NO_CHOOSER_SCRIPT = """
const click = HTMLInputElement.prototype.click;
HTMLInputElement.prototype.click = function () {
  if (this.type !== 'file') return click.call(this);
};
"""

DROP_SCRIPT = """
const bytes = Uint8Array.from(atob(arguments[0]), c => c.charCodeAt(0));
const file = new File([bytes], arguments[1], {type: 'image/png'});
const dt = new DataTransfer();
dt.items.add(file);
const canvas = document.getElementById('texplore');
const r = canvas.getBoundingClientRect();
const at = {clientX: r.width * 0.3, clientY: r.height * 0.5};
for (const kind of ['dragenter', 'dragover', 'drop']) {
  canvas.dispatchEvent(new DragEvent(kind, Object.assign({bubbles: true, cancelable: true, dataTransfer: dt}, at)));
}
"""


def presentation(p):
    """Presentation mode, entered and left with P: in it the film is the image's size in
    screen pixels (the image fills the canvas's height), out of it the preset's resolution."""
    before = p.status()
    preset = (before.get("filmWidth"), before.get("filmHeight"))
    # The window takes keys once its canvas has the focus: a click on the status line.
    p.d.click(WIDTH * 0.6, HEIGHT - 8)
    p.d.key("p")

    def follows():
        s = p.status()
        w, h = s.get("filmWidth", 0), s.get("filmHeight", 0)
        iw, ih = s.get("imageWidth", 0), s.get("imageHeight", 0)
        return s if s.get("presenting") == 1 and abs(w - iw) <= 1.5 and abs(h - ih) <= 1.5 else None

    s = p.wait("presentation mode's film follows the image", follows, 30)
    if not s:
        p.fail(f"in presentation mode the film should be the image's size: {p.status()}")
    else:
        film = (s["filmWidth"], s["filmHeight"])
        print(f"  presentation mode (P): film {film[0]:.0f}x{film[1]:.0f} for an image of "
              f"{s['imageWidth']:.0f}x{s['imageHeight']:.0f} pixels on a {WIDTH}x{HEIGHT} canvas "
              f"(the preset's {preset[0]:.0f}x{preset[1]:.0f} before it)")
        if film[1] < HEIGHT * 0.75 or film[0] <= preset[0]:
            p.fail(f"presentation mode's film {film} should fill the canvas's height {HEIGHT}")
        p.wait("a pass in presentation mode", lambda: (p.status().get("spp") or 0) >= 1, 60)
        p.shot("presentation.png")
    p.d.key("p")
    if not p.wait("the preset's resolution after presentation mode",
                  lambda: p.status().get("presenting") == 0
                  and (p.status().get("filmWidth"), p.status().get("filmHeight")) == preset, 30):
        p.fail(f"after presentation mode the film should be the preset's {preset}: {p.status()}")
    p.settled()


def run_checks(p, url, name, update_reference):
    """The checks in one browser; returns the figures it printed."""
    d = p.d
    figures = {}
    Counting.sent.clear()
    # The Earth's image is held back: the sphere stands grey until it is in.
    earth = threading.Event()
    Counting.held = {"/" + EARTH_IMAGE: earth}
    t0 = time.time()
    d.go(url + "?workers=2&widgets")

    # 1. The first image, and what the first visit fetched before it.
    if not p.started():
        text = d.js("var s = document.getElementById('status'); return s && s.textContent")
        p.fail(f"the page says {text!r}")
        return figures
    print(f"  window started after {time.time() - t0:.1f} s")
    # 1a. A scene whose image is downloading stands it in (a grey sphere), then shows it.
    grey = p.wait("a grey stand-in while the Earth's image downloads",
                  lambda: (lambda s, i: i if s.get("standIns") == 1 and colours(i, image_box(i))["grey"] > 2000
                           else None)(p.status(), p.shot()), 120)
    if grey:
        p.shot("stand-in.png")
        print(f"  a grey stand-in after {time.time() - t0:.1f} s while {EARTH_IMAGE} downloads: "
              f"{colours(grey, image_box(grey))}")
    earth.set()
    t_let_go = time.time()
    first = p.wait("an Earth on the canvas", lambda: (lambda i: i if looks_like_earth(i) else None)(p.shot()), 180)
    if not first:
        return figures
    t_first = time.time()
    p.shot("first.png")
    fetched = [(t, path, n) for t, path, n in Counting.sent if t <= t_first]
    total = sum(n for _, _, n in fetched)
    figures["first_load"] = total
    print(f"  first image of the Earth after {t_first - t0:.1f} s ({t_first - t_let_go:.1f} s after its "
          f"image was let go); the visit fetched "
          f"{total / 1e6:.2f} MB in {len(fetched)} requests before it:")
    for path, n in sorted({(path, n) for _, path, n in fetched}, key=lambda e: -e[1])[:6]:
        print(f"    {n / 1e6:8.3f} MB  {path}")
    if total > MAX_FIRST_LOAD:
        p.fail(f"the first visit fetched {total} bytes before the first image (at most {MAX_FIRST_LOAD})")
    if p.settled():
        s = p.status()
        figures["rays_per_second"] = s.get("raysPerSecond")
        print(f"  settled after {time.time() - t0:.1f} s: {s.get('spp')} spp, "
              f"{s.get('raysPerSecond', 0) / 1e6:.2f} M rays/s")
        img = p.shot("earth.png")
        if update_reference:
            with open(REFERENCE, "wb") as f:
                f.write(img.png)
            print(f"  wrote {REFERENCE}")
        elif os.path.exists(REFERENCE):
            with open(REFERENCE, "rb") as f:
                ref = Image(f.read())
            if (ref.width, ref.height) != (img.width, img.height):
                p.fail(f"the reference is {ref.width}x{ref.height}, the page {img.width}x{img.height}")
            else:
                worst, mean = compare_blocks(ref, img)
                print(f"  against {os.path.relpath(REFERENCE, ROOT)}: largest block difference "
                      f"{worst:.1f}, mean {mean:.2f}")
                if worst > MAX_BLOCK_DIFF or mean > MAX_MEAN_DIFF:
                    p.fail(f"the Earth differs from the reference: block {worst:.1f} > {MAX_BLOCK_DIFF} "
                           f"or mean {mean:.2f} > {MAX_MEAN_DIFF}")

    # 2. Two workers rendered it.
    s = p.status()
    chunks, memory = s.get("workerChunks", []), s.get("workerMemory", [])
    print(f"  workers: {s.get('workers')}, chunks rendered {chunks}, memory "
          f"{[round(m / 1e6, 1) for m in memory]} MB")
    figures["worker_memory"] = memory
    if s.get("workers", 0) < 2 or len(chunks) < 2 or min(chunks) == 0:
        p.fail(f"two workers should have rendered the Earth: {s}")

    # 3. Presentation mode (P): the film follows the image drawn, as on the desktop, and goes
    #    back to the preset's resolution after it.
    presentation(p)

    # 4. The app's keys lose the browser's default; copying and the browser's own keys keep it.
    taken = [["F5", {"key": "F5", "code": "F5"}], ["F1", {"key": "F1", "code": "F1"}],
             ["Ctrl+S", {"key": "s", "code": "KeyS", "ctrlKey": True}],
             ["Ctrl+O", {"key": "o", "code": "KeyO", "ctrlKey": True}],
             ["Ctrl+Z", {"key": "z", "code": "KeyZ", "ctrlKey": True}],
             ["Ctrl+Shift+Z", {"key": "Z", "code": "KeyZ", "ctrlKey": True, "shiftKey": True}],
             ["Ctrl+=", {"key": "=", "code": "Equal", "ctrlKey": True}],
             ["Ctrl+0", {"key": "0", "code": "Digit0", "ctrlKey": True}]]
    kept = [["Ctrl+C", {"key": "c", "code": "KeyC", "ctrlKey": True}],
            ["F12", {"key": "F12", "code": "F12"}], ["Ctrl+T", {"key": "t", "code": "KeyT", "ctrlKey": True}]]
    prevented = d.js(KEYS_SCRIPT, taken + kept)
    print(f"  browser default prevented: {prevented}")
    if not all(prevented[k] for k, _ in taken) or any(prevented[k] for k, _ in kept):
        p.fail(f"the app's keys should lose their browser default, the others keep it: {prevented}")

    # 5. A link opening a lesson's experiment, in the open page.
    p.follow(f"#texplore1-l-{LESSON_1}~1")
    if p.wait("the link opens lesson 1", lambda: p.status().get("lesson") == LESSON_1, 60):
        p.settled()
        img = p.shot("link-experiment.png")
        c = colours(img, image_box(img))
        print(f"  the link opened lesson 1 at its first experiment: {c}")
        if c["land"] > 20 or c["blue"] < 200:
            p.fail(f"the link's experiment \"A constant blue\" should turn the Earth blue: {c}")
        if not p.widget("A constant blue, seen from the side"):
            p.fail("the Lessons panel does not show lesson 1's experiments")
        before = img

        # 6. A lesson experiment, pressed.
        if p.press("A different image: the cat"):
            p.wait("the experiment changes the render", lambda: p.status().get("finished") == 0, 20)
            p.settled()
            after = p.shot("experiment.png")
            worst, mean = compare_blocks(before, after, image_box(after))
            print(f"  after the experiment: largest block difference {worst:.1f}, mean {mean:.2f}")
            if worst < 30:
                p.fail("pressing \"A different image: the cat\" did not change the image")

            # 7. A reload keeps the lesson, its experiment and the panel.
            time.sleep(1)
            d.refresh()
            if p.started() and p.wait("the reload reopens lesson 1", lambda: p.status().get("lesson") == LESSON_1, 60):
                p.wait("the reload puts the experiment back",
                       lambda: p.widget("A different image: the cat") and p.status().get("finished") == 1, 120)
                again = p.shot("reload.png")
                worst, mean = compare_blocks(after, again, image_box(again))
                print(f"  after the reload: lesson {p.status().get('lesson')}, against before it: "
                      f"largest block difference {worst:.1f}, mean {mean:.2f}")
                if mean > MAX_MEAN_DIFF:
                    p.fail(f"the reload did not put the cat back: mean block difference {mean:.2f}")

    # 8. A lesson whose mesh downloads when it opens (lesson 9's two triangles): it opens at its
    #    experiment without an error, the mesh stood in until it is in.
    p.follow(f"#texplore1-l-{LESSON_9}~1")
    if p.wait("the link opens lesson 9", lambda: p.status().get("lesson") == LESSON_9, 60):
        # Its scene, built with the mesh in, at the experiment, rendered.
        def shown():
            s = p.status()
            if not (s.get("scene", "").endswith("two-triangles.ron") and s.get("standIns") == 0
                    and s.get("finished") == 1):
                return None
            img = p.shot()
            c = colours(img, image_box(img))
            return (img, c) if c["red"] >= 100 and c["green"] >= 100 else None

        img, c = p.wait("lesson 9's two triangles in (u, v)", shown, 120) or (p.shot(), None)
        with open(os.path.join(p.out, "mesh-lesson.png"), "wb") as f:
            f.write(img.png)
        c, s = c or colours(img, image_box(img)), p.status()
        fetched = any(path == "/" + MESH for _, path, _ in Counting.sent)
        print(f"  lesson 9's mesh fetched when the lesson opened: {fetched}; (u, v) shown: {c}")
        if s.get("error") or not fetched or c["red"] < 100 or c["green"] < 100:
            p.fail(f"lesson 9 should show its two triangles' (u, v) in red and green: {c}, "
                   f"{MESH} fetched: {fetched}, the window's error: {s.get('error')!r}")

    # 9. An exercise's Check, on the exercise's own scene.
    p.follow(f"#texplore1-l-{LESSON_6}")
    if p.wait("the link opens lesson 6", lambda: p.status().get("lesson") == LESSON_6, 60):
        p.settled()
        if p.press("Show solution") and p.press("Check"):
            verdict = p.wait("the exercise's verdict", lambda: p.widget("Correct", prefix=True), 60)
            # The formulas' scene restarts the render (unless it has already): then it settles.
            until = time.time() + 10
            while time.time() < until and p.status().get("finished") == 1:
                time.sleep(0.2)
            p.settled()
            img = p.shot("exercise.png")
            if verdict:
                print(f"  Check: {verdict['label'][:70]!r}")
            if not looks_like_earth(img):
                p.fail(f"Check should put the formulas on the Earth: {colours(img)}")

    # 10. A link opening a scene, then a student's own image on the sphere: Browse…, and a drop.
    p.follow("#" + scene_link("earth.ron"))
    # Check's formulas are the student's own change: the page asks before it drops them.
    if p.wait("the scene link asks before dropping Check's formulas",
              lambda: p.widget("Discard changes"), 20):
        p.press("Discard changes")
    if p.wait("the scene link opens the Earth (the lesson ends)", lambda: p.status().get("lesson") == "", 60):
        p.settled()
        if not p.widget("Browse…"):
            p.press("Scene")
        red = png_encode_rgb(64, 32, lambda x, y: (220, 30, 30) if (x // 8) % 2 else (240, 240, 240))
        path = os.path.join(p.out, "my-image.png")
        with open(path, "wb") as f:
            f.write(red)
        # Where the click counts as the user's (Chromium), the page clicks its file input and
        # the browser's own chooser opens, which WebDriver cannot reach (headless Chromium
        # cancels it at once); the input then waits for the file as it does without a chooser.
        d.js(NO_CHOOSER_SCRIPT)
        if p.press("Browse…"):
            field = p.wait("the page's file input", lambda: d.js("return !!document.getElementById('rfd-input')"), 10)
            if field:
                d.send_keys(d.find_css("#rfd-input"), path)
                got = p.wait("the chosen image on the sphere",
                             lambda: colours(p.shot())["red"] > 300, 120)
                p.settled()
                img = p.shot("upload.png")
                print(f"  Browse…: my-image.png on the sphere: {colours(img)}")
                if not got:
                    p.fail("the image chosen with Browse… did not reach the sphere")
        green = png_encode_rgb(64, 32, lambda x, y: (30, 200, 40) if (y // 8) % 2 else (240, 240, 240))
        d.js(DROP_SCRIPT, base64.b64encode(green).decode(), "dropped.png")
        got = p.wait("the dropped image on the sphere", lambda: colours(p.shot())["green"] > 300, 120)
        p.settled()
        img = p.shot("drop.png")
        print(f"  drop: dropped.png on the sphere: {colours(img)}")
        if not got:
            p.fail("the image dropped on the page did not reach the sphere")

    # 11. No error or warning from the page.
    logged = d.js("return globalThis.texploreConsole || []") or []
    entries = d.chromium_console()
    if entries is not None:
        logged += [f"{e.get('level')}: {e.get('message')}" for e in entries
                   if e.get("level") in ("SEVERE", "WARNING") and e.get("source") in ("console-api", "javascript")]
    for line in dict.fromkeys(logged):
        if any(e in line for e in ENVIRONMENT):
            print(f"  console (this machine has no GPU): {line[:120]}")
        else:
            p.fail(f"console: {line}")
    return figures


def lesson_preset(lesson):
    """The file name of the preset lesson `lesson` (lessons/NAME.toml) starts on."""
    with open(os.path.join(ROOT, "lessons", lesson + ".toml"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("preset"):
                return os.path.basename(line.split("=", 1)[1].strip().strip('"'))
    raise ValueError(f"lessons/{lesson}.toml names no preset")


def bench(p, url, workers, runs, lessons=()):
    """The Earth (or each lesson in `lessons`, opened by its link on its own scene) rendered to
    its scene's samples per pixel with each number of workers, `runs` times each (scenes and
    counts alternated, so a busy minute spreads over all): the status line's rays per second,
    the time to the last pass, the window's frames per second meanwhile and each worker's
    memory."""
    scenes = [(lesson, lesson_preset(lesson)) for lesson in lessons] or [("", "")]
    results = {(name, n): [] for name, _ in scenes for n in workers}
    for r in range(runs):
        for name, preset in scenes:
            for n in workers:
                what = f"lesson {name}" if name else "the Earth"
                p.d.go("about:blank")
                p.d.go(f"{url}?workers={n}" + (f"#texplore1-l-{name}" if name else ""))
                if not p.started():
                    continue
                # A lesson's scene replaces the Earth once the link is read and its files are in:
                # wait for its preset (builds before the status named the scene: the lesson,
                # then a moment for its scene to build), then for a render of it under way.
                if name and not p.wait(f"{what} opens on {preset}",
                                       lambda: p.status().get("lesson") == name
                                       and p.status().get("scene", preset).endswith(preset), 120):
                    continue
                if name and "scene" not in p.status():
                    time.sleep(3)
                p.wait("a render under way", lambda: p.status().get("spp") is not None, 120)
                s0, t0 = p.status(), time.time()
                if not p.settled(300):
                    continue
                s1, t1 = p.status(), time.time()
                fps = (s1.get("frames", 0) - s0.get("frames", 0)) / max(t1 - t0, 1e-3)
                memory = [round(m / 1e6, 1) for m in s1.get("workerMemory", [])]
                film = f"{s1.get('filmWidth', 0):.0f}x{s1.get('filmHeight', 0):.0f}"
                results[(name, n)].append((s1["raysPerSecond"], s1["elapsed"], fps, memory))
                print(f"  run {r + 1}, {what}, {n} workers: {s1['raysPerSecond'] / 1e6:.2f} M rays/s, "
                      f"{s1.get('spp', 0):.0f} spp at {film} after {s1['elapsed']:.1f} s, {fps:.1f} frames/s, "
                      f"worker memory {memory} MB (load {os.getloadavg()[0]:.1f})")
                if name:
                    p.shot(f"bench-{name}-{n}.png")
    for (name, n), rs in results.items():
        if rs:
            med = sorted(x[0] for x in rs)[len(rs) // 2]
            lo, hi = min(x[0] for x in rs), max(x[0] for x in rs)
            el = sorted(x[1] for x in rs)[len(rs) // 2]
            fps = sorted(x[2] for x in rs)[len(rs) // 2]
            print(f"{f'lesson {name}' if name else 'the Earth'}, {n} workers: median {med / 1e6:.2f} M rays/s "
                  f"({lo / 1e6:.2f}-{hi / 1e6:.2f}, {len(rs)} runs), last pass after {el:.1f} s, {fps:.1f} frames/s")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--site", default=os.path.join(ROOT, "target", "web"))
    ap.add_argument("--out", default=os.path.join(ROOT, "target", "web-smoke"))
    ap.add_argument("--browser", choices=["chromium", "firefox", "both"], default="both")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    ap.add_argument("--firefox", default="/usr/bin/firefox-esr")
    ap.add_argument("--geckodriver", default="geckodriver")
    ap.add_argument("--bench", metavar="N,N,...",
                    help="instead of the checks, time the Earth's render with these numbers of workers "
                         "(0: on the page's thread alone)")
    ap.add_argument("--runs", type=int, default=3, help="--bench: runs per number of workers")
    ap.add_argument("--lesson", action="append", default=[], metavar="NAME",
                    help="--bench: time this lesson's own scene (lessons/NAME.toml, opened by its link) "
                         "instead of the Earth; repeat for several")
    ap.add_argument("--update-reference", action="store_true",
                    help="write Chromium's settled screenshot as web/smoke-earth.png")
    a = ap.parse_args()
    # WebDriver takes only absolute paths for a file input, and the checkout's own target/ is
    # relative when CARGO_TARGET_DIR is unset (as on CI).
    a.site, a.out = os.path.abspath(a.site), os.path.abspath(a.out)
    failures = {}

    handler = functools.partial(Counting, directory=a.site)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", free_port()), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/index.html"

    browsers = ["chromium", "firefox"] if a.browser == "both" else [a.browser]
    for name in browsers:
        print(f"== {name}")
        out = os.path.join(a.out, name)
        os.makedirs(out, exist_ok=True)
        failures[name] = []
        port = free_port()
        procs = []
        env = dict(os.environ)
        try:
            if name == "chromium":
                procs.append(subprocess.Popen([a.chromedriver, f"--port={port}"],
                                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
                caps = chromium_session(port, a.chromium)
            else:
                # Firefox has no WebGL2 fully headless here: a virtual display of its own.
                xvfb = subprocess.Popen(["Xvfb", "-displayfd", "1", "-screen", "0", "1920x1200x24",
                                         "-nolisten", "tcp"], stdout=subprocess.PIPE,
                                        stderr=subprocess.DEVNULL)
                procs.append(xvfb)
                env["DISPLAY"] = ":" + xvfb.stdout.readline().decode().strip()
                env.pop("MOZ_HEADLESS", None)
                procs.append(subprocess.Popen([a.geckodriver, f"--port={port}", "--log", "error"], env=env,
                                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
                caps = firefox_session(a.firefox)
            driver = Driver(port)
            driver.wait_ready()
            driver.start(caps)
            try:
                driver.go("about:blank")
                driver.size_viewport(WIDTH, HEIGHT)
                page = Page(driver, out, failures[name])
                if a.bench:
                    bench(page, url, [int(n) for n in a.bench.split(",")], a.runs, a.lesson)
                else:
                    run_checks(page, url, name, a.update_reference and name == "chromium")
            finally:
                driver.quit()
        except Exception as e:  # noqa: BLE001 - reported as this browser's failure
            failures[name].append(f"{type(e).__name__}: {e}")
        finally:
            for proc in reversed(procs):
                proc.terminate()
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.kill()
    server.shutdown()

    failed = False
    for name, fs in failures.items():
        for f in fs:
            print(f"FAIL ({name}): {f}", file=sys.stderr)
        print(f"web smoke test in {name}: " + ("FAILED" if fs else "passed"))
        failed |= bool(fs)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
