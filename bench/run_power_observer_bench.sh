#!/usr/bin/env bash
# `feint power observer` and `feint observer fit`: a build against a reference binary, in one run,
# alternating, as CPU seconds (user + sys) per run and their ratio.
#
#   bench/run_power_observer_bench.sh NEW_FEINT OLD_FEINT [REPS]
#
# NEW_FEINT, OLD_FEINT: feint binaries (e.g. build/feint and a copy of the previous release);
# REPS: repetitions of each (default 3). The commands:
#   power observer --participants 10,20,30,40            (400 studies per size, both cores)
#   observer fit LOGS --no-learning                        (a simulated study, 60 participants x 20)
# CPU time is reported because the machine may be shared; each line gives the median of REPS.
set -euo pipefail

new=${1:?usage: $0 NEW_FEINT OLD_FEINT [REPS]}
old=${2:?usage: $0 NEW_FEINT OLD_FEINT [REPS]}
reps=${3:-3}
for b in "$new" "$old"; do [[ -x $b ]] || { echo "$b: not an executable" >&2; exit 64; }; done

work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$new" simulate study -o "$work/study" -p 30 -n 20 --seed 1 >/dev/null 2>&1

# cpu BIN ARGS...: CPU seconds of one run (stderr and stdout discarded).
cpu() {
  local t=$work/time
  /usr/bin/time -o "$t" -f "%U %S" "$@" >/dev/null 2>&1
  awk '{ printf "%.2f", $1 + $2 }' "$t"
}
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

bench() {
  local name=$1; shift
  local a=() b=()
  for ((i = 0; i < reps; ++i)); do
    a+=("$(cpu "$new" "$@")")
    b+=("$(cpu "$old" "$@")")
  done
  local ma mb
  ma=$(median "${a[@]}"); mb=$(median "${b[@]}")
  printf '%-34s %10s %10s %8.2f   (new: %s; old: %s)\n' "$name" "$ma" "$mb" "$(echo "$mb / $ma" | bc -l)" \
    "${a[*]}" "${b[*]}"
}

printf '%-34s %10s %10s %8s\n' "CPU s per run (median of $reps)" "new" "old" "old/new"
bench "power observer 10,20,30,40" power observer --participants 10,20,30,40
bench "observer fit 60 x 20 (no learning)" observer fit "$work/study/logs" --no-learning
# Same results: the power table of a seed does not depend on the number of threads.
"$new" power observer --participants 10,20 --studies 100 --threads 1 -o "$work/t1.txt"
"$new" power observer --participants 10,20 --studies 100 --threads 2 -o "$work/t2.txt"
cmp -s "$work/t1.txt" "$work/t2.txt" && echo "power observer: 1 and 2 threads give the same table" \
  || { echo "power observer: 1 and 2 threads differ" >&2; exit 1; }
