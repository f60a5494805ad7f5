#!/usr/bin/env bash
# The mixed ANOVA of the paper's design (2 conditions x 20 iterations) in feint and in R
# (afex::aov_ez), timed in one run on the same scores file; prints seconds per fit and the ratio.
#
#   bench/run_anova_bench.sh [BUILD_DIR] [SCORES.csv] [METRIC]
#
# BUILD_DIR: a Release build with -DFEINT_BUILD_BENCH=ON (default build); SCORES: default the demo
# study's scores (made by `feint analyze data/demo`, 40 participants x 20 iterations). Both sides
# fit in-process (data already loaded) and are repeated; process start-up is timed separately.
set -euo pipefail

build=${1:-build}
work=$(mktemp -d "${TMPDIR:-/tmp}/feint-anova-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
scores=${2:-}
metric=${3:-error}
[[ -x $build/bench/anova_timing && -x $build/feint ]] || {
  echo "build first: cmake -S . -B $build -DCMAKE_BUILD_TYPE=Release -DFEINT_BUILD_BENCH=ON &&" \
       "cmake --build $build --target feint anova_timing" >&2
  exit 64
}
if [[ -z $scores ]]; then
  "$build/feint" analyze data/demo -o "$work/demo" --formats csv 2>/dev/null
  scores=$work/demo/scores.csv
fi
command -v Rscript >/dev/null || { echo "Rscript not found (needs r-cran-afex)" >&2; exit 69; }

feint_reps=2000
r_reps=20
feint_s=$("$build/bench/anova_timing" "$scores" "$metric" "$feint_reps")
r_s=$(Rscript -e "
  suppressPackageStartupMessages(library(afex))
  d <- read.csv('$scores'); d\$iteration <- factor(d\$iteration)
  fit <- function() suppressMessages(aov_ez('participant', '$metric', d, between = 'condition', within = 'iteration'))
  invisible(fit())
  t <- system.time(for (i in seq_len($r_reps)) fit())[['elapsed']]
  cat(sprintf('%.9g', t / $r_reps))")
# End to end: one process each (start-up, reading, fitting, printing).
t0=$(date +%s.%N); "$build/feint" anova "$scores" --metric "$metric" >/dev/null; t1=$(date +%s.%N)
Rscript -e "suppressPackageStartupMessages(library(afex)); d <- read.csv('$scores');
  d\$iteration <- factor(d\$iteration);
  print(suppressMessages(aov_ez('participant', '$metric', d, between = 'condition', within = 'iteration')))" \
  >/dev/null 2>&1
t2=$(date +%s.%N)
awk -v f="$feint_s" -v r="$r_s" -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN {
  printf "mixed ANOVA fit (in-process): feint %.1f us, R afex::aov_ez %.1f ms, ratio R/feint = %.0f\n", f * 1e6, r * 1e3, r / f
  printf "one process end to end:       feint %.3f s, Rscript %.3f s, ratio %.0f\n", b - a, c - b, (c - b) / (b - a)
}'
