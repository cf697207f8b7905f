#!/usr/bin/env python3
"""A small driver of Chromium through the DevTools protocol over a pipe
(--remote-debugging-pipe: messages are JSON, each ended by a NUL byte, the
browser reading fd 3 and writing fd 4), so tests need no WebSocket library,
no port and no npm package: Debian's chromium and Python's standard library.

    b = Browser(chrome, user_dir, 800, 600)
    s = b.page()                         # the first tab's session
    b.send("Page.navigate", {"url": u}, session=s)
    b.wait(s, "window.lamina && lamina.ready", timeout=60)
    b.eval(s, "lamina.show(3)")
    png = b.screenshot(s)                # bytes of a PNG
    b.close()

Waits poll a condition in the page (never a fixed sleep), up to a timeout
that only bounds a hung browser."""
import base64
import json
import os
import subprocess
import time


class Browser:
    def __init__(self, chrome, user_dir, width=800, height=600, extra=()):
        to_chrome_r, to_chrome_w = os.pipe()
        from_chrome_r, from_chrome_w = os.pipe()
        # dup above 4 first, so the child's dup2 onto 3 and 4 never meets its own source
        src_r, src_w = os.dup(to_chrome_r), os.dup(from_chrome_w)
        os.close(to_chrome_r)
        os.close(from_chrome_w)

        def child():
            os.dup2(src_r, 3)
            os.dup2(src_w, 4)

        args = [chrome, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
                "--force-device-scale-factor=1", "--user-data-dir=" + user_dir,
                "--window-size=%d,%d" % (width, height), "--remote-debugging-pipe"] + list(extra) + ["about:blank"]
        self.proc = subprocess.Popen(args, preexec_fn=child, close_fds=False, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                     env=dict(os.environ, HOME=user_dir))
        os.close(src_r)
        os.close(src_w)
        self.out = os.fdopen(to_chrome_w, "wb", buffering=0)
        self.inp = os.fdopen(from_chrome_r, "rb", buffering=0)
        self.buf = b""
        self.id = 0
        self.events = []

    def _read(self):
        while b"\0" not in self.buf:
            d = self.inp.read(1 << 20)
            if not d:
                raise RuntimeError("the browser closed its pipe")
            self.buf += d
        m, self.buf = self.buf.split(b"\0", 1)
        return json.loads(m)

    def send(self, method, params=None, session=None):
        """one command; its result (events met on the way are kept in .events)"""
        self.id += 1
        msg = {"id": self.id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        self.out.write(json.dumps(msg).encode() + b"\0")
        while True:
            m = self._read()
            if m.get("id") == self.id:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m.get("result", {})
            self.events.append(m)

    def page(self):
        """a session on the browser's first tab"""
        tabs = [t for t in self.send("Target.getTargets")["targetInfos"] if t["type"] == "page"]
        return self.send("Target.attachToTarget", {"targetId": tabs[0]["targetId"], "flatten": True})["sessionId"]

    def eval(self, session, expr):
        """the value of a JavaScript expression (JSON-able), or an exception's text raised"""
        r = self.send("Runtime.evaluate", {"expression": expr, "returnByValue": True, "awaitPromise": True},
                      session=session)
        if "exceptionDetails" in r:
            raise RuntimeError("%s: %s" % (expr, r["exceptionDetails"].get("exception", {}).get("description",
                                                                                               r["exceptionDetails"])))
        return r["result"].get("value")

    def wait(self, session, cond, timeout=120, every=0.02):
        """poll until the expression cond is true in the page; its value, or RuntimeError after timeout s"""
        end = time.monotonic() + timeout
        while True:
            try:
                v = self.eval(session, cond)
            except RuntimeError:
                v = None
            if v:
                return v
            if time.monotonic() > end:
                raise RuntimeError("timed out waiting for " + cond)
            time.sleep(every)

    def screenshot(self, session):
        return base64.b64decode(self.send("Page.captureScreenshot", {"format": "png"}, session=session)["data"])

    def close(self):
        try:
            self.send("Browser.close")
        except (RuntimeError, OSError):
            pass
        try:
            self.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
