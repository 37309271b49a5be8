#!/usr/bin/env python3
"""Opens a `tessera check` report with failing scenes in headless Chromium and
asserts on what its script made of the page: the rows and their order, images
that really loaded, the slider/flicker toggle and the pixel zoom; that no image
of an earlier run is left in the report folder; that the folder alone, moved
away from the goldens as a CI artifact is, still shows every image; that the
first screen's large images are painted in the first screenshot (no
decoding="async" there); and that an EXR golden's preview shows the colours of
the render's PNG. Writes screenshots beside the report. Skips (exit 77) where
Chromium is absent.

usage: report_browser_test.py TESSERA WORK_DIR

Chromium is driven through the DevTools protocol over a pipe
(--remote-debugging-pipe: JSON messages ending in NUL on fds 3 and 4), so
nothing listens on the network and no package beyond Debian's chromium is needed.
"""
import base64
import html.parser
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

SKIP = 77


def run(cmd, expect):
    status = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if status.returncode != expect:
        sys.exit(f"{' '.join(cmd)}: exit status {status.returncode}, expected {expect}\n{status.stdout}")


def make_report(tessera, work, scenes):
    """A report with a failure (wrong golden), a small failure (a few pixels), an error, and a pass."""
    golden = os.path.join(work, "golden")
    args = [tessera, "check", os.path.join(scenes, "*.toml"), os.path.join(scenes, "more", "*.toml"),
            "--golden", golden, "--report", os.path.join(work, "report"), "-q"]
    run(args + ["--update=missing"], 1)  # broken.toml stays an error
    shutil.copyfile(os.path.join(golden, "cube.png"), os.path.join(golden, "ball.png"))
    run(["oiiotool", "--pattern", "constant:color=1,0,1", "3x2", "3", os.path.join(golden, "more", "glint.png"),
         "--paste", "+40+30", "-o", os.path.join(golden, "more", "glint.png")], 0)
    run(args, 1)
    return os.path.join(work, "report", "index.html")


def make_exr_report(tessera, work, scenes):
    """A large render (1024x768) against an EXR golden with a bright patch in a corner: a failure whose three
    images fill the first screen."""
    golden = os.path.join(work, "exr_golden")
    args = [tessera, "check", os.path.join(scenes, "ball.toml"), "--golden", golden, "--width", "1024", "--height", "768",
            "--report", os.path.join(work, "exr_report"), "-q"]
    run(args + ["--update=missing", "--new-golden-format", "exr"], 0)
    exr = os.path.join(golden, "ball.exr")
    run(["oiiotool", "--pattern", "constant:color=8,8,8", "40x30", "3", exr, "--paste", "+0+0", "-d", "half",
         "-o", exr], 0)  # the patch (the stack's second image) pasted into the golden
    run(args, 1)
    return os.path.join(work, "exr_report", "index.html")


