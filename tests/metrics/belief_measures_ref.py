#!/usr/bin/env python3
"""Independent reference of feint's belief-trace measures (docs/metrics.md, "Belief-trace measures").

Exact rational arithmetic (fractions.Fraction), standard library only. The window measures are
computed differently from feint: every point where the pad crosses T, 1/2 + delta or 1/2 - delta is
added as a breakpoint, so that on each piece the trace is linear and on one side of each line; a
piece's membership is decided at its midpoint.

  belief_measures_ref.py --examples            print the worked examples A-E as exact fractions
  belief_measures_ref.py --check FEINT WORKDIR  write the worked examples and random traces as a log,
                                               run `FEINT score` on it and compare (exit 1 on a
                                               difference above 1e-12, 0 when all agree)
"""
import csv
import os
import random
import subprocess
import sys
from fractions import Fraction as F

HALF = F(1, 2)


def interp(ts, mus, x):
    """mu at time x (piecewise linear)."""
    for i in range(len(ts) - 1):
        if ts[i] <= x <= ts[i + 1]:
            return mus[i] + (mus[i + 1] - mus[i]) * (x - ts[i]) / (ts[i + 1] - ts[i])
    raise ValueError("outside the trace")


def pieces(ts, mus, lo, hi, levels):
    """Breakpoints of [lo, hi]: samples inside, the ends, and every crossing of a level."""
    pts = {lo, hi}
    for i in range(len(ts) - 1):
        t0, t1, m0, m1 = ts[i], ts[i + 1], mus[i], mus[i + 1]
        if lo < t0 < hi:
            pts.add(t0)
        if m0 != m1:
            for lev in levels:
                if min(m0, m1) < lev < max(m0, m1):
                    x = t0 + (t1 - t0) * (lev - m0) / (m1 - m0)
                    if lo < x < hi:
                        pts.add(x)
    return sorted(pts)


def flips(mus, delta):
    """Direction changes, each counted once the pad has come back more than delta."""
    count, direction, low, high = 0, 0, mus[0], mus[0]
    for m in mus[1:]:
        low, high = min(low, m), max(high, m)
        if direction >= 0 and high - m > delta:
            count += direction != 0
            direction, low, high = -1, m, m
        elif direction <= 0 and m - low > delta:
            count += direction != 0
            direction, low, high = 1, m, m
    return count


def measures(ts, mus, T, delta, trim_start=F(1, 20), trim_end=F(1, 20)):
    ts = [F(t) for t in ts]
    mus = [F(m) for m in mus]
    T, delta = F(T), F(delta)
    t0, tau = ts[0], ts[-1] - ts[0]
    a, b = t0 + trim_start * tau, t0 + (1 - trim_end) * tau
    out = {"flips": flips(mus, delta)}
    if T == HALF:
        out.update(signed_area=None, max_deviation=None, time_deceived=None, final_belief_time=None)
        return out
    sigma = 1 if T < HALF else -1
    false_line = HALF + sigma * delta  # beyond it (on the false side): deceived
    true_line = HALF - sigma * delta   # beyond it (on the true side): true belief
    grid = pieces(ts, mus, a, b, [T, false_line, true_line])
    area = deceived = F(0)
    for x0, x1 in zip(grid, grid[1:]):
        m0, m1 = interp(ts, mus, x0), interp(ts, mus, x1)
        area += sigma * ((m0 + m1) / 2 - T) * (x1 - x0)
        mid = (m0 + m1) / 2
        if sigma * (mid - HALF) > delta:
            deceived += x1 - x0
    out["signed_area"] = area / (b - a)
    out["time_deceived"] = deceived / (b - a)
    out["max_deviation"] = max(sigma * (interp(ts, mus, x) - HALF) for x in grid)
    # Final correct belief: the last piece of the whole trace that is on the true side beyond delta,
    # if it reaches the end; its start (merged with the pieces before it on the same side).
    grid = pieces(ts, mus, ts[0], ts[-1], [true_line])

    def true_side(m):
        return -sigma * (m - HALF) > delta

    if not true_side(mus[-1]):
        out["final_belief_time"] = None
        return out
    # The set {true_side} must hold on all of (start, end]: a piece counts when its midpoint is
    # inside, and the walk stops at the first breakpoint that is not (touching the line is not
    # "beyond" it).
    start = ts[-1]
    for x0, x1 in reversed(list(zip(grid, grid[1:]))):
        mid = (interp(ts, mus, x0) + interp(ts, mus, x1)) / 2
        if not true_side(mid):
            break
        start = x0
        if not true_side(interp(ts, mus, x0)):
            break
    out["final_belief_time"] = start - t0
    return out


