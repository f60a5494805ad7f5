"""A minimal W3C WebDriver client for the browser tests (check_report.py, collect_browser.py).

Talks to chromedriver on 127.0.0.1 with urllib + json (Python 3 standard library only).
"""
import base64
import json
import shutil
import socket
import time
import urllib.error
import urllib.request


def find(names):
    """The first of `names` found on PATH, or None."""
    for n in names:
        p = shutil.which(n)
        if p:
            return p
    return None


def free_port():
    """A free TCP port on the loopback interface."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class WebDriver:
    """One chromedriver on 127.0.0.1:`port`, and at most one session of it."""

    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.sid = None

    def call(self, method, path, body=None, timeout=60):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=timeout) as r:
                return json.loads(r.read() or b"{}").get("value")
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"WebDriver {method} {path}: {e.code} {e.read()[:500]!r}")

    def wait_ready(self, tries=100):
        """Waits (up to tries x 0.1 s) until chromedriver answers /status."""
        for _ in range(tries):
            try:
                if self.call("GET", "/status", timeout=2).get("ready"):
                    return
            except Exception:
                pass
            time.sleep(0.1)

    def new_session(self, always_match):
        """Starts the browser with the capabilities `always_match`."""
        # chromedriver reaches the browser's DevTools at "localhost": a system where that name does
        # not resolve (no /etc/hosts, as in a bare debootstrap chroot) fails with "unable to connect
        # to renderer". Say so instead of leaving the reader with that message.
        try:
            socket.getaddrinfo("localhost", None)
        except OSError:
            raise RuntimeError("the name 'localhost' does not resolve on this system (is /etc/hosts "
                               "missing?); chromedriver needs it to reach the browser")
        created = self.call("POST", "/session", {"capabilities": {"alwaysMatch": always_match}})
        self.sid = created["sessionId"]

    def s(self, method, path, body=None, timeout=60):
        """A command of the current session."""
        return self.call(method, f"/session/{self.sid}{path}", body, timeout)

    def js(self, script, *args):
        return self.s("POST", "/execute/sync", {"script": script, "args": list(args)})

    def el(self, css):
        v = self.s("POST", "/element", {"using": "css selector", "value": css})
        return list(v.values())[0]

    def click(self, css):
        self.s("POST", f"/element/{self.el(css)}/click", {})

    def keys(self, actions):
        self.s("POST", "/actions",
               {"actions": [{"type": "key", "id": "keyboard", "actions": actions}]})

    def release(self):
        self.s("DELETE", "/actions")

    def wait(self, script, timeout=20.0, what=""):
        """Polls `script` until it returns something true; that value."""
        end = time.time() + timeout
        while time.time() < end:
            v = self.js(script)
            if v:
                return v
            time.sleep(0.02)
        raise RuntimeError(f"timed out waiting for {what or script}")

    def screenshot_png(self):
        return base64.b64decode(self.s("GET", "/screenshot"))

    def screenshot(self, path):
        with open(path, "wb") as f:
            f.write(self.screenshot_png())

    def quit(self):
        """Ends the session (the browser); errors are ignored, as this runs in `finally`."""
        if self.sid:
            try:
                self.call("DELETE", f"/session/{self.sid}")
            except Exception:
                pass
            self.sid = None
