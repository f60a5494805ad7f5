#!/bin/sh
# collect_sampling.sh FEINT_EXE [OUT.json] - the sampling interval the feint collect page achieves
# in headless Chromium (median and 99th percentile of the time between animation frames, over a
# whole session of 22 rounds). It runs the browser test, which plays the session with key presses.
set -eu
here=$(dirname "$0")
exe=${1:?usage: collect_sampling.sh FEINT_EXE [OUT.json]}
out=${2:-collect_sampling.json}
python3 "$here/../tests/browser/collect_browser.py" "$exe" --json "$out"
cat "$out"; echo
