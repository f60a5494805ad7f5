#!/bin/bash
# model_null_rates.sh FEINT FIRST_SEED COUNT > rates.txt
# The mixed models' tests under a true null (docs/findings.md, "What is not done yet"): for each
# seed, `feint simulate study` (30 + 30 participants x 20 iterations, adaptive with lambda 0, i.e.
# selection as random's), `feint score`, then `feint model` for error with iteration as a factor
# and as a linear trend, each with a random intercept and with a random slope for the iteration
# (the factor model with a random slope needs a build that allows it: see the docs). One line per
# study: seed, then p of the interaction and the condition main effect (factor model) and of the
# slope difference (trend model), random intercept first, then random slope. Two studies at a time.
FEINT=${1:?feint binary}; FIRST=${2:-5001}; COUNT=${3:-400}
one() {
  s=$1; d=$(mktemp -d); F=$FEINT
  "$F" simulate study -o "$d" -p 30 -n 20 -l 0 -s "$s" > /dev/null 2>&1
  "$F" score "$d/logs" -o "$d/scores.csv" > /dev/null 2>&1
  out=""
  for opts in "" "--trend" "--random-slope" "--trend --random-slope"; do
    m=$("$F" model "$d/scores.csv" --metric error $opts --format csv 2>/dev/null)
    case "$opts" in
      *trend*) out="$out $(echo "$m" | awk -F, '$2=="fixef" && $3 ~ /^condition.*:iteration$/{print $16}')";;
      *) out="$out $(echo "$m" | awk -F, '$2=="anova" && $3=="condition:iteration"{print $16}') $(echo "$m" | awk -F, '$2=="anova" && $3=="condition"{print $16}')";;
    esac
  done
  echo "$s$out"
  rm -rf "$d"
}
export -f one; export FEINT
seq "$FIRST" $((FIRST + COUNT - 1)) | xargs -P 2 -I{} bash -c 'one {}'
