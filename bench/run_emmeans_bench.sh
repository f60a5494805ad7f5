#!/usr/bin/env bash
# `feint anova|model SCORES --emmeans --contrasts ...` (Tukey: one studentized-range probability
# per contrast) for two feint binaries in the same run, R doing the same work in one session, and
# a check that the two binaries' outputs agree.
#
#   bench/run_emmeans_bench.sh OLD_FEINT NEW_FEINT [SCORES.csv] [REPS]
#
# SCORES: default reports/demo/scores.csv (60 participants x 20 iterations: 2 x 190 pairs of
# iterations per command); REPS: default 5. Each feint figure is the median user CPU time of REPS
# whole processes (start, CSV, fit, contrasts, JSON); CPU time, not wall time, because the
# machine may be shared. R (bench/emmeans_r_timing.R; skipped without Rscript) runs the same
# analyses in one session: "in session" is the median of REPS warm runs after the packages are
# loaded (the comparison that favours R, and the one the "R/new" column uses); "incl. loading" is
# R's start-up and package loading plus the first run, what one Rscript call costs.
# Then bench/compare_emmeans_outputs.py compares every --contrasts/--adjust output of the two
# binaries (numbers to 1e-8 relative); the script exits 1 if they differ.
set -euo pipefail

old=${1:?usage: run_emmeans_bench.sh OLD_FEINT NEW_FEINT [SCORES] [REPS]}
new=${2:?usage: run_emmeans_bench.sh OLD_FEINT NEW_FEINT [SCORES] [REPS]}
here=$(cd "$(dirname "$0")/.." && pwd)
scores=${3:-$here/reports/demo/scores.csv}
reps=${4:-5}
for b in "$old" "$new"; do [[ -x $b ]] || { echo "not executable: $b" >&2; exit 64; }; done

# Median user CPU seconds of $reps runs of: feint ARGS...
median_user() {
  local t=()
  for ((i = 0; i < reps; ++i)); do
    t+=("$({ /usr/bin/time -f "%U" "$@" --format json -o /dev/null; } 2>&1 >/dev/null | tail -1)")
  done
  printf '%s\n' "${t[@]}" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.0f", a / (b > 0.01 ? b : 0.01) }'; }

cases=(
  "anova --emmeans --contrasts pairwise"
  "model --emmeans --contrasts pairwise"
  "anova --emmeans --contrasts pairwise --contrasts simple"
  "model --emmeans --contrasts pairwise --contrasts simple"
  "model --ddf kenward-roger --emmeans --contrasts pairwise"
)
declare -A r_session r_total
if command -v Rscript >/dev/null; then
  r_out=$(Rscript "$here/bench/emmeans_r_timing.R" "$scores" "$reps")
  load=$(awk '$1 == "load" { print $2 }' <<< "$r_out")
  for m in anova model; do
    r_session[$m]=$(awk -v m="$m" '$1 == m { print $2 }' <<< "$r_out")
    r_total[$m]=$(awk -v m="$m" -v l="$load" '$1 == m { print l + $4 }' <<< "$r_out")
  done
fi

printf '%s, median user CPU s of %s runs (/usr/bin/time: 0.01 s steps)\n' "$scores" "$reps"
printf '%-58s %7s %7s %7s %9s %7s\n' "command" "old" "new" "old/new" "R sess." "R/new"
for c in "${cases[@]}"; do
  read -r -a args <<< "$c"
  o=$(median_user "$old" "${args[@]}" "$scores")
  n=$(median_user "$new" "${args[@]}" "$scores")
  r="" rr=""
  if [[ $c == *"--contrasts pairwise" && $c != *kenward* && -n ${r_session[${args[0]}]:-} ]]; then
    r=${r_session[${args[0]}]}
    rr=$(ratio "$r" "$n")
  fi
  printf '%-58s %7.2f %7.2f %7s %9s %7s\n' "feint $c" "$o" "$n" "$(ratio "$o" "$n")" "$r" "$rr"
done
if [[ -n ${r_session[anova]:-} ]]; then
  printf 'R afex::aov_ez + emmeans pairwise (Tukey): %s s in session, %s s incl. loading\n' \
    "${r_session[anova]}" "${r_total[anova]}"
  printf 'R lmer + lmerTest + emmeans pairwise (Satterthwaite, Tukey): %s s in session, %s s incl. loading\n' \
    "${r_session[model]}" "${r_total[model]}"
fi

# The old build labels some per-iteration contrasts 'A≈B' where the current one writes 'n.s.'
# (a labelling change unrelated to the contrasts).
echo
python3 "$here/bench/compare_emmeans_outputs.py" "$old" "$new" "$scores" --accept 'A≈B' 'n.s.' |
  grep -v ': max relative difference'
exit "${PIPESTATUS[0]}"
