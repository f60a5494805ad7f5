#!/usr/bin/env bash
# `feint analyze STUDY` with two binaries in one run: user CPU and wall time per run (median of
# REPS runs each, the two binaries alternating so that both see the same load), and whether every
# finding keeps its label (findings.json: id -> evidence).
#
#   bench/run_analyze_bench.sh OLD_FEINT NEW_FEINT [STUDY] [REPS]
#
# STUDY: default data/demo; REPS: default 5. CONFIG=FILE passes --config FILE to both binaries
# (for an old binary that cannot read the study's feint.toml). Exits 1 when a finding's label
# differs or a finding is missing from either run.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
old=${1:?usage: run_analyze_bench.sh OLD_FEINT NEW_FEINT [STUDY] [REPS]}
new=${2:?usage: run_analyze_bench.sh OLD_FEINT NEW_FEINT [STUDY] [REPS]}
study=${3:-$here/data/demo}
reps=${4:-5}
for b in "$old" "$new"; do [[ -x $b ]] || { echo "not an executable: $b" >&2; exit 64; }; done
command -v python3 >/dev/null || { echo "python3 is needed to compare findings.json" >&2; exit 69; }

work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
config=()
[[ -n ${CONFIG:-} ]] && config=(--config "$CONFIG")

run() {  # run NAME BINARY: one timed run into $work/NAME, "user wall" appended to $work/NAME.times
  /usr/bin/time -a -o "$work/$1.times" -f "%U %e" "$2" analyze "$study" "${config[@]}" -o "$work/$1" \
    > /dev/null 2> "$work/$1.err" || { cat "$work/$1.err" >&2; exit 1; }
}
for ((i = 0; i < reps; ++i)); do
  run old "$old"
  run new "$new"
done

median() {  # median of column $2 of file $1
  sort -g -k"$2","$2" "$1" | awk -v c="$2" '{ v[NR] = $c } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
printf '%s, %s runs each (median; the binaries alternating)\n' "feint analyze $study" "$reps"
printf '%-8s %12s %12s   %s\n' "" "user CPU s" "wall s" "binary"
for name in old new; do
  bin=$old
  [[ $name == new ]] && bin=$new
  printf '%-8s %12.3f %12.3f   %s\n' "$name" "$(median "$work/$name.times" 1)" "$(median "$work/$name.times" 2)" "$bin"
done
printf '%-8s %12.1f\n' "old/new" "$(echo "$(median "$work/old.times" 1) / $(median "$work/new.times" 1)" | bc -l)"

python3 - "$work/old/findings.json" "$work/new/findings.json" <<'EOF'
import json, sys
def labels(path):
    return {f["id"]: f["evidence"] for f in json.load(open(path))}
old, new = labels(sys.argv[1]), labels(sys.argv[2])
differ = [(k, old.get(k), new.get(k)) for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]
print(f"findings: {len(old)} old, {len(new)} new; labels differing: {len(differ)}")
for k, a, b in differ:
    print(f"  {k}: {a!r} -> {b!r}")
sys.exit(1 if differ else 0)
EOF