def png_pixel(path, x, y):
    """The RGB of one pixel of an 8-bit RGB or RGBA, non-interlaced PNG (Chromium's screenshots)."""
    data = open(path, "rb").read()
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and body[12] == 0, "8-bit, non-interlaced"
            channels = {2: 3, 6: 4}[color]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, previous = zlib.decompress(idat), width * channels, bytearray(width * channels)
    for row in range(y + 1):
        kind, line = raw[row * (stride + 1)], bytearray(raw[row * (stride + 1) + 1:(row + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        previous = line
    return tuple(previous[x * channels:x * channels + 3])


class Sources(html.parser.HTMLParser):
    """Every src and href of a page."""

    def __init__(self):
        super().__init__()
        self.links = []

    def handle_starttag(self, tag, attrs):
        self.links += [value for name, value in attrs if name in ("src", "href") and value]


class Chromium:
    """One headless Chromium, driven over --remote-debugging-pipe; always stopped by its PID."""

    def __init__(self, profile, log):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()

        def child_fds():  # the protocol's fds: 3 reads commands, 4 writes replies
            os.dup2(to_browser_r, 3)
            os.dup2(from_browser_w, 4)

        self.process = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--user-data-dir=" + profile, "--remote-debugging-pipe",
             "--allow-file-access-from-files",  # file:// images may be read back through a canvas
             "--window-size=1400,1000", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=log,
            # close_fds would run after preexec_fn and close 3 and 4 again
            preexec_fn=child_fds, close_fds=False)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.next_id = 0
        self.buffer = b""
        self.session = None

    def send(self, method, params=None, session=True):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        while True:  # replies and events share the pipe: skip events
            while b"\0" not in self.buffer:
                chunk = os.read(self.from_browser, 1 << 20)
                if not chunk:
                    raise RuntimeError("chromium closed the DevTools pipe")
                self.buffer += chunk
            raw, self.buffer = self.buffer.split(b"\0", 1)
            reply = json.loads(raw)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})

    def open(self, url):
        target = self.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True}, session=False)["sessionId"]
        self.send("Page.enable")
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": 1400, "height": 1000, "deviceScaleFactor": 1, "mobile": False})
        self.send("Page.navigate", {"url": url})

    def js(self, expression):
        result = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, expression, what, seconds=60):  # generous: CI machines are busy
        deadline = time.time() + seconds
        while time.time() < deadline:
            if self.js(expression):
                return
            time.sleep(0.1)
        state = self.js("[document.URL, document.readyState, document.images.length]")
        raise AssertionError(f"timed out waiting for {what}: {expression} (page: {state})")

    def click(self, selector):
        box = self.js(f"(() => {{ const e = document.querySelector({json.dumps(selector)}); e.scrollIntoView({{block: 'center'}});"
                      " const r = e.getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2]; })()")
        for kind in ("mousePressed", "mouseReleased"):  # a real click: hit-testing, events, default actions
            self.send("Input.dispatchMouseEvent", {"type": kind, "x": box[0], "y": box[1], "button": "left", "clickCount": 1})

    def screenshot(self, path):
        with open(path, "wb") as out:
            out.write(base64.b64decode(self.send("Page.captureScreenshot", {"format": "png"})["data"]))

    def stop(self):
        try:
            self.send("Browser.close", session=False)
            self.process.wait(timeout=10)
        except Exception:
            pass
        if self.process.poll() is None:
            self.process.kill()  # by its PID, never by name
            self.process.wait()
        os.close(self.to_browser)
        os.close(self.from_browser)


failures = []


def check(condition, what):
    print(("ok     " if condition else "FAILED ") + what)
    if not condition:
        failures.append(what)


