#!/usr/bin/env python3
"""Drives headless Chromium over the DevTools protocol (through --remote-debugging-pipe: no
websocket library needed) for the live page's checks. Usage as a module:

    with Browser() as b:
        page = b.open("file:///.../mechdraw.html")
        page.eval("document.title")
        page.mouse("mousePressed", x, y)
        page.screenshot("shot.png")
"""
import base64, json, os, shutil, subprocess, tempfile, time


def _pipe_fds(read_end, write_end):
    """In the child: the browser reads commands on fd 3 and writes replies on fd 4."""
    import fcntl
    a = fcntl.fcntl(read_end, fcntl.F_DUPFD, 10)
    b = fcntl.fcntl(write_end, fcntl.F_DUPFD, 10)
    os.dup2(a, 3)
    os.dup2(b, 4)


class Page:
    def __init__(self, browser, session):
        self.b, self.session = browser, session

    def call(self, method, **params):
        return self.b.call(method, params, self.session)

    def eval(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expr}: {r['exceptionDetails']}")
        return r["result"].get("value")

    def mouse(self, kind, x, y, buttons=1):
        self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                  buttons=0 if kind == "mouseReleased" else buttons, clickCount=1)

    def touch(self, kind, points):
        """A touch event (touchStart, touchMove, touchEnd) with fingers at `points` [(x, y)]."""
        self.call("Input.dispatchTouchEvent", type=kind, touchPoints=[{"x": x, "y": y} for x, y in points])

    def key(self, key, code=None, modifiers=0, text=None):
        """A key pressed and released (`ArrowRight`, `n`, `z` with modifiers 2 = Ctrl, 8 = Shift)."""
        base = {"key": key, "code": code or key, "modifiers": modifiers}
        vk = {"ArrowLeft": 37, "ArrowUp": 38, "ArrowRight": 39, "ArrowDown": 40, "Tab": 9, "Enter": 13, "Escape": 27}
        if key in vk:
            base["windowsVirtualKeyCode"] = vk[key]
        elif len(key) == 1:
            base["windowsVirtualKeyCode"] = ord(key.upper())
        down = dict(base, type="keyDown")
        if text is not None:
            down["text"] = text
        self.call("Input.dispatchKeyEvent", **down)
        self.call("Input.dispatchKeyEvent", **dict(base, type="keyUp"))

    def errors(self):
        """Console errors and uncaught exceptions the page has reported so far."""
        return list(self.b.errors.get(self.session, []))

    def screenshot(self, path):
        data = self.call("Page.captureScreenshot", format="png")["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))


class Browser:
    def __init__(self, width=1400, height=1000):
        self.profile = tempfile.mkdtemp()
        r1, w1 = os.pipe()  # we write, the browser reads (its fd 3)
        r2, w2 = os.pipe()  # the browser writes (its fd 4), we read
        exe = shutil.which("chromium") or shutil.which("chromium-browser")
        self.proc = subprocess.Popen(
            [exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-dev-shm-usage", f"--user-data-dir={self.profile}",
             f"--window-size={width},{height}", "--remote-debugging-pipe", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            preexec_fn=lambda: _pipe_fds(r1, w2), close_fds=False)
        os.close(r1)
        os.close(w2)
        self.out, self.inp = os.fdopen(w1, "wb"), os.fdopen(r2, "rb")
        self.next_id, self.buf = 0, b""
        # Console errors and exceptions per page session (events read while waiting for replies).
        self.errors = {}

    def call(self, method, params=None, session=None):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        self.out.write(json.dumps(msg).encode() + b"\0")
        self.out.flush()
        while True:
            while b"\0" not in self.buf:
                chunk = os.read(self.inp.fileno(), 1 << 20)
                if not chunk:
                    raise RuntimeError("chromium closed the pipe")
                self.buf += chunk
            raw, self.buf = self.buf.split(b"\0", 1)
            reply = json.loads(raw)
            method_ = reply.get("method")
            if method_ == "Runtime.exceptionThrown":
                d = reply["params"]["exceptionDetails"]
                text = d.get("exception", {}).get("description") or d.get("text")
                self.errors.setdefault(reply.get("sessionId"), []).append(text)
            elif method_ == "Runtime.consoleAPICalled" and reply["params"].get("type") == "error":
                args = reply["params"].get("args", [])
                self.errors.setdefault(reply.get("sessionId"), []).append(" ".join(str(a.get("value", a.get("description"))) for a in args))
            elif method_ == "Log.entryAdded" and reply["params"]["entry"].get("level") == "error":
                self.errors.setdefault(reply.get("sessionId"), []).append(reply["params"]["entry"].get("text"))
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def open(self, url, wait_for="true", timeout=30, setup=None):
        """Opens `url` in a new tab and waits until `wait_for` holds; `setup(page)` runs before
        the navigation (device emulation)."""
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        page = Page(self, session)
        page.call("Page.enable")
        page.call("Runtime.enable")
        page.call("Log.enable")
        if setup:
            setup(page)
        page.call("Page.navigate", url=url)
        end = time.time() + timeout
        while time.time() < end:
            try:
                if page.eval(f"document.readyState === 'complete' && ({wait_for})"):
                    return page
            except RuntimeError:
                pass
            time.sleep(0.05)
        raise RuntimeError(f"{url}: not ready after {timeout} s")

    def __enter__(self):
        return self

    def __exit__(self, *a):
        self.proc.kill()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)
