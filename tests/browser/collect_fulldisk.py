#!/usr/bin/env python3
"""`feint collect` on a full disk, in headless Chromium at 1280 px and 390 px.

The server's files are stopped from growing (`prlimit --fsize` on the running server: every
write past that size fails with EFBIG, as ENOSPC on a full disk). The participant finishes a
round: the page says "Could not save, please wait" and keeps retrying; the admin page shows the
red banner. Then the limit is lifted ("space again"): the page's retry saves the round by itself,
the banner goes, and the log has every round exactly once.

Usage: collect_fulldisk.py FEINT_EXE [--screenshots DIR]
Exit 77 (skipped) when chromium, chromedriver or prlimit is missing. Loopback only.
"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import tempfile

from webdriver import WebDriver, free_port

SKIP = 77


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 64
    feint = sys.argv[1]
    shots = sys.argv[sys.argv.index("--screenshots") + 1] if "--screenshots" in sys.argv else None
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_exe = shutil.which("chromedriver")
    prlimit = shutil.which("prlimit")
    if not chromium or not driver_exe or not prlimit:
        print("SKIPPED: chromium, chromedriver and prlimit (util-linux) are needed")
        return SKIP
    work = tempfile.mkdtemp(prefix="feint-collect-fulldisk-")
    study = os.path.join(work, "study")
    os.makedirs(study)
    with open(os.path.join(study, "feint.toml"), "w") as f:
        f.write('[collect]\nrobot-speed = 6\npractice = 1\niterations = 3\n')
    procs, wd, failures = [], None, []

    def check(cond, what):
        if not cond:
            failures.append(what)

    def files():
        out = []
        for root, _, names in os.walk(study):
            out += [os.path.join(root, n) for n in names]
        return out

    try:
        srv = subprocess.Popen([feint, "collect", study, "--port", "0", "--admin-token", "tok"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        procs.append(srv)
        port = None
        for line in srv.stdout:
            if line.startswith("port: "):
                port = int(line.split()[1])
                break
        if not port:
            raise RuntimeError("feint collect did not start")
        dport = free_port()
        drv = subprocess.Popen([driver_exe, f"--port={dport}"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        procs.append(drv)
        wd = WebDriver(dport)
        wd.wait_ready()
        wd.new_session({"browserName": "chrome", "goog:chromeOptions": {
            "binary": chromium,
            "args": ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                     "--disable-background-networking", "--disable-component-update", "--disable-sync",
                     "--disable-dev-shm-usage", f"--user-data-dir={work}/profile", "--window-size=1280,900"]}})
        base = f"http://127.0.0.1:{port}"
        wd.s("POST", "/url", {"url": base + "/?participant=FD1"})
        ready = ("return document.body.dataset.state === 'game' && document.body.dataset.round === 'ready'"
                 " && !document.getElementById('start').disabled")

        def play(hold_ms=200):
            wd.wait(ready, what="a round to start")
            wd.click("#start")
            wd.wait("return document.body.dataset.round === 'running'", what="round running")
            wd.keys([{"type": "keyDown", "value": "\ue014"}, {"type": "pause", "duration": hold_ms},
                     {"type": "keyUp", "value": "\ue014"}])

        play()  # the practice round, saved normally
        wd.wait(ready, what="the practice round saved")
        # The disk is full: no file may grow past the largest one's size now.
        limit = max(os.path.getsize(p) for p in files()) + 400  # an event line, not a round
        subprocess.run([prlimit, f"--pid={srv.pid}", f"--fsize={limit}:unlimited"], check=True)
        play()
        status = wd.wait("return document.body.dataset.saveProblem === '1' && "
                         "document.getElementById('status').textContent", what="the save problem")
        check(status.startswith("Could not save, please wait"), f"the page says: {status!r}")
        if shots:
            wd.screenshot(os.path.join(shots, "collect-fulldisk-1280.png"))
            wd.s("POST", "/window/rect", {"width": 390, "height": 844})
            wd.screenshot(os.path.join(shots, "collect-fulldisk-390.png"))
            wd.s("POST", "/window/rect", {"width": 1280, "height": 900})
        # The admin page, in a second tab of the same browser.
        wd.s("POST", "/window/new", {"type": "tab"})
        handles = wd.s("GET", "/window/handles")
        game = wd.s("GET", "/window")
        wd.s("POST", "/window", {"handle": [h for h in handles if h != game][0]})
        wd.s("POST", "/url", {"url": base + "/admin?token=tok"})
        banner = wd.js("var b = document.getElementById('write-failure');"
                       "return b && [b.textContent, getComputedStyle(b).backgroundColor];")
        check(bool(banner) and "Saving fails" in banner[0], f"the admin banner: {banner}")
        check(bool(banner) and banner[1] == "rgb(201, 42, 42)", f"the banner is red: {banner}")
        if shots:
            wd.screenshot(os.path.join(shots, "collect-admin-fulldisk-1280.png"))
            wd.s("POST", "/window/rect", {"width": 390, "height": 844})
            wd.screenshot(os.path.join(shots, "collect-admin-fulldisk-390.png"))
            wd.s("POST", "/window/rect", {"width": 1280, "height": 900})
        rows = list(csv.DictReader(open(os.path.join(study, "logs", "FD1.csv")))) \
            if os.path.exists(os.path.join(study, "logs", "FD1.csv")) else []
        check(rows == [], f"nothing of the unsaved round is in the log ({len(rows)} rows)")
        # Space again: the page's retry (back-off up to 4 s) saves the round by itself.
        subprocess.run([prlimit, f"--pid={srv.pid}", "--fsize=unlimited:unlimited"], check=True)
        wd.s("POST", "/window", {"handle": game})
        wd.wait("return document.getElementById('status').textContent === 'Saved.'", timeout=15,
                what="the retried save")
        wd.s("POST", "/window", {"handle": [h for h in handles if h != game][0]})
        wd.s("POST", "/url", {"url": base + "/admin?token=tok"})
        check(wd.js("return document.getElementById('write-failure') === null"),
              "the banner is gone once saving works again")
        wd.s("POST", "/window", {"handle": game})
        play()
        play()
        wd.wait("return document.body.dataset.state === 'questionnaire'", what="the questionnaire")
    finally:
        if wd:
            wd.quit()
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
    rows = list(csv.DictReader(open(os.path.join(study, "logs", "FD1.csv"))))
    its = [r["iteration"] for r in rows]
    check(sorted(set(its)) == ["1", "2", "3"], f"rounds 1-3 saved, got {sorted(set(its))}")
    check(all(its[i] <= its[i + 1] for i in range(len(its) - 1)), "rounds in order, none twice")
    check(sum(1 for i in range(1, len(its)) if its[i] != its[i - 1]) == 2, "each round once")
    events = open(os.path.join(study, "collect", "events.csv")).read()
    check(",FD1,server_error," in events, "the failed write is in the events log")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        print(f"(folder kept: {work})")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("OK: full disk -> 'could not save, please wait' + red admin banner; space again -> saved, nothing lost")
    return 0


if __name__ == "__main__":
    sys.exit(main())
