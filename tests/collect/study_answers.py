#!/usr/bin/env python3
"""From `feint collect` (defaults) to a study's answers, with no setting made by hand.

Starts `feint collect STUDY` on an empty folder (so it writes the study's feint.toml), plays 24
people through the HTTP API the game uses (join, every round, the questionnaire), stops the server
and runs `feint analyze STUDY -o OUT` with no flag. Then checks what a co-author would: the two
conditions are compared; no reference is off the scores' scale; every computed finding has the
fields of docs/findings.md with finite effect sizes and intervals; results-text.md/.tex exist with
paragraphs of at most 250 words; and no label anywhere reads "≈" without BF01 >= 3 or TOST.

usage: study_answers.py FEINT_EXE WORK_DIR
"""
import csv
import json
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import urllib.request

FEINT, WORK = sys.argv[1], sys.argv[2]
PEOPLE = 24
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def post(port, path, body=""):
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=body.encode(), method="POST")
    with urllib.request.urlopen(req, timeout=30) as r:
        return json.loads(r.read().decode() or "null")


def trace(duration, speed, rng, deceived):
    """A pad trace a person could make: toward the decoy for a while, then to the other side."""
    samples, pad, t = [], 0.5, 0.0
    turn = duration * (rng.uniform(0.3, 0.8) if deceived else rng.uniform(0.0, 0.25))
    first = rng.choice([-1.0, 1.0])
    while t < duration:
        samples.append((t, pad))
        direction = first if t < turn else -first
        if rng.random() < 0.2:
            direction = 0.0  # a pause
        t_next = min(duration, t + 1 / 60)
        pad = min(1.0, max(0.0, pad + direction * 0.9 * speed * (t_next - t)))
        t = t_next
    samples.append((duration, pad))
    return "".join(f"{a!r},{b!r}\n" for a, b in samples)


def play(port, pid, rng):
    status = post(port, f"/api/join?participant={pid}")
    speed = status["pad_speed"]
    for _ in range(status["practice"] + status["iterations"]):
        r = post(port, f"/api/round/start?participant={pid}")
        deceived = rng.random() < 0.5
        body = trace(r["duration"], speed, rng, deceived)
        post(port, f"/api/round/submit?participant={pid}&kind={r['kind']}&iteration={r['iteration']}", body)
    answers = "&".join(f"{i['name']}={rng.randint(1, 7)}" for i in status["items"])
    if status.get("yes_no"):
        answers += f"&{status['yes_no']['name']}={rng.choice(['yes', 'no'])}"
    post(port, f"/api/questionnaire?participant={pid}", answers)


def collect(study):
    log = open(os.path.join(WORK, "collect.stdout"), "w")
    server = subprocess.Popen([FEINT, "collect", study, "--port", "0", "--admin-token", "tok"],
                              stdout=log, stderr=subprocess.STDOUT)
    port = None
    for _ in range(400):
        time.sleep(0.025)
        for line in open(os.path.join(WORK, "collect.stdout")):
            if line.startswith("port: "):
                port = int(line[6:])
        if port:
            break
    check(port is not None, "feint collect printed its port")
    rng = random.Random(7)
    for k in range(PEOPLE):
        play(port, f"P{k + 1:02d}", rng)
    server.send_signal(signal.SIGTERM)
    server.wait(timeout=30)


def labels_earned(out):
    """No "≈" without BF01 >= 3 or a TOST p < alpha, in any table with a label column."""
    for name in sorted(os.listdir(out)):
        if not name.endswith(".csv"):
            continue
        with open(os.path.join(out, name), newline="") as f:
            rows = list(csv.DictReader(f))
        for row in rows:
            label = row.get("label") or ""
            if "\u2248" not in label:
                continue
            bf01 = float(row["bf01"]) if row.get("bf01") else 0.0
            check(bf01 >= 3.0, f"{name}: '{label}' with BF01 = {bf01} and no TOST")


def findings_complete(out):
    findings = json.load(open(os.path.join(out, "findings.json")))
    check(len(findings) > 0, "findings.json has findings")
    for f in findings:
        if f["strength"] == "not computable":
            continue
        for key in ("test", "p", "contrast"):
            check(f.get(key) not in (None, ""), f"{f['id']}: field {key} is empty")
        # Which way: every finding but an F of several df (an interaction has no one direction).
        check(f.get("direction") or "\u00d7" in f.get("contrast", ""), f"{f['id']}: no direction")
        es = f.get("effect_size")
        check(es is not None, f"{f['id']}: no effect size")
        if es:
            for key in ("value", "ci_low", "ci_high"):
                check(es.get(key) is not None and math.isfinite(es[key]), f"{f['id']}: effect_size.{key}")
        check(f.get("bf10") is not None or f.get("bf_note"), f"{f['id']}: no BF10 and no bf_note")


def results_text(out):
    for ext in ("md", "tex"):
        path = os.path.join(out, f"results-text.{ext}")
        check(os.path.exists(path), f"results-text.{ext} written")
    path = os.path.join(out, "results-text.md")
    if os.path.exists(path):
        paragraphs = [p for p in open(path).read().split("\n\n") if p.strip() and not p.startswith("#")]
        check(len(paragraphs) >= 2, "a paragraph per hypothesis")
        for p in paragraphs:
            check(len(p.split()) <= 250, f"a paragraph of {len(p.split())} words")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    study, out = os.path.join(WORK, "study"), os.path.join(WORK, "out")
    os.makedirs(study)
    collect(study)
    check(os.path.exists(os.path.join(study, "feint.toml")), "feint collect wrote feint.toml")
    # One scale: confusion scored on the scale of its reference (the study's feint.toml says so).
    toml = open(os.path.join(study, "feint.toml")).read()
    check('confusion-norm = "raw"' in toml and "confusion=0.95@raw" in toml, "confusion and its reference on one scale")
    run = subprocess.run([FEINT, "analyze", study, "-o", out, "--no-figures"], capture_output=True, text=True)
    check(run.returncode == 0, f"feint analyze exit {run.returncode}: {run.stderr[-2000:]}")
    if run.returncode == 0:
        check(os.path.exists(os.path.join(out, "table1_compare.csv")), "the conditions are compared")
        check(os.path.exists(os.path.join(out, "likert_compare.csv")), "the questionnaire is compared")
        findings_complete(out)
        labels_earned(out)
        results_text(out)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
