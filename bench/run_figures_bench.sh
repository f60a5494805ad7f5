#!/usr/bin/env bash
# How long `feint analyze data/demo` takes with and without the figures and report.html.
#
#   bench/run_figures_bench.sh [BUILD_DIR] [RUNS]
#
# BUILD_DIR: a Release build (default build); RUNS: runs per variant (default 7). Each variant
# writes into a fresh folder under ${TMPDIR:-/tmp} (deleted afterwards); the median and the range of
# the wall-clock times are reported, with the CPU time (user + sys) of the median run.
set -euo pipefail

build=${1:-build}
runs=${2:-7}
here=$(cd "$(dirname "$0")/.." && pwd)
feint=$build/feint
[[ -x $feint ]] || { echo "build first: cmake --build $build --target feint" >&2; exit 64; }

work=$(mktemp -d "${TMPDIR:-/tmp}/feint-figures-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT

measure() {  # label, extra options...
  local label=$1; shift
  local times=()
  for ((i = 0; i < runs; i++)); do
    rm -rf "$work/out"
    /usr/bin/time -f '%e %U %S' -o "$work/t" "$feint" analyze "$here/data/demo" -o "$work/out" \
      "$@" 2>/dev/null
    times+=("$(cat "$work/t")")
  done
  local files
  files=$(find "$work/out" -type f | wc -l)
  printf '%s\n' "${times[@]}" | sort -n | awk -v label="$label" -v files="$files" '
    { wall[NR] = $1; cpu[NR] = $2 + $3 }
    END { m = int((NR + 1) / 2);
          printf "%-34s median %.2f s (min %.2f, max %.2f), CPU %.2f s, %d files\n",
                 label, wall[m], wall[1], wall[NR], cpu[m], files }'
}

echo "feint analyze data/demo ($runs runs each; $(nproc) CPUs)"
measure "tables only (--no-figures --no-report)" --no-figures --no-report
measure "tables + report.html (--no-figures)" --no-figures
measure "tables + figures (pdf, svg) + report" 
measure "tables + figures (pdf, svg, png) + report" --figure-formats pdf,svg,png