def main():
    tessera, work = sys.argv[1], sys.argv[2]
    scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    report = make_report(tessera, work, scenes)
    profile = tempfile.mkdtemp(prefix="tessera-chromium-")
    log = open(os.path.join(work, "chromium.log"), "w")
    browser = Chromium(profile, log)
    try:
        browser.open("file://" + report)
        browser.wait_for("document.readyState === 'complete' && document.body.dataset.ready === 'true'", "the report's script")

        rows = browser.js("[...document.querySelectorAll('.scene')].map(s => [s.dataset.name, s.dataset.status])")
        print("rows:", rows)
        check(rows == [["broken", "error"], ["ball", "fail"], ["more/glint", "fail"], ["cube", "pass"]],
              "rows: errors first, then failures worst first (the wrong golden before the 6 wrong pixels), then passes")
        check(browser.js("document.title") == "tessera check: 3 of 4 not passing", "title counts what is not passing")
        check("6 pixels differ" in browser.js("document.querySelector('#scene-more\\\\/glint .reason').textContent"),
              "the small failure's reason counts its 6 pixels")

        visible_images = "[...document.querySelectorAll('.side img')].filter(i => i.getBoundingClientRect().top < innerHeight)"
        browser.wait_for(f"{visible_images}.every(i => i.complete)", "the images in view to load")
        loaded = browser.js(f"{visible_images}.map(i => [i.alt, i.naturalWidth, i.naturalHeight])")
        print("images in view:", loaded)
        check(len(loaded) >= 3 and all(w == 96 and h == 64 for _, w, h in loaded),
              "every image in view loaded from disk at its size (96x64)")
        attributes = browser.js("[...document.querySelectorAll('.scene')].map((row, i) => [i, [...row.querySelectorAll('.side img')]"
                                ".map(img => [img.loading, img.getAttribute('decoding')])])")
        print("loading, decoding per row:", attributes)
        check(all(a == ["eager", "sync"] for i, imgs in attributes[:3] for a in imgs) and
              all(a == ["lazy", "async"] for i, imgs in attributes[3:] for a in imgs),
              "the first screen's rows load eagerly and decode synchronously (no decoding=async), later rows lazily")
        browser.js("document.querySelector('#scene-cube').scrollIntoView()")
        browser.wait_for("(i => i.complete && i.naturalWidth === 96)(document.querySelector('#scene-cube img'))",
                         "the passing row's image (linked golden) to load when scrolled to")
        browser.js("scrollTo(0, 0)")

        row = "#scene-ball"
        check(browser.js(f"document.querySelector('{row} .stack').offsetHeight === 0 && document.querySelector('{row} .side').offsetHeight > 0"),
              "side by side at first")
        browser.click(f"{row} .modes button[data-mode=slider]")
        check(browser.js(f"document.querySelector('{row}').dataset.mode") == "slider", "clicking 'slider' switches the row")
        check(browser.js(f"document.querySelector('{row} .side').offsetHeight === 0 && document.querySelector('{row} .stack').offsetHeight > 0"),
              "the slider view shows, the side-by-side hides")
        check(browser.js(f"document.querySelector('{row} img.over').style.clipPath") == "inset(0px 50% 0px 0px)",
              "the slider starts half way")
        browser.js(f"(s => {{ s.value = 80; s.dispatchEvent(new Event('input')); }})(document.querySelector('{row} .stack input'))")
        check(browser.js(f"document.querySelector('{row} img.over').style.clipPath") == "inset(0px 20% 0px 0px)",
              "moving the slider moves the split")
        check(browser.js("document.querySelector('#scene-more\\\\/glint').dataset.mode") == "side", "other rows keep their view")
        browser.screenshot(os.path.join(work, "report_slider.png"))

        browser.click(f"{row} .modes button[data-mode=flicker]")
        shown = set()
        for _ in range(8):
            shown.add(browser.js(f"document.querySelector('{row} img.over').style.visibility"))
            time.sleep(0.2)
        check(shown == {"visible", "hidden"}, "flicker alternates expected and actual")

        browser.click("#scene-more\\/glint .side img[alt=diff]")
        check(browser.js("document.getElementById('zoom').open"), "clicking an image opens the zoom")
        check(browser.js("document.querySelectorAll('#zoom .pane img').length") == 3, "the zoom shows expected, actual and diff")
        check(browser.js("document.querySelector('#zoom .pane img').style.width") == "768px", "at 8x (96 px wide image)")
        browser.wait_for("[...document.querySelectorAll('#zoom .pane img')].every(i => i.complete && i.naturalWidth > 0)",
                         "the zoomed images")
        browser.screenshot(os.path.join(work, "report_zoom.png"))
        browser.js("document.getElementById('zoom').close()")
        browser.click("nav button[data-mode=side]")
        browser.js("scrollTo(0, 0)")
        browser.screenshot(os.path.join(work, "report.png"))

        # Stale images: the first run wrote an actual image for every scene; the second left only what it shows.
        report_dir = os.path.dirname(report)
        page = Sources()
        page.feed(open(report).read())
        shown = {os.path.normpath(link) for link in page.links if link != "#"}
        on_disk = {os.path.normpath(os.path.relpath(os.path.join(folder, f), report_dir))
                   for folder, _, files in os.walk(os.path.join(report_dir, "images")) for f in files}
        print("report images on disk:", sorted(on_disk))
        check(on_disk == shown, "the report folder holds exactly the images the page shows (none of the earlier run)")
        check(not os.path.exists(os.path.join(report_dir, "images", "cube.actual.png")),
              "the passing scene's image of the earlier run is gone")

        # The folder alone, as a CI artifact: moved away, the goldens deleted, every image still loads.
        artifact = os.path.join(work, "artifact", "check-report")
        shutil.copytree(report_dir, artifact)
        shutil.rmtree(os.path.join(work, "golden"))
        check(all(not link.startswith(("/", "file:", "..")) and ":" not in link for link in page.links),
              "every link of the page is relative and inside its folder")
        browser.open("file://" + os.path.join(artifact, "index.html"))
        browser.wait_for("document.readyState === 'complete' && document.body.dataset.ready === 'true'", "the moved report")
        browser.js("document.querySelectorAll('img').forEach(i => { i.loading = 'eager'; })")  # load the lazy rows too
        browser.wait_for("[...document.querySelectorAll('img')].every(i => i.complete)", "every image of the moved report")
        broken = browser.js("[...document.querySelectorAll('img')].filter(i => i.naturalWidth === 0).map(i => i.src)")
        check(broken == [], f"the moved folder alone shows every image (broken: {broken})")
    finally:
        browser.stop()
        shutil.rmtree(profile, ignore_errors=True)
        log.close()
    check_exr_report(make_exr_report(tessera, work, scenes), work)
    if failures:
        sys.exit(f"{len(failures)} browser checks failed")
    print("the report works in Chromium")


