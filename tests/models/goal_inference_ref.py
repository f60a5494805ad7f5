#!/usr/bin/env python3
"""Independent reference of the goal-inference observer and its deceptiveness measures
(docs/observer.md), python3 standard library only.

Writes a few robot paths, runs `feint simulate trajectories --path ... -f json` on each, and checks
every measure against this file's own implementation to within 1e-12. Exit 0 on agreement, 1 on a
mismatch, 77 (skip) when the feint binary is missing.

    goal_inference_ref.py --feint build/feint --work /tmp/dir
"""
import argparse
import json
import math
import os
import subprocess
import sys

GOALS = {"left": (-2.0, 4.0), "right": (2.0, 4.0)}


def logistic(z):
    if z >= 0:
        return 1.0 / (1.0 + math.exp(-z))
    e = math.exp(z)
    return e / (1.0 + e)


def belief_right(start, q, beta, prior):
    """P(right | S -> Q) = logistic(logit prior - beta [(V_R(Q) - V_R(S)) - (V_L(Q) - V_L(S))])."""
    (rx, ry), (lx, ly) = GOALS["right"], GOALS["left"]
    right_rise = math.hypot(q[0] - rx, q[1] - ry) - math.hypot(start[0] - rx, start[1] - ry)
    left_rise = math.hypot(q[0] - lx, q[1] - ly) - math.hypot(start[0] - lx, start[1] - ly)
    return logistic(math.log(prior) - math.log1p(-prior) - beta * (right_rise - left_rise))


def position_at(path, t):
    if t <= path[0][0]:
        return path[0][1], path[0][2]
    if t >= path[-1][0]:
        return path[-1][1], path[-1][2]
    for k in range(1, len(path)):
        if path[k][0] > t:
            a, b = path[k - 1], path[k]
            w = (t - a[0]) / (b[0] - a[0])
            return a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2])
    return path[-1][1], path[-1][2]


def score(times, mu, target, v, fs=0.05, fe=0.05, eps=1e-9):
    """The paper's error (eq. 3) and confusion (eq. 4, `speed` norm) as the metrics page fixes them."""
    t0 = times[0]
    tau = times[-1] - t0
    a, b = t0 + fs * tau, t0 + (1 - fe) * tau

    def at(i, t):
        return mu[i] + (mu[i + 1] - mu[i]) * (t - times[i]) / (times[i + 1] - times[i])

    integral = 0.0
    for i in range(len(times) - 1):
        s, e = max(times[i], a), min(times[i + 1], b)
        if e <= s:
            continue
        integral += (abs(target - at(i, s)) + abs(target - at(i, e))) / 2 * (e - s)
    error = integral / (b - a)
    dirs = []
    for i in range(len(times) - 1):
        d = mu[i + 1] - mu[i]
        dirs.append(1 if d > eps else (-1 if d < -eps else 0))
    first = next((d for d in dirs if d != 0), 0)
    rev = next((i for i, d in enumerate(dirs) if first != 0 and d == -first), None)
    overspeed = 0
    for i in range(len(times) - 1):
        if abs(mu[i + 1] - mu[i]) / (times[i + 1] - times[i]) > v * (1 + 1e-6):
            overspeed += 1
    if rev is None:
        return error, 0.0, overspeed
    c = max(a, times[rev])
    m = 0.0
    for i in range(len(times) - 1):
        s, e = max(times[i], c), min(times[i + 1], b)
        if e <= s:
            continue
        speed = abs(mu[i + 1] - mu[i]) / (times[i + 1] - times[i])
        m += min(1.0, speed / v) * ((e - t0) ** 2 - (s - t0) ** 2) / 2
    d = ((b - t0) ** 2 - (a - t0) ** 2) / 2
    return error, m / d, overspeed


