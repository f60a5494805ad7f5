#!/usr/bin/env python3
"""Browser test of `feint collect`: headless Chromium plays a whole session as a person would.

It presses the arrow keys (WebDriver key actions), reloads the page in the middle of a round,
answers the questionnaire and reaches the completion page. Then it checks the log (20 analysed
rounds, practice rounds apart, the trace agrees with the keys pressed and the pad speed, `feint
score` finds no overspeed segment) and runs `feint analyze` on the study folder.

Usage: collect_browser.py FEINT_EXE [--screenshots DIR] [--json FILE]
Exit 77 (skipped) when chromium, chromedriver or a free loopback port are missing.
Only python3's standard library is used (urllib + json talk to chromedriver).
"""
import csv
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import urllib.request

from webdriver import WebDriver, free_port

SKIP = 77
ARROW = {"right": "\ue014", "left": "\ue012"}
PAD_SPEED = 0.8


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def start_browser(wd, binary, profile, size):
    wd.new_session({"browserName": "chrome", "goog:chromeOptions": {
        "binary": binary,
        "args": ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage", f"--user-data-dir={profile}", f"--window-size={size}"]}})


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 64
    feint = sys.argv[1]
    shots = sys.argv[sys.argv.index("--screenshots") + 1] if "--screenshots" in sys.argv else None
    json_out = sys.argv[sys.argv.index("--json") + 1] if "--json" in sys.argv else None
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_exe = shutil.which("chromedriver")
    if not chromium or not driver_exe:
        skip("chromium and chromedriver are needed (Debian: apt-get install chromium chromium-driver)")

    work = tempfile.mkdtemp(prefix="feint-collect-browser-")
    study = os.path.join(work, "study")
    os.makedirs(study)
    with open(os.path.join(study, "feint.toml"), "w") as f:
        # Fast robot so that 22 rounds take half a minute; everything else as in the paper.
        f.write('[collect]\nrobot-speed = 6\ncompletion-url = "http://127.0.0.1:9/done?cc=C0DE"\n'
                'consent = "You may stop at any time."\n')
    procs = []
    wd = None
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
        start_browser(wd, chromium, os.path.join(work, "profile"), "1000,1000")
        base = f"http://127.0.0.1:{port}"
        wd.s("POST", "/url", {"url": base + "/?participant=BT1"})
        wd.wait("return document.body.dataset.state === 'consent'", what="consent")
        wd.click("#agree")

        plan = {}   # (kind, iteration) -> (direction, hold seconds)
        intervals = []
        reloaded = False
        n = 0
        while True:
            state = wd.wait("var s = document.body.dataset.state, r = document.body.dataset.round;"
                            "return (s === 'game' && r === 'ready' && !document.getElementById('start').disabled)"
                            " || s === 'questionnaire' ? s : null", what="a round or the questionnaire")
            if state == "questionnaire":
                break
            n += 1
            direction = "right" if n % 2 else "left"
            hold = 0.15 + 0.05 * (n % 5)  # 0.15 .. 0.35 s
            wd.click("#start")
            rnd = wd.wait("return document.body.dataset.round === 'running' && window.__feint && "
                          "document.getElementById('progress').textContent", what="round running")
            if n == 1 and shots:  # a practice round (not checked below): the pad mid-way
                wd.keys([{"type": "keyDown", "value": ARROW["right"]}, {"type": "pause", "duration": 220}])
                wd.screenshot(os.path.join(shots, "collect-game.png"))
                wd.release()
            if not reloaded and rnd.startswith("Round 5 "):
                # A reload in the middle of a round: the key is still held when the page goes.
                wd.keys([{"type": "keyDown", "value": ARROW["right"]}, {"type": "pause", "duration": 150}])
                wd.s("POST", "/refresh", {})
                wd.release()
                reloaded = True
                continue
            if n == 2:  # the second practice round with the on-screen button, as on a touch screen
                x, y = wd.js("var r = document.getElementById('right').getBoundingClientRect();"
                             "return [Math.round(r.left + r.width / 2), Math.round(r.top + r.height / 2)];")
                wd.s("POST", "/actions", {"actions": [{"type": "pointer", "id": "finger",
                     "parameters": {"pointerType": "mouse"}, "actions": [
                         {"type": "pointerMove", "origin": "viewport", "x": x, "y": y},
                         {"type": "pointerDown", "button": 0}, {"type": "pause", "duration": 250},
                         {"type": "pointerUp", "button": 0}]}]})
                wd.release()
                wd.wait("return document.body.dataset.round !== 'running'", what="round end")
                continue
            wd.keys([{"type": "keyDown", "value": ARROW[direction]},
                     {"type": "pause", "duration": int(hold * 1000)},
                     {"type": "keyUp", "value": ARROW[direction]}])
            wd.wait("return document.body.dataset.round !== 'running'", what="round end")
            trace = wd.js("var t = window.__feint.lastTrace; var i = window.__feint.intervals;"
                          "window.__feint.intervals = []; return [t && t.kind, t && t.iteration, i, t && t.keys];")
            intervals += trace[2]
            plan[(trace[0], trace[1])] = (direction, hold, trace[3])
        # The questionnaire, as a person fills it in.
        for item, v in [("entertainment", 6), ("deception", 5), ("intelligence", 7), ("trust", 2)]:
            wd.click(f"#{item}-{v}")
        wd.click("#intentional-yes")
        wd.click("#qsubmit")
        wd.wait("return document.body.dataset.state === 'done'", what="completion page")
        href = wd.js("return document.getElementById('completion-link').href")
        assert href == "http://127.0.0.1:9/done?cc=C0DE", href
        if shots:
            for other in ["P02", "P03", "P04"]:  # a few more people, so that the table shows something
                urllib.request.urlopen(urllib.request.Request(
                    f"{base}/api/join?participant={other}", data=b"", method="POST")).read()
            wd.s("POST", "/url", {"url": base + "/admin?token=tok"})
            wd.wait("return document.querySelector('table') !== null", what="admin page")
            wd.screenshot(os.path.join(shots, "collect-admin.png"))
    finally:
        if wd:
            wd.quit()
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()

    failures = []

    def check(cond, what):
        if not cond:
            failures.append(what)

    # ---- the log ----
    rows = read_rows(os.path.join(study, "logs", "BT1.csv"))
    iterations = sorted({int(r["iteration"]) for r in rows})
    check(iterations == list(range(1, 21)), f"20 analysed rounds in logs/BT1.csv, got {iterations}")
    practice = read_rows(os.path.join(study, "practice", "BT1.csv"))
    check(sorted({int(r["iteration"]) for r in practice}) == [1, 2], "2 practice rounds in practice/")
    check({r["strategy"] for r in practice} == {"optimal"}, "practice rounds use the optimal strategy")
    button = [float(r["pad"]) for r in practice if r["iteration"] == "2"]
    check(0.5 + 0.8 * 0.15 < button[-1] < 0.5 + 0.8 * 0.5,
          f"practice round 2: the on-screen button held 0.25 s moved the pad to {button[-1]}")
    events = open(os.path.join(study, "collect", "events.csv")).read()
    check(",BT1,interrupted," in events, "the reload mid-round is recorded as an interruption")
    worst = 0.0
    for it in range(1, 21):
        tr = [r for r in rows if int(r["iteration"]) == it]
        t = [float(r["t"]) for r in tr]
        pad = [float(r["pad"]) for r in tr]
        direction, hold, keys = plan[("main", it)]
        moved = pad[-1] - 0.5
        check((moved > 0) == (direction == "right"), f"round {it}: pad moved {moved:+.3f}, key {direction}")
        # The key events as the page saw them: WebDriver delivered the intended hold (give or take
        # the scheduling of a loaded machine) ...
        downs = [k[0] for k in keys if k[1] == direction and k[2]]
        ups = [k[0] for k in keys if k[1] == direction and not k[2]]
        seen = (ups[-1] if ups else t[-1]) - (downs[0] if downs else 0.0)
        worst = max(worst, abs(seen - hold))
        check(len(downs) == 1 and abs(seen - hold) < 0.25,
              f"round {it}: key {direction} held {hold:.3f} s by WebDriver, page saw {keys}")
        # ... and the logged trace is exactly the pad speed integrated over the held keys.
        state = {"left": False, "right": False}
        p, last, k = 0.5, 0.0, 0
        events = sorted((e for e in keys if e[0] > 0), key=lambda e: e[0])
        for k0 in keys:
            if k0[0] == 0:
                state[k0[1]] = k0[2]
        for ti, pi in zip(t, pad):
            while k < len(events) and events[k][0] <= ti:
                d = (1 if state["right"] else 0) - (1 if state["left"] else 0)
                p = min(1.0, max(0.0, p + d * PAD_SPEED * (events[k][0] - last)))
                last = events[k][0]
                state[events[k][1]] = events[k][2]
                k += 1
            d = (1 if state["right"] else 0) - (1 if state["left"] else 0)
            p = min(1.0, max(0.0, p + d * PAD_SPEED * (ti - last)))
            last = ti
            if abs(p - pi) > 1e-9:
                check(False, f"round {it}: at t = {ti} the log has pad {pi}, the keys give {p}")
                break
        speeds = [abs(pad[i + 1] - pad[i]) / (t[i + 1] - t[i]) for i in range(len(t) - 1)]
        check(max(speeds) <= PAD_SPEED * (1 + 1e-6), f"round {it}: faster than the pad speed")
    # ---- feint score and feint analyze on the folder ----
    scores = os.path.join(work, "scores.csv")
    r = subprocess.run([feint, "score", os.path.join(study, "logs"), "-o", scores], capture_output=True, text=True)
    check(r.returncode == 0, f"feint score: {r.stderr}")
    if r.returncode == 0:
        sc = read_rows(scores)
        check(len(sc) == 20, f"feint score: {len(sc)} trials")
        check(all(s["overspeed_segments"] == "0" for s in sc), "feint score finds overspeed segments")
    r = subprocess.run([feint, "analyze", study, "-o", os.path.join(work, "out")], capture_output=True, text=True)
    check(r.returncode == 0, f"feint analyze: {r.stderr}")
    check(os.path.exists(os.path.join(work, "out", "likert_summary.csv")), "feint analyze read the questionnaire")

    iv = sorted(intervals)
    med = statistics.median(iv) if iv else float("nan")
    p99 = iv[min(len(iv) - 1, int(0.99 * len(iv)))] if iv else float("nan")
    print(f"sampling interval in headless Chromium: median {med:.2f} ms, p99 {p99:.2f} ms "
          f"({len(iv)} frames); WebDriver key-hold timing off by at most {worst * 1000:.0f} ms")
    if json_out:
        with open(json_out, "w") as f:
            json.dump({"frames": len(iv), "median_ms": med, "p99_ms": p99}, f)
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        print(f"(study folder kept: {study})")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("OK: 20 rounds played with the keys, reload resumed, questionnaire saved, feint analyze ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
