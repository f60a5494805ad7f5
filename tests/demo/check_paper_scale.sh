#!/bin/sh
# The shipped demo study against the paper's Table 1 (docs/paper-scale.md):
# score data/demo on the paper's (raw) confusion scale, then bench/paper_scale.py checks that at
# least 30 of the paper's 40 means fall inside the demo's 95 % CIs, that no CI is more than twice
# as wide as the paper's, and that adaptive stays above random in iterations 5-20 (error, pooled).
# usage: check_paper_scale.sh FEINT SOURCE_DIR WORK_DIR
set -eu
feint=$1; src=$2; work=$3
command -v python3 >/dev/null 2>&1 || { echo "python3 not installed: paper-scale check skipped"; exit 77; }
rm -rf "$work"; mkdir -p "$work"
"$feint" score "$src/data/demo/logs" --confusion-norm raw -o "$work/scores.csv"
python3 "$src/bench/paper_scale.py" "$feint" "$work/scores.csv" --markdown "$work/paper-scale.md"
