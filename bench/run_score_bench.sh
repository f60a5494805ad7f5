#!/usr/bin/env bash
# Throughput and peak memory of `feint score` on a large synthetic log.
#
#   bench/run_score_bench.sh [BUILD_DIR] [BYTES] [--gzip]
#
# BUILD_DIR: a Release build configured with -DFEINT_BUILD_BENCH=ON (default build-score-rel);
# BYTES: size of the generated log (default 1100000000, i.e. > 1 GB). The log is written to
# ${TMPDIR:-/tmp}, scored with /usr/bin/time -v, and deleted afterwards (also on failure).
# Reports MB/s and rows/s by wall clock and by CPU time (user + sys), and the peak RSS.
set -euo pipefail

build=${1:-build-score-rel}
bytes=${2:-1100000000}
gzip=${3:-}
feint=$build/feint
gen=$build/bench/gen_logs
[[ -x $feint && -x $gen ]] || {
  echo "build first: cmake -S . -B $build -DCMAKE_BUILD_TYPE=Release -DFEINT_BUILD_BENCH=ON &&" \
       "cmake --build $build --target feint gen_logs" >&2
  exit 64
}

work=$(mktemp -d "${TMPDIR:-/tmp}/feint-score-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
log=$work/log.csv
[[ $gzip == --gzip ]] && log=$work/log.csv.gz

avail=$(df -B1 --output=avail "$work" | tail -1)
if (( avail < bytes * 2 )); then
  echo "not enough space in $work: $avail bytes free, need ~$((bytes * 2))" >&2
  exit 74
fi

echo "generating $bytes bytes of log ($log) ..." >&2
"$gen" --bytes "$bytes" --seed 7 --out "$log" 2>/dev/null
stored=$(stat -c %s "$log")
if [[ $gzip == --gzip ]]; then
  size=$(zcat "$log" | wc -c)          # MB/s are of uncompressed CSV
  rows=$(( $(zcat "$log" | wc -l) - 1 ))
else
  size=$stored
  rows=$(( $(wc -l < "$log") - 1 ))
fi

# Warm the page cache so the figure is about feint, not the disk.
cat "$log" > /dev/null

/usr/bin/time -v "$feint" score "$log" -o "$work/scores.csv" 2> "$work/time.txt" || {
  cat "$work/time.txt" >&2
  exit 1
}
wall=$(grep "Elapsed (wall clock)" "$work/time.txt" | awk '{print $NF}' |
       awk -F: '{ if (NF == 3) print $1 * 3600 + $2 * 60 + $3; else print $1 * 60 + $2 }')
user=$(grep "User time" "$work/time.txt" | awk '{print $NF}')
sys=$(grep "System time" "$work/time.txt" | awk '{print $NF}')
rss=$(grep "Maximum resident" "$work/time.txt" | awk '{print $NF}')
summary=$(grep "^feint score:" "$work/time.txt" || true)

awk -v size="$size" -v stored="$stored" -v rows="$rows" -v wall="$wall" -v user="$user" -v sys="$sys" -v rss="$rss" \
    -v cores="$(nproc)" -v load="$(cut -d' ' -f1 /proc/loadavg)" 'BEGIN {
  cpu = user + sys
  printf "input: %.1f MB of CSV (%.1f MB on disk), %d rows\n", size / 1e6, stored / 1e6, rows
  printf "wall:  %.2f s  -> %.0f MB/s, %.2f M rows/s\n", wall, size / 1e6 / wall, rows / 1e6 / wall
  printf "cpu:   %.2f s (user %.2f + sys %.2f) -> %.0f MB/s, %.2f M rows/s per CPU second\n",
         cpu, user, sys, size / 1e6 / cpu, rows / 1e6 / cpu
  printf "peak RSS: %.1f MB\n", rss / 1024
  printf "machine: %d cores, load average %s at the end\n", cores, load
}'
echo "$summary"
