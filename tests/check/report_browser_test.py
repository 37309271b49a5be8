#!/usr/bin/env python3
"""Opens a `tessera check` report with failing scenes in headless Chromium and
asserts on what its script made of the page: the rows and their order, images
that really loaded, the slider/flicker toggle and the pixel zoom. Writes
screenshots beside the report. Skips (exit 77) where Chromium is absent.

usage: report_browser_test.py TESSERA WORK_DIR

Chromium is driven through the DevTools protocol over a pipe
(--remote-debugging-pipe: JSON messages ending in NUL on fds 3 and 4), so
nothing listens on the network and no package beyond Debian's chromium is needed.
"""
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

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
             "--user-data-dir=" + profile, "--remote-debugging-pipe", "--window-size=1400,1000", "about:blank"],
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

    def wait_for(self, expression, what, seconds=20):
        deadline = time.time() + seconds
        while time.time() < deadline:
            if self.js(expression):
                return
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {what}: {expression}")

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
        check(browser.js("[...document.querySelectorAll('img')].every(i => i.loading === 'lazy')"), "every image is lazy")
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
        print("screenshots:", ", ".join(os.path.join(work, f) for f in ("report.png", "report_slider.png", "report_zoom.png")))
    finally:
        browser.stop()
        shutil.rmtree(profile, ignore_errors=True)
        log.close()
    if failures:
        sys.exit(f"{len(failures)} browser checks failed")
    print("the report works in Chromium")


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
if __name__ == "__main__":
    if not CHROMIUM:
        print("skipped: no chromium on PATH (tools/install_dependencies.sh installs Debian's chromium)")
        sys.exit(SKIP)
    if not shutil.which("oiiotool"):
        print("skipped: no oiiotool (openimageio-tools) to make the failing golden")
        sys.exit(SKIP)
    main()