def measures(path, goal, beta, tau, prior, v):
    start = (path[0][1], path[0][2])
    n = len(path)
    arc = [0.0]
    for i in range(1, n):
        arc.append(arc[-1] + math.hypot(path[i][1] - path[i - 1][1], path[i][2] - path[i - 1][2]))
    t0 = path[0][0]
    T = path[-1][0] - t0
    straight = math.hypot(path[-1][1] - start[0], path[-1][2] - start[1])
    p = []
    for s in path:
        b = belief_right(start, (s[1], s[2]), beta, prior)
        p.append(b if goal == "right" else 1.0 - b)
    num = deceived = 0.0
    for i in range(1, n):
        dt = path[i][0] - path[i - 1][0]
        f0, f1 = T - (path[i - 1][0] - t0), T - (path[i][0] - t0)
        num += (p[i - 1] * f0 + p[i] * f1) / 2 * dt
        d0, d1 = p[i - 1] - 0.5, p[i] - 0.5
        if d0 < 0 and d1 < 0:
            deceived += dt
        elif d0 < 0 <= d1:
            deceived += dt * (-d0) / (d1 - d0)
        elif d0 >= 0 > d1:
            deceived += dt * (-d1) / (d0 - d1)
    last = None
    for i in range(n - 1, -1, -1):
        if p[i] - 0.5 <= 0:
            last = i
            break
    if last is None:
        ldp = 0.0
    elif last == n - 1:
        ldp = 1.0
    else:
        d0, d1 = p[last] - 0.5, p[last + 1] - 0.5
        frac = -d0 / (d1 - d0)
        ldp = (arc[last] + frac * (arc[last + 1] - arc[last])) / arc[-1]
    times = [s[0] for s in path]
    belief = [belief_right(start, position_at(path, t - tau), beta, prior) for t in times]
    err, conf, over = score(times, belief, 1.0 if goal == "right" else 0.0, v)
    return {
        "duration": T, "path_length": arc[-1], "cost_overhead": arc[-1] / straight - 1,
        "legibility": num / (T * T / 2), "time_deceived": deceived / T, "last_deceptive_point": ldp,
        "final_belief": p[-1], "belief_error": err, "belief_confusion": conf,
        "belief_overspeed_segments": over,
    }


def polyline(points, times):
    """Samples of the polyline at the given arc-length fractions' times (uneven on purpose)."""
    cum = [0.0]
    for i in range(1, len(points)):
        cum.append(cum[-1] + math.hypot(points[i][0] - points[i - 1][0], points[i][1] - points[i - 1][1]))
    out = []
    for k, t in enumerate(times):
        s = cum[-1] * k / (len(times) - 1)
        j = 1
        while j + 1 < len(points) and cum[j] < s:
            j += 1
        seg = cum[j] - cum[j - 1]
        w = (s - cum[j - 1]) / seg if seg > 0 else 1.0
        out.append((t, points[j - 1][0] + w * (points[j][0] - points[j - 1][0]),
                    points[j - 1][1] + w * (points[j][1] - points[j - 1][1])))
    return out


CASES = [
    # name, path, goal, beta, tau, prior, pad speed
    ("straight", polyline([(0, 0), (2, 4)], [0.1 * i for i in range(46)]), "right", 1.0, 0.0, 0.5, 0.8),
    ("exaggerating", polyline([(0, 0), (-2, 2.4), (2, 4)], [0.13 * i + 0.01 * (i % 3) for i in range(60)]),
     "right", 2.0, 0.3, 0.5, 0.8),
    ("ambiguous-left", polyline([(0, 0), (0, 3.2), (-2, 4)], [0.08 * i for i in range(70)]),
     "left", 2.5, 0.35, 0.3, 0.5),
    ("switching", polyline([(0, 0), (-0.8, 0.75), (0.8, 1.5), (-0.8, 2.25), (0.8, 3.0), (2, 4)],
                           [0.11 * i for i in range(75)]), "right", 4.0, 0.2, 0.6, 1.0),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--feint", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    if not os.path.exists(args.feint):
        print(f"feint binary {args.feint} not found: skipped")
        return 77
    os.makedirs(args.work, exist_ok=True)
    worst = 0.0
    failures = 0
    for name, path, goal, beta, tau, prior, v in CASES:
        file = os.path.join(args.work, f"{name}.csv")
        with open(file, "w") as f:
            f.write("t,x,y\n")
            for t, x, y in path:
                f.write(f"{t!r},{x!r},{y!r}\n")
        out = subprocess.run([args.feint, "simulate", "trajectories", "--path", file, "--target", goal,
                              "--beta", repr(beta), "--tau", repr(tau), "--prior", repr(prior),
                              "--pad-speed", repr(v), "-f", "json"], capture_output=True, text=True)
        if out.returncode != 0:
            print(f"{name}: feint failed ({out.returncode}): {out.stderr}")
            failures += 1
            continue
        got = json.loads(out.stdout)[0]
        ref = measures(path, goal, beta, tau, prior, v)
        for key, want in ref.items():
            diff = abs(got[key] - want)
            worst = max(worst, diff)
            ok = diff <= 1e-12 * max(1.0, abs(want))
            print(f"{name:15s} {key:26s} feint {got[key]!r:24s} python {want!r:24s} {'ok' if ok else 'MISMATCH'}")
            failures += not ok
    print(f"largest difference {worst:.3g}; {failures} mismatch(es)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
