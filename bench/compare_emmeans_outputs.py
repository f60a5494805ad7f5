#!/usr/bin/env python3
"""Compares `feint anova` and `feint model` with --emmeans and every --contrasts / --adjust
between two feint binaries (tidy JSON), field by field: the largest relative difference
|a - b| / max(|a|, |b|) per table and field, and where the worst one is.

  bench/compare_emmeans_outputs.py OLD_FEINT NEW_FEINT [SCORES] [--rel-tol 1e-8] [--accept OLD NEW]

SCORES defaults to reports/demo/scores.csv. Exit 1 when a row count, a text field or a null
differs, or a number differs by more than --rel-tol relative (default 1e-8: the old ptukey erred
by up to ~2e-9 at the demo's 20 means, which moves Tukey p-values and interval ends by up to
~5e-9 relative; the emmeans goldens hold feint to 1e-6). --accept OLD NEW (repeatable) accepts
a text value that changed on purpose between the two builds, e.g. the label 'A≈B' that became
'n.s.' (a labelling change of the current build, unrelated to the contrasts).
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def runs():
    for command in ("anova", "model"):
        for contrasts in (["pairwise"], ["simple"], ["poly"], ["pairwise", "simple", "poly"]):
            adjusts = [None, "holm", "none"] + ([] if "poly" in contrasts else ["tukey"])
            for adjust in adjusts:
                args = [command, "--emmeans"]
                for c in contrasts:
                    args += ["--contrasts", c]
                if adjust:
                    args += ["--adjust", adjust]
                yield args
    yield ["model", "--ddf", "kenward-roger", "--emmeans", "--contrasts", "pairwise",
           "--contrasts", "simple"]


def output(feint, args, scores):
    done = subprocess.run([feint, *args, scores, "--format", "json"], capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout)


def main():
    cli = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    cli.add_argument("old")
    cli.add_argument("new")
    cli.add_argument("scores", nargs="?", default=str(ROOT / "reports/demo/scores.csv"))
    cli.add_argument("--rel-tol", type=float, default=1e-8)
    cli.add_argument("--accept", nargs=2, action="append", default=[], metavar=("OLD", "NEW"))
    opts = cli.parse_args()
    old, new, scores = opts.old, opts.new, opts.scores
    worst = {}  # (table, field) -> (rel, abs, a, b, where)
    failures = 0
    for args in runs():
        a_rows, b_rows = output(old, args, scores), output(new, args, scores)
        where = " ".join(args)
        run_max = 0.0
        if len(a_rows) != len(b_rows):
            print(f"{where}: {len(a_rows)} rows vs {len(b_rows)}")
            failures += 1
            continue
        for i, (a, b) in enumerate(zip(a_rows, b_rows)):
            for field in sorted(set(a) | set(b)):
                x, y = a.get(field), b.get(field)
                if isinstance(x, (int, float)) and isinstance(y, (int, float)) and \
                        not isinstance(x, bool):
                    rel = abs(x - y) / max(abs(x), abs(y)) if x != y else 0.0
                    run_max = max(run_max, rel)
                    if rel > opts.rel_tol:
                        print(f"{where} | row {i} {field}: {x!r} vs {y!r} (relative {rel:.3g})")
                        failures += 1
                    key = (a.get("table"), field)
                    if rel >= worst.get(key, (-1,))[0]:
                        worst[key] = (rel, abs(x - y), x, y, f"{where} | row {i} {a.get('term')} "
                                      f"{a.get('group') or ''} {a.get('contrast') or a.get('level') or ''}")
                elif x != y and [x, y] not in opts.accept:
                    print(f"{where} | row {i} {field}: {x!r} vs {y!r}")
                    failures += 1
        print(f"{where}: max relative difference {run_max:.3g}")
    print(f"{'table':<14} {'field':<12} {'max rel diff':>12} {'abs diff':>10}  worst at")
    for (table, field), (rel, ab, x, y, where) in sorted(worst.items(), key=lambda kv: -kv[1][0]):
        if rel > 0:
            print(f"{table!s:<14} {field:<12} {rel:12.3g} {ab:10.3g}  {where} ({x!r} vs {y!r})")
    top = max((v[0] for v in worst.values()), default=0.0)
    print(f"max relative difference over all numbers: {top:.3g} (tolerance {opts.rel_tol:g}); "
          f"{failures} difference(s) beyond it or in text")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
