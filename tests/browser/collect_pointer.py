#!/usr/bin/env python3
"""Browser test of `feint collect` with K = 3 targets and the belief as a point held on the map.

Headless Chromium plays a few rounds as two people would: one with the mouse in a 1280 px wide
window, one with a finger (WebDriver touch actions) in a 390 px wide one. Each holds the pointer on
a point of the map, moves it, and lets go before the end in some rounds. Then the logs on disk are
checked: the K-target columns, the trial's layout constant within it, every belief point inside the
map, t = 0 at the first touch and at the point touched, samples at the study's sample rate, the
point held after a release, the robot at the true target at the end.

Usage: collect_pointer.py FEINT_EXE [--screenshots DIR]
Exit 77 (skipped) when chromium or chromedriver is missing.
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
K = 3
RATE = 25.0


def start_browser(wd, binary, profile, size, mobile=False):
    opts = {"binary": binary,
            "args": ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                     "--disable-background-networking", "--disable-component-update",
                     "--disable-sync", "--disable-dev-shm-usage", f"--user-data-dir={profile}",
                     f"--window-size={size}"]}
    if mobile:  # a phone: 390 css px wide, touch
        w, h = (int(v) for v in size.split(","))
        opts["mobileEmulation"] = {"deviceMetrics": {"width": w, "height": h, "pixelRatio": 2,
                                                     "touch": True}}
    wd.new_session({"browserName": "chrome", "goog:chromeOptions": opts})


def pointer(wd, kind, steps, release=True):
    """Pointer actions on map points: steps are ("down"|"move", x, y, pause ms)."""
    acts = []
    for what, x, y, pause in steps:
        cx, cy = wd.js("return window.__feint.toClient(arguments[0], arguments[1]);", x, y)
        acts.append({"type": "pointerMove", "origin": "viewport", "x": int(round(cx)),
                     "y": int(round(cy)), "duration": 0})
        if what == "down":
            acts.append({"type": "pointerDown", "button": 0})
        acts.append({"type": "pause", "duration": pause})
    if release:
        acts.append({"type": "pointerUp", "button": 0})
    wd.s("POST", "/actions", {"actions": [{"type": "pointer", "id": "p-" + kind,
                                            "parameters": {"pointerType": kind}, "actions": acts}]})


held_at_shot = {}


def play(wd, base, pid, kind, shots, shot_name):
    """Plays every round of `pid`; returns {(kind, iteration): (steps, released early)}."""
    wd.s("POST", "/url", {"url": f"{base}/?participant={pid}"})
    plan = {}
    n = 0
    while True:
        state = wd.wait("var s = document.body.dataset.state, r = document.body.dataset.round;"
                        "return (s === 'game' && r === 'ready' && !document.getElementById('start').disabled)"
                        " || s === 'questionnaire' ? s : null", what="a round or the questionnaire")
        if state == "questionnaire":
            return plan
        n += 1
        wd.click("#start")
        wd.wait("return document.body.dataset.round === 'waiting'", what="the map, waiting for a touch")
        rnd = wd.js("var r = window.__feint; return [document.getElementById('progress').textContent];")
        steps = [("down", -1.5 + 0.5 * n, 3.0, 250), ("move", 1.0, 2.0 + 0.3 * n, 250),
                 ("move", 0.5, 4.0, 200)]
        early = n % 2 == 0  # every other round: let go before the end; the last point holds
        if n == 1 and shots:
            pointer(wd, kind, steps[:2], release=False)
            held_at_shot[pid] = wd.js("return window.__feint.held();")
            wd.screenshot(os.path.join(shots, shot_name))
            wd.release()
            early = True
            steps = steps[:2]
        else:
            pointer(wd, kind, steps, release=early)
        wd.wait("return document.body.dataset.round !== 'running'", timeout=30, what="round end")
        if not early:
            wd.release()
        t = wd.js("var t = window.__feint.lastTrace; return [t.kind, t.iteration];")
        plan[(t[0], t[1])] = (steps, early, rnd[0])


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 64
    feint = sys.argv[1]
    shots = sys.argv[sys.argv.index("--screenshots") + 1] if "--screenshots" in sys.argv else None
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_exe = shutil.which("chromedriver")
    if not chromium or not driver_exe:
        print("SKIPPED: chromium and chromedriver are needed")
        return SKIP
    work = tempfile.mkdtemp(prefix="feint-collect-pointer-")
    study = os.path.join(work, "study")
    os.makedirs(study)
    with open(os.path.join(study, "feint.toml"), "w") as f:
        # A slow enough robot that the scripted pointer acts inside the round.
        f.write('[collect]\nrobot-speed = 2\niterations = 3\npractice = 1\nyes-no = ""\n'
                f'targets = {K}\nlayout = "random"\n')
    procs, wd = [], None
    plans = {}
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
        base = f"http://127.0.0.1:{port}"
        dport = free_port()
        procs.append(subprocess.Popen([driver_exe, f"--port={dport}"], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL))
        for pid, kind, size, mobile, shot in [("M1", "mouse", "1280,900", False, "collect-pointer-1280.png"),
                                              ("T1", "touch", "390,844", True, "collect-pointer-390.png")]:
            wd = WebDriver(dport)
            wd.wait_ready()
            start_browser(wd, chromium, os.path.join(work, "profile-" + pid), size, mobile)
            plans[pid] = play(wd, base, pid, kind, shots, shot)
            wd.quit()
            wd = None
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

    xmin, xmax, ymin, ymax = -4.0, 4.0, -1.0, 6.0  # the map of the default region, 1 m around
    header = (["participant", "condition", "iteration", "strategy", "variant", "target", "t",
               "belief_x", "belief_y", "start_x", "start_y"]
              + [f"target{k}_{c}" for k in range(K) for c in "xy"] + ["robot_x", "robot_y"])
    for pid, plan in plans.items():
        for folder, kind, count in [("practice", "practice", 1), ("logs", "main", 3)]:
            with open(os.path.join(study, folder, pid + ".csv"), newline="") as f:
                rows = list(csv.reader(f))
            check(rows[0] == header, f"{pid} {folder}: header {rows[0]}")
            body = rows[1:]
            its = sorted({int(r[2]) for r in body})
            check(its == list(range(1, count + 1)), f"{pid} {folder}: rounds {its}")
            for it in its:
                tr = [r for r in body if int(r[2]) == it]
                trial = {tuple(r[3:6] + r[9:11 + 2 * K]) for r in tr}
                check(len(trial) == 1, f"{pid} {kind} {it}: the layout changes within the trial")
                t = [float(r[6]) for r in tr]
                x = [float(r[7]) for r in tr]
                y = [float(r[8]) for r in tr]
                check(all(xmin <= a <= xmax and ymin <= b <= ymax for a, b in zip(x, y)),
                      f"{pid} {kind} {it}: a belief point outside the map")
                check(t[0] == 0 and all(b > a for a, b in zip(t, t[1:])), f"{pid} {kind} {it}: times")
                steps = [abs(b - a - 1 / RATE) < 1e-9 for a, b in zip(t[:-2], t[1:-1])]
                check(all(steps), f"{pid} {kind} {it}: samples not at {RATE}/s")
                steps_done, early, _ = plan[(kind, it)]
                sx, sy = steps_done[0][1], steps_done[0][2]
                check(abs(x[0] - sx) < 0.06 and abs(y[0] - sy) < 0.06,
                      f"{pid} {kind} {it}: first sample ({x[0]}, {y[0]}), touched ({sx}, {sy})")
                lx, ly = steps_done[-1][1], steps_done[-1][2]
                if early:  # released: the last point held stays the belief to the end
                    check(abs(x[-1] - lx) < 0.06 and abs(y[-1] - ly) < 0.06,
                          f"{pid} {kind} {it}: last sample ({x[-1]}, {y[-1]}), held ({lx}, {ly})")
                moved = len({(a, b) for a, b in zip(x, y)})
                check(moved >= len(steps_done), f"{pid} {kind} {it}: {moved} distinct points")
                k = int(tr[-1][5])
                check(0 <= k < K and tr[-1][-2:] == tr[-1][11 + 2 * k:13 + 2 * k],
                      f"{pid} {kind} {it}: the robot ends at {tr[-1][-2:]}, not target {k}")
    for pid, held in held_at_shot.items():  # the screenshot shows the point while it is held
        check(held, f"{pid}: the pointer was not held when the screenshot was taken")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        print(f"(study folder kept: {study})")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print(f"OK: K = {K}, pointer rounds played with the mouse (1280 px) and touch (390 px)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