# The worked examples of docs/metrics.md (trials A-E of the metrics specification).
EXAMPLES = {
    "A": (list(range(11)), ["0.5", "0.75"] + ["1"] * 9, "1"),
    "B": (list(range(11)), ["0.5", "0.25", "0", "0", "0", "0", "0", "0.25", "0.5", "0.75", "1"], "1"),
    "C": (list(range(11)), ["0.5", "0.75"] * 5 + ["0.5"], "0"),
    "D": (["0", "0.5", "2", "3.5", "4"], ["0.5", "0.5", "0.2", "0.6", "0.6"], "0.3"),
    "E": (["0", "0.3", "1", "2", "4"], ["0.5", "0.6", "0.4", "0.4", "0.9"], "1"),
}
COLUMNS = ["signed_area", "max_deviation", "flips", "time_deceived", "final_belief_time"]


def fmt(v):
    if v is None:
        return "(empty)"
    if isinstance(v, int):
        return str(v)
    return f"{v.numerator}/{v.denominator} = {float(v):.6g}" if v.denominator != 1 else str(v.numerator)


def print_examples():
    for delta in (F(1, 20), F(0)):
        print(f"delta = {delta}")
        for name, (ts, mus, T) in EXAMPLES.items():
            m = measures([F(t) for t in ts], [F(x) for x in mus], F(T), delta)
            print(name, "; ".join(f"{c} {fmt(m[c])}" for c in COLUMNS))


def random_traces(rng, count):
    """Random walks with plateaus, crossings of 1/2 and of the dead band, on uneven times."""
    out = []
    for k in range(count):
        n = rng.randint(2, 40)
        t, mu = 0.0, 0.5
        ts, mus = [], []
        for _ in range(n):
            ts.append(round(t, 4))
            mus.append(round(mu, 4))
            t += rng.choice([0.04, 0.033, rng.uniform(0.001, 0.5)])
            if rng.random() < 0.7:
                mu = min(1.0, max(0.0, mu + rng.uniform(-0.3, 0.3)))
        ts = sorted(set(ts))
        mus = mus[: len(ts)]
        if len(ts) < 2:
            ts, mus = [0.0, 1.0], [0.5, 0.7]
        T = rng.choice([0.0, 1.0, 1.0, 0.0, round(rng.uniform(0, 1), 3), 0.5])
        out.append((f"R{k:03d}", ts, mus, T))
    return out


def check(feint, workdir):
    os.makedirs(workdir, exist_ok=True)
    log = os.path.join(workdir, "belief_ref_log.csv")
    scores = os.path.join(workdir, "belief_ref_scores.csv")
    rng = random.Random(20261125)
    trials = [(name, [float(F(t)) for t in ts], [float(F(m)) for m in mus], float(F(T)))
              for name, (ts, mus, T) in EXAMPLES.items()]
    trials += random_traces(rng, 200)
    deltas = {"0.05": 0.05, "0": 0.0, "0.1": 0.1}
    failures = 0
    compared = 0
    with open(log, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["participant", "iteration", "target", "t", "pad"])
        for i, (name, ts, mus, T) in enumerate(trials):
            for t, m in zip(ts, mus):
                w.writerow([name, i + 1, repr(T), repr(t), repr(m)])
    for text, delta in deltas.items():
        cmd = [feint, "score", log, "-o", scores, "--confusion-norm", "raw", "--belief-deadband", text]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            print("feint failed:", " ".join(cmd), r.stderr, sep="\n")
            return 1
        with open(scores, newline="") as f:
            rows = list(csv.DictReader(f))
        if len(rows) != len(trials):
            print(f"feint scored {len(rows)} trials of {len(trials)}")
            return 1
        for row, (name, ts, mus, T) in zip(rows, trials):
            want = measures([F(t) for t in ts], [F(m) for m in mus], F(T), F(delta))
            for c in COLUMNS:
                got = row[c]
                expected = want[c]
                compared += 1
                if expected is None:
                    ok = got == ""
                elif c == "flips":
                    ok = got != "" and int(got) == expected
                else:
                    ok = got != "" and abs(float(got) - float(expected)) <= 1e-12
                if not ok:
                    failures += 1
                    print(f"delta {text}, trial {name} (T = {T}): {c} feint '{got}', reference "
                          f"{fmt(expected)}\n  t = {ts}\n  pad = {mus}")
    print(f"{compared} values compared ({len(trials)} trials x {len(COLUMNS)} measures x "
          f"{len(deltas)} dead bands), {failures} differ")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] == "--examples":
        print_examples()
        sys.exit(0)
    if len(sys.argv) == 4 and sys.argv[1] == "--check":
        sys.exit(check(sys.argv[2], sys.argv[3]))
    print(__doc__)
    sys.exit(64)
