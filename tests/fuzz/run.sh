#!/bin/sh
# tests/fuzz/run.sh [SECONDS] [TARGET...] - builds each libFuzzer target with Debian's clang
# (-fsanitize=fuzzer,address,undefined) and runs it for SECONDS (default 60) on a working copy of
# its seed corpus, two targets at a time, niced. Findings (crash-*, leak-*, timeout-*) are left in
# build-fuzz/<target>/ and make the script exit 1: minimise one, add it to regressions/<target>/
# (replayed by feint_tests_fuzz), fix, re-run. Figures: build-fuzz/<target>.log (docs/fuzzing.md).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
seconds=${1:-60}
[ $# -gt 0 ] && shift
targets=${*:-number trace scores csv questionnaire}
out=${FEINT_FUZZ_BUILD:-$root/build-fuzz}
cxx=${CLANGXX:-clang++}
mkdir -p "$out"
# FEINT_CSV_CHUNK: the CSV reader's block size, tiny here so that records cross block boundaries.
flags="-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer,address,undefined
  -fno-sanitize-recover=undefined -DFEINT_CSV_CHUNK=64 -DFEINT_GZ_BUFFER=8192 -I$root/include -I$here"

# The loaders once, as a fuzzer-instrumented static library.
objs=""
for src in "$root"/src/io/*.cpp "$root"/src/metrics/*.cpp "$here"/harness_*.cpp; do
  o="$out/$(basename "$(dirname "$src")")_$(basename "$src" .cpp).o"
  if [ ! -f "$o" ] || [ "$src" -nt "$o" ] || [ -n "$(find "$root/include" -newer "$o" -name '*.hpp' | head -1)" ]; then
    echo "compile $src"
    # -fsanitize=fuzzer-no-link: instrumented, but no second main().
    nice $cxx $(echo "$flags" | sed 's/fuzzer,/fuzzer-no-link,/') -c "$src" -o "$o"
  fi
  objs="$objs $o"
done

run_one() {
  t=$1
  nice $cxx $flags -DFEINT_FUZZ_TARGET="$t" "$here/libfuzzer/main.cpp" $objs -lfmt -lz -lpthread \
    -o "$out/fuzz_$t"
  mkdir -p "$out/$t/corpus"
  cp -n "$here/corpus/$t/"* "$out/$t/corpus/" 2>/dev/null || true
  [ -d "$here/regressions/$t" ] && cp -n "$here/regressions/$t/"* "$out/$t/corpus/" 2>/dev/null || true
  dict=""
  [ -f "$here/dict/$t.dict" ] && dict="-dict=$here/dict/$t.dict"
  (cd "$out/$t" && nice "$out/fuzz_$t" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
     -rss_limit_mb=2048 -print_final_stats=1 $dict corpus >"$out/$t.log" 2>&1)
}

status=0
set -- $targets
while [ $# -gt 0 ]; do
  a=$1; shift
  b=""
  if [ $# -gt 0 ]; then b=$1; shift; fi
  echo "fuzz $a${b:+ and $b} for ${seconds}s"
  run_one "$a" & pa=$!
  pb=""
  if [ -n "$b" ]; then run_one "$b" & pb=$!; fi
  wait $pa || { echo "fuzz_$a: FINDING (see $out/$a.log, $out/$a/)"; status=1; }
  if [ -n "$pb" ]; then wait $pb || { echo "fuzz_$b: FINDING (see $out/$b.log, $out/$b/)"; status=1; }; fi
done
for t in $targets; do
  printf '%s: ' "$t"
  grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units|Done [0-9]+ runs)' "$out/$t.log" | tr '\n' ' '
  echo
done
exit $status