def check_exr_report(report, work):
    """The first screenshot after load shows the large images (not black boxes), and the EXR golden's preview
    has the colours of the render's PNG where the two agree."""
    log = open(os.path.join(work, "chromium_exr.log"), "w")
    profile = tempfile.mkdtemp(prefix="tessera-chromium-")
    browser = Chromium(profile, log)
    try:
        browser.open("file://" + report)
        browser.wait_for("document.readyState === 'complete' && document.body.dataset.ready === 'true'", "the EXR report")
        shot = os.path.join(work, "report_first_screen.png")
        browser.screenshot(shot)  # at once: no waiting for the images beyond the page's load
        boxes = browser.js("[...document.querySelectorAll('#scene-ball .side img')].map(i => { const r = i.getBoundingClientRect();"
                           " return [i.alt, Math.round(r.left + r.width / 2), Math.round(r.top + r.height / 2)]; })")
        centres = {alt: png_pixel(shot, x, y) for alt, x, y in boxes}
        print("first screenshot, image centres:", centres)
        check(all(max(centres[alt]) > 40 for alt in ("expected", "actual")),
              "the first screenshot shows the large expected and actual images, not black boxes")
        # Colours through the browser's colour management: a canvas gets what the screen would show.
        colours = browser.js("""(() => [...document.querySelectorAll('#scene-ball .side img')].slice(0, 2).map(img => {
            const c = document.createElement('canvas'); c.width = img.naturalWidth; c.height = img.naturalHeight;
            const g = c.getContext('2d'); g.drawImage(img, 0, 0);
            return [[512, 384], [900, 700]].map(([x, y]) => [...g.getImageData(x, y, 1, 1).data.slice(0, 3)]); }))()""")
        print("expected, actual at (512, 384) and (900, 700):", colours)
        expected, actual = colours
        check(all(abs(e - a) <= 2 for pe, pa in zip(expected, actual) for e, a in zip(pe, pa)),
              "the EXR golden's preview shows the render's colours where the radiance agrees (tone-mapped, sRGB)")
    finally:
        browser.stop()
        shutil.rmtree(profile, ignore_errors=True)
        log.close()


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
if __name__ == "__main__":
    if not CHROMIUM:
        print("skipped: no chromium on PATH (tools/install_dependencies.sh installs Debian's chromium)")
        sys.exit(SKIP)
    if not shutil.which("oiiotool"):
        print("skipped: no oiiotool (openimageio-tools) to make the failing golden")
        sys.exit(SKIP)
    main()
