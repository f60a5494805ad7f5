#!/usr/bin/env bash
# `feint model` against R (lme4::lmer + lmerTest::anova + emmeans contrasts) on the paper's design
# (2 conditions x 30 participants x 20 iterations, 3 % missing trials), in one run, as a ratio.
#
#   bench/run_model_bench.sh [BUILD_DIR] [REPS]
#
# BUILD_DIR: a Release build holding `feint` (default build); REPS: repetitions (default 20).
# feint is timed as whole processes (start, CSV parse, fit, Satterthwaite, contrasts, rendering);
# R is timed inside one session after loading the packages (fit + anova + emmeans only), so the
# comparison favours R. R is needed only here, never by feint or its tests.
set -euo pipefail

build=${1:-build}
reps=${2:-20}
here=$(cd "$(dirname "$0")/.." && pwd)
data=$here/tests/golden/models/lmm_paper20_missing.csv
feint=$build/feint
[[ -x $feint ]] || { echo "build first: cmake --build $build --target feint" >&2; exit 64; }
command -v Rscript >/dev/null || { echo "Rscript not found (r-base-core, r-cran-lmertest, r-cran-emmeans)" >&2; exit 69; }

# Wall clock and CPU time (user + sys): the machine may be shared, CPU time is the steadier figure.
cpu=$(mktemp); trap 'rm -f "$cpu"' EXIT
start=$(date +%s.%N)
for ((i = 0; i < reps; ++i)); do
  /usr/bin/time -a -o "$cpu" -f "%U %S" "$feint" model "$data" --metric error --p-adjust holm \
    --format csv -o /dev/null
done
end=$(date +%s.%N)
feint_s=$(echo "($end - $start) / $reps" | bc -l)
feint_cpu=$(awk -v n="$reps" '{ s += $1 + $2 } END { printf "%.6f", s / n }' "$cpu")

r_s=$(Rscript - "$data" "$reps" <<'REOF'
suppressPackageStartupMessages({ library(lme4); library(lmerTest); library(emmeans) })
emm_options(lmer.df = "satterthwaite", lmerTest.limit = 1e6)
args <- commandArgs(TRUE); reps <- as.integer(args[2])
d <- read.csv(args[1]); d$iteration <- factor(d$iteration); d$condition <- factor(d$condition)
run <- function() {
  m <- lmer(error ~ condition * iteration + (1 | participant), d)
  a <- anova(m)
  e <- summary(emmeans(m, pairwise ~ condition | iteration, adjust = "none")$contrasts)
  p <- p.adjust(e$p.value, "holm")
  invisible(list(a, p))
}
run()  # warm-up
t <- system.time(for (i in seq_len(reps)) run())
cat(t[["elapsed"]] / reps, (t[["user.self"]] + t[["sys.self"]]) / reps)
REOF
)
printf 'paper design (60 participants x 20 iterations, %s trials), %s repetitions\n' \
  "$(($(wc -l < "$data") - 1))" "$reps"
read -r r_wall r_cpu <<< "$r_s"
printf '%-40s %10s %10s\n' "" "wall s/run" "CPU s/run"
printf '%-40s %10.4f %10.4f\n' "feint model (whole process)" "$feint_s" "$feint_cpu"
printf '%-40s %10.4f %10.4f\n' "R lmer + anova + emmeans (in session)" "$r_wall" "$r_cpu"
printf '%-40s %10.1f %10.1f\n' "ratio R / feint" "$(echo "$r_wall / $feint_s" | bc -l)" \
  "$(echo "$r_cpu / $feint_cpu" | bc -l)"
